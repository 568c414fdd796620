// Seed placement for the Voronoi partition: farthest-point sampling over the mesh's edge
// graph, or uniform random vertices. Both put at least one seed on every face-connected
// component and never use isolated vertices.
#pragma once

#include <cstdint>
#include <vector>

#include "generators.h"  // Random
#include "mesh.h"

namespace vorogeo {

// The edge graph of a mesh with connectivity built, as compressed adjacency lists.
struct VertexGraph {
    std::vector<uint32_t> offset;    // V + 1 entries: neighbours of v are [offset[v], offset[v+1])
    std::vector<uint32_t> neighbor;
    std::vector<double> length;      // Euclidean edge length, parallel to neighbor

    explicit VertexGraph(const Mesh& mesh);
    uint32_t vertexCount() const { return uint32_t(offset.size() - 1); }
};

// Number of face-connected components, and per vertex its component (kNoComponent for
// isolated vertices), as vertexComponents() in mesh_stats.h.
uint32_t componentCount(const std::vector<uint32_t>& vertexComponent);

// Farthest-point sampling: each next seed is the vertex farthest from all seeds so far
// (ties to the smaller index), by shortest paths in the edge graph where an edge weighs its
// length over the mean length of the edges at its two ends (about 1 per edge anywhere, so
// seeds spread evenly by vertex count where the mesh density varies, and by distance where
// it does not). Distances are kept up to date by a Dijkstra pruned to the vertices the new
// seed brings closer. With `mirrorBoundary`, the domain boundary counts as seeds standing
// mirrored beyond it (a vertex starts at twice its distance to the boundary), so seeds keep
// off the boundary and border cells are not halved; the first seed of a component is then
// its vertex farthest from the boundary, and a component without a boundary starts at a
// random vertex. A component without a seed is infinitely far, so every component gets
// one before any gets a second. `count` must be at least the number of components and at
// most the number of used vertices.
std::vector<uint32_t> farthestPointSeeds(const Mesh& mesh, const VertexGraph& graph, uint32_t count, Random& rng,
                                         bool mirrorBoundary = true);

// Random sampling as in the thesis: a random vertex of every component (in component
// order), then distinct vertices drawn uniformly from the rest. Same limits on `count`.
std::vector<uint32_t> randomSeeds(const Mesh& mesh, uint32_t count, Random& rng);

// Index in [0, n) from a Random (n > 0).
inline uint32_t randomIndex(Random& rng, uint32_t n) {
    const uint32_t i = uint32_t(rng.uniform() * double(n));
    return i < n ? i : n - 1;
}

}  // namespace vorogeo
