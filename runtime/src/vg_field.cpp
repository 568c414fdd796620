// Multi-source all-destinations distances (thesis 3.7.2): one Dijkstra over the second
// layer everywhere (every patch must be reached, so the overlay saves nothing), then every
// other vertex takes the best of its patch's settled nodes plus the stored entry.
#include "vg_query.h"
#include "vg_search.h"

namespace {

using namespace vg;

// Vertices of one patch that are not active nodes: best over its settled active nodes.
void fillPatch(const vg_graph& g, const Patch& p, const Frontier& f, vg_workspace& ws, float* out) {
    const uint32_t* slots = g.slots + p.slotBegin;
    uint32_t reached = 0;
    for (uint32_t i = 0; i < p.nodeCount; ++i) {
        const uint32_t n = slots[i];
        if (nodeActive(g, n) && f.labelled(n)) {
            ws.patchNodeSlot[reached] = i;
            ws.patchNodeDistance[reached] = f.dist[n];
            ++reached;
        }
    }
    for (uint32_t r = 0; r < reached; ++r) {
        const uint32_t i = ws.patchNodeSlot[r];
        const float base = ws.patchNodeDistance[r];
        const uint64_t row = rowStart(p, i) - (i + 1);
        // Merged-away nodes (slots before the interior ones) take the node rows as well.
        for (uint32_t j = 0; j < p.nodeCount; ++j) {
            const uint32_t n = slots[j];
            if (nodeActive(g, n)) continue;
            const float d = base + entry(p, g.secondDistances, i, j);
            float& o = out[g.nodeVertex[n]];
            if (d < o) o = d;
        }
        for (uint32_t j = p.nodeCount; j < p.slotCount; ++j) {
            const uint32_t q = quantum(g.secondDistances, row + j);
            if (q == kNoPathQuantum) continue;
            const float d = base + float(q) * p.scale;
            float& o = out[slots[j]];
            if (d < o) o = d;
        }
    }
}

}  // namespace

extern "C" vg_status vg_distance_field(const vg_graph* graph, vg_workspace* workspace, const uint32_t* sources,
                                       size_t source_count, float* out_distances) {
    const vg_status st = vg::checkQuery(graph, workspace, out_distances);
    if (st != VG_OK) return st;
    if (source_count > 0 && sources == nullptr) return VG_ERR_INVALID_ARGUMENT;
    const vg_graph& g = *graph;
    for (size_t i = 0; i < source_count; ++i)
        if (sources[i] >= g.vertexCount) return VG_ERR_INVALID_VERTEX;

    vg_workspace& ws = *workspace;
    const uint32_t gen = beginQuery(ws);
    const float inf = __builtin_inff();
    for (uint32_t v = 0; v < g.vertexCount; ++v) out_distances[v] = inf;

    Frontier& F = ws.forward;
    const Scope everywhere{ws.detail, gen, true};
    auto key = [](uint32_t, float dv) { return dv; };
    auto none = [](uint32_t, float) {};
    for (size_t i = 0; i < source_count; ++i)
        if (g.vertexPatch[sources[i]] != kNone) seedEndpoint(g, sources[i], 0.0f, F, key, none);
    while (!F.empty()) {
        const uint32_t u = F.pop().node;
        relaxNode(g, u, F.dist[u], everywhere, F, key, none);
    }

    for (uint32_t n = 0; n < g.nodeCount; ++n)
        if (nodeActive(g, n) && F.labelled(n)) out_distances[g.nodeVertex[n]] = F.dist[n];
    for (uint32_t p = 0; p < g.secondCount; ++p) fillPatch(g, g.second[p], F, ws, out_distances);
    // A source's own patches also hold the direct entries: paths that touch no node.
    for (size_t i = 0; i < source_count; ++i) {
        const uint32_t s = sources[i];
        if (g.vertexPatch[s] != kNone) {
            forEachPatchOf(g, s, [&](uint32_t patch, uint32_t slot) {
                const Patch& p = g.second[patch];
                for (uint32_t j = 0; j < p.slotCount; ++j) {
                    const uint32_t id = g.slots[p.slotBegin + j];
                    const uint32_t v = j < p.nodeCount ? g.nodeVertex[id] : id;
                    const float d = entry(p, g.secondDistances, slot, j);
                    if (d < out_distances[v]) out_distances[v] = d;
                }
            });
        }
        out_distances[s] = 0.0f;
    }
    return VG_OK;
}
