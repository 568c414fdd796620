#include "hub_label_runs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

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
constexpr uint32_t kNoSlot = UINT32_MAX;

// Row `row` (S quanta; column `slot` is the node itself, kNoNode columns have none) of a
// node whose relaxing lanes are `source` (+inf in the others), against the lanes of the
// row's nodes (`bound`, kLanes per node, `to`): the columns where some lane of source +
// quantum * scale, in Real, is lower, into hitColumn. Returns their number. With doubles
// against the distances, the exact test; with floats against their upper bounds, the
// screen (BlockRuns::search: why it keeps every column the exact test would).
template <class Real>
uint32_t lowerHits(const Real* source, double scale, const uint16_t* row, uint32_t S, uint32_t slot, uint32_t noPath,
                   const uint32_t* to, const Real* bound, uint32_t* hitColumn) {
    uint32_t hits = 0;
    for (uint32_t j = 0; j < S; ++j) {
        if (row[j] == noPath || j == slot || to[j] == kNoNode) continue;
        const Real w = Real(double(row[j]) * scale);
        const Real* n = bound + uint64_t(to[j]) * kLanes;
        uint32_t mask = 0;
        for (uint32_t i = 0; i < kLanes; ++i) mask |= uint32_t(source[i] + w < n[i]) << i;
        hitColumn[hits] = j;
        hits += mask != 0;
    }
    return hits;
}

#if VG_LABEL_RUNS_AVX2
// The exact test, four lanes per instruction (the same sums and comparisons).
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

// The screen, eight float lanes per instruction: a node's 16 bounds are one cache line.
__attribute__((target("avx2"))) uint32_t screenHitsAvx2(const float* source, double scale, const uint16_t* row,
                                                        uint32_t S, uint32_t slot, uint32_t noPath, const uint32_t* to,
                                                        const float* near, uint32_t* hitColumn) {
    const __m256 s0 = _mm256_loadu_ps(source), s1 = _mm256_loadu_ps(source + 8);
    uint32_t hits = 0;
    for (uint32_t j = 0; j < S; ++j) {
        if (row[j] == noPath || j == slot || to[j] == kNoNode) continue;
        const __m256 w = _mm256_set1_ps(float(double(row[j]) * scale));
        const float* n = near + uint64_t(to[j]) * kLanes;
        const __m256 below0 = _mm256_cmp_ps(_mm256_add_ps(s0, w), _mm256_load_ps(n), _CMP_LT_OQ);
        const __m256 below1 = _mm256_cmp_ps(_mm256_add_ps(s1, w), _mm256_load_ps(n + 8), _CMP_LT_OQ);
        hitColumn[hits] = j;
        hits += _mm256_movemask_ps(_mm256_or_ps(below0, below1)) != 0;
    }
    return hits;
}
#endif

// Whether to take the AVX2 kernels: allowed and the processor has it.
bool avx2Usable(bool allowed) {
#if VG_LABEL_RUNS_AVX2
    return allowed && __builtin_cpu_supports("avx2");
#else
    (void)allowed;
    return false;
#endif
}

// d as a float, +inf beyond the floats' range (where a conversion is undefined). The
// distances of a run that screens all lie within it (screenable).
float toFloat(double d) {
    return d <= double(std::numeric_limits<float>::max()) ? float(d) : std::numeric_limits<float>::infinity();
}

// A float at least d * (1 + 2^-21) (d >= 0): round to nearest moves d * (1 + 2^-20) by at
// most 2^-24 of itself.
float upperBound(double d) { return toFloat(d * (1.0 + 0x1p-20)); }

// Whether every finite distance of a run over `o` is 0 or a normal float, so that the
// screen's roundings are relative: each step per quantum 0 or in [1e-30, 1e20] (a
// shortest path has fewer than 2^32 edges of at most 65535 quanta: below 3e34).
bool screenable(const LabelOverlay& o) {
    for (double s : o.scale)
        if (!(s == 0 || (s >= 1e-30 && s <= 1e20))) return false;
    return true;
}

// The unit every distance of a run over `o` is a whole multiple of: the lowest set bit of
// any patch's step per quantum (a float, so a quantum's distance is exact in a double), or
// 0 where a step is not a finite positive or zero double.
double commonUnit(const LabelOverlay& o) {
    double unit = HUGE_VAL;
    for (double s : o.scale) {
        if (s == 0) continue;
        if (!(s > 0 && s < HUGE_VAL)) return 0;
        int exponent;
        std::frexp(s, &exponent);
        // s = m * 2^(exponent - 53) with m a whole number below 2^53: strip m's zero bits.
        uint64_t m = uint64_t(std::ldexp(s, 53 - exponent));
        int shift = exponent - 53;
        while ((m & 1u) == 0) m >>= 1, ++shift;
        unit = std::min(unit, std::ldexp(1.0, shift));
    }
    return unit;
}

// One step of Floyd-Warshall on row `row` of an S-column matrix through row `through`
// (`via` = row[k]): row[j] = min(row[j], via + through[j]). Both terms are at most 4095
// (closePatchMatrix: why), so sums fit 16 bits.
void closeRow(uint16_t* row, const uint16_t* through, uint16_t via, uint32_t S) {
    for (uint32_t j = 0; j < S; ++j) {
        const uint16_t sum = uint16_t(via + through[j]);
        row[j] = sum < row[j] ? sum : row[j];
    }
}

