// Point-to-point distance (thesis 3.7.1): bidirectional A* over the two-layer graph with
// the straight-line heuristic. Both directions search one graph: the second layer of the
// first-layer patches around the source and the target, the overlay everywhere else (a
// path that crosses another first-layer patch does so along one overlay edge, which is
// the shortest crossing through that patch's second layer). Searching the same graph in
// both directions is what makes the usual stopping rule sound.
//
// Potentials are the average of the two directions, p(v) = (|v - t| - |v - s|) / 2 for
// the forward search and -p(v) backward, so both searches see the same non-negative
// reduced edge lengths: no undiscovered path is shorter than topForward + topBackward.
// Quantisation can make a stored length a hair shorter than the straight line; a node
// whose label drops after it was settled is simply queued again.
#include "vg_query.h"
#include "vg_search.h"

namespace {

using namespace vg;

float pointToPoint(const vg_graph& g, vg_workspace& ws, uint32_t s, uint32_t t, float bound) {
    const float inf = __builtin_inff();
    if (s == t) return 0.0f;
    if (g.vertexPatch[s] == kNone || g.vertexPatch[t] == kNone) return inf;
    if (vertexComponent(g, s) != vertexComponent(g, t)) return inf;

    const uint32_t gen = beginQuery(ws);
    float best = inf;
    // Two vertices of one second-layer patch: the stored entry is a path already.
    forEachPatchOf(g, s, [&](uint32_t ps, uint32_t slotS) {
        forEachPatchOf(g, t, [&](uint32_t pt, uint32_t slotT) {
            if (ps == pt) {
                const float d = entry(g.second[ps], g.secondDistances, slotS, slotT);
                if (d < best) best = d;
            }
        });
    });

    detailAround(g, s, ws.detail, gen);
    detailAround(g, t, ws.detail, gen);
    const Scope scope{ws.detail, gen, false};

    const float* ps = g.positions + 3 * uint64_t(s);
    const float* pt = g.positions + 3 * uint64_t(t);
    auto potential = [&](uint32_t node) {
        if (ws.potentialStamp[node] != gen) {
            const float* p = g.positions + 3 * uint64_t(g.nodeVertex[node]);
            const float ax = p[0] - pt[0], ay = p[1] - pt[1], az = p[2] - pt[2];
            const float bx = p[0] - ps[0], by = p[1] - ps[1], bz = p[2] - ps[2];
            ws.potential[node] =
                0.5f * (__builtin_sqrtf(ax * ax + ay * ay + az * az) - __builtin_sqrtf(bx * bx + by * by + bz * bz));
            ws.potentialStamp[node] = gen;
        }
        return ws.potential[node];
    };
    Frontier& F = ws.forward;
    Frontier& B = ws.backward;
    auto forwardKey = [&](uint32_t v, float dv) { return dv + potential(v); };
    auto backwardKey = [&](uint32_t v, float dv) { return dv - potential(v); };
    auto meetForward = [&](uint32_t v, float dv) {
        if (B.labelled(v) && dv + B.dist[v] < best) best = dv + B.dist[v];
    };
    auto meetBackward = [&](uint32_t v, float dv) {
        if (F.labelled(v) && dv + F.dist[v] < best) best = dv + F.dist[v];
    };
    seedEndpoint(g, s, 0.0f, F, forwardKey, meetForward);
    seedEndpoint(g, t, 0.0f, B, backwardKey, meetBackward);

    // One side exhausted: every node it can reach is final, so the best meeting is known.
    while (!F.empty() && !B.empty()) {
        const float lower = F.topKey() + B.topKey();
        if (!(lower < best) || lower > bound) break;
        if (F.topKey() <= B.topKey()) {
            const uint32_t u = F.pop().node;
            relaxNode(g, u, F.dist[u], scope, F, forwardKey, meetForward);
        } else {
            const uint32_t u = B.pop().node;
            relaxNode(g, u, B.dist[u], scope, B, backwardKey, meetBackward);
        }
    }
    return best <= bound ? best : inf;
}

}  // namespace

extern "C" vg_status vg_distance(const vg_graph* graph, vg_workspace* workspace, uint32_t source,
                                 uint32_t target, float* out_distance) {
    return vg_distance_within(graph, workspace, source, target, __builtin_inff(), out_distance);
}

extern "C" vg_status vg_distance_within(const vg_graph* graph, vg_workspace* workspace, uint32_t source,
                                        uint32_t target, float max_distance, float* out_distance) {
    const vg_status st = vg::checkQuery(graph, workspace, out_distance);
    if (st != VG_OK) return st;
    *out_distance = __builtin_inff();
    if (source >= graph->vertexCount || target >= graph->vertexCount) return VG_ERR_INVALID_VERTEX;
    if (max_distance != max_distance) return VG_ERR_INVALID_ARGUMENT;  // NaN bound
    *out_distance = pointToPoint(*graph, *workspace, source, target, max_distance);
    return VG_OK;
}
