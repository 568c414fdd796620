// Graph pruning (thesis 3.5-3.6, Algorithm 2): merges pairs of neighbouring graph nodes
// whose rows of distances are nearly the same into one "average node", so that the query
// search has fewer nodes and edges.
//
// A layer's graph has one node per shared patch vertex and, inside every patch, an edge
// between every two of its nodes (weights: the patch matrix). A pair (u, v) is eligible
// when u and v are joined by a mesh edge, each lies in at most two patches of the layer,
// and both lie in the same patches. Its error is the mean, over the other active nodes k of
// those patches, of |w(u,k) - w(v,k)|. Pairs are taken smallest error first (errors are
// recomputed when taken, since earlier merges change rows); while the error is below
// delta, v is merged into u: u's weights to every other node become the mean of u's and
// v's (infinite if either is), v becomes inactive, and u inherits v's neighbours as new
// candidate pairs.
//
// Unlike the thesis, the merged node keeps its exact weight to the node it absorbed, and the
// absorbed node keeps its own exact row: the graph search never enters an inactive node,
// but a query that starts or ends at one still uses its exact row (as for an interior
// vertex), so lookups between two vertices of one patch never return a merged value 0.
//
// Deterministic: ties are broken by node vertex ids; single-threaded (milliseconds).
#pragma once

#include <cstdint>
#include <vector>

#include "mesh.h"
#include "patch_geodesics.h"

namespace vorogeo {

struct PruneStats {
    uint64_t nodes = 0, prunedNodes = 0;  // nodes of the layer graph, and how many were merged away
    uint64_t edges = 0, prunedEdges = 0;  // node-node entries of all patches, before and removed
};

// Prunes one layer in place. `inactive` (per mesh vertex) gets 1 for every merged-away node.
// When `compact` is set (first layer: its matrices serve only the graph), merged-away nodes
// are removed from the matrices; otherwise (second layer: its matrices also answer lookups)
// they stay, with their exact rows.
PruneStats pruneLayer(const Mesh& mesh, std::vector<PatchMatrix>& layer, double delta, bool compact,
                      std::vector<uint8_t>& inactive);

}  // namespace vorogeo
