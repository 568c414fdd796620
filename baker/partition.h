// The baker's partition stage (thesis 3.3; Algorithm 1 steps 1-3 and the second-layer
// partitioning): the mesh is split into first-layer geodesic Voronoi patches, and every
// first-layer patch into second-layer Voronoi patches. Every patch of both layers is a
// topological disk, so that it has exactly one border ring.
//
// How a layer is made, for one domain (the whole mesh, or one first-layer patch):
//  1. Seeds: farthest-point sampling (the default) or uniform random vertices; every
//     face-connected component of the domain gets at least one seed.
//  2. Distance and labels: exact geodesic Voronoi. Each vertex gets its nearest seed by the
//     exact polyhedral geodesic distance (the exact MMP engine), ties to the smaller seed
//     index. Second-layer distances are measured inside the first-layer patch (paths do not
//     leave it), as the precomputation will measure them. The engine returns distances but
//     not which source is nearest, so every seed runs alone (in parallel), bounded by the
//     radius of its cell in the edge graph (edge paths are never shorter than geodesics, so
//     each vertex is reached by the seed that is nearest along edges); a vertex is certain
//     once every seed that did not reach it is known to be farther (its bound, or its
//     straight-line distance, is at least the vertex's distance), else that seed runs again
//     further. Cost on igea (134K vertices, 45 seeds): 2.5 s of CPU, 1.3 s on 2 threads,
//     against 1.6-1.9 s (one thread, not parallel) for one multi-source run of all seeds,
//     whose distances would still need labels: propagated over that field (each vertex
//     taking the label of the neighbour minimising D(u) + |uv|, tried first) they named the
//     wrong seed for 9 of 54 vertices of a coarse second-layer patch of twoComponents, up
//     to about 3 edge lengths farther than the nearest; so per-seed runs replace the
//     multi-source run.
//  3. Faces: a face goes to the label held by at least two of its vertices, else to the
//     smallest of the three seed indices. Pieces of a patch cut off from the piece at its
//     seed (mostly single faces touching it at a vertex) go to the edge-adjacent patch
//     whose seed is nearest in a straight line, so every patch is face-connected.
//  4. Disks: a patch that is not a disk (several boundary loops, a handle, a closed
//     component, a vertex where two fans of its faces touch) gets one more seed: the
//     pinched vertex, else the vertex of largest D on one of its boundary loops other than
//     the longest, else its vertex of largest D. The new seeds' exact fields (one bounded
//     run each, in parallel, up to the current largest D, so the update is exact) lower D
//     and relabel the vertices they are nearest to; this repeats (at most 32 rounds).
//     A patch still not a disk after that is cut into disks by greedy face growth (never
//     needed on the test or shared meshes; counted in PartitionStats). The shared meshes
//     need up to 17 such seeds (armadillo-50k: patches wrapped around its limbs).
//  5. Border/interior: a patch vertex is a border vertex (Bv) if one of its faces belongs
//     to another patch or it lies on a mesh boundary (hole-adjacent vertices are always
//     border vertices); otherwise it is an interior vertex (Iv). Second-layer borders
//     therefore include the first-layer borders.
//
// Automatic sizes: n1 = max(1, round(V / 3000)) for V vertices used by faces, aiming at
// first-layer patches of about 3,000 vertices; n2 = max(1, round(Vp / 100)) for a
// first-layer patch of Vp vertices, aiming at second-layer patches of about 100 vertices.
// n1 is raised to the number of face-connected components; an explicit n2 larger than a
// patch's vertex count is lowered to it. Making patches disks adds seeds, so a layer may
// end with more patches than requested (and a seed whose cell gets no face makes none).
//
// Sampling, measured by the hidden test "[.measure]" (vertices per patch, border vertices
// counted in every patch they touch; automatic sizes, seed 1, 2 threads):
//                           first layer                        second layer
//   bumpyTorus  28,800 V  FPS     10 patches  2127-4938 sd  764   304 patches  70-218 sd 27
//                         Random  11 patches  1771-4891 sd  916   308 patches   4-547 sd 73
//   igea       134,345 V  FPS     45 patches  2280-4102 sd  474  1416 patches  71-249 sd 24
//                         Random  45 patches   692-7836 sd 1539  1421 patches   3-542 sd 63
//   spot         2,930 V  one seed split into 2 disks either way; second layer sd 38 / 62
// Farthest-point sampling is the default. On igea its patches are 2.6-3x more uniform in
// both layers (sd 15% and 20% of the mean against 49% and 51%): no patch far beyond the
// planned size (the precomputation grows with |Bv|^2 and |Iv|^2 per patch) and no sliver
// patches of 3-4 vertices. It is also faster (1.9 s against 4.8 s on igea: random cells
// are uneven and the exact runs must reach across the largest). Its distance counts edges
// relative to their local length (see farthestPointSeeds), so seeds follow vertex density
// and patch vertex counts stay even where the density varies (nefertiti-50k first layer
// sd 1310 -> 640, second 52 -> 26 against plain edge lengths), and second-layer seeds
// keep off the first-layer border, which halved the second-layer spread.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "mesh.h"

