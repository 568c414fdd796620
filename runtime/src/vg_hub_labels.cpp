#include "vg_hub_labels.h"

#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define VG_HUB_AVX2 1
#include <immintrin.h>
#define VG_AVX2_TARGET __attribute__((target("avx2")))
#else
#define VG_HUB_AVX2 0
#endif

namespace vg {

namespace {

constexpr uint16_t kNoStep = 65535;

// The label kernels work in 16-bit label steps with saturating sums: "no path" (65535)
// stays "no path", and the baker leaves headroom above its largest label so that real
// sums never reach it. Portable and AVX2 versions give the same numbers.
uint16_t saturatingSum(uint32_t a, uint32_t b) { return uint16_t(a + b < 65535u ? a + b : 65535u); }

// d[k] = min(d[k], base + steps[k]) for k < n.
void lowerSteps(uint16_t* d, const uint16_t* steps, uint32_t n, uint16_t base) {
    for (uint32_t k = 0; k < n; ++k) {
        const uint16_t c = saturatingSum(steps[k], base);
        d[k] = c < d[k] ? c : d[k];
    }
}

// min over k < n of d[k] + steps[k].
uint16_t meetSteps(const uint16_t* d, const uint16_t* steps, uint32_t n) {
    uint16_t best = kNoStep;
    for (uint32_t k = 0; k < n; ++k) {
        const uint16_t c = saturatingSum(d[k], steps[k]);
        best = c < best ? c : best;
    }
    return best;
}

#if VG_HUB_AVX2
VG_AVX2_TARGET void lowerStepsAvx2(uint16_t* d, const uint16_t* steps, uint32_t n, uint16_t base) {
    const __m256i b = _mm256_set1_epi16(short(base));
    uint32_t k = 0;
    for (; k + 16 <= n; k += 16) {
        const __m256i x = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(steps + k));
        const __m256i y = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(d + k));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(d + k), _mm256_min_epu16(y, _mm256_adds_epu16(x, b)));
    }
    lowerSteps(d + k, steps + k, n - k, base);
}

VG_AVX2_TARGET uint16_t meetStepsAvx2(const uint16_t* d, const uint16_t* steps, uint32_t n) {
    __m256i best = _mm256_set1_epi16(-1);
    uint32_t k = 0;
    for (; k + 16 <= n; k += 16) {
        const __m256i x = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(steps + k));
        const __m256i y = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(d + k));
        best = _mm256_min_epu16(best, _mm256_adds_epu16(x, y));
    }
    const __m128i half = _mm_min_epu16(_mm256_castsi256_si128(best), _mm256_extracti128_si256(best, 1));
    const uint16_t lanes = uint16_t(_mm_cvtsi128_si32(_mm_minpos_epu16(half)));
    const uint16_t rest = meetSteps(d + k, steps + k, n - k);
    return lanes < rest ? lanes : rest;
}
#endif

void lowerStepsOn(const vg_graph& g, uint16_t* d, const uint16_t* steps, uint32_t n, uint16_t base) {
#if VG_HUB_AVX2
    if (g.avx2) return lowerStepsAvx2(d, steps, n, base);
#endif
    lowerSteps(d, steps, n, base);
}

uint16_t meetStepsOn(const vg_graph& g, const uint16_t* d, const uint16_t* steps, uint32_t n) {
#if VG_HUB_AVX2
    if (g.avx2) return meetStepsAvx2(d, steps, n);
#endif
    return meetSteps(d, steps, n);
}

// A distance in label steps, rounded, saturated to "no path".
uint16_t toSteps(float d, float scale) {
    const float x = d / scale + 0.5f;
    return x < 65535.0f ? uint16_t(x) : kNoStep;  // also +inf and NaN (a zero scale)
}

// Where a query vertex enters the labels: as a hub itself, or through its first-layer patch.
struct Side {
    uint32_t node;   // its node id, kNone for a patch-interior vertex
    uint32_t hub;    // its hub number, kNone when it is no first-layer node
    uint32_t first;  // not a hub: its first-layer patch
    uint32_t tree;   // its tree node: the hub's, or the leaf of its patch
};

uint32_t pathLength(const vg_graph& g, uint32_t t) { return g.hubTree[t].pathBegin + g.hubTree[t].hubCount; }

// The tree node holding hub h: the last with hubBegin <= h (the ranges tile the hubs in
// tree order, so a later node begins after h).
uint32_t treeOfHub(const vg_graph& g, uint32_t h) {
    uint32_t lo = 0, hi = g.hubTreeCount;
    while (hi - lo > 1) {
        const uint32_t mid = lo + (hi - lo) / 2;
        if (g.hubTree[mid].hubBegin <= h) lo = mid;
        else hi = mid;
    }
    return lo;
}

