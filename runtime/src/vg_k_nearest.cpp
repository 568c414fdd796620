// The k nearest of a set of surface points: one Dijkstra from the source, through the
// second layer of the first-layer patches around the source and the targets and the
// overlay elsewhere (as vg_nearest). Targets are filed under their patch; settling a node
// offers every target of the node's patches (node distance + interpolated entry). The k
// best offers so far live in the caller's output arrays, and the search stops once the
// smallest open label cannot beat the k-th of them: every later offer is at least that
// label. Targets are resolved in chunks of kTargetChunk (workspace memory is fixed), one
// search per chunk, the k best carried across chunks.
#include "vg_fan.h"
#include "vg_query.h"
#include "vg_search.h"

namespace {

using namespace vg;

// The k best (distance, index) pairs, sorted, at most one entry per index.
struct KBest {
    size_t* index;
    float* distance;
    size_t k, count;

    float bound() const { return count < k ? __builtin_inff() : distance[count - 1]; }

    static bool before(float d, size_t i, float e, size_t j) { return d < e || (d == e && i < j); }

    void offer(float d, size_t i) {
        if (!(d < __builtin_inff())) return;
        for (size_t a = 0; a < count; ++a) {
            if (index[a] != i) continue;
            if (!before(d, i, distance[a], i)) return;
            for (size_t b = a; b + 1 < count; ++b) {  // drop the old offer; the new one goes in below
                index[b] = index[b + 1];
                distance[b] = distance[b + 1];
            }
            --count;
            break;
        }
        if (count == k && !before(d, i, distance[k - 1], index[k - 1])) return;
        size_t at = count < k ? count++ : k - 1;
        for (; at > 0 && before(d, i, distance[at - 1], index[at - 1]); --at) {
            index[at] = index[at - 1];
            distance[at] = distance[at - 1];
        }
        index[at] = i;
        distance[at] = d;
    }
};

// One search for targets [first, first + n).
void searchChunk(const vg_graph& g, vg_workspace& ws, const Endpoint& source, const vg_point* targets, size_t first,
                 uint32_t n, KBest& best) {
    const uint32_t gen = beginQuery(ws);
    const uint32_t component = endpointComponent(g, source);
    Endpoint* resolved = ws.targetEndpoints;
    bool any = false;
    for (uint32_t i = 0; i < n; ++i) {
        Endpoint& t = resolved[i];
        resolvePoint(g, targets[first + i], t);  // checked by the caller
        if (endpointComponent(g, t) != component) continue;
        best.offer(localPath(g, source, t), first + i);  // around a shared vertex (vg_fan.h)
        const uint32_t patch = t.isVertex() ? g.vertexPatch[t.vertex] : t.patch;  // a vertex under its home patch
        ws.vertexNextTarget[i] = ws.patchStamp[patch] == gen ? ws.patchTargets[patch] : kNone;
        ws.patchTargets[patch] = i;
        ws.patchStamp[patch] = gen;
        detailAround(g, t, ws.detail, gen);
        any = true;
    }
    if (!any) return;
    detailAround(g, source, ws.detail, gen);
    // Offers every target filed under `patch`, from distances dist(j) to its slots.
    auto offerPatch = [&](uint32_t patch, float base, auto&& dist) {
        if (ws.patchStamp[patch] != gen) return;
        for (uint32_t i = ws.patchTargets[patch]; i != kNone; i = ws.vertexNextTarget[i]) {
            const Endpoint& t = resolved[i];
            const uint32_t slotT = t.isVertex() ? uint32_t(g.vertexSlot[t.vertex]) : kNone;
            best.offer(base + toEndpointInPatch(t, slotT, dist), first + i);
        }
    };
    forEachEndpointPatch(g, source, [&](uint32_t patch, uint32_t, auto&& dist) { offerPatch(patch, 0.0f, dist); });
    // Two points of one face: the straight segment.
    if (!source.isVertex())
        for (uint32_t i = ws.patchStamp[source.patch] == gen ? ws.patchTargets[source.patch] : kNone; i != kNone;
             i = ws.vertexNextTarget[i])
            if (!resolved[i].isVertex() && resolved[i].face == source.face)
                best.offer(distance3(source.position, resolved[i].position), first + i);

    Frontier& F = ws.forward;
    const Scope scope{ws.detail, gen};
    auto key = [](uint32_t, float dv) { return dv; };
    auto none = [](uint32_t, float) {};
    seedEndpoint(g, source, 0, F, key, none);
    while (!F.empty() && F.topKey() < best.bound()) {
        const uint32_t u = F.pop().node;
        const float du = F.label[u].dist;
        for (uint32_t m = g.nodeSecondBegin[u]; m < g.nodeSecondBegin[u + 1]; ++m) {
            const uint32_t patch = g.nodeSecond[m].patch, slot = g.nodeSecond[m].slot;
            const Patch& p = g.second[patch];
            offerPatch(patch, du, [&](uint32_t j) { return entry(p, g.secondDistances, slot, j); });
        }
        relaxNode(g, u, du, scope, F, key, none);
    }
}

}  // namespace

extern "C" vg_status vg_point_k_nearest(const vg_graph* graph, vg_workspace* workspace, const vg_point* source,
                                        const vg_point* targets, size_t target_count, size_t k, size_t* out_indices,
                                        float* out_distances, size_t* out_found) {
    vg_status st = vg::checkQuery(graph, workspace, out_found);
    if (st != VG_OK) return st;
    *out_found = 0;
    if (source == nullptr || (target_count > 0 && targets == nullptr) ||
        (k > 0 && (out_indices == nullptr || out_distances == nullptr)))
        return VG_ERR_INVALID_ARGUMENT;
    const vg_graph& g = *graph;
    for (size_t i = 0; i < k; ++i) {
        out_indices[i] = target_count;
        out_distances[i] = __builtin_inff();
    }
    Endpoint s;
    if (resolvePoint(g, *source, s) != VG_OK) return VG_ERR_INVALID_POINT;
    for (size_t i = 0; i < target_count; ++i) {
        Endpoint t;
        if (resolvePoint(g, targets[i], t) != VG_OK) return VG_ERR_INVALID_POINT;
    }
    if (k == 0) return VG_OK;
    KBest best{out_indices, out_distances, k, 0};
    const uint32_t chunk = g.vertexCount < kTargetChunk ? g.vertexCount : kTargetChunk;
    for (size_t first = 0; first < target_count; first += chunk) {
        const size_t left = target_count - first;
        searchChunk(g, *workspace, s, targets, first, uint32_t(left < chunk ? left : chunk), best);
    }
    *out_found = best.count;
    return VG_OK;
}

extern "C" vg_status vg_point_nearest(const vg_graph* graph, vg_workspace* workspace, const vg_point* source,
                                      const vg_point* targets, size_t target_count, size_t* out_index,
                                      float* out_distance) {
    if (out_index == nullptr || out_distance == nullptr) return VG_ERR_INVALID_ARGUMENT;
    size_t found = 0;
    return vg_point_k_nearest(graph, workspace, source, targets, target_count, 1, out_index, out_distance, &found);
}
