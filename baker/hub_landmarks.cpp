#include "hub_landmarks.h"

#include <cmath>
#include <limits>

#include "hub_labels.h"
#include "parallel.h"
#include "quad_heap.h"

namespace vorogeo {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// One landmark's values at every node: the table's at the first-layer nodes, then a
// Dijkstra over the overlay from all of them at once (each node settles once, at the least
// of its own value and a settled neighbour's plus the entry between them).
void lowerLandmark(const fb::Graph& g, const FirstLayerOverlay& o, uint32_t k, std::vector<double>& dist,
                   QuadHeap& queue) {
    const uint32_t N = g.node_vertex()->size(), K = g.landmark_scale()->size();
    const double scale = double(g.landmark_scale()->Get(k));
    dist.assign(N, kInf);
    queue.reset(N);
    auto before = [&](uint32_t a, uint32_t b) { return dist[a] < dist[b] || (dist[a] == dist[b] && a < b); };
    const auto* firstBegin = g.node_first_begin();
    for (uint32_t n = 0; n < N; ++n) {
        const uint16_t q = g.node_landmarks()->Get(n * K + k);
        if (firstBegin->Get(n) == firstBegin->Get(n + 1) || q == kHubUnreachable) continue;
        dist[n] = double(q) * scale;
        queue.push(n, before);
    }
    while (!queue.empty()) {
        const uint32_t u = queue.pop(before);
        for (uint32_t m = firstBegin->Get(u); m < firstBegin->Get(u + 1); ++m) {
            const fb::Membership* ms = g.node_first()->Get(m);
            const uint32_t p = ms->patch(), slot = ms->slot();
            const fb::PatchRecord& r = *g.first_patches()->Get(p);
            const uint32_t S = r.slot_count();
            const uint16_t* row = o.quanta.data() + o.quantaBegin[p] + uint64_t(slot) * S;
            for (uint32_t j = 0; j < S; ++j) {
                if (j == slot || row[j] == o.noPath) continue;
                const uint32_t to = o.slotNode[r.slot_begin() + j];
                const double d = dist[u] + double(row[j]) * o.scale[p];
                if (!(d < dist[to])) continue;
                dist[to] = d;
                queue.push(to, before);
            }
        }
    }
}

uint16_t stepsDown(double d, float scale) {
    if (!std::isfinite(d) || !(scale > 0.0f)) return kHubUnreachable;
    uint32_t steps = d / double(scale) < 65534.0 ? uint32_t(d / double(scale)) : 65534u;
    while (steps > 0 && double(float(steps) * scale) > d) --steps;  // the runtime's product
    return uint16_t(steps);
}

}  // namespace

std::vector<uint16_t> hubLandmarkSteps(const fb::Graph& g, const FirstLayerOverlay& overlay,
                                       const std::vector<uint32_t>& hubNode) {
    const uint32_t K = g.landmark_scale() ? g.landmark_scale()->size() : 0;
    const size_t H = hubNode.size();
    std::vector<uint16_t> out(H * K, kHubUnreachable);
    if (K == 0) return out;
    struct Scratch {
        std::vector<double> dist;
        QuadHeap queue;
    };
    PerThread<Scratch> scratch;
    parallelFor(K, [&](size_t k) {
        Scratch& s = scratch.local();
        lowerLandmark(g, overlay, uint32_t(k), s.dist, s.queue);
        const float scale = g.landmark_scale()->Get(uint32_t(k));
        for (size_t h = 0; h < H; ++h) out[h * K + k] = stepsDown(s.dist[hubNode[h]], scale);
    });
    return out;
}

}  // namespace vorogeo