namespace vorogeo {

struct PartitionOptions {
    uint32_t firstLayerSeeds = 0;   // n1; 0 = automatic: max(1, round(V / 3000))
    uint32_t secondLayerSeeds = 0;  // n2 per first-layer patch; 0 = automatic: max(1, round(Vp / 100))
    uint64_t seed = 1;              // all randomness comes from this
    enum class Sampling { FarthestPoint, Random } sampling = Sampling::FarthestPoint;
};

struct Patch {                       // one Voronoi patch
    std::vector<uint32_t> faces;     // sorted mesh face ids
    std::vector<uint32_t> border;    // Bv: sorted vertex ids on the patch's border ring
    std::vector<uint32_t> interior;  // Iv: sorted vertex ids not on the border
    uint32_t seedVertex = 0;         // the Voronoi seed (mesh vertex id)
    uint32_t parent = UINT32_MAX;    // second layer: index of the first-layer patch
};

// What the partition did beyond the requested seeds (for reports and tests).
struct PartitionStats {
    uint32_t firstSeeds = 0;            // first-layer seeds sampled (n1 after the rules above)
    uint32_t firstDiskSeeds = 0;        // first-layer seeds added to make patches disks
    uint32_t firstDiskRounds = 0;       // rounds of adding them
    uint32_t firstCutPatches = 0;       // first-layer patches made by the fallback cut
    uint32_t secondSeeds = 0;           // second-layer seeds sampled, all patches together
    uint32_t secondDiskSeeds = 0;
    uint32_t secondCutPatches = 0;
    double firstLayerSeconds = 0, secondLayerSeconds = 0;
};

struct Partition {
    std::vector<Patch> first, second;
    std::vector<uint32_t> faceFirst, faceSecond;  // per mesh face: its patch index in each layer
    PartitionStats stats;
};

// Progress: stage name and fraction done in [0, 1]. Calls never overlap, but during the
// second layer they come from TBB worker threads.
using PartitionProgress = std::function<void(const char* stage, double fraction)>;

// Partitions a prepared mesh (connectivity built) into two layers of disk-shaped
// geodesic Voronoi patches; deterministic for a given mesh, options and seed, whatever
// the number of TBB threads. Throws std::invalid_argument on bad parameters: a mesh
// without connectivity or faces, n1 or n2 larger than the vertices used by faces.
Partition partitionMesh(const Mesh& mesh, const PartitionOptions& options,
                        const PartitionProgress& progress = PartitionProgress());

// Vertices per patch (border and interior together) over a list of patches.
struct PatchSizeStats {
    size_t patches = 0;
    size_t minVertices = 0, maxVertices = 0;
    double meanVertices = 0, stddevVertices = 0;
};
PatchSizeStats patchSizeStats(const std::vector<Patch>& patches);

}  // namespace vorogeo