// Parents come before their children (preorder), so the larger of two distinct nodes is
// never the other's ancestor.
uint32_t commonAncestor(const vg_graph& g, uint32_t a, uint32_t b) {
    while (a != b) {
        if (a > b) a = g.hubTree[a].parent;
        else b = g.hubTree[b].parent;
    }
    return a;
}

// False when the vertex lies in second-layer patches of several first-layer patches
// without being a hub (a first-layer node merged away by pruning): the search takes it.
bool sideOf(const vg_graph& g, uint32_t v, Side& side) {
    side.node = vertexNode(g, v);
    side.hub = side.node == kNone ? kNone : g.nodeHub[side.node];
    if (side.hub != kNone) {
        side.first = kNone;
        side.tree = treeOfHub(g, side.hub);
        return true;
    }
    side.first = g.second[g.vertexPatch[v]].parent;
    side.tree = g.hubFirstLeaf[side.first];
    bool inside = true;
    forEachPatchOf(g, v, [&](uint32_t patch, uint32_t) { inside &= g.second[patch].parent == side.first; });
    return inside;
}

bool hubInPatch(const vg_graph& g, uint32_t node, uint32_t first) {
    for (uint32_t m = g.nodeFirstBegin[node]; m < g.nodeFirstBegin[node + 1]; ++m)
        if (g.nodeFirst[m].patch == first) return true;
    return false;
}

bool shareFirstPatch(const vg_graph& g, const Side& a, const Side& b) {
    if (a.hub == kNone && b.hub == kNone) return a.first == b.first;
    if (a.hub == kNone) return hubInPatch(g, b.node, a.first);
    if (b.hub == kNone) return hubInPatch(g, a.node, b.first);
    for (uint32_t m = g.nodeFirstBegin[a.node]; m < g.nodeFirstBegin[a.node + 1]; ++m)
        if (hubInPatch(g, b.node, g.nodeFirst[m].patch)) return true;
    return false;
}

// Row of `node` among the inner rows of first-layer patch `first`, kNone if absent.
uint32_t innerRow(const vg_graph& g, uint32_t first, uint32_t node) {
    const uint32_t* nodes = g.hubInnerNode + g.hubInnerBegin[first];
    uint32_t lo = 0, hi = g.hubInnerBegin[first + 1] - g.hubInnerBegin[first];
    while (lo < hi) {
        const uint32_t mid = lo + (hi - lo) / 2;
        if (nodes[mid] < node) lo = mid + 1;
        else hi = mid;
    }
    return lo < g.hubInnerBegin[first + 1] - g.hubInnerBegin[first] && nodes[lo] == node ? lo : kNone;
}

const uint16_t* innerRowData(const vg_graph& g, uint32_t first, uint32_t row) {
    return g.hubInner + g.hubInnerMatrixBegin[first] + uint64_t(row) * g.first[first].slotCount;
}

// Calls f(node, distance) for the active nodes of x's second-layer patches (not x itself)
// with x's row entry to each, where there is a path.
template <class F>
void forEachRowNode(const vg_graph& g, uint32_t x, F&& f) {
    forEachPatchOf(g, x, [&](uint32_t patch, uint32_t slot) {
        const Patch& p = g.second[patch];
        for (uint32_t j = 0; j < p.nodeCount; ++j) {
            const uint32_t n = g.slots[p.slotBegin + j];
            if (j == slot || !nodeActive(g, n)) continue;
            const uint32_t q = quantum(g.secondDistances, entryIndex(p, slot, j));
            if (q != kNoPathQuantum) f(n, float(q) * p.scale);
        }
    });
}

// v[k]: the distance inside the side's first-layer patch from vertex x to its k-th slot
// (a first-layer node), in label steps: x's patch rows to the active nodes of its patches,
// then their inner rows (an active node is an inner row itself).
void innerSteps(const vg_graph& g, uint32_t x, const Side& side, uint16_t* v) {
    const uint32_t first = side.first, K = g.first[first].slotCount;
    for (uint32_t k = 0; k < K; ++k) v[k] = kNoStep;
    if (side.node != kNone && nodeActive(g, side.node)) {
        const uint32_t r = innerRow(g, first, side.node);
        if (r != kNone) lowerStepsOn(g, v, innerRowData(g, first, r), K, 0);
        return;
    }
    forEachRowNode(g, x, [&](uint32_t n, float d) {
        const uint16_t base = toSteps(d, g.hubLabelScale);
        const uint32_t r = base == kNoStep ? kNone : innerRow(g, first, n);
        if (r != kNone) lowerStepsOn(g, v, innerRowData(g, first, r), K, base);
    });
}

const uint16_t* labelOf(const vg_graph& g, uint32_t hub, uint32_t* length) {
    *length = uint32_t(g.hubLabelBegin[hub + 1] - g.hubLabelBegin[hub]);
    return g.hubLabels + g.hubLabelBegin[hub];
}

