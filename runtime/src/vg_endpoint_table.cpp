// vg_endpoint_table_size / _build / vg_workspace_use_endpoint_table: the optional table of
// the label queries' per-endpoint steps (vg_endpoint_table.h). The layout is measured and
// carved by the same calls, so that the size query and the build cannot disagree.
#include <string.h>

#include "vg_endpoint_table.h"
#include "vg_huge_pages.h"
#include "vg_hub_labels.h"
#include "vg_inner_rows.h"
#include "vg_layout.h"
#include "vg_workspace.h"

namespace {

using namespace vg;

constexpr size_t kAlign = 64;

// The node distances' rows of first-layer patch f: its inner rows, or none where its
// search would not fit the fixed scratch (a blob that stores its inner rows may have such
// patches; their pairs are searched).
uint64_t nodeDistanceRows(const vg_graph& g, uint32_t f) {
    return searchFits(g, f) ? g.hubInnerBegin[f + 1] - g.hubInnerBegin[f] : 0;
}

// Carves the table's arrays from L (L.base null: only measures); the header first.
vg_endpoint_table* layOut(const vg_graph& g, Layout& L) {
    vg_endpoint_table* t = L.take<vg_endpoint_table>(1);
    uint64_t rows = 0, columns = 0, entries = 0;
    for (uint32_t q = 0; q < g.secondCount; ++q) {
        const Patch& p = g.second[q];
        const uint64_t K = g.first[p.parent].slotCount;
        rows += uint64_t(p.slotCount - p.nodeCount) * K;
        columns += uint64_t(endpointColumnStride(p.nodeCount)) * K;
        entries += uint64_t(p.slotCount - p.nodeCount) * p.nodeCount;
    }
    uint64_t* rowBegin = L.take<uint64_t>(uint64_t(g.secondCount) + 1);
    uint16_t* vertexRows = L.take<uint16_t>(rows);
    uint64_t* columnBegin = L.take<uint64_t>(uint64_t(g.secondCount) + 1);
    uint16_t* patchColumns = L.take<uint16_t>(columns);
    uint64_t* entryBegin = L.take<uint64_t>(uint64_t(g.secondCount) + 1);
    uint16_t* vertexEntries = L.take<uint16_t>(entries);
    float* vertexLandmarks = L.take<float>(uint64_t(g.vertexCount) * g.landmarkCount);
    uint64_t nodeDistanceCount = 0, largestMatrix = 0;
    for (uint32_t f = 0; f < g.firstCount; ++f) {
        const uint64_t R = nodeDistanceRows(g, f);
        nodeDistanceCount += R * R;
        largestMatrix = R * R > largestMatrix ? R * R : largestMatrix;
    }
    uint64_t* nodeDistanceBegin = L.take<uint64_t>(uint64_t(g.firstCount) + 1);
    // (+2: the pair kernel reads a 32-bit word at each entry, vg_patch_pairs.cpp)
    uint16_t* nodeDistances = L.take<uint16_t>(nodeDistanceCount + 2);
    float* nodeDistanceScale = L.take<float>(g.firstCount);
    uint64_t nodeSlotEnd = 0;
    for (uint32_t q = 0; q < g.secondCount; ++q) {
        const uint64_t end = uint64_t(g.second[q].slotBegin) + g.second[q].nodeCount;
        nodeSlotEnd = end > nodeSlotEnd ? end : nodeSlotEnd;
    }
    uint32_t* nodeRank = L.take<uint32_t>(nodeSlotEnd);
    float* scratch = L.take<float>((largestFirstPatch(g) + 8) * (uint64_t(g.landmarkCount) + 1));
    uint32_t* nodeRows = L.take<uint32_t>(largestSecondPatchNodes(g));
    void* searchScratch = L.take<unsigned char>(innerRowsScratchSize());
    float* nodeDistanceScratch = L.take<float>(largestMatrix);
    uint32_t* rankScratch = L.take<uint32_t>(2 * uint64_t(largestInnerRows(g)));  // places, then their inverse
    if (t != nullptr) {
        *t = vg_endpoint_table{&g, rowBegin, vertexRows, columnBegin, patchColumns, entryBegin, vertexEntries, vertexLandmarks,
                               nodeDistanceBegin, nodeDistances, nodeDistanceScale, nodeRank, scratch, nodeRows,
                               searchScratch, nodeDistanceScratch, rankScratch};
        nodeDistanceBegin[0] = 0;
        for (uint32_t f = 0; f < g.firstCount; ++f) {
            const uint64_t R = nodeDistanceRows(g, f);
            nodeDistanceBegin[f + 1] = nodeDistanceBegin[f] + R * R;
        }
    }
    return t;
}

size_t tableBytes(const vg_graph& g) {
    Layout L{nullptr, kAlign};
    layOut(g, L);
    return L.used + kAlign - 1;  // the start is aligned within the memory given
}

}  // namespace

