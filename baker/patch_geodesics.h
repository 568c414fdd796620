// The baker's precomputation stage (thesis 3.4; Algorithm 1 steps 4-5): exact geodesic
// distances inside every patch, computed with the exact engine on the patch's faces
// (optionally grown by margin rings of faces, see below).
//
//  - first layer:  node x node, where a node is a patch vertex shared with another
//                  first-layer patch (the thesis's Bv x Bv);
//  - second layer: every patch vertex x every patch vertex, nodes first: the Bv x Bv
//                  block is the second-layer graph, Bv x Iv connects a query's endpoints
//                  to it, Iv x Iv answers queries inside one patch by lookup.
//
// "Node" is stricter than the partition's Bv: a vertex on a mesh boundary that no other
// patch touches is no crossing point between patches, so it is stored as an interior
// vertex and never enters the graph.
//
// Margin rings: a shortest path between two vertices of a non-convex patch may leave it,
// and the patch-local distance is then too long (the thesis's main error source). With
// margin rings, the domain of the computation is the patch plus every face that shares a
// vertex with it, repeated `marginRings` times; the stored values stay between patch
// vertices. Measured in BENCHMARKS.md ("Margin rings").
//
// Deterministic: every distance comes from one single-source run with fixed inputs,
// written to a fixed slot, whatever the number of threads.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "mesh.h"
#include "partition.h"

namespace vorogeo {

// One patch's local vertex order and its packed symmetric distance matrix.
struct PatchMatrix {
    std::vector<uint32_t> vertices;  // local order: nodes (sorted), then the rest (sorted)
    uint32_t nodeCount = 0;
    uint32_t rows = 0;               // matrix order: nodeCount (first layer) or vertices.size()
    std::vector<double> upper;       // strictly upper triangle of rows x rows, row by row

    double at(uint32_t i, uint32_t j) const;  // any i, j < rows; 0 on the diagonal
};

// Index of (i, j), i < j, in a packed strictly upper triangle of order n.
inline size_t upperIndex(size_t n, size_t i, size_t j) { return i * (2 * n - i - 1) / 2 + (j - i - 1); }

struct PatchGeodesicsOptions {
    uint32_t marginRings = 1;  // rings of faces added around each patch for the computation
    // How first-layer node x node distances are made: Composed = shortest paths over the
    // second-layer node graph inside the first-layer patch (fast, the default); Exact = one
    // exact run per node on the whole first-layer patch (the thesis; kept for measurement).
    enum class FirstLayer { Composed, Exact } firstLayer = FirstLayer::Composed;
};

struct PatchGeodesicsStats {
    uint64_t sourceRuns = 0;       // single-source exact runs
    uint64_t storedDistances = 0;  // matrix entries
    double firstLayerSeconds = 0, secondLayerSeconds = 0;
};

struct PatchGeodesics {
    std::vector<PatchMatrix> first, second;
    PatchGeodesicsStats stats;
};

// Per mesh vertex: how many distinct patches of one layer own a face around it.
std::vector<uint8_t> patchesPerVertex(const Mesh& mesh, const std::vector<uint32_t>& facePatch);

// The faces of `faces` grown by `rings` rings of faces sharing a vertex (sorted).
std::vector<uint32_t> growFaces(const Mesh& mesh, const std::vector<uint32_t>& faces, uint32_t rings);

using StageProgress = std::function<void(const char* stage, double fraction)>;

// Runs the precomputation for both layers with TBB. Progress calls never overlap.
// First-layer node x node distances as shortest paths over the second-layer node graphs
// (their node x node blocks) of the second-layer patches inside each first-layer patch.
// Reports progress per first-layer patch as "first-layer overlay".
void composeFirstLayer(const Mesh& mesh, const Partition& partition, const std::vector<PatchMatrix>& second,
                       std::vector<PatchMatrix>& first, const StageProgress& progress = StageProgress());

PatchGeodesics computePatchGeodesics(const Mesh& mesh, const Partition& partition,
                                     const PatchGeodesicsOptions& options,
                                     const StageProgress& progress = StageProgress());

}  // namespace vorogeo
