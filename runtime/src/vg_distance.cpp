// Point-to-point distance (thesis 3.7.1) over the two-layer graph: the second layer of the
// first-layer patches around the source and the target, the overlay everywhere else (a
// path that crosses another first-layer patch does so along one overlay edge, which is
// the shortest crossing through that patch's second layer). Lower bounds b(v, x) are the
// straight line tightened by landmark bounds (vg_lower_bound.h). Two searches, chosen per
// workspace (vg_workspace_set_search):
//
// * directed (the default): A* from s with the whole bound b(v, t) as its potential; the
//   target side only seeds t's patch nodes (and relaxes t's own rows when t is a node),
//   so that the search meets it there, also across the border edges next to t. It stops
//   once the smallest key reaches the best meeting: every key bounds every path through
//   its node from below. A short pair is searched from both ends (pointToPoint, below).
// * bidirectional (the thesis's): both directions search one graph with the average
//   potentials p(v) = (b(v, t) - b(v, s)) / 2 forward and -p(v) backward, so both see the
//   same non-negative reduced edge lengths and no undiscovered path is shorter than
//   topForward + topBackward (searching the same graph in both directions is what makes
//   that stopping rule sound). Halving the bound is what makes it slower: on igea's
//   longest pairs it settles 1.6-1.9x the nodes of the directed search and takes 2-2.5x
//   its time (BENCHMARKS.md).
//
// Quantisation can make a stored length a hair shorter than a bound; a node whose label
// drops after it was settled is simply queued again.
#include "vg_fan.h"
#include "vg_hub_labels.h"
#include "vg_patch_pairs.h"
#include "vg_point_to_point.h"
#include "vg_query.h"
#include "vg_lower_bound.h"
#include "vg_search.h"

namespace {

using namespace vg;

// Pairs closer than this share of the bounding-box diagonal count as short (directed mode).
constexpr float kShortPair = 0.1f;

// One order for both directions of a pair, so that d(s, t) and d(t, s) are the same number.
bool endpointLess(const Endpoint& a, const Endpoint& b) {
    if (a.isVertex() != b.isVertex()) return a.isVertex();
    if (a.isVertex()) return a.vertex < b.vertex;
    if (a.face != b.face) return a.face < b.face;
    for (int k = 0; k < 3; ++k)
        if (a.weight[k] != b.weight[k]) return a.weight[k] < b.weight[k];
    return false;
}

bool sameEndpoint(const Endpoint& a, const Endpoint& b) { return !endpointLess(a, b) && !endpointLess(b, a); }

}  // namespace