namespace vg {

uint32_t largestInnerRows(const vg_graph& g) {
    uint32_t largest = 0;
    for (uint32_t f = 0; g.hubTreeCount && f < g.firstCount; ++f) {
        const uint32_t R = g.hubInnerBegin[f + 1] - g.hubInnerBegin[f];
        largest = R > largest ? R : largest;
    }
    return largest;
}

// Places first-layer patch f's inner rows in the order its second-layer patches first
// hold them (table.rankScratch by inner row, table.nodeRank by node slot).
void rankNodes(const vg_graph& g, uint32_t f, vg_endpoint_table& table) {
    const uint32_t* rowNode = g.hubInnerNode + g.hubInnerBegin[f];
    const uint32_t R = g.hubInnerBegin[f + 1] - g.hubInnerBegin[f];
    uint32_t* rank = table.rankScratch;
    for (uint32_t r = 0; r < R; ++r) rank[r] = kNone;
    uint32_t next = 0;
    for (uint32_t q = 0; q < g.secondCount; ++q) {
        const Patch& p = g.second[q];
        if (p.parent != f) continue;
        for (uint32_t j = 0; j < p.nodeCount; ++j) {
            const uint32_t n = g.slots[p.slotBegin + j];
            const uint32_t r = nodeActive(g, n) ? sortedIndex(rowNode, R, n) : kNone;
            if (r != kNone && rank[r] == kNone) rank[r] = next++;
            table.nodeRank[p.slotBegin + j] = r == kNone ? kNone : rank[r];
        }
    }
    for (uint32_t r = 0; r < R; ++r)
        if (rank[r] == kNone) rank[r] = next++;  // a row no node slot holds (none in any blob seen)
}

vg_status fillNodeDistances(const vg_graph& g, vg_endpoint_table& table) {
    constexpr uint32_t kTopStep = 65534, kNoPathStep = 65535;
    for (uint32_t f = 0; f < g.firstCount; ++f) {
        const uint64_t R = table.nodeDistanceBegin[f + 1] - table.nodeDistanceBegin[f] == 0 ? 0
                           : g.hubInnerBegin[f + 1] - g.hubInnerBegin[f];
        table.nodeDistanceScale[f] = 1.0f;
        if (R == 0) continue;  // none kept (nodeDistanceRows)
        rankNodes(g, f, table);
        const uint32_t* rank = table.rankScratch;
        uint32_t* order = table.rankScratch + R;  // the inner rows by place: a patch's nodes together
        for (uint32_t r = 0; r < R; ++r) order[rank[r]] = r;
        float* d = table.nodeDistanceScratch;
        const vg_status st = computeNodeDistances(g, f, g.avx2, table.searchScratch, order, d);
        if (st != VG_OK) return st;
        // The patch's own step, from its longest distance: a pair inside one first-layer
        // patch is short, and steps of the labels' scale (which spans the whole mesh) would
        // be a coarse share of it.
        float longest = 0.0f;
        for (uint64_t e = 0; e < R * R; ++e) longest = d[e] != __builtin_inff() && d[e] > longest ? d[e] : longest;
        const float scale = longest > 0.0f ? longest / float(kTopStep) : 1.0f;
        table.nodeDistanceScale[f] = scale;
        uint16_t* out = table.nodeDistances + table.nodeDistanceBegin[f];
        for (uint64_t a = 0; a < R; ++a)
            for (uint64_t b = 0; b < R; ++b) {
                const float x = d[a * R + b];
                const float steps = __builtin_floorf(x / scale + 0.5f);
                out[uint64_t(rank[a]) * R + rank[b]] =
                    x == __builtin_inff() ? uint16_t(kNoPathStep) : uint16_t(steps < float(kTopStep) ? steps : float(kTopStep));
            }
    }
    return VG_OK;
}

}  // namespace vg

extern "C" size_t vg_endpoint_table_size(const vg_graph* graph) {
    if (graph == nullptr || graph->hubTreeCount == 0) return 0;
    return tableBytes(*graph);
}

extern "C" vg_status vg_endpoint_table_build(const vg_graph* graph, void* memory, size_t memory_size,
                                             const vg_endpoint_table** out_table) {
    if (out_table == nullptr) return VG_ERR_INVALID_ARGUMENT;
    *out_table = nullptr;
    if (graph == nullptr || memory == nullptr) return VG_ERR_INVALID_ARGUMENT;
    if (graph->hubTreeCount == 0) return VG_ERR_NO_HUB_LABELS;
    if (memory_size < tableBytes(*graph)) return VG_ERR_BUFFER_TOO_SMALL;
    vg::adviseHugePages(memory, memory_size);  // before the first write (vg_huge_pages.h)
    unsigned char* base = reinterpret_cast<unsigned char*>(
        (reinterpret_cast<uintptr_t>(memory) + kAlign - 1) & ~uintptr_t(kAlign - 1));
    // Every byte written once: the parts no vertex fills are defined (zeros), and no query
    // pays for a page's first touch.
    memset(base, 0, tableBytes(*graph) - (kAlign - 1));
    Layout L{base, kAlign};
    vg_endpoint_table* table = layOut(*graph, L);
    fillEndpointTable(*graph, *table);
    const vg_status st = fillNodeDistances(*graph, *table);
    if (st != VG_OK) return st;
    *out_table = table;
    return VG_OK;
}

extern "C" vg_status vg_workspace_use_endpoint_table(vg_workspace* workspace, const vg_endpoint_table* table) {
    if (workspace == nullptr) return VG_ERR_INVALID_ARGUMENT;
    if (table != nullptr && table->graph != workspace->graph) return VG_ERR_WRONG_WORKSPACE;
    workspace->endpointTable = table;
    return VG_OK;
}
