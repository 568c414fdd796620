// The graph search of the point-to-point and nearest queries (thesis 3.7; one-to-all takes
// only its seeding from here and searches a patch at a time, vg_field.cpp). Nodes are the
// second-layer border vertices. Settling node u relaxes
//   * inside every second-layer patch of u whose first-layer patch is "detailed" (holds
//     an endpoint of the query): the patch matrix row of u, to every active node;
//   * elsewhere: u's first-layer overlay rows (node x node shortest paths across a whole
//     first-layer patch), so a search crosses a far first-layer patch in one step.
// A query endpoint that is not an active node enters the graph through its patch rows.
#pragma once

#include "vg_point.h"
#include "vg_workspace.h"

namespace vg {

// Which first-layer patches a direction searches through their second layer.
struct Scope {
    const uint32_t* detail;  // per first-layer patch: == generation when detailed
    uint32_t generation;

    bool detailed(uint32_t firstPatch) const { return detail[firstPatch] == generation; }
};

// Relaxes row `i` of second-layer patch `patch` (its active node columns) from distance
// du of node `parent` (kNone for an endpoint). keyOf(v, dv) gives v's queue key, +inf to leave v alone (it cannot improve the
// answer); onImprove(v, dv) runs after v's label dropped to dv.
template <class KeyOf, class OnImprove>
inline void relaxSecondRow(const vg_graph& g, uint32_t patch, uint32_t i, float du, uint32_t origin, uint32_t parent,
                           Frontier& f, KeyOf&& keyOf, OnImprove&& onImprove) {
    const Patch& p = g.second[patch];
    const uint32_t* slots = g.slots + p.slotBegin;
    const uint8_t* packed = g.secondDistances;
    auto visit = [&](uint32_t j, uint64_t k) {
        const uint32_t q = quantum(packed, k);
        if (q == kNoPathQuantum) return;
        const uint32_t v = slots[j];
        if (!nodeActive(g, v)) return;
        const float dv = du + float(q) * p.scale;
        if (!f.better(v, dv)) return;
        const float key = keyOf(v, dv);
        if (key == __builtin_inff()) return;
        f.improve(v, dv, key, patch, origin, parent);
        onImprove(v, dv);
    };
    if (i < p.nodeCount) {  // a node: its own row, whole
        const uint64_t row = nodeRowStart(p, i);
        for (uint32_t j = 0; j < p.nodeCount; ++j)
            if (j != i) visit(j, row + j);
    } else {  // an endpoint's slot after the nodes: its column of the node x other block
        const uint64_t stride = p.slotCount - p.nodeCount;
        uint64_t k = interiorRowStart(p, 0) + (i - p.nodeCount);
        for (uint32_t j = 0; j < p.nodeCount; ++j, k += stride) visit(j, k);
    }
}

// Relaxes row `i` of first-layer patch `patch` (stored whole, so the row is contiguous).
template <class KeyOf, class OnImprove>
inline void relaxFirstRow(const vg_graph& g, uint32_t patch, uint32_t i, float du, uint32_t origin, uint32_t parent,
                          Frontier& f, KeyOf&& keyOf, OnImprove&& onImprove) {
    const Patch& p = g.first[patch];
    const uint32_t* slots = g.slots + p.slotBegin;
    const uint64_t row = p.matrixBegin + uint64_t(i) * p.slotCount;
    for (uint32_t j = 0; j < p.slotCount; ++j) {
        const uint32_t q = quantum(g.firstDistances, row + j);
        if (q == kNoPathQuantum || j == i) continue;
        const uint32_t v = slots[j];
        const float dv = du + float(q) * p.scale;
        if (!f.better(v, dv)) continue;
        const float key = keyOf(v, dv);
        if (key == __builtin_inff()) continue;
        f.improve(v, dv, key, patch | kFirstLayerBit, origin, parent);
        onImprove(v, dv);
    }
}

// Relaxes every edge of node u (label du) allowed by the scope, except the row of the
// patch that labelled u: a patch matrix holds shortest paths inside the patch, so going
// on through the same patch cannot beat the row u came from.
template <class KeyOf, class OnImprove>
inline void relaxNode(const vg_graph& g, uint32_t u, float du, const Scope& scope, Frontier& f, KeyOf&& keyOf,
                      OnImprove&& onImprove) {
    const uint32_t from = f.route[u].via, origin = f.route[u].origin;
    for (uint32_t m = g.nodeSecondBegin[u]; m < g.nodeSecondBegin[u + 1]; ++m) {
        const uint32_t patch = g.nodeSecond[m].patch;
        if (patch != from && scope.detailed(g.second[patch].parent))
            relaxSecondRow(g, patch, g.nodeSecond[m].slot, du, origin, u, f, keyOf, onImprove);
    }
    for (uint32_t m = g.nodeFirstBegin[u]; m < g.nodeFirstBegin[u + 1]; ++m) {
        const uint32_t patch = g.nodeFirst[m].patch;
        if ((patch | kFirstLayerBit) != from && !scope.detailed(patch))
            relaxFirstRow(g, patch, g.nodeFirst[m].slot, du, origin, u, f, keyOf, onImprove);
    }
}

// Marks the first-layer patches around vertex x as detailed for a direction.
inline void detailAround(const vg_graph& g, uint32_t x, uint32_t* detail, uint32_t generation) {
    forEachPatchOf(g, x, [&](uint32_t patch, uint32_t) { detail[g.second[patch].parent] = generation; });
}

// Gives the search its start labels for endpoint x (source number `origin`): an active
// node starts at itself; any other vertex at the active nodes of its patches.
template <class KeyOf, class OnImprove>
inline void seedEndpoint(const vg_graph& g, uint32_t x, uint32_t origin, Frontier& f, KeyOf&& keyOf,
                         OnImprove&& onImprove) {
    const float offset = 0.0f;
    const uint32_t node = vertexNode(g, x);
    if (node != kNone && nodeActive(g, node)) {
        if (!f.better(node, offset)) return;
        const float key = keyOf(node, offset);
        if (key == __builtin_inff()) return;
        f.improve(node, offset, key, kNone, origin, kNone);
        onImprove(node, offset);
        return;
    }
    forEachPatchOf(g, x, [&](uint32_t patch, uint32_t slot) {
        relaxSecondRow(g, patch, slot, offset, origin, kNone, f, keyOf, onImprove);
    });
}

}  // namespace vg

