// Geodesic Voronoi partition of a mesh's vertices (thesis 3.8): Poisson-disk seeds, then
// spheres growing around the seeds, each vertex settled with point-to-point queries
// bounded by its best distance so far.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh.h"
#include "vorogeo.h"

namespace vorogeo::tools {

// Up to `count` vertices at least a radius apart (Euclidean), by dart throwing over the
// vertices in a random order; the radius shrinks until `count` fit. Deterministic for a seed.
std::vector<uint32_t> poissonDiskSeeds(const Mesh& mesh, uint32_t count, uint64_t seed, double& radius);

struct VoronoiResult {
    std::vector<uint32_t> label;    // per vertex: index into the seeds, seeds.size() = unreachable
    std::vector<float> distance;    // per vertex: to that seed
    uint64_t queries = 0;           // point-to-point queries run
    uint64_t boundedQueries = 0;    // of which bounded by an earlier candidate
    uint32_t rounds = 0;            // sphere radii tried
};

// Growing spheres: the sphere radius starts at radius / 2 and grows by `growth` (0.25 =
// 25%) per round. A vertex asks only the seeds that entered its sphere since the last
// round, bounded by its best distance so far, and is assigned once that distance lies
// inside the sphere: a seed outside is farther in straight line, so farther along the
// surface too. (The thesis assigns a vertex as soon as a sphere covers it; this waits for
// the proof, so the labels are those of the nearest seed under the runtime's distance.)
VoronoiResult growingSpheres(const Mesh& mesh, const vg_graph* graph, vg_workspace* workspace,
                             const std::vector<uint32_t>& seeds, double radius, double growth = 0.25);

}  // namespace vorogeo::tools
