// vg_endpoint_table_size / _build / vg_workspace_use_endpoint_table: the optional table of
// the label queries' per-endpoint steps (vg_endpoint_table.h). The layout is measured and
// carved by the same calls, so that the size query and the build cannot disagree.
#include <string.h>

#include "vg_endpoint_table.h"
#include "vg_huge_pages.h"
#include "vg_hub_labels.h"
#include "vg_layout.h"
#include "vg_workspace.h"

namespace {

using namespace vg;

constexpr size_t kAlign = 64;

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
    uint64_t largest = 0;
    for (uint32_t f = 0; f < g.firstCount; ++f) largest = g.first[f].slotCount > largest ? g.first[f].slotCount : largest;
    float* scratch = L.take<float>((largest + 8) * (uint64_t(g.landmarkCount) + 1));
    uint64_t nodes = 0;
    for (uint32_t q = 0; q < g.secondCount; ++q) nodes = g.second[q].nodeCount > nodes ? g.second[q].nodeCount : nodes;
    uint32_t* nodeRows = L.take<uint32_t>(nodes);
    if (t != nullptr)
        *t = vg_endpoint_table{&g, rowBegin, vertexRows, columnBegin, patchColumns, entryBegin, vertexEntries, vertexLandmarks,
                               scratch, nodeRows};
    return t;
}

size_t tableBytes(const vg_graph& g) {
    Layout L{nullptr, kAlign};
    layOut(g, L);
    return L.used + kAlign - 1;  // the start is aligned within the memory given
}

}  // namespace

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
    *out_table = table;
    return VG_OK;
}

extern "C" vg_status vg_workspace_use_endpoint_table(vg_workspace* workspace, const vg_endpoint_table* table) {
    if (workspace == nullptr) return VG_ERR_INVALID_ARGUMENT;
    if (table != nullptr && table->graph != workspace->graph) return VG_ERR_WRONG_WORKSPACE;
    workspace->endpointTable = table;
    return VG_OK;
}