namespace vg {

namespace {

// One search (see the top of this file), from the endpoint that comes first in the pair's
// one order (endpointLess), or with `fromSecond` from the other. *shortPair tells whether
// s and t are close: in one first-layer patch, or nearer than kShortPair of the
// bounding-box diagonal.
float search(const vg_graph& g, vg_workspace& ws, Endpoint s, Endpoint t, float maxDistance, vg_search_mode mode,
             bool fromSecond, Meeting* how, bool* shortPair) {
    const float inf = __builtin_inff();
    Meeting scratch;
    Meeting& m = how ? *how : scratch;
    m.kind = Meeting::kUnreached;
    m.swapped = endpointLess(t, s) != fromSecond;
    if (m.swapped) {
        const Endpoint x = s;
        s = t;
        t = x;
    }
    m.s = s;
    m.t = t;
    if (sameEndpoint(s, t)) {
        m.kind = Meeting::kSame;
        return 0.0f;
    }
    if ((s.isVertex() && g.vertexPatch[s.vertex] == kNone) || (t.isVertex() && g.vertexPatch[t.vertex] == kNone))
        return inf;
    if (endpointComponent(g, s) != endpointComponent(g, t)) return inf;

    const uint32_t gen = beginQuery(ws);
    float best = nearbyDistance(g, s, t, m);

    detailAround(g, s, ws.detail, gen);
    const bool oneFirstPatch = nearDetailed(g, t, ws.detail, gen);
    detailAround(g, t, ws.detail, gen);
    const Scope scope{ws.detail, gen};

    const float* ps = s.position;
    const float* pt = t.position;
    landmarkDistances(g, s, ws.landmarkSource);
    landmarkDistances(g, t, ws.landmarkTarget);
    const bool directed = mode == VG_SEARCH_DIRECTED;
    // Directed: the forward potential is the whole bound to t. Bidirectional: half of
    // (bound to t - bound to s), and its negation backward.
    auto potential = [&](uint32_t node) {
        Potential& p = ws.potential[node];
        if (p.stamp != gen) {
            const float* r = ws.nodeRecords + uint64_t(node) * (3 + g.landmarkCount);
            const float toT = nodeBound(g, r, pt, ws.landmarkTarget);
            p.value = directed ? toT : 0.5f * (toT - nodeBound(g, r, ps, ws.landmarkSource));
            p.stamp = gen;
        }
        return p.value;
    };
    Frontier& F = ws.forward;
    Frontier& B = ws.backward;
    // Any path through v is at least its key (directed), or its key plus half a lower
    // bound of d(s, t) (bidirectional: the potentials are halves of lower bounds): such a
    // node is left alone once that reaches the best found, with a margin for the unfolded
    // crossings, which can undercut the best path through a node by a few percent.
    float bound = distance3(ps, pt);
    const float viaLandmarks = landmarkBound(g, ws.landmarkSource, ws.landmarkTarget);
    if (viaLandmarks > bound) bound = viaLandmarks;
    if (shortPair) *shortPair = oneFirstPatch || bound < kShortPair * g.bboxDiagonal;
    const float keyMargin = directed ? 0.0f : 0.5f * bound;
    auto prune = [&](float key) { return key + keyMargin < kUnfoldSlack * best ? key : __builtin_inff(); };
    auto forwardKey = [&](uint32_t v, float dv) { return prune(dv + potential(v)); };
    // Directed: the backward labels are never searched from, their key is their distance.
    auto backwardKey = [&](uint32_t v, float dv) { return prune(directed ? dv : dv - potential(v)); };
    // A node labelled from both sides joins the two searches: through the node itself,
    // and across each mesh edge to a neighbour node labelled from both sides too.
    auto meet = [&](uint32_t v) {
        if (!F.labelled(v) || !B.labelled(v)) return;
        const float fv = F.label[v].dist, bv = B.label[v].dist;
        if (fv + bv < best) {
            best = fv + bv;
            m.kind = Meeting::kNode;
            m.node = v;
        }
        for (uint32_t e = g.nodeEdgeBegin[v]; e < g.nodeEdgeBegin[v + 1]; ++e) {
            const uint32_t w = g.nodeEdge[e];
            if (!F.labelled(w) || !B.labelled(w)) continue;
            const float d = crossing(fv, F.label[w].dist, bv, B.label[w].dist, euclidean(g, g.nodeVertex[v], g.nodeVertex[w]));
            if (d < best) {
                best = d;
                m.kind = Meeting::kCrossing;
                m.node = v;
                m.other = w;
            }
        }
    };
    auto onLabel = [&](uint32_t v, float) { meet(v); };
    seedEndpoint(g, s, 0, F, forwardKey, onLabel);
    seedEndpoint(g, t, 0, B, backwardKey, onLabel);

    if (directed) {
        // A target that is a node itself: its rows label the nodes around it, so that the
        // search can meet it across the border edges next to it, not only at it.
        while (!B.empty() && B.label[B.heap[0].node].dist == 0.0f) {
            const uint32_t u = B.pop().node;
            relaxNode(g, u, 0.0f, scope, B, backwardKey, onLabel);
        }
        while (!F.empty()) {
            const float lower = F.topKey();
            if (!(lower < best) || lower > kUnfoldSlack * maxDistance) break;
            const uint32_t u = F.pop().node;
            relaxNode(g, u, F.label[u].dist, scope, F, forwardKey, onLabel);
        }
    } else {
        // One side exhausted: every node it can reach is final, so the best meeting is known.
        while (!F.empty() && !B.empty()) {
            const float lower = F.topKey() + B.topKey();
            if (!(lower < best) || lower > kUnfoldSlack * maxDistance) break;
            if (F.topKey() <= B.topKey()) {
                const uint32_t u = F.pop().node;
                relaxNode(g, u, F.label[u].dist, scope, F, forwardKey, onLabel);
            } else {
                const uint32_t u = B.pop().node;
                relaxNode(g, u, B.label[u].dist, scope, B, backwardKey, onLabel);
            }
        }
    }
    if (!(best <= maxDistance)) {
        m.kind = Meeting::kUnreached;
        return inf;
    }
    return best;
}

}  // namespace

float nearbyDistance(const vg_graph& g, const Endpoint& s, const Endpoint& t, Meeting& m) {
    float best = __builtin_inff();
    // Two points of one face: the straight segment.
    if (!s.isVertex() && !t.isVertex() && s.face == t.face) {
        best = distance3(s.position, t.position);
        m.kind = Meeting::kSegment;
    }
    // Two points around one vertex: the exact local paths (vg_fan.h).
    uint32_t fanVertex = kNone, fanWay = 0;
    const float local = localPath(g, s, t, &fanVertex, &fanWay);
    if (local < best) {
        best = local;
        m.kind = Meeting::kFan;
        m.vertex = fanVertex;
        m.way = fanWay;
    }
    // Two endpoints of one second-layer patch: the stored (or interpolated) entry is a path already.
    forEachEndpointPatch(g, s, [&](uint32_t ps, uint32_t, auto&& fromS) {
        forEachEndpointPatch(g, t, [&](uint32_t pt, uint32_t slotT, auto&&) {
            if (ps != pt) return;
            const float d = toEndpointInPatch(t, slotT, fromS);
            if (d < best) {
                best = d;
                m.kind = Meeting::kPatch;
                m.patch = ps;
            }
        });
    });
    return best;
}

float directedSearch(const vg_graph& g, vg_workspace& ws, Endpoint s, Endpoint t, float maxDistance, bool fromSecond) {
    return search(g, ws, s, t, maxDistance, VG_SEARCH_DIRECTED, fromSecond, nullptr, nullptr);
}

float pointToPoint(const vg_graph& g, vg_workspace& ws, Endpoint s, Endpoint t, float maxDistance, vg_search_mode mode,
                   Meeting* how) {
    if (mode == VG_SEARCH_HUB_LABELS) {
        float labelled = 0.0f;
        if (how == nullptr && s.isVertex() && t.isVertex() &&
            (hubDistance(g, ws, s.vertex, t.vertex, maxDistance, &labelled) ||
             patchPairDistance(g, ws, s.vertex, t.vertex, maxDistance, &labelled)))
            return labelled;
        mode = VG_SEARCH_DIRECTED;
    }
    if (mode != VG_SEARCH_DIRECTED || how != nullptr) return search(g, ws, s, t, maxDistance, mode, false, how, nullptr);
    // A short pair is searched from both ends and keeps the shorter answer: a directed
    // search unfolds the border crossings next to its target, which for short pairs are a
    // larger share of the distance, and both searches stay small there (from the other end
    // rather than bidirectionally, which meets in the middle: more accurate on average and
    // faster, BENCHMARKS.md).
    bool shortPair = false;
    const float directed = search(g, ws, s, t, maxDistance, VG_SEARCH_DIRECTED, false, nullptr, &shortPair);
    if (!shortPair) return directed;
    const float back = directedSearch(g, ws, s, t, maxDistance, true);
    return back < directed ? back : directed;
}

}  // namespace vg

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
    *out_distance = pointToPoint(*graph, *workspace, vertexEndpoint(*graph, source), vertexEndpoint(*graph, target),
                                 max_distance, workspace->searchMode);
    return VG_OK;
}

extern "C" vg_status vg_point_distance(const vg_graph* graph, vg_workspace* workspace, const vg_point* source,
                                       const vg_point* target, float* out_distance) {
    return vg_point_distance_within(graph, workspace, source, target, __builtin_inff(), out_distance);
}

extern "C" vg_status vg_point_distance_within(const vg_graph* graph, vg_workspace* workspace, const vg_point* source,
                                              const vg_point* target, float max_distance, float* out_distance) {
    const vg_status st = vg::checkQuery(graph, workspace, out_distance);
    if (st != VG_OK) return st;
    *out_distance = __builtin_inff();
    if (source == nullptr || target == nullptr || max_distance != max_distance) return VG_ERR_INVALID_ARGUMENT;
    vg::Endpoint s, t;
    if (vg::resolvePoint(*graph, *source, s) != VG_OK || vg::resolvePoint(*graph, *target, t) != VG_OK)
        return VG_ERR_INVALID_POINT;
    *out_distance = pointToPoint(*graph, *workspace, s, t, max_distance, workspace->searchMode);
    return VG_OK;
}
