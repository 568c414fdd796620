// Exact polyhedral geodesic distances by window propagation (Mitchell-Mount-Papadimitriou,
// in the interval-propagation style of Surazhsky et al. 2005).
//
// Each edge carries a sorted list of windows: intervals of the edge whose shortest paths
// come straight from one (pseudo-)source, unfolded into the plane of the edge. Windows are
// popped from a priority queue by their smallest distance and propagated across the face
// on their far side; new windows are merged into the lists of the two opposite edges by
// keeping, point by point, the smaller distance. Saddle and boundary vertices, where
// shortest paths can bend, become pseudo-sources once their distance is known.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "bucket_queue.h"
#include "mesh.h"

namespace vorogeo {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// A point inside face `face` with barycentric weights of faces[face][0..2].
struct SurfacePoint {
    uint32_t face = 0;
    double bary[3] = {1.0, 0.0, 0.0};
};

inline Vec3 positionOf(const Mesh& mesh, const SurfacePoint& p) {
    Vec3 x{0, 0, 0};
    for (int k = 0; k < 3; ++k) x = x + mesh.positions[mesh.faces[p.face][k]] * p.bary[k];
    return x;
}

// A source of the distance field: a vertex, or a point on the surface.
struct GeodesicSource {
    bool isVertex = true;
    uint32_t vertex = 0;
    SurfacePoint point;

    static GeodesicSource atVertex(uint32_t v) {
        GeodesicSource s;
        s.vertex = v;
        return s;
    }
    static GeodesicSource atPoint(const SurfacePoint& p) {
        GeodesicSource s;
        s.isVertex = false;
        s.point = p;
        return s;
    }
};

struct ExactQuery {
    std::vector<GeodesicSource> sources;  // distance 0 at each
    double maxDistance = kInfinity;       // propagation stops beyond it; farther vertices get +inf
    std::vector<uint32_t> targets;        // if non-empty, stop once every target is final
};

struct ExactStats {
    uint64_t windowsCreated = 0;     // windows that survived merging into an edge list
    uint64_t windowsPropagated = 0;  // windows popped and propagated across a face
    uint64_t peakWindows = 0;        // most windows alive at once
    uint64_t pseudoSources = 0;      // vertex events (sources included)
};

// The immutable, shareable part of the engine for one domain: the whole mesh or a patch
// given as a set of faces. Distances are indexed by domain vertex (localVertex()).
class ExactGeodesic {
public:
    // Whole mesh; `mesh` must outlive this object and have connectivity built.
    explicit ExactGeodesic(const Mesh& mesh);
    // Patch: the given faces of `mesh` (which need not outlive this object). Domain faces
    // and vertices follow the input's order, or with `spatialOrder` the faces' Morton
    // order and the vertices in the order the faces name them: neighbours then share cache
    // lines, and runs on inputs in scanline order are faster (BENCHMARKS.md). Distances
    // agree either way; map with localVertex/localFace.
    ExactGeodesic(const Mesh& mesh, const std::vector<uint32_t>& faces, bool spatialOrder = false);

    const Mesh& mesh() const { return *mesh_; }
    uint32_t vertexCount() const { return mesh_->vertexCount(); }
    // Domain <-> input mesh indices. For the whole mesh both are the identity.
    uint32_t globalVertex(uint32_t local) const { return owned_ ? toGlobal_[local] : local; }
    // -1 if the vertex is not in the domain. A patch vertex where two fans of patch faces
    // meet has one domain vertex per fan (all at the same distance); this returns the first.
    int64_t localVertex(uint32_t global) const;
    int64_t localFace(uint32_t global) const;    // -1 if the face is not in the domain
    // True where shortest paths may pass through the vertex (saddle or boundary).
    bool isPseudoSourceVertex(uint32_t v) const { return pseudo_[v] != 0; }

private:
    friend class ExactWorkspace;
    friend class WavefrontWorkspace;
    void precompute();
    void splitPinchedVertices();

    std::unique_ptr<Mesh> owned_;  // the extracted patch, when the domain is one
    const Mesh* mesh_ = nullptr;
    std::vector<uint32_t> toGlobal_;      // local vertex -> input vertex (patch only); copies of split vertices last
    std::vector<uint32_t> alias_;         // circular lists of copies of split vertices
    std::vector<uint32_t> faceToGlobal_;  // local face -> input face (patch only)
    std::vector<std::pair<uint32_t, uint32_t>> vertexLookup_, faceLookup_;  // (input, local), sorted (patch only)

