// Hub landmark distances in the labels' metric (vg_hub_landmarks.h). Per group of up to
// 16 landmarks, one label-correcting search over the first-layer nodes: every hub starts
// with its table values, leaves the queue keyed by the smallest lane lowered since it last
// relaxed, relaxes its rows of every first-layer patch it is a slot of with those lanes,
// and comes back when a lane of it is lowered again. Each value is a float path sum (a
// table value, then matrix entries), and the result is the least such sum per hub and
// landmark: the same numbers in any order, so every workspace holds the same.
#include "vg_hub_landmarks.h"

namespace vg {
namespace {

constexpr float kInf = __builtin_inff();

struct Queue {
    const HubLandmarkScratch& s;
    uint32_t size;

    bool before(uint32_t a, uint32_t b) const { return s.key[a] < s.key[b] || (s.key[a] == s.key[b] && a < b); }

    void siftUp(uint32_t at) {
        const uint32_t hub = s.heap[at];
        while (at > 0) {
            const uint32_t up = (at - 1) / 2;
            if (!before(hub, s.heap[up])) break;
            s.heap[at] = s.heap[up];
            s.heapAt[s.heap[at]] = at;
            at = up;
        }
        s.heap[at] = hub;
        s.heapAt[hub] = at;
    }

    // Queues hub h with key `key`, or lowers its key if it is queued with a larger one.
    void offer(uint32_t h, float key) {
        if (s.heapAt[h] != kNone) {
            if (!(key < s.key[h])) return;
            s.key[h] = key;
            siftUp(s.heapAt[h]);
            return;
        }
        s.key[h] = key;
        s.heap[size] = h;
        siftUp(size++);
    }

