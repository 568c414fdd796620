// Exact polyhedral geodesic distances to vertices by triangle-oriented wavefront
// propagation (in the style of Qin et al. 2016, "VTP"): the same windows as the MMP engine
// (geodesic_exact.h), but handled as lists per half-edge and propagated across a face all
// at once, in the order of a vertex queue.
//
// Why a second engine: the MMP engine keeps every window on its edge for the rest of the
// run (its overlap resolution compares each newcomer with the edge's earlier windows), so
// on meshes with many near-flat saddles its memory grows to the whole exact field (~1 GB on
// igea). Here a window lives only until it has crossed its face: windows are pruned by the
// distances of the face's vertices and by "one angle, two sides" (of the windows of one
// list, only the one giving the face's third vertex its distance may reach both of the
// face's other edges), so the working set stays the wavefront. Distances are exact at the
// vertices, as MMP's; there are no distances between vertices afterwards (distanceAt needs
// the MMP engine's windows).
#pragma once

#include <cstdint>
#include <vector>

#include "geodesic_exact.h"

namespace vorogeo {

class WavefrontWorkspace {
public:
    // Distances from the source vertices to every domain vertex (+inf if unreachable or
    // beyond maxDistance: windows that start beyond it are dropped, so a bounded run does
    // only the work inside the bound). Throws std::invalid_argument on an out-of-range
    // source or a negative bound.
    void run(const ExactGeodesic& geo, const std::vector<uint32_t>& sources, std::vector<double>& distances,
             ExactStats* stats = nullptr, double maxDistance = kInfinity);

    // A target vertex and the largest distance at which it is wanted.
    struct Target {
        uint32_t vertex;
        double bound;
    };
    // Distances from one source vertex to `targets`: exact for a target whose distance is
    // within its bound, +inf for one beyond it. A window is dropped once no path through it
    // can reach any target within that target's bound (its minimum plus the straight way
    // to the target, a lower bound of every such path, exceeds it), so a run does only
    // the work between the source and the targets. Give bounds a little slack for
    // rounding (the exact first layer adds 1e-6 relative). Other vertices' distances are
    // not meaningful afterwards. Throws as run() does, and on a negative or NaN bound.
    void runToTargets(const ExactGeodesic& geo, uint32_t source, const std::vector<Target>& targets,
                      std::vector<double>& distances, ExactStats* stats = nullptr);

    size_t memoryBytes() const;

private:
    struct Window {
        double b0, b1;  // extent along the half-edge, from its tail
        double sx, sy;  // (pseudo-)source in the half-edge's frame (below it: sy <= 0)
        double sigma;   // distance from the real source to the pseudo-source
    };
    enum : uint8_t { kOutside = 0, kFront = 1, kInside = 2 };

    void reset(const ExactGeodesic& geo);
    // Both runs, after their arguments are checked.
    void propagate(const ExactGeodesic& geo, const std::vector<uint32_t>& sources, std::vector<double>& distances,
                   ExactStats* stats, double maxDistance);
    uint32_t allocBlock();
    void append(int32_t h, double b0, double b1, double sx, double sy, double sigma);
    void pushList(int32_t h);
    void improve(uint32_t v, double d);
    void emitFromVertex(uint32_t v, bool insideArea);
    void propagateList(int32_t h);
    void popVertex(uint32_t v);
    // runToTargets: the largest distance at v from which some target can still be reached
    // within its bound (max over targets of bound - straight way); 1-Lipschitz, so an
    // edge's points have at most (budget(a) + budget(b) + length) / 2.
    double budget(uint32_t v);
    // The vertex heap (a binary heap on distance with positions, for decrease-key).
    void heapUpdate(uint32_t v);
    uint32_t heapPop();

    const ExactGeodesic* geo_ = nullptr;
    std::vector<double>* dist_ = nullptr;
    static constexpr uint32_t kBlockWindows = 8;
    struct Block {
        Window windows[kBlockWindows];
        uint32_t count, next;  // windows used; the list's next block
    };
    std::vector<Block> blocks_;
    std::vector<uint32_t> freeBlocks_;
    std::vector<uint32_t> listHead_, listTail_;  // per half-edge: first and last block
    std::vector<int32_t> fifo_;                  // half-edges whose lists wait to cross their face
    size_t fifoHead_ = 0;
    std::vector<uint8_t> state_;
    std::vector<uint32_t> heap_, heapPos_;
    struct Pending {  // a window of the list crossing its face
        Window window;
        double split;  // where its way to the apex leaves the edge (clamped to the window)
        double at;     // where the straight line from its source to the apex meets the edge
    };
    std::vector<Pending> batch_;
    uint64_t alive_ = 0;
    double maxDistance_ = kInfinity;
    bool targeted_ = false;  // this run is a runToTargets: windows must fit the targets' budget
    struct TargetLanes {  // the targets' positions and bounds by decreasing bound
        std::vector<double> x, y, z, bound;
    };
    TargetLanes targetLanes_;
    std::vector<uint32_t> byBound_;
    std::vector<double> budget_;
    std::vector<uint32_t> budgetStamp_;  // budget_[v] holds for this run when equal to runStamp_
    uint32_t runStamp_ = 0;
    ExactStats stats_;
};

// One source vertex to every vertex of `geo`'s domain with the wavefront engine.
std::vector<double> wavefrontDistancesFrom(const ExactGeodesic& geo, uint32_t source);

// Runs independent single-source problems in parallel (TBB), one workspace per worker,
// with the wavefront engine. Returns one distance array per source vertex.
std::vector<std::vector<double>> exactDistancesBatch(const ExactGeodesic& geo,
                                                     const std::vector<uint32_t>& sources,
                                                     double maxDistance = kInfinity);

}  // namespace vorogeo