#if VG_LABEL_RUNS_AVX2
__attribute__((target("avx2"))) void closeRowAvx2(uint16_t* row, const uint16_t* through, uint16_t via, uint32_t S) {
    const __m256i v = _mm256_set1_epi16(short(via));
    uint32_t j = 0;
    for (; j + 16 <= S; j += 16) {
        __m256i* r = reinterpret_cast<__m256i*>(row + j);
        const __m256i t = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(through + j));
        _mm256_storeu_si256(r, _mm256_min_epu16(_mm256_loadu_si256(r), _mm256_add_epi16(t, v)));
    }
    closeRow(row + j, through + j, via, S - j);
}
#endif

}  // namespace

void closePatchMatrix(LabelOverlay& o, uint32_t p, bool avx2) {
    const uint32_t S = o.slotBegin[p + 1] - o.slotBegin[p];
    uint16_t* m = o.quanta.data() + o.quantaBegin[p];
    const uint32_t* node = o.slotNode.data() + o.slotBegin[p];
    if (o.closed.size() != o.scale.size())
        throw std::logic_error("closePatchMatrix: o.closed is not sized to the patches");
    for (uint32_t i = 0; i < S; ++i)
        for (uint32_t j = 0; j < S; ++j) {
            const uint16_t entry = m[uint64_t(i) * S + j];
            if (node[i] != kNoNode && node[j] != kNoNode && (entry >= o.noPath || entry > 4094))
                return;  // "no path", or entries past 12 bits that could sum past 16: left open
        }
    const bool useAvx2 = avx2Usable(avx2);
    // Only rows of slots with a node are read by the runs, and only those are closed; the
    // chains pass only through such slots, as the graph's paths do. Each sum is of an entry
    // between two of them (under 4095) and one of at most 4095 (a column without a node may
    // say "no path"; the runs never read those columns): it fits 16 bits.
    for (uint32_t k = 0; k < S; ++k) {
        if (node[k] == kNoNode) continue;
        const uint16_t* through = m + uint64_t(k) * S;
        for (uint32_t i = 0; i < S; ++i) {
            uint16_t* row = m + uint64_t(i) * S;
            if (i == k || node[i] == kNoNode) continue;
#if VG_LABEL_RUNS_AVX2
            if (useAvx2) {
                closeRowAvx2(row, through, row[k], S);
                continue;
            }
#endif
            closeRow(row, through, row[k], S);
        }
    }
    o.closed[p] = 1;
}

void BlockRuns::lower(uint32_t node, const double* lanes, uint32_t via) {
    double* d = dist_.data() + uint64_t(node) * kLanes;
    double key = kInf, largest = 0;
    uint32_t lowered = 0;
    for (uint32_t i = 0; i < kLanes; ++i) {
        if (!(lanes[i] < d[i])) continue;
        d[i] = lanes[i];
        near_[uint64_t(node) * kLanes + i] = upperBound(lanes[i]);
        via_[uint64_t(node) * kLanes + i] = via;
        lowered |= 1u << i;
        key = std::min(key, lanes[i]);
        largest = std::max(largest, lanes[i]);
    }
    if (lowered == 0) return;
    largest_ = std::max(largest_, largest);
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
    const bool useAvx2 = avx2Usable(avx2);
    const bool anyClosed = std::find(o.closed.begin(), o.closed.end(), uint8_t(1)) != o.closed.end();
    search(o, sources, count, leafBegin, leafEnd, useAvx2, anyClosed);
    skippedRows_ = anyClosed;
    if (!anyClosed) return;
    // Skipping rows gives a Dijkstra's distances only if every sum was exact (search: why):
    // each is some assigned distance plus one entry, all whole multiples of the unit, so
    // exact while below 2^53 units. Else (never seen) the search again without skipping.
    double longestEntry = 0;
    for (double scale : o.scale) longestEntry = std::max(longestEntry, scale * 65535.0);
    const double unit = commonUnit(o);
    if (!(unit > 0 && largest_ + longestEntry <= std::ldexp(unit, 53))) {
        search(o, sources, count, leafBegin, leafEnd, useAvx2, false);
        skippedRows_ = false;
    }
}

