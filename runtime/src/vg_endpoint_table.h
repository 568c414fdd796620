// The endpoint table (vorogeo.h, vg_endpoint_table_*): what a hub-label query otherwise
// works out per endpoint from ~55 inner rows, stored per vertex and per second-layer
// patch. Built once per graph into caller memory, read by any number of workspaces.
// Internal to the runtime.
#pragma once

#include "vg_graph.h"

struct vg_endpoint_table {
    const vg_graph* graph;
    // Per second-layer patch (secondCount + 1 offsets): the rows of its vertices that are
    // no node, in slot order, each the vertex's distance in label steps to every slot of
    // the patch's first-layer patch (its inner steps: what innerSteps computes).
    uint64_t* vertexRowBegin;
    uint16_t* vertexRows;
    // Per second-layer patch (secondCount + 1 offsets): per slot k of its first-layer patch
    // a column of endpointColumnStride(nodeCount) steps, entry j node j's inner row at k
    // (kNoStep for a node without one and for the padding): the meeting next to t reads
    // only the columns of the exits it kept.
    uint64_t* patchColumnBegin;
    uint16_t* patchColumns;
    // Per second-layer patch (secondCount + 1 offsets): the same vertices' entries to the
    // patch's nodes in quanta (the matrix's column of each, a cache line per node there);
    // kNoPathQuantum also for a node the labels do not reach (merged away, or without an
    // inner row), which the meeting next to t skips as it skips a missing entry.
    uint64_t* vertexEntryBegin;
    uint16_t* vertexEntries;
    // Per vertex (landmarkCount floats each; the interior ones filled, the others zeros):
    // its landmark distances in the labels' metric as a label query takes them through
    // its patch's first-layer nodes (landmarksThroughSlots).
    float* vertexLandmarks;
    // Per first-layer patch (firstCount + 1 offsets): the distances between its inner-row
    // nodes over its own second-layer graph, R x R entries (R: its inner rows), in steps
    // of the patch's nodeDistanceScale (65535: no path). Two endpoints inside one
    // first-layer patch meet through them (vg_patch_pairs.cpp). The nodes are in their
    // order of first appearance in the patch's second-layer patches, so that a
    // second-layer patch's nodes lie together in a row: per node slot of a second-layer
    // patch (slotBegin + j), nodeRank is its node's place there (kNone: merged away).
    uint64_t* nodeDistanceBegin;
    uint16_t* nodeDistances;
    float* nodeDistanceScale;
    uint32_t* nodeRank;
    // The build's scratch: one first-layer patch's hub landmark distances landmark by
    // landmark, then a vertex's distances to its slots (rows of the largest slot count,
    // padded to whole groups of 8, landmarkCount + 1 of them).
    float* scratch;
    uint32_t* nodeRows;  // ... and one second-layer patch's nodes' inner rows (its largest node count),
    void* searchScratch;         // ... the node distances' search (computeNodeDistances)
    float* nodeDistanceScratch;  // ... one first-layer patch's node distances as floats,
    uint32_t* rankScratch;       // ... and its inner rows' places, and the rows in that order
};

namespace vg {

// A patch's columns are padded to whole AVX2 vectors of 16 steps.
inline uint32_t endpointColumnStride(uint32_t nodeCount) { return (nodeCount + 15) / 16 * 16; }

// Interior vertex x's row (x on no patch border: vertexNode(g, x) == kNone).
inline const uint16_t* endpointVertexRow(const vg_graph& g, const vg_endpoint_table& table, uint32_t x) {
    const uint32_t patch = g.vertexPatch[x];
    const uint32_t K = g.first[g.second[patch].parent].slotCount;
    return table.vertexRows + table.vertexRowBegin[patch] + uint64_t(g.vertexSlot[x] - g.second[patch].nodeCount) * K;
}

// Interior vertex x's entries to its patch's nodes, in quanta (kNoPathQuantum: none).
inline const uint16_t* endpointVertexEntries(const vg_graph& g, const vg_endpoint_table& table, uint32_t x) {
    const uint32_t patch = g.vertexPatch[x];
    const uint32_t n = g.second[patch].nodeCount;
    return table.vertexEntries + table.vertexEntryBegin[patch] + uint64_t(g.vertexSlot[x] - n) * n;
}

// The largest inner-row count of a first-layer patch (0 without labels).
uint32_t largestInnerRows(const vg_graph& g);

// Fills the table's node distances (nodeDistanceBegin must be laid out): per first-layer
// patch the searches of computeNodeDistances, rounded to steps of max / 65534.
vg_status fillNodeDistances(const vg_graph& g, vg_endpoint_table& table);

}  // namespace vg
