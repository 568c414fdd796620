// The point-to-point search (vg_distance.cpp), shared with the path query, which needs to
// know how the best distance was found to rebuild it as a polyline.
// Internal to the runtime.
#pragma once

#include "vg_workspace.h"

namespace vg {

// How pointToPoint's answer was reached. The search labels stay in the workspace's two
// frontiers (forward from s, backward from t) until the next query.
struct Meeting {
    enum Kind : uint32_t {
        kUnreached,  // +inf (or beyond the bound)
        kSame,       // s and t are one point
        kSegment,    // one face: the straight segment
        kFan,        // faces around `vertex`: way 0 / 1 across its fan, 2 through it
        kPatch,      // one second-layer `patch` holds both
        kNode,       // the searches met at `node`
        kCrossing,   // they met across the mesh edge (node, other)
    };
    uint32_t kind;
    bool swapped;  // s and t are the caller's target and source (one order for both directions)
    Endpoint s, t;
    uint32_t patch, node, other, vertex, way;
};

// Distance from s to t (+inf beyond maxDistance) by the given search (vg_distance.cpp);
// with `how`, also how it was found, and then exactly that one search runs (the directed
// mode's second search of a short pair, from the other end, would overwrite the labels
// `how` refers to).
float pointToPoint(const vg_graph& g, vg_workspace& ws, Endpoint s, Endpoint t, float maxDistance,
                   vg_search_mode mode, Meeting* how = nullptr);

// The answers that need no search (the meeting kinds kSame aside): the segment of two
// points on one face, the local paths around one vertex, the entry of two endpoints of one
// second-layer patch; the shortest of them (+inf: none), and how it was found in m.
float nearbyDistance(const vg_graph& g, const Endpoint& s, const Endpoint& t, Meeting& m);

// One directed search from the endpoint that comes first in the pair's one order (the
// same for (s, t) and (t, s)), or with `fromSecond` from the other; no second search.
float directedSearch(const vg_graph& g, vg_workspace& ws, Endpoint s, Endpoint t, float maxDistance, bool fromSecond);

}  // namespace vg