// Calls f(k, label, n) for every slot k of first-layer patch `first` that is a hub: its
// label, cut to at most `length` entries (the common part of two tree paths).
template <class F>
void forEachSlotLabel(const vg_graph& g, uint32_t first, uint32_t length, F&& f) {
    const Patch& fp = g.first[first];
    for (uint32_t k = 0; k < fp.slotCount; ++k) {
        const uint32_t hub = g.nodeHub[g.slots[fp.slotBegin + k]];
        if (hub == kNone) continue;
        uint32_t n = 0;
        const uint16_t* label = labelOf(g, hub, &n);
        f(k, label, n < length ? n : length);
    }
}

// d[i], i < length: the side's distance to the i-th hub of its tree path, in label steps.
void hubDistances(const vg_graph& g, vg_workspace& ws, uint32_t x, const Side& side, uint16_t* d, uint32_t length) {
    for (uint32_t i = 0; i < length; ++i) d[i] = kNoStep;
    if (side.hub != kNone) {
        uint32_t n = 0;
        const uint16_t* label = labelOf(g, side.hub, &n);
        lowerStepsOn(g, d, label, n < length ? n : length, 0);
        return;
    }
    const uint16_t* v = ws.hubSlotSteps;
    innerSteps(g, x, side, ws.hubSlotSteps);
    forEachSlotLabel(g, side.first, length, [&](uint32_t k, const uint16_t* label, uint32_t m) {
        if (v[k] != kNoStep) lowerStepsOn(g, d, label, m, v[k]);
    });
}

}  // namespace

bool hubDistance(const vg_graph& g, vg_workspace& ws, uint32_t s, uint32_t t, float maxDistance, float* out) {
    if (g.hubTreeCount == 0 || s == t || g.vertexPatch[s] == kNone || g.vertexPatch[t] == kNone) return false;
    if (t < s) {  // one order for both directions: d(s, t) and d(t, s) are the same number
        const uint32_t x = s;
        s = t;
        t = x;
    }
    Side a, b;
    if (!sideOf(g, s, a) || !sideOf(g, t, b) || shareFirstPatch(g, a, b)) return false;
    const uint32_t common = pathLength(g, commonAncestor(g, a.tree, b.tree));
    uint16_t* dS = ws.hubSteps;
    hubDistances(g, ws, s, a, dS, common);
    const float scale = g.hubLabelScale;
    auto distanceOf = [&](uint16_t steps) { return steps == kNoStep ? __builtin_inff() : float(steps) * scale; };
    float best = __builtin_inff();
    uint32_t n = 0;
    if (b.hub != kNone) {
        const uint16_t* label = labelOf(g, b.hub, &n);
        best = distanceOf(meetStepsOn(g, dS, label, n < common ? n : common));
    } else {
        // s's distance to each first-layer node of t's patch, then to t's patch nodes.
        const uint32_t first = b.first;
        const Patch& fp = g.first[first];
        uint16_t* w = ws.hubSlotSteps;
        for (uint32_t k = 0; k < fp.slotCount; ++k) w[k] = kNoStep;
        forEachSlotLabel(g, first, common, [&](uint32_t k, const uint16_t* label, uint32_t m) {
            w[k] = meetStepsOn(g, dS, label, m);
        });
        const uint32_t gen = beginQuery(ws);
        Frontier& F = ws.forward;
        Frontier& B = ws.backward;
        uint32_t* met = ws.patchNodeSlot;  // the nodes labelled from both sides
        uint32_t metCount = 0;
        auto label = [&](uint32_t u, float fromT) {
            if (!B.labelled(u)) {
                const uint32_t r = innerRow(g, first, u);
                if (r == kNone) return;
                F.label[u] = Label{distanceOf(meetStepsOn(g, w, innerRowData(g, first, r), fp.slotCount)), gen};
                B.label[u] = Label{fromT, gen};
                if (metCount < kMaxPatchSlots) met[metCount++] = u;
            } else if (fromT < B.label[u].dist) {
                B.label[u].dist = fromT;
            }
        };
        if (b.node != kNone && nodeActive(g, b.node)) label(b.node, 0.0f);
        forEachRowNode(g, t, label);
        // Meetings at a node, and across a mesh edge between two of them (vg_distance.cpp).
        for (uint32_t i = 0; i < metCount; ++i) {
            const uint32_t v = met[i];
            const float fv = F.label[v].dist, bv = B.label[v].dist;
            if (fv + bv < best) best = fv + bv;
            for (uint32_t e = g.nodeEdgeBegin[v]; e < g.nodeEdgeBegin[v + 1]; ++e) {
                const uint32_t x = g.nodeEdge[e];
                if (!B.labelled(x)) continue;
                const float d = crossing(fv, F.label[x].dist, bv, B.label[x].dist,
                                         euclidean(g, g.nodeVertex[v], g.nodeVertex[x]));
                if (d < best) best = d;
            }
        }
    }
    *out = best <= maxDistance ? best : __builtin_inff();
    return true;
}

}  // namespace vg