    uint32_t pop() {
        const uint32_t top = s.heap[0];
        s.heapAt[top] = kNone;
        const uint32_t last = s.heap[--size];
        if (size == 0) return top;
        uint32_t at = 0;
        for (;;) {
            uint32_t child = 2 * at + 1;
            if (child >= size) break;
            if (child + 1 < size && before(s.heap[child + 1], s.heap[child])) ++child;
            if (!before(s.heap[child], last)) break;
            s.heap[at] = s.heap[child];
            s.heapAt[s.heap[at]] = at;
            at = child;
        }
        s.heap[at] = last;
        s.heapAt[last] = at;
        return top;
    }
};

// Whether every first-layer slot's node has a hub number (the labels' paths then run
// between hubs only).
bool everySlotIsHub(const vg_graph& g) {
    for (uint32_t p = 0; p < g.firstCount; ++p)
        for (uint32_t j = 0; j < g.first[p].slotCount; ++j)
            if (g.nodeHub[g.slots[g.first[p].slotBegin + j]] == kNone) return false;
    return true;
}

// Relaxes hub h's lanes `from` (+inf: not pending) over its rows of every first-layer
// patch it is a slot of.
void relax(const vg_graph& g, const HubLandmarkScratch& s, Queue& q, uint32_t h, const float* from) {
    const uint32_t node = s.hubNode[h];
    for (uint32_t m = g.nodeFirstBegin[node]; m < g.nodeFirstBegin[node + 1]; ++m) {
        const Membership ms = g.nodeFirst[m];
        const Patch& p = g.first[ms.patch];
        const uint64_t row = p.matrixBegin + uint64_t(ms.slot) * p.slotCount;
        for (uint32_t j = 0; j < p.slotCount; ++j) {
            const uint32_t w = quantum(g.firstDistances, row + j);
            if (j == ms.slot || w == kNoPathQuantum) continue;
            const float length = float(w) * p.scale;
            const uint32_t to = g.nodeHub[g.slots[p.slotBegin + j]];
            float* d = s.distance + uint64_t(to) * kHubLandmarkLanes;
            uint32_t lowered = 0;
            float lowest = kInf;
            for (uint32_t l = 0; l < kHubLandmarkLanes; ++l) {
                const float c = from[l] + length;
                if (c < d[l]) {
                    d[l] = c;
                    lowered |= 1u << l;
                    lowest = c < lowest ? c : lowest;
                }
            }
            if (lowered == 0) continue;
            s.pending[to] = uint16_t(s.pending[to] | lowered);
            q.offer(to, lowest);
        }
    }
}

// A distance in landmark steps, rounded down (so that steps times the scale, as the
// queries compute it, is never above it), at most the largest step.
uint16_t stepsDown(float d, float scale) {
    if (!(d < kInf) || !(scale > 0.0f)) return kLandmarkUnreachable;
    const double x = double(d) / double(scale);
    uint32_t steps = x < 65534.0 ? uint32_t(x) : 65534u;
    while (steps > 0 && float(steps) * scale > d) --steps;
    return uint16_t(steps);
}

}  // namespace

HubLandmarkScratch takeHubLandmarkScratch(const vg_graph& g, Layout& L) {
    const uint64_t H = g.hubTreeCount && g.landmarkCount ? g.hubCount : 0;
    HubLandmarkScratch s;
    s.distance = L.take<float>(H * kHubLandmarkLanes);
    s.key = L.take<float>(H);
    s.heap = L.take<uint32_t>(H);
    s.heapAt = L.take<uint32_t>(H);
    s.pending = L.take<uint16_t>(H);
    s.hubNode = L.take<uint32_t>(H);
    return s;
}

void computeHubLandmarks(const vg_graph& g, const HubLandmarkScratch& s, uint16_t* out) {
    const uint32_t H = g.hubCount, K = g.landmarkCount;
    if (g.hubTreeCount == 0 || K == 0) return;
    if (!everySlotIsHub(g)) {
        for (uint64_t i = 0; i < uint64_t(H) * K; ++i) out[i] = kLandmarkUnreachable;
        return;
    }
    for (uint32_t n = 0; n < g.nodeCount; ++n)
        if (g.nodeHub[n] != kNone) s.hubNode[g.nodeHub[n]] = n;
    for (uint32_t k0 = 0; k0 < K; k0 += kHubLandmarkLanes) {
        const uint32_t lanes = K - k0 < kHubLandmarkLanes ? K - k0 : kHubLandmarkLanes;
        Queue q{s, 0};
        for (uint32_t h = 0; h < H; ++h) {
            float* d = s.distance + uint64_t(h) * kHubLandmarkLanes;
            const uint16_t* table = g.nodeLandmarks + uint64_t(s.hubNode[h]) * K + k0;
            float lowest = kInf;
            uint32_t pending = 0;
            for (uint32_t l = 0; l < kHubLandmarkLanes; ++l) {
                d[l] = l < lanes && table[l] != kLandmarkUnreachable ? float(table[l]) * g.landmarkScale[k0 + l] : kInf;
                if (d[l] < kInf) pending |= 1u << l;
                lowest = d[l] < lowest ? d[l] : lowest;
            }
            s.pending[h] = uint16_t(pending);
            s.heapAt[h] = kNone;
            if (pending) q.offer(h, lowest);
        }
        while (q.size > 0) {
            const uint32_t h = q.pop();
            float from[kHubLandmarkLanes];
            const float* d = s.distance + uint64_t(h) * kHubLandmarkLanes;
            for (uint32_t l = 0; l < kHubLandmarkLanes; ++l) from[l] = (s.pending[h] >> l) & 1u ? d[l] : kInf;
            s.pending[h] = 0;
            relax(g, s, q, h, from);
        }
        for (uint32_t h = 0; h < H; ++h)
            for (uint32_t l = 0; l < lanes; ++l)
                out[uint64_t(h) * K + k0 + l] = stepsDown(s.distance[uint64_t(h) * kHubLandmarkLanes + l], g.landmarkScale[k0 + l]);
    }
}

}  // namespace vg
