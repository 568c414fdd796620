// Nearest of a set: one Dijkstra from the source, through the second layer of the source's
// and every target's first-layer patches and the overlay elsewhere. Targets are filed
// under their home patch; settling a node offers every target of the node's patches
// (node distance + stored entry), and the search stops once the queue's smallest label
// cannot beat the best offer.
#include "vg_query.h"
#include "vg_search.h"

namespace {

using namespace vg;

struct Best {
    float distance;
    uint32_t index;  // first index in the caller's list

    void offer(float d, uint32_t i) {
        if (d < distance || (d == distance && i < index)) {
            distance = d;
            index = i;
        }
    }
};

}  // namespace

extern "C" vg_status vg_nearest(const vg_graph* graph, vg_workspace* workspace, uint32_t source,
                                const uint32_t* targets, size_t target_count, size_t* out_index,
                                float* out_distance) {
    vg_status st = vg::checkQuery(graph, workspace, out_distance);
    if (st != VG_OK) return st;
    if (out_index == nullptr || (target_count > 0 && targets == nullptr)) return VG_ERR_INVALID_ARGUMENT;
    *out_index = target_count;
    *out_distance = __builtin_inff();
    const vg_graph& g = *graph;
    if (source >= g.vertexCount) return VG_ERR_INVALID_VERTEX;
    if (target_count >= kNone) return VG_ERR_INVALID_ARGUMENT;
    for (size_t i = 0; i < target_count; ++i)
        if (targets[i] >= g.vertexCount) return VG_ERR_INVALID_VERTEX;

    vg_workspace& ws = *workspace;
    const uint32_t gen = beginQuery(ws);
    Best best{__builtin_inff(), kNone};
    for (size_t i = 0; i < target_count; ++i)
        if (targets[i] == source) best.offer(0.0f, uint32_t(i));
    const bool used = g.vertexPatch[source] != kNone;

    // File the reachable targets under their home patches (first listing wins).
    bool any = false;
    if (used) {
        const uint32_t component = vertexComponent(g, source);
        for (size_t i = 0; i < target_count; ++i) {
            const uint32_t t = targets[i];
            if (g.vertexPatch[t] == kNone || ws.vertexStamp[t] == gen || vertexComponent(g, t) != component) continue;
            ws.vertexStamp[t] = gen;
            ws.vertexTargetIndex[t] = uint32_t(i);
            const uint32_t patch = g.vertexPatch[t];
            ws.vertexNextTarget[t] = ws.patchStamp[patch] == gen ? ws.patchTargets[patch] : kNone;
            ws.patchTargets[patch] = t;
            ws.patchStamp[patch] = gen;
            detailAround(g, t, ws.detail, gen);
            any = true;
        }
    }
    if (any) {
        detailAround(g, source, ws.detail, gen);
        // Offers every target filed under `patch` from slot `slot` at distance `base`.
        auto offerPatch = [&](uint32_t patch, uint32_t slot, float base) {
            if (ws.patchStamp[patch] != gen) return;
            const Patch& p = g.second[patch];
            for (uint32_t t = ws.patchTargets[patch]; t != kNone; t = ws.vertexNextTarget[t])
                best.offer(base + entry(p, g.secondDistances, slot, g.vertexSlot[t]), ws.vertexTargetIndex[t]);
        };
        forEachPatchOf(g, source, [&](uint32_t patch, uint32_t slot) { offerPatch(patch, slot, 0.0f); });

        Frontier& F = ws.forward;
        const Scope scope{ws.detail, gen};
        auto key = [](uint32_t, float dv) { return dv; };
        auto none = [](uint32_t, float) {};
        seedEndpoint(g, source, 0, F, key, none);
        while (!F.empty() && F.topKey() < best.distance) {
            const uint32_t u = F.pop().node;
            const float du = F.label[u].dist;
            const uint32_t v = g.nodeVertex[u];
            if (ws.vertexStamp[v] == gen) best.offer(du, ws.vertexTargetIndex[v]);
            for (uint32_t m = g.nodeSecondBegin[u]; m < g.nodeSecondBegin[u + 1]; ++m)
                offerPatch(g.nodeSecond[m].patch, g.nodeSecond[m].slot, du);
            relaxNode(g, u, du, scope, F, key, none);
        }
    }
    if (best.index != kNone) {
        *out_index = best.index;
        *out_distance = best.distance;
    }
    return VG_OK;
}
