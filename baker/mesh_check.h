// Defect detection on a triangle soup (Mesh positions + faces, no connectivity needed).
// Shared by validation (which reports) and repair (which fixes what it finds).
#pragma once

#include <cstdint>
#include <vector>

#include "mesh.h"

namespace vorogeo {

// Counts and first offenders (lowest index; -1 if none) of every defect validation knows.
// The edge and vertex checks look only at faces that are neither degenerate nor
// duplicates, so that their counts describe what repair would still have to split.
struct MeshDefects {
    uint64_t outOfRangeFaces = 0;   // faces with an index >= vertex count
    int64_t firstOutOfRangeFace = -1;
    uint64_t badIndex = 0;          // the offending index of that first face
    uint64_t nonFiniteVertices = 0; // NaN or Inf coordinate
    int64_t firstNonFiniteVertex = -1;
    uint64_t degenerateFaces = 0;   // repeated index or exactly zero area
    int64_t firstDegenerateFace = -1;
    uint64_t duplicateFaces = 0;    // same vertex set as an earlier face (either orientation)
    int64_t firstDuplicateFace = -1;
    uint64_t misorientedEdges = 0;  // two faces, both traversing the edge in the same direction
    uint32_t firstMisorientedEdge[2] = {0, 0};
    uint64_t nonManifoldEdges = 0;  // more than two faces
    uint32_t firstNonManifoldEdge[2] = {0, 0};
    uint64_t nonManifoldVertices = 0;  // faces around the vertex form more than one edge-connected fan
    int64_t firstNonManifoldVertex = -1;
    uint64_t unreferencedVertices = 0;  // used by no face: allowed, they are isolated vertices

    // True when nothing prevents buildConnectivity (unreferenced vertices are fine).
    bool clean() const {
        return !outOfRangeFaces && !nonFiniteVertices && !degenerateFaces && !duplicateFaces &&
               !misorientedEdges && !nonManifoldEdges && !nonManifoldVertices;
    }
};

// Runs every check. Out-of-range indices stop the checks that would dereference them.
MeshDefects checkMesh(const Mesh& mesh);

// Per-face flags (1 = affected), for repair.
std::vector<uint8_t> degenerateFaces(const Mesh& mesh);
// Faces repeating the vertex set of a lower-numbered face; faces flagged in `ignore` take no part.
std::vector<uint8_t> duplicateFaces(const Mesh& mesh, const std::vector<uint8_t>& ignore);

// Half-edges of the live faces grouped by undirected edge: group g holds
// halfedges[start[g] .. start[g+1]), sorted by half-edge index.
struct EdgeGroups {
    std::vector<int32_t> halfedges;
    std::vector<uint32_t> start;
    uint32_t count() const { return uint32_t(start.size() - 1); }
};
EdgeGroups groupEdges(const Mesh& mesh, const std::vector<uint8_t>& ignore);

// Union-find over face corners (corner 3f+k is faces[f][k]).
class CornerSets {
public:
    explicit CornerSets(size_t corners) : parent_(corners) {
        for (size_t i = 0; i < corners; ++i) parent_[i] = uint32_t(i);
    }
    uint32_t find(uint32_t c) {
        while (parent_[c] != c) c = parent_[c] = parent_[parent_[c]];
        return c;
    }
    // Keeps the lower corner as root so that results do not depend on union order.
    void unite(uint32_t a, uint32_t b) {
        a = find(a);
        b = find(b);
        if (a == b) return;
        if (a < b) parent_[b] = a;
        else parent_[a] = b;
    }

private:
    std::vector<uint32_t> parent_;
};

// The corner of half-edge h's face that sits at vertex v (v must be an end of h).
inline uint32_t cornerAt(const Mesh& mesh, int32_t h, uint32_t v) {
    return uint32_t(mesh.tail(h) == v ? h : Mesh::next(h));
}

}  // namespace vorogeo