void BlockRuns::search(const LabelOverlay& o, const uint32_t* sources, uint32_t count, uint32_t leafBegin,
                       uint32_t leafEnd, bool useAvx2, bool skipClosed) {
    const size_t nodes = o.memberBegin.size() - 1;
    if (pending_.size() != nodes) {
        dist_.assign(nodes * kLanes, kInf);
        via_.assign(nodes * kLanes, kNoSlot);
        // A node's 16 bounds on one cache line: 64-byte aligned.
        nearStorage_.assign(nodes * kLanes + kLanes, std::numeric_limits<float>::infinity());
        near_ = nearStorage_.data() + (16 - (reinterpret_cast<uintptr_t>(nearStorage_.data()) / 4) % 16) % 16;
        key_.assign(nodes, kInf);
        queue_.reset(nodes);
        pending_.assign(nodes, 0);
        reached_.assign(nodes, 0);
        touched_.clear();
    }
    for (uint32_t n : touched_) {
        std::fill(dist_.begin() + int64_t(n) * kLanes, dist_.begin() + int64_t(n + 1) * kLanes, kInf);
        std::fill(near_ + uint64_t(n) * kLanes, near_ + uint64_t(n + 1) * kLanes,
                  std::numeric_limits<float>::infinity());
        pending_[n] = 0;
        reached_[n] = 0;
    }
    touched_.clear();
    queue_.clear();
    largest_ = 0;
    rowsRead_ = 0;
    auto reach = [&](uint32_t n) {
        if (reached_[n]) return;
        reached_[n] = 1;
        touched_.push_back(n);
    };
    double lanes[kLanes];
    for (uint32_t i = 0; i < count; ++i) {
        for (uint32_t k = 0; k < kLanes; ++k) lanes[k] = k == i ? 0.0 : kInf;
        reach(sources[i]);
        lower(sources[i], lanes, kNoSlot);
    }
    // Each column is screened against the nodes' float upper bounds (near_, half the bytes
    // of their doubles): if source + w < n in double (w = quantum * scale), then in float
    // fl(fl(source) + fl(w)) <= (source + w)(1 + 2^-24)^2 < n (1 + 2^-22) < upperBound(n),
    // every rounding relative where screenable holds. So the screen keeps every column the
    // double test would, and lower() decides on doubles: the same distances, bit for bit.
    //
    // Skipping (skipClosed): a lane that node u got through slot c of a closed patch P
    // (from v's row, at d(v) + P[v][c]) is not relaxed along u's row at c. When v relaxed,
    // every column x of that row was offered d(v) + P[v][x] <= d(v) + P[v][c] + P[c][x]
    // (P closed), which is what u's row would offer; with exact sums (run checks them) the
    // search still ends at a Dijkstra's distances. Half of the rows go (igea).
    const bool screen = screenable(o);
    double source[kLanes], candidate[kLanes];
    float sourceFloat[kLanes];
    const auto before = [this](uint32_t a, uint32_t b) { return this->before(a, b); };
    while (!queue_.empty()) {
        const uint32_t u = queue_.pop(before);
        const uint32_t relax = pending_[u];
        pending_[u] = 0;
        const double* du = distances(u);
        const uint32_t* viaU = via_.data() + uint64_t(u) * kLanes;
        uint32_t loaded = UINT32_MAX;  // the lanes source holds (none yet)
        for (uint32_t m = o.memberBegin[u]; m < o.memberBegin[u + 1]; ++m) {
            const uint32_t p = o.members[m].first, slot = o.members[m].second;
            if (o.patchLeaf[p] < leafBegin || o.patchLeaf[p] >= leafEnd) continue;  // outside the subtree
            uint32_t lanesHere = relax;
            if (skipClosed && o.closed[p]) {
                const uint32_t here = o.slotBegin[p] + slot;
                for (uint32_t i = 0; i < kLanes; ++i)
                    if (viaU[i] == here) lanesHere &= ~(1u << i);
                if (lanesHere == 0) continue;
            }
            if (lanesHere != loaded) {
                for (uint32_t i = 0; i < kLanes; ++i) {
                    source[i] = (lanesHere >> i) & 1u ? du[i] : kInf;
                    sourceFloat[i] = toFloat(source[i]);
                }
                loaded = lanesHere;
            }
            ++rowsRead_;
            const uint32_t S = o.slotBegin[p + 1] - o.slotBegin[p];
            const uint16_t* row = o.quanta.data() + o.quantaBegin[p] + uint64_t(slot) * S;
            const uint32_t* to = o.slotNode.data() + o.slotBegin[p];
            const double scale = o.scale[p];
            if (hitColumn_.size() < S) hitColumn_.resize(S);
            uint32_t* hitColumn = hitColumn_.data();
            uint32_t hits;
#if VG_LABEL_RUNS_AVX2
            if (useAvx2)
                hits = screen ? screenHitsAvx2(sourceFloat, scale, row, S, slot, o.noPath, to, near_, hitColumn)
                              : lowerHitsAvx2(source, scale, row, S, slot, o.noPath, to, dist_.data(), hitColumn);
            else
#endif
                hits = screen ? lowerHits(sourceFloat, scale, row, S, slot, o.noPath, to, near_, hitColumn)
                              : lowerHits(source, scale, row, S, slot, o.noPath, to, dist_.data(), hitColumn);
            // A node at two columns of one row (two slots of a patch) passes at most twice;
            // lower() tests against its lanes as they are then, so the second is exact too.
            const uint32_t viaBase = o.slotBegin[p];
            for (uint32_t h = 0; h < hits; ++h) {
                const uint32_t j = hitColumn[h];
                const double w = double(row[j]) * scale;
                for (uint32_t i = 0; i < kLanes; ++i) candidate[i] = source[i] + w;
                reach(to[j]);
                lower(to[j], candidate, viaBase + j);
            }
        }
    }
}

}  // namespace vorogeo
