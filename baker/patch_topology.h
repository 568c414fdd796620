// Topology of a labelling of a mesh's faces into regions (patches): whether each region is
// a topological disk, its boundary loops, and a cut of any face set into disks.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh.h"

namespace vorogeo {

constexpr uint32_t kNoRegion = 0xFFFFFFFFu;  // a face in no region

struct RegionTopology {
    uint32_t faces = 0, vertices = 0, edges = 0;
    uint32_t components = 0;         // face-connected pieces
    uint32_t boundaryLoops = 0;      // cycles of border edges (mesh boundary edges included)
    uint32_t pinchedVertices = 0;    // vertices where two or more fans of the region's faces meet
    int64_t firstPinchedVertex = -1; // the smallest of them
    int64_t euler() const { return int64_t(vertices) - int64_t(edges) + int64_t(faces); }
    // One piece, no pinched vertex, Euler characteristic 1: a manifold surface with
    // chi = 2 - 2g - b = 1, hence genus 0 and exactly one boundary loop.
    bool isDisk() const { return faces > 0 && components == 1 && pinchedVertices == 0 && euler() == 1; }
};

// One entry per region in [0, regionCount); faces labelled kNoRegion are ignored.
// Requires built connectivity. Linear in the mesh size.
std::vector<RegionTopology> regionTopology(const Mesh& mesh, const std::vector<uint32_t>& faceRegion,
                                           uint32_t regionCount);

// The boundary loops of one region, each as the vertices it visits in walking order.
std::vector<std::vector<uint32_t>> regionBoundaryLoops(const Mesh& mesh, const std::vector<uint32_t>& faceRegion,
                                                       uint32_t region);

// Splits a set of faces into face-connected topological disks by greedy growth: from the
// smallest face left, a piece takes neighbouring faces breadth-first as long as each
// addition keeps it a disk (a face across one piece edge whose third vertex is new, or a
// face filling the notch between two piece edges). Pieces come out in order of their
// smallest face, each sorted.
std::vector<std::vector<uint32_t>> cutIntoDisks(const Mesh& mesh, const std::vector<uint32_t>& faces);

}  // namespace vorogeo