    struct HalfedgeFrame {  // the face of h unfolded with tail(h) at 0 and head(h) on +x
        double apexX, apexY;
    };
    std::vector<HalfedgeFrame> frame_;  // per half-edge
    std::vector<int32_t> edgeOf_;       // half-edge -> edge
    std::vector<int32_t> canonical_;    // edge -> its canonical half-edge
    std::vector<double> edgeLength_;    // per edge
    std::vector<uint8_t> pseudo_;       // per vertex
    double queueBucketWidth_ = 1.0;
    size_t queueBuckets_ = 1;
};

// Per-thread scratch memory. Reusing one workspace for many runs makes the hot loop
// allocation-free once its buffers have grown to the problem size.
class ExactWorkspace {
public:
    // Distances from the query's sources to every domain vertex (+inf if unreachable or
    // beyond maxDistance). Throws std::invalid_argument on an out-of-range source/target.
    void run(const ExactGeodesic& geo, const ExactQuery& query, std::vector<double>& distances,
             ExactStats* stats = nullptr);

    // After run(): the exact distance from the run's sources to surface point q (a face of
    // the same domain), from the final windows on q's face's edges, the face's corners
    // (`distances`: what run() returned) and any source inside the face. Exact for a
    // complete run (no maxDistance or targets).
    double distanceAt(const SurfacePoint& q, const std::vector<double>& distances) const;

    // Bytes of scratch memory the workspace holds (it keeps its buffers between runs).
    size_t memoryBytes() const;

private:
    struct Window {
        double b0, b1;  // extent on the edge, in the edge's canonical frame
        double sx, sy;  // (pseudo-)source, unfolded into the canonical frame
        double sigma;   // distance from the real source to the pseudo-source
        int32_t h;      // the window's paths continue into face(h)
        uint32_t next;  // next window along the same edge
    };  // 48 bytes: the run is memory-bound, so bookkeeping lives in ticket_ instead
    struct QueueEntry {
        double key;
        uint32_t id;      // window id, or vertex id when ticket == kVertexEvent
        uint32_t ticket;  // must equal ticket_[id] for a window entry to be current
    };
    struct Piece {
        double lo, hi;
        uint32_t owner;  // window id, kCandidate, or kNone
    };

    void reset(const ExactGeodesic& geo);
    void emitFromPoint(const Vec3& p, uint32_t face, double sigma);
    void emitFromVertex(uint32_t v);
    void propagate(uint32_t id);
    // Merges a candidate window (coordinates in the frame of half-edge g, which it enters).
    void insertCandidate(int32_t g, double b0, double b1, double sx, double sy, double sigma);
    void relaxVertex(uint32_t v, double d);
    uint32_t allocWindow();
    void freeWindow(uint32_t id);
    void schedule(uint32_t id);  // queue window `id` for propagation

    const ExactGeodesic* geo_ = nullptr;
    std::vector<Window> pool_;
    std::vector<uint32_t> ticket_;  // per window: its queue ticket while pending, else 0
    uint32_t nextTicket_ = 1;
    std::vector<uint32_t> freeList_;
    std::vector<uint32_t> edgeHead_;
    BucketQueue<QueueEntry> queue_;
    std::vector<uint32_t> overlap_;
    std::vector<Piece> pieces_;
    std::vector<double>* dist_ = nullptr;
    std::vector<SurfacePoint> pointSources_;  // the last run's surface-point sources
    std::vector<uint8_t> isTarget_;
    double maxDistance_ = kInfinity;
    bool targetsDirty_ = false;
    uint64_t alive_ = 0;
    ExactStats stats_;
};

// The exact distance from one source vertex to every vertex of the whole mesh (+inf where
// unreachable): a one-off run with its own workspace.
std::vector<double> exactDistancesFrom(const Mesh& mesh, uint32_t source);


// Shortest paths along mesh edges (Dijkstra): the fast, inexact baseline.
// Stops early once `target` (if >= 0) is settled.
void edgeDijkstra(const Mesh& mesh, uint32_t source, std::vector<double>& distances,
                  int64_t target = -1);

}  // namespace vorogeo
