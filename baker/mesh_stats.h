// Descriptive statistics of a prepared mesh (one that passed prepareMesh/loadMesh,
// so that its connectivity is built): topology, size, edge lengths, curvature sign.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh.h"

namespace vorogeo {

struct ComponentStats {
    uint64_t vertices = 0, faces = 0, edges = 0, boundaryLoops = 0;
    int64_t euler = 0, genus = 0;
};

// A saddle whose angle sum is below 2*pi * (1 + this) counts as near-flat.
constexpr double kNearFlatSaddleExcess = 1e-3;

struct MeshStats {
    uint64_t vertices = 0;          // all vertices, isolated ones included
    uint64_t faces = 0;
    uint64_t edges = 0;             // undirected edges
    uint64_t boundaryEdges = 0;
    uint64_t boundaryLoops = 0;
    uint64_t components = 0;        // face-connected components
    uint64_t isolatedVertices = 0;  // vertices used by no face (not counted as components)
    int64_t euler = 0;              // V - E + F over the vertices used by faces
    int64_t genus = 0;              // sum over components of (2 - chi - boundary loops) / 2
    Vec3 bboxMin, bboxMax;          // over all vertices
    double bboxDiag = 0;
    double edgeLenMin = 0, edgeLenMean = 0, edgeLenMax = 0;  // over undirected edges
    uint64_t interiorVertices = 0;  // used by faces and not on a boundary
    uint64_t saddleVertices = 0;    // interior vertices with angle sum > 2*pi (negative curvature)
    double saddleRatio = 0;         // saddleVertices / interiorVertices (0 if none)
    // Saddles whose angle excess is below kNearFlatSaddleExcess of 2*pi: each casts a thin
    // shadow that the exact engine must cover with windows of its own, so their share
    // predicts its cost (armadillo-50k 11% of saddles, igea 83%: BENCHMARKS.md).
    uint64_t nearFlatSaddleVertices = 0;
    double nearFlatSaddleRatio = 0;  // nearFlatSaddleVertices / interiorVertices (0 if none)
    double area = 0;
    std::vector<ComponentStats> componentList;
};

// Requires built connectivity (throws std::invalid_argument otherwise).
MeshStats computeStats(const Mesh& mesh);

// Marks isolated vertices in vertexComponents().
constexpr uint32_t kNoComponent = 0xFFFFFFFFu;

// Face-connected component id (0, 1, ... in order of the lowest face) of every vertex;
// kNoComponent for isolated vertices. `faceComponent`, if given, receives the id per face.
std::vector<uint32_t> vertexComponents(const Mesh& mesh, std::vector<uint32_t>* faceComponent = nullptr);

struct BoundaryLoops {
    // Each loop as its boundary half-edges in walking order (the mesh lies to their left).
    std::vector<std::vector<int32_t>> loops;
    // Per vertex: index of the loop it lies on, or -1 (interior or isolated).
    std::vector<int32_t> vertexLoop;
};
BoundaryLoops boundaryLoops(const Mesh& mesh);

// 1 for every vertex on a hole's (boundary loop's) rim, else 0.
std::vector<uint8_t> holeAdjacentVertices(const Mesh& mesh);

}  // namespace vorogeo
