// The graph search shared by every query (thesis 3.7). Nodes are the second-layer border
// vertices. Settling node u relaxes
//   * inside every second-layer patch of u whose first-layer patch is "detailed" (holds
//     an endpoint of the query): the patch matrix row of u, to every active node;
//   * elsewhere: u's first-layer overlay rows (node x node shortest paths across a whole
//     first-layer patch), so a search crosses a far first-layer patch in one step.
// A query endpoint that is not an active node enters the graph through its patch rows.
#pragma once

#include "vg_workspace.h"

namespace vg {

// Which first-layer patches a direction searches through their second layer.
struct Scope {
    const uint32_t* detail;  // per first-layer patch: == generation when detailed
    uint32_t generation;
    bool everywhere;         // one-to-all: second layer everywhere, no overlay

    bool detailed(uint32_t firstPatch) const { return everywhere || detail[firstPatch] == generation; }
};

// Relaxes row `i` of patch `p` (its node columns) from a node at distance du.
// keyOf(v, dv) gives v's queue key; onImprove(v, dv) runs after v's label dropped to dv.
template <class KeyOf, class OnImprove>
inline void relaxRow(const vg_graph& g, const Patch& p, const uint8_t* packed, bool skipMerged, uint32_t i,
                     float du, Frontier& f, KeyOf&& keyOf, OnImprove&& onImprove) {
    const uint32_t* slots = g.slots + p.slotBegin;
    auto visit = [&](uint32_t j, uint64_t k) {
        const uint32_t q = quantum(packed, k);
        if (q == kNoPathQuantum) return;
        const uint32_t v = slots[j];
        if (skipMerged && !nodeActive(g, v)) return;
        const float dv = du + float(q) * p.scale;
        if (f.labelled(v) && !(dv < f.dist[v])) return;
        f.improve(v, dv, keyOf(v, dv));
        onImprove(v, dv);
    };
    const uint32_t before = i < p.nodeCount ? i : p.nodeCount;  // an endpoint's slot may follow the nodes
    for (uint32_t j = 0; j < before; ++j) visit(j, rowStart(p, j) + (i - j - 1));
    const uint64_t row = rowStart(p, i) - (i + 1);
    for (uint32_t j = i + 1; j < p.nodeCount; ++j) visit(j, row + j);
}

// Relaxes every edge of node u (label du) allowed by the scope.
template <class KeyOf, class OnImprove>
inline void relaxNode(const vg_graph& g, uint32_t u, float du, const Scope& scope, Frontier& f, KeyOf&& keyOf,
                      OnImprove&& onImprove) {
    for (uint32_t m = g.nodeSecondBegin[u]; m < g.nodeSecondBegin[u + 1]; ++m) {
        const Patch& p = g.second[g.nodeSecond[m].patch];
        if (scope.detailed(p.parent))
            relaxRow(g, p, g.secondDistances, true, g.nodeSecond[m].slot, du, f, keyOf, onImprove);
    }
    if (scope.everywhere) return;
    for (uint32_t m = g.nodeFirstBegin[u]; m < g.nodeFirstBegin[u + 1]; ++m) {
        if (scope.detailed(g.nodeFirst[m].patch)) continue;
        const Patch& p = g.first[g.nodeFirst[m].patch];
        relaxRow(g, p, g.firstDistances, false, g.nodeFirst[m].slot, du, f, keyOf, onImprove);
    }
}

// Marks the first-layer patches around vertex x as detailed for a direction.
inline void detailAround(const vg_graph& g, uint32_t x, uint32_t* detail, uint32_t generation) {
    forEachPatchOf(g, x, [&](uint32_t patch, uint32_t) { detail[g.second[patch].parent] = generation; });
}

// Gives the search its start labels for endpoint x at distance `offset`: an active node
// starts at itself; any other vertex at the active nodes of its patches.
template <class KeyOf, class OnImprove>
inline void seedEndpoint(const vg_graph& g, uint32_t x, float offset, Frontier& f, KeyOf&& keyOf,
                         OnImprove&& onImprove) {
    const uint32_t node = vertexNode(g, x);
    if (node != kNone && nodeActive(g, node)) {
        if (f.labelled(node) && !(offset < f.dist[node])) return;
        f.improve(node, offset, keyOf(node, offset));
        onImprove(node, offset);
        return;
    }
    forEachPatchOf(g, x, [&](uint32_t patch, uint32_t slot) {
        const Patch& p = g.second[patch];
        relaxRow(g, p, g.secondDistances, true, slot, offset, f, keyOf, onImprove);
    });
}

}  // namespace vg