namespace vg {

// Marks the first-layer patches around an endpoint as detailed.
inline void detailAround(const vg_graph& g, const Endpoint& e, uint32_t* detail, uint32_t generation) {
    if (e.isVertex()) detailAround(g, e.vertex, detail, generation);
    else detail[g.second[e.patch].parent] = generation;
}

// True when a first-layer patch around the endpoint is detailed already.
inline bool nearDetailed(const vg_graph& g, const Endpoint& e, const uint32_t* detail, uint32_t generation) {
    if (!e.isVertex()) return detail[g.second[e.patch].parent] == generation;
    bool near = false;
    forEachPatchOf(g, e.vertex, [&](uint32_t patch, uint32_t) { near |= detail[g.second[patch].parent] == generation; });
    return near;
}

// seedEndpoint for any endpoint: a surface point starts at the active nodes of its
// face's patch, at interpolated distances.
template <class KeyOf, class OnImprove>
inline void seedEndpoint(const vg_graph& g, const Endpoint& e, uint32_t origin, Frontier& f, KeyOf&& keyOf,
                         OnImprove&& onImprove) {
    if (e.isVertex()) {
        seedEndpoint(g, e.vertex, origin, f, keyOf, onImprove);
        return;
    }
    const Patch& p = g.second[e.patch];
    for (uint32_t j = 0; j < p.nodeCount; ++j) {
        const uint32_t n = g.slots[p.slotBegin + j];
        if (!nodeActive(g, n)) continue;
        const float d = pointToSlot(g, e, j);
        if (d == __builtin_inff() || !f.better(n, d)) continue;
        const float key = keyOf(n, d);
        if (key == __builtin_inff()) continue;
        f.improve(n, d, key, e.patch, origin, kNone);
        onImprove(n, d);
    }
}

}  // namespace vg
