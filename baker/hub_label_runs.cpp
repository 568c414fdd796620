#include "hub_label_runs.h"

#include <algorithm>
#include <limits>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define VG_LABEL_RUNS_AVX2 1
#else
#define VG_LABEL_RUNS_AVX2 0
#endif

namespace vorogeo {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr uint32_t kLanes = BlockRuns::kLanes;
constexpr uint32_t kNoNode = UINT32_MAX;

// Row `row` (S quanta; column `slot` is the node itself, kNoNode columns have none) of a
// node whose relaxing lanes are `source` (+inf in the others), against the lanes of the
// row's nodes (dist, kLanes per node, `to`): the columns where some lane of source +
// quantum * scale is lower, into hitColumn. Returns their number.
uint32_t lowerHits(const double* source, double scale, const uint16_t* row, uint32_t S, uint32_t slot, uint32_t noPath,
                   const uint32_t* to, const double* dist, uint32_t* hitColumn) {
    uint32_t hits = 0;
    for (uint32_t j = 0; j < S; ++j) {
        if (row[j] == noPath || j == slot || to[j] == kNoNode) continue;
        const double w = double(row[j]) * scale;
        const double* n = dist + uint64_t(to[j]) * kLanes;
        uint32_t mask = 0;
        for (uint32_t i = 0; i < kLanes; ++i) mask |= uint32_t(source[i] + w < n[i]) << i;
        hitColumn[hits] = j;
        hits += mask != 0;
    }
    return hits;
}

#if VG_LABEL_RUNS_AVX2
// The same, four lanes per instruction (the same sums and comparisons).
__attribute__((target("avx2"))) uint32_t lowerHitsAvx2(const double* source, double scale, const uint16_t* row,
                                                       uint32_t S, uint32_t slot, uint32_t noPath, const uint32_t* to,
                                                       const double* dist, uint32_t* hitColumn) {
    const __m256d s0 = _mm256_loadu_pd(source), s1 = _mm256_loadu_pd(source + 4), s2 = _mm256_loadu_pd(source + 8),
                  s3 = _mm256_loadu_pd(source + 12);
    uint32_t hits = 0;
    for (uint32_t j = 0; j < S; ++j) {
        if (row[j] == noPath || j == slot || to[j] == kNoNode) continue;
        const __m256d w = _mm256_set1_pd(double(row[j]) * scale);
        const double* n = dist + uint64_t(to[j]) * kLanes;
        const int m0 = _mm256_movemask_pd(_mm256_cmp_pd(_mm256_add_pd(s0, w), _mm256_loadu_pd(n), _CMP_LT_OQ));
        const int m1 = _mm256_movemask_pd(_mm256_cmp_pd(_mm256_add_pd(s1, w), _mm256_loadu_pd(n + 4), _CMP_LT_OQ));
        const int m2 = _mm256_movemask_pd(_mm256_cmp_pd(_mm256_add_pd(s2, w), _mm256_loadu_pd(n + 8), _CMP_LT_OQ));
        const int m3 = _mm256_movemask_pd(_mm256_cmp_pd(_mm256_add_pd(s3, w), _mm256_loadu_pd(n + 12), _CMP_LT_OQ));
        hitColumn[hits] = j;
        hits += (m0 | m1 | m2 | m3) != 0;
    }
    return hits;
}
#endif

}  // namespace

void BlockRuns::lower(uint32_t node, const double* lanes) {
    double* d = dist_.data() + uint64_t(node) * kLanes;
    double key = kInf;
    uint32_t lowered = 0;
    for (uint32_t i = 0; i < kLanes; ++i) {
        if (!(lanes[i] < d[i])) continue;
        d[i] = lanes[i];
        lowered |= 1u << i;
        key = std::min(key, lanes[i]);
    }
    if (lowered == 0) return;
    pending_[node] = uint16_t(pending_[node] | lowered);
    push(node, key);
}

void BlockRuns::push(uint32_t node, double key) {
    if (queue_.queued(node) && !(key < key_[node])) return;
    key_[node] = key;
    queue_.push(node, [this](uint32_t a, uint32_t b) { return before(a, b); });
}

void BlockRuns::run(const LabelOverlay& o, const uint32_t* sources, uint32_t count, uint32_t leafBegin,
                    uint32_t leafEnd, bool avx2) {
    const size_t nodes = o.memberBegin.size() - 1;
    if (pending_.size() != nodes) {
        dist_.assign(nodes * kLanes, kInf);
        key_.assign(nodes, kInf);
        queue_.reset(nodes);
        pending_.assign(nodes, 0);
        reached_.assign(nodes, 0);
        touched_.clear();
    }
    for (uint32_t n : touched_) {
        std::fill(dist_.begin() + int64_t(n) * kLanes, dist_.begin() + int64_t(n + 1) * kLanes, kInf);
        pending_[n] = 0;
        reached_[n] = 0;
    }
    touched_.clear();
    queue_.clear();
#if VG_LABEL_RUNS_AVX2
    const bool useAvx2 = avx2 && __builtin_cpu_supports("avx2");
#else
    const bool useAvx2 = false;
    (void)avx2;
#endif
    auto reach = [&](uint32_t n) {
        if (reached_[n]) return;
        reached_[n] = 1;
        touched_.push_back(n);
    };
    double lanes[kLanes];
    for (uint32_t i = 0; i < count; ++i) {
        for (uint32_t k = 0; k < kLanes; ++k) lanes[k] = k == i ? 0.0 : kInf;
        reach(sources[i]);
        lower(sources[i], lanes);
    }
    double source[kLanes], candidate[kLanes];
    const auto before = [this](uint32_t a, uint32_t b) { return this->before(a, b); };
    while (!queue_.empty()) {
        const uint32_t u = queue_.pop(before);
        const uint32_t relax = pending_[u];
        pending_[u] = 0;
        const double* du = distances(u);
        for (uint32_t i = 0; i < kLanes; ++i) source[i] = (relax >> i) & 1u ? du[i] : kInf;
        for (uint32_t m = o.memberBegin[u]; m < o.memberBegin[u + 1]; ++m) {
            const uint32_t p = o.members[m].first, slot = o.members[m].second;
            if (o.patchLeaf[p] < leafBegin || o.patchLeaf[p] >= leafEnd) continue;  // outside the subtree
            const uint32_t S = o.slotBegin[p + 1] - o.slotBegin[p];
            const uint16_t* row = o.quanta.data() + o.quantaBegin[p] + uint64_t(slot) * S;
            const uint32_t* to = o.slotNode.data() + o.slotBegin[p];
            const double scale = o.scale[p];
            if (hitColumn_.size() < S) hitColumn_.resize(S);
#if VG_LABEL_RUNS_AVX2
            const uint32_t hits = useAvx2 ? lowerHitsAvx2(source, scale, row, S, slot, o.noPath, to, dist_.data(), hitColumn_.data())
                                          : lowerHits(source, scale, row, S, slot, o.noPath, to, dist_.data(), hitColumn_.data());
#else
            const uint32_t hits = lowerHits(source, scale, row, S, slot, o.noPath, to, dist_.data(), hitColumn_.data());
#endif
            // Each column is a different node, so lowering one never changes another's test.
            for (uint32_t h = 0; h < hits; ++h) {
                const uint32_t j = hitColumn_[h];
                const double w = double(row[j]) * scale;
                for (uint32_t i = 0; i < kLanes; ++i) candidate[i] = source[i] + w;
                reach(to[j]);
                lower(to[j], candidate);
            }
        }
    }
}

}  // namespace vorogeo
