// Pulling a traced path taut. The traced polyline (vg_path_trace.h) follows the stored
// fields leg by leg and passes through the border nodes where the legs meet, so it is as
// long as the sum the search added up, a little longer than the geodesic. Here the faces
// it runs through become a corridor (where it passes a vertex: the faces on the side of
// the smaller angle), the corridor is unfolded into the plane, and the shortest way
// through it (the funnel algorithm) replaces the traced one. Internal to the runtime.
#pragma once

#include "vg_path_trace.h"

namespace vg {

// A corridor edge crossed from one face into the next: half-edge `halfedge` of the face
// left behind, its ends as seen travelling (right = the half-edge's tail), unfolded.
struct Portal {
    uint32_t halfedge;
    uint32_t leftVertex, rightVertex;
    double left[2], right[2];
};

// A corner of the taut polyline: the start, a vertex it bends around, the end.
struct Apex {
    double at[2];
    uint32_t portal;  // index of the portal whose end it is (0: start, portals + 1: end)
    uint32_t vertex;  // kNone for the start and end
};

// Raw path points and corridor portals the workspace has room for; a longer path is
// returned as traced.
inline uint64_t maxRawPathPoints(uint64_t faceCount) { return faceCount * 2 + 64 < 16384 ? faceCount * 2 + 64 : 16384; }
inline uint64_t maxPortals(uint64_t faceCount) { return faceCount * 4 + 64 < 32768 ? faceCount * 4 + 64 : 32768; }

// Passes of pullTaut at most (each starts from the last). They stop after a pass that
// leaves no bend worth turning round (see pullTaut's `bendable`), or after a second or
// later pass that shortened the path by less than kTautGain (the first one always gains
// most: it removes the trace's kinks at the patch nodes).
constexpr uint32_t kTautPasses = 4;
constexpr double kTautGain = 2e-4;

// Length of a polyline of path points.
inline double polylineLength(const vg_path_point* p, size_t count) {
    double length = 0.0;
    for (size_t i = 1; i < count; ++i) length += distance3(p[i - 1].position, p[i].position);
    return length;
}

// Writes the taut form of the `count` (>= 2) points of `raw` to `out` (first and last
// point kept) and its length to `length`; `bendable`: it bends round a vertex whose other
// side is shorter, so another pass can shorten it. False, with nothing written, when the
// corridor cannot be built or does not fit the workspace: the caller then keeps the
// traced path.
bool pullTaut(const vg_graph& g, vg_workspace& ws, const vg_path_point* raw, size_t count, PathWriter& out,
              double& length, bool& bendable);

}  // namespace vg
