// The searches of the hub-label stage (hub_labels.h), 16 sources at a time: a label
// block's hubs (up to kHubBlock consecutive hubs of a tree node) over the first-layer
// patches of the node's subtree, or 16 first-layer nodes of a patch over its second-layer
// node graph (its inner rows).
//
// A run per source reads, for every node it settles, that node's rows of its patches'
// matrices; the runs of neighbouring sources (a block's hubs lie along one separator)
// settle nearly the same nodes in nearly the same order, so each row came from memory
// once per source. Here a node holds a vector of 16 distances (lane i: from source i),
// and a row read once lowers all lanes. The search is label-correcting: a node is taken from the
// queue by the smallest of its lanes lowered since it last relaxed, and relaxes those
// lanes (a lane may be lowered again after it relaxed, and then relaxes again). It ends
// at the shortest distances over the subtree's patches, as separate Dijkstra runs do.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "quad_heap.h"

namespace vorogeo {

// A graph of patch matrices as the block runs read it: the first-layer overlay for the
// labels (every first-layer matrix unpacked, nodes renumbered to the overlay's own), or a
// first-layer patch's second-layer node graph for its inner rows.
struct LabelOverlay {
    uint32_t noPath = 0;                  // the quantum that means "no path"
    std::vector<uint64_t> quantaBegin;    // patches + 1 offsets into quanta
    std::vector<uint16_t> quanta;         // per patch its slot x slot matrix
    std::vector<double> scale;            // per patch: distance per quantum
    std::vector<uint32_t> slotBegin;      // patches + 1 offsets into slotNode
    std::vector<uint32_t> slotNode;       // per slot: its overlay node (UINT32_MAX: none, skipped)
    std::vector<uint32_t> memberBegin;    // nodes + 1 offsets into members
    std::vector<std::pair<uint32_t, uint32_t>> members;  // per node: its rows (patch, slot)
    std::vector<uint32_t> patchLeaf;      // per patch: its leaf tree node (tree in preorder), or 0
    // Per patch, 1 where closePatchMatrix closed its matrix (empty: none): a run then never
    // reads a node's row there for the lanes that reached the node through that very row's
    // slot (BlockRuns::search: why that gives the same distances).
    std::vector<uint8_t> closed;
};

// Closes patch p's matrix under the triangle inequality, in whole quanta and through slots
// that have a node (entry i, j: the shortest chain of entries inside the patch), and marks
// it in o.closed (sized to the patches by the caller, so that patches may be closed in
// parallel) if no entry between two slots with nodes is "no path"; else leaves it as it
// is. The overlay's shortest paths are unchanged: every new entry is the length of a
// chain the graph has (in the double sums of a run, exactly so where run's check holds).
// avx2: use AVX2 where the processor has it (the same entries either way).
void closePatchMatrix(LabelOverlay& o, uint32_t p, bool avx2 = true);

// Scratch of one thread's block runs.
class BlockRuns {
public:
    static constexpr uint32_t kLanes = 16;  // = kHubBlock

    // Distances from sources[0, count) (nodes, count <= kLanes; lane i from sources[i]) to
    // every node over the patches whose leaf lies in [leafBegin, leafEnd) (a subtree: a
    // range of tree nodes in preorder). avx2: use AVX2 where the
    // processor has it (the same numbers either way).
    void run(const LabelOverlay& o, const uint32_t* sources, uint32_t count, uint32_t leafBegin, uint32_t leafEnd,
             bool avx2 = true);
    // Node n's lanes after run (+inf: not reached).
    const double* distances(uint32_t n) const { return dist_.data() + uint64_t(n) * kLanes; }
    // What the last run did: the matrix rows it read, and whether it skipped rows of closed
    // patches (false: none closed, or its sums were not all exact and it searched again).
    uint64_t rowsRead() const { return rowsRead_; }
    bool skippedRows() const { return skippedRows_; }

private:
    // Lowers node's lanes to `lanes` where those are smaller, their way in through global
    // slot `via` (kNoSlot: a source).
    void lower(uint32_t node, const double* lanes, uint32_t via);
    // The search itself; skipClosed: skip the rows of closed patches as run describes.
    void search(const LabelOverlay& o, const uint32_t* sources, uint32_t count, uint32_t leafBegin, uint32_t leafEnd,
                bool useAvx2, bool skipClosed);
    std::vector<double> dist_;       // overlay nodes x kLanes
    std::vector<uint32_t> via_;      // overlay nodes x kLanes: the global slot of each lane's last lowering
    double largest_ = 0;             // the largest distance assigned in this search
    uint64_t rowsRead_ = 0;
    bool skippedRows_ = false;
    // Per node and lane a float at least its distance (upperBound in the .cpp): a row's
    // columns are screened against these, a cache line per node instead of dist_'s two,
    // and only the columns that pass read dist_.
    std::vector<float> nearStorage_;
    float* near_ = nullptr;          // nearStorage_ from its first 64-byte boundary
    std::vector<uint16_t> pending_;  // per node: lanes lowered since it last relaxed
    std::vector<uint8_t> reached_;   // per node: some lane finite (then in touched_)
    std::vector<uint32_t> touched_;  // nodes with a finite lane, reset at the next run
    std::vector<uint32_t> hitColumn_;  // a row's columns that lower some lane
    // The queue: nodes with pending lanes, by their smallest pending lane (then node id),
    // one entry per node, its key lowered in place.
    void push(uint32_t node, double key);
    bool before(uint32_t a, uint32_t b) const { return key_[a] < key_[b] || (key_[a] == key_[b] && a < b); }
    std::vector<double> key_;
    QuadHeap queue_;
};

}  // namespace vorogeo
