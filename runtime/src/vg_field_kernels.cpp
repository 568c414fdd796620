// Kernels of the one-to-all query (vg_field_kernels.h). The row kernels: a portable
// version that unpacks four entries per 6-byte word, and an AVX2 version that unpacks
// sixteen entries from 24 bytes with one byte shuffle and works on eight at a time; each
// entry point does a whole patch, so the per-call cost is paid once per patch rather
// than once per row. The crossing kernel: one loop body, compiled for both.
#include "vg_field_kernels.h"

#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define VG_ROW_KERNELS_AVX2 1
#include <cpuid.h>
#include <immintrin.h>
#else
#define VG_ROW_KERNELS_AVX2 0
#endif

namespace vg {
namespace {

// A run of n consecutive entries k0 .. k0 + n - 1 of a packed array that ends (one past
// its last byte) at `end`; no kernel reads at or beyond `end`.
struct PackedRun {
    const uint8_t* packed;
    const uint8_t* end;
    uint64_t k0;
    uint32_t n;
};

// Row a of patch p over the slots after it, and over its first `count` of those.
PackedRun rowRun(const vg_graph& g, const Patch& p, uint32_t a, uint32_t count) {
    return PackedRun{g.secondDistances, g.secondDistancesEnd, rowStart(p, a), count};
}

constexpr uint32_t kChunk = 64;  // entries unpacked at a time by the portable kernels

// Entries [k0, k0 + n) into out; four at a time from the 48 bits that hold them.
void unpackPortable(const PackedRun& r, uint64_t k0, uint32_t n, uint32_t* __restrict out) {
    uint32_t t = 0;
    if ((k0 & 1) && n > 0) out[t++] = quantum(r.packed, k0);
    const uint8_t* g = r.packed + 3 * ((k0 + t) >> 1);
    for (; t + 4 <= n && g + 6 <= r.end; t += 4, g += 6) {
        const uint64_t w = uint64_t(g[0]) | (uint64_t(g[1]) << 8) | (uint64_t(g[2]) << 16) | (uint64_t(g[3]) << 24) |
                           (uint64_t(g[4]) << 32) | (uint64_t(g[5]) << 40);
        out[t] = uint32_t(w) & 0xFFFu;
        out[t + 1] = uint32_t(w >> 12) & 0xFFFu;
        out[t + 2] = uint32_t(w >> 24) & 0xFFFu;
        out[t + 3] = uint32_t(w >> 36) & 0xFFFu;
    }
    for (; t < n; ++t) out[t] = quantum(r.packed, k0 + t);
}

// Lowers best / from from `base` over the run; its entries (* scale, +inf for no path) go
// to `entries` too when that is not null.
void lowerPortable(const PackedRun& r, float base, float scale, uint32_t tag, float* __restrict best,
                   uint32_t* __restrict from, float* __restrict entries = nullptr) {
    uint32_t q[kChunk];
    for (uint32_t j0 = 0; j0 < r.n; j0 += kChunk) {
        const uint32_t m = r.n - j0 < kChunk ? r.n - j0 : kChunk;
        unpackPortable(r, r.k0 + j0, m, q);
        float* __restrict b = best + j0;
        uint32_t* __restrict f = from + j0;
        for (uint32_t x = 0; x < m; ++x) {
            const float v = base + float(int32_t(q[x])) * scale, cur = b[x];
            const bool lower = (v < cur) & (q[x] != kNoPathQuantum);
            const uint32_t mask = 0u - uint32_t(lower);  // selects written as masks vectorise
            b[x] = lower ? v : cur;
            f[x] = (tag & mask) | (f[x] & ~mask);
        }
        if (entries)
            for (uint32_t x = 0; x < m; ++x)
                entries[j0 + x] = q[x] == kNoPathQuantum ? __builtin_inff() : float(int32_t(q[x])) * scale;
    }
}

// The first entry of the run whose value is `target` (the caller found it there).
uint32_t firstAt(const PackedRun& r, const float* src, float scale, float target) {
    for (uint32_t x = 0; x < r.n; ++x) {
        const uint32_t q = quantum(r.packed, r.k0 + x);
        if (q != kNoPathQuantum && src[x] + float(int32_t(q)) * scale == target) return x;
    }
    return 0;
}

float minPortable(const PackedRun& r, const float* src, float scale) {
    uint32_t q[kChunk];
    float lanes[4] = {__builtin_inff(), __builtin_inff(), __builtin_inff(), __builtin_inff()};
    for (uint32_t j0 = 0; j0 < r.n; j0 += kChunk) {
        const uint32_t m = r.n - j0 < kChunk ? r.n - j0 : kChunk;
        unpackPortable(r, r.k0 + j0, m, q);
        const float* s = src + j0;
        for (uint32_t x = 0; x < m; ++x) {  // four running minima: no chain through one
            const float d = q[x] != kNoPathQuantum ? s[x] + float(int32_t(q[x])) * scale : __builtin_inff();
            float& lane = lanes[x & 3];
            lane = d < lane ? d : lane;
        }
    }
    const float a = lanes[0] < lanes[1] ? lanes[0] : lanes[1], b = lanes[2] < lanes[3] ? lanes[2] : lanes[3];
    return a < b ? a : b;
}

// after[a] = the smallest source label after slot a (up to `last`): a node whose best is
// no more than that cannot be lowered by those sources (entries are >= 0), so its row
// need not be read for them.
void sourcesAfter(const float* src, uint32_t last, float* after) {
    float m = __builtin_inff();
    for (uint32_t a = last + 1; a-- > 0;) {
        after[a] = m;
        m = src[a] < m ? src[a] : m;
    }
}

void relaxNodeBlockPortable(const vg_graph& g, const Patch& p, uint32_t a, uint32_t last, const float* src,
                            const float* after, float* best, uint32_t* from) {
    // Row a of the triangle (a <= last): lowers the nodes after a source, then gives a
    // the best of the sources after it.
    const uint32_t n = p.nodeCount;
    if (src[a] != __builtin_inff() && a + 1 < n)
        lowerPortable(rowRun(g, p, a, n - a - 1), src[a], p.scale, a, best + a + 1, from + a + 1);
    if (a == last || !(after[a] < best[a])) return;
    const PackedRun run = rowRun(g, p, a, last - a);
    const float m = minPortable(run, src + a + 1, p.scale);
    if (m < best[a]) {
        best[a] = m;
        from[a] = a + 1 + firstAt(run, src + a + 1, p.scale, m);
    }
}

// unfoldPoint(c, e, l) for the target side, then crossingLength (vg_graph.h); inlined
// into both the portable and the AVX2 function, where the compiler vectorises it.
__attribute__((always_inline)) inline void crossBatchBody(CrossingBatch& batch) {
    const float* __restrict A = batch.a;
    const float* __restrict B = batch.b;
    const float* __restrict C = batch.c;
    const float* __restrict E = batch.e;
    const float* __restrict L = batch.l;
    const float* __restrict LL = batch.ll;
    const float* __restrict H = batch.half;
    const float* __restrict SX = batch.sx;
    const float* __restrict SY = batch.sy;
    float* __restrict out = batch.length;
    const uint32_t n = batch.count;
    for (uint32_t i = 0; i < n; ++i) {
        const float c = C[i], e = E[i], l = L[i], sx = SX[i], sy = SY[i];
        const float tx = (c * c - e * e + LL[i]) * H[i];
        const float y2 = c * c - tx * tx;
        const bool unfolds = y2 > 0.0f;
        const float ty = __builtin_sqrtf(unfolds ? y2 : 1.0f);
        const float x = sx + (tx - sx) * (sy / (sy + ty));
        const bool meets = (x > 0.0f) & (x < l);
        const float dx = tx - sx, dy = ty + sy;
        const float d = __builtin_sqrtf(dx * dx + dy * dy);
        const float viaU = A[i] + c, viaW = B[i] + e;
        const float viaNode = (viaU < viaW ? viaU : viaW) / kUnfoldSlack;
        const float length = d < viaNode ? viaNode : d;
        out[i] = unfolds & meets ? length : __builtin_inff();
    }
}

#if VG_ROW_KERNELS_AVX2

#define VG_AVX2 __attribute__((target("avx2")))

VG_AVX2 void crossBatchAvx2(CrossingBatch& batch) { crossBatchBody(batch); }

// Sixteen consecutive entries as two vectors of eight 32-bit quanta. An entry starts at
// bit 12k: an even one in the low 12 bits of bytes (3k/2, +1), an odd one in the high 12
// bits of the two bytes it ends in. A byte shuffle puts each entry's two bytes in a
// 16-bit lane, one multiply lifts the lanes whose entry sits low by 4 bits, and one shift
// right by 4 leaves every entry. A run starting at an odd entry reads from the byte that
// holds its high half, with the lane patterns swapped, so blocks always start at the
// run's first entry (and the caller's arrays are accessed at the same offsets for every
// row, which lets the CPU forward one row's stores to the next row's loads).
struct Unpacker {
    __m256i pick, lift;
    const uint8_t* p;  // the next block's first byte
};

VG_AVX2 inline Unpacker unpackerFor(const PackedRun& r) {
    Unpacker u;
    if (r.k0 & 1) {  // entry k0 lies in the high 12 bits of the bytes after 3 (k0 - 1) / 2
        u.pick = _mm256_setr_epi8(0, 1, 2, 3, 3, 4, 5, 6, 6, 7, 8, 9, 9, 10, 11, 12,  //
                                  0, 1, 2, 3, 3, 4, 5, 6, 6, 7, 8, 9, 9, 10, 11, 12);
        u.lift = _mm256_setr_epi16(1, 16, 1, 16, 1, 16, 1, 16, 1, 16, 1, 16, 1, 16, 1, 16);
        u.p = r.packed + 3 * (r.k0 >> 1) + 1;
    } else {
        u.pick = _mm256_setr_epi8(0, 1, 1, 2, 3, 4, 4, 5, 6, 7, 7, 8, 9, 10, 10, 11,  //
                                  0, 1, 1, 2, 3, 4, 4, 5, 6, 7, 7, 8, 9, 10, 10, 11);
        u.lift = _mm256_setr_epi16(16, 1, 16, 1, 16, 1, 16, 1, 16, 1, 16, 1, 16, 1, 16, 1);
        u.p = r.packed + 3 * (r.k0 >> 1);
    }
    return u;
}

// True when every block of the run stays before the end of the packed array (a block
// reads 28 bytes: two 16-byte loads, 12 apart).
VG_AVX2 inline bool runFits(const Unpacker& u, const PackedRun& r) {
    const uint32_t blocks = (r.n + 15) / 16;
    return blocks == 0 || u.p + 24 * uint64_t(blocks - 1) + 28 <= r.end;
}

VG_AVX2 inline void unpack16(Unpacker& u, __m256i* q) {
    const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(u.p));
    const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(u.p + 12));
    const __m256i bytes = _mm256_inserti128_si256(_mm256_castsi128_si256(a), b, 1);
    const __m256i words = _mm256_srli_epi16(_mm256_mullo_epi16(_mm256_shuffle_epi8(bytes, u.pick), u.lift), 4);
    q[0] = _mm256_cvtepu16_epi32(_mm256_castsi256_si128(words));
    q[1] = _mm256_cvtepu16_epi32(_mm256_extracti128_si256(words, 1));
    u.p += 24;
}

VG_AVX2 inline __m256i laneIndex(uint32_t x) {
    return _mm256_add_epi32(_mm256_set1_epi32(int32_t(x)), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
}

// Lanes x .. x + 7 with lo <= lane < hi whose entry has a path.
VG_AVX2 inline __m256i usable(__m256i q, uint32_t x, uint32_t lo, uint32_t hi) {
    const __m256i lane = laneIndex(x);
    const __m256i inside = _mm256_andnot_si256(_mm256_cmpgt_epi32(_mm256_set1_epi32(int32_t(lo)), lane),
                                               _mm256_cmpgt_epi32(_mm256_set1_epi32(int32_t(hi)), lane));
    return _mm256_andnot_si256(_mm256_cmpeq_epi32(q, _mm256_set1_epi32(int32_t(kNoPathQuantum))), inside);
}

// Entries for lanes x .. x + 7 (quanta q, `use` from usable) lower best / from from `base`.
// The arrays are read and written whole (within kRowSlack); the other lanes keep their
// values: masked stores are slow on some CPUs.
VG_AVX2 inline void lowerStep(__m256i q, uint32_t x, __m256i use, __m256 base, __m256 scale, __m256i tag, float* best,
                              uint32_t* from, float* entries = nullptr) {
    const __m256 e = _mm256_mul_ps(_mm256_cvtepi32_ps(q), scale);
    if (entries) {
        const __m256i none = _mm256_cmpeq_epi32(q, _mm256_set1_epi32(int32_t(kNoPathQuantum)));
        _mm256_storeu_ps(entries + x, _mm256_blendv_ps(e, _mm256_set1_ps(__builtin_inff()), _mm256_castsi256_ps(none)));
    }
    const __m256 v = _mm256_add_ps(base, e);
    const __m256 cur = _mm256_loadu_ps(best + x);
    const __m256i lower = _mm256_and_si256(use, _mm256_castps_si256(_mm256_cmp_ps(v, cur, _CMP_LT_OQ)));
    _mm256_storeu_ps(best + x, _mm256_blendv_ps(cur, v, _mm256_castsi256_ps(lower)));
    __m256i* f = reinterpret_cast<__m256i*>(from + x);
    _mm256_storeu_si256(f, _mm256_blendv_epi8(_mm256_loadu_si256(f), tag, lower));
}

// Running minimum of src[lane] + entry over lanes x .. x + 7, per lane, with the first
// lane index that gave each lane its minimum.
VG_AVX2 inline void minStep(__m256i q, uint32_t x, __m256i use, const float* src, __m256 scale, __m256& m,
                            __m256i& arg) {
    const __m256 d = _mm256_add_ps(_mm256_loadu_ps(src + x), _mm256_mul_ps(_mm256_cvtepi32_ps(q), scale));
    const __m256 lower = _mm256_and_ps(_mm256_castsi256_ps(use), _mm256_cmp_ps(d, m, _CMP_LT_OQ));
    m = _mm256_blendv_ps(m, d, lower);
    arg = _mm256_blendv_epi8(arg, laneIndex(x), _mm256_castps_si256(lower));
}

// The smallest lane minimum, and the first index among the lanes that hold it.
VG_AVX2 inline float reduceMin(__m256 m, __m256i arg, uint32_t& first) {
    __m256 h = _mm256_min_ps(m, _mm256_permute2f128_ps(m, m, 1));
    h = _mm256_min_ps(h, _mm256_shuffle_ps(h, h, _MM_SHUFFLE(1, 0, 3, 2)));
    h = _mm256_min_ps(h, _mm256_shuffle_ps(h, h, _MM_SHUFFLE(2, 3, 0, 1)));
    const float v = _mm256_cvtss_f32(h);
    if (v == __builtin_inff()) return v;
    alignas(32) uint32_t lanes[8];
    _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), arg);
    first = ~0u;
    for (uint32_t holds = uint32_t(_mm256_movemask_ps(_mm256_cmp_ps(m, h, _CMP_EQ_OQ))); holds; holds &= holds - 1) {
        const uint32_t x = lanes[__builtin_ctz(holds)];
        first = x < first ? x : first;
    }
    return v;
}

VG_AVX2 void relaxNodeBlockAvx2(const vg_graph& g, const Patch& p, uint32_t last, const float* src,
                                const float* after, float* best, uint32_t* from) {
    const uint32_t n = p.nodeCount;
    const __m256 scale = _mm256_set1_ps(p.scale);
    for (uint32_t a = 0; a <= last; ++a) {
        // One walk over row a serves both ways: it lowers the nodes after a when a is a
        // source, and gives a the best of the sources after it (up to the last). Its
        // lanes are whole slots from a multiple of 8 on (entries of the row before it fill
        // the lanes up to a, masked), so that every row reads and writes best at the
        // same offsets and the CPU forwards one row's stores to the next row's loads.
        const bool lowers = src[a] != __builtin_inff(), lowered = after[a] < best[a];
        const uint32_t endSlot = lowers ? n : lowered ? last + 1 : a + 1;
        const uint32_t s0 = (a + 1) & ~7u, lead = a + 1 - s0;
        const uint64_t k0 = rowStart(p, a);
        const PackedRun run{g.secondDistances, g.secondDistancesEnd, k0 - lead, endSlot - s0};
        if (endSlot <= a + 1) continue;
        Unpacker u = unpackerFor(run);
        if (k0 < lead || !runFits(u, run)) {
            relaxNodeBlockPortable(g, p, a, last, src, after, best, from);
            continue;
        }
        const __m256 base = _mm256_set1_ps(src[a]);
        const __m256i tag = _mm256_set1_epi32(int32_t(a));
        __m256 m = _mm256_set1_ps(__builtin_inff());
        __m256i arg = _mm256_setzero_si256();
        for (uint32_t x = s0; x < endSlot; x += 16) {
            __m256i q[2];
            unpack16(u, q);
            for (uint32_t h = 0; h < 2; ++h) {
                const uint32_t at = x + 8 * h;
                if (lowers && at < n) lowerStep(q[h], at, usable(q[h], at, a + 1, n), base, scale, tag, best, from);
                if (lowered && at <= last) minStep(q[h], at, usable(q[h], at, a + 1, last + 1), src, scale, m, arg);
            }
        }
        uint32_t first = 0;
        const float v = reduceMin(m, arg, first);
        if (v < best[a]) {
            best[a] = v;
            from[a] = first;
        }
    }
}

// Lowers best / from over the whole run from `base`; false (nothing done) when the run's
// blocks would read past the packed array.
VG_AVX2 inline bool lowerRunAvx2(const PackedRun& run, float base, float scale, uint32_t tag, float* best,
                                 uint32_t* from, float* entries = nullptr) {
    Unpacker u = unpackerFor(run);
    if (!runFits(u, run)) return false;
    const __m256 b = _mm256_set1_ps(base), s = _mm256_set1_ps(scale);
    const __m256i t = _mm256_set1_epi32(int32_t(tag));
    for (uint32_t x = 0; x < run.n; x += 16) {
        __m256i q[2];
        unpack16(u, q);
        lowerStep(q[0], x, usable(q[0], x, 0, run.n), b, s, t, best, from, entries);
        if (x + 8 < run.n) lowerStep(q[1], x + 8, usable(q[1], x + 8, 0, run.n), b, s, t, best, from, entries);
    }
    return true;
}

VG_AVX2 void relaxNodeRowAvx2(const vg_graph& g, const Patch& p, uint32_t a, float du, float* best, uint32_t* from) {
    const PackedRun run = rowRun(g, p, a, p.nodeCount - a - 1);
    if (!lowerRunAvx2(run, du, p.scale, a, best + a + 1, from + a + 1))
        lowerPortable(run, du, p.scale, a, best + a + 1, from + a + 1);
}

VG_AVX2 void lowerInteriorAvx2(const vg_graph& g, const Patch& p, const uint64_t* rows, const float* bases,
                               uint32_t count, float* best, uint32_t* from, float* entries, uint32_t stride) {
    const uint32_t interior = p.slotCount - p.nodeCount;
    for (uint32_t r = 0; r < count; ++r) {
        const PackedRun run{g.secondDistances, g.secondDistancesEnd, rows[r], interior};
        float* out = entries + uint64_t(r) * stride;
        if (!lowerRunAvx2(run, bases[r], p.scale, r, best, from, out))
            lowerPortable(run, bases[r], p.scale, r, best, from, out);
    }
}

VG_AVX2 bool decodeAvx2(const PackedRun& run, float scale, float* out) {
    Unpacker u = unpackerFor(run);
    if (!runFits(u, run)) return false;
    const __m256 s = _mm256_set1_ps(scale), inf = _mm256_set1_ps(__builtin_inff());
    const __m256i none = _mm256_set1_epi32(int32_t(kNoPathQuantum));
    for (uint32_t x = 0; x < run.n; x += 16) {
        __m256i q[2];
        unpack16(u, q);
        for (uint32_t h = 0; h < 2; ++h) {
            const __m256 e = _mm256_mul_ps(_mm256_cvtepi32_ps(q[h]), s);
            _mm256_storeu_ps(out + x + 8 * h, _mm256_blendv_ps(e, inf, _mm256_castsi256_ps(_mm256_cmpeq_epi32(q[h], none))));
        }
    }
    return true;
}

#endif

}  // namespace

void relaxNodeBlock(bool avx2, const vg_graph& g, const Patch& p, uint32_t last, const float* src, float* scratch,
                    float* best, uint32_t* from) {
    sourcesAfter(src, last, scratch);
#if VG_ROW_KERNELS_AVX2
    if (avx2) return relaxNodeBlockAvx2(g, p, last, src, scratch, best, from);
#endif
    (void)avx2;
    // Without vectors, one row per source is cheaper than the whole triangle.
    for (uint32_t a = 0; a <= last; ++a)
        if (src[a] != __builtin_inff()) relaxNodeSource(false, g, p, a, src[a], best, from);
}

void relaxNodeSource(bool avx2, const vg_graph& g, const Patch& p, uint32_t a, float du, float* best, uint32_t* from) {
    // The column above the diagonal, entry by entry: entry (j + 1, a) sits slotCount - j - 2
    // after entry (j, a).
    uint64_t e = p.matrixBegin + a - 1;
    for (uint32_t j = 0; j < a; e += p.slotCount - j - 2, ++j) {
        const uint32_t q = quantum(g.secondDistances, e);
        const float d = du + float(int32_t(q)) * p.scale;
        if (q != kNoPathQuantum && d < best[j]) {
            best[j] = d;
            from[j] = a;
        }
    }
    if (a + 1 >= p.nodeCount) return;
#if VG_ROW_KERNELS_AVX2
    if (avx2) return relaxNodeRowAvx2(g, p, a, du, best, from);
#endif
    (void)avx2;
    lowerPortable(rowRun(g, p, a, p.nodeCount - a - 1), du, p.scale, a, best + a + 1, from + a + 1);
}

void lowerInteriorFromRows(bool avx2, const vg_graph& g, const Patch& p, const uint64_t* rows, const float* bases,
                           uint32_t count, float* best, uint32_t* from, float* entries, uint32_t stride) {
#if VG_ROW_KERNELS_AVX2
    if (avx2) return lowerInteriorAvx2(g, p, rows, bases, count, best, from, entries, stride);
#endif
    (void)avx2;
    const uint32_t interior = p.slotCount - p.nodeCount;
    for (uint32_t r = 0; r < count; ++r)
        lowerPortable(PackedRun{g.secondDistances, g.secondDistancesEnd, rows[r], interior}, bases[r], p.scale, r,
                      best, from, entries + uint64_t(r) * stride);
}

void decodeInteriorRow(bool avx2, const vg_graph& g, const Patch& p, uint64_t row, float* out) {
    const PackedRun run{g.secondDistances, g.secondDistancesEnd, row, p.slotCount - p.nodeCount};
#if VG_ROW_KERNELS_AVX2
    if (avx2 && decodeAvx2(run, p.scale, out)) return;
#endif
    (void)avx2;
    uint32_t q[kChunk];
    for (uint32_t j0 = 0; j0 < run.n; j0 += kChunk) {
        const uint32_t m = run.n - j0 < kChunk ? run.n - j0 : kChunk;
        unpackPortable(run, run.k0 + j0, m, q);
        for (uint32_t x = 0; x < m; ++x)
            out[j0 + x] = q[x] == kNoPathQuantum ? __builtin_inff() : float(int32_t(q[x])) * p.scale;
    }
}

void crossBatch(bool avx2, CrossingBatch& batch) {
#if VG_ROW_KERNELS_AVX2
    if (avx2) return crossBatchAvx2(batch);
#endif
    (void)avx2;
    crossBatchBody(batch);
}

bool cpuHasAvx2() {
#if VG_ROW_KERNELS_AVX2
    unsigned a, b, c, d;
    if (!__get_cpuid(1, &a, &b, &c, &d) || !(c & bit_OSXSAVE) || !(c & bit_AVX)) return false;
    unsigned lo, hi;
    __asm__("xgetbv" : "=a"(lo), "=d"(hi) : "c"(0));  // the OS saves the YMM registers
    if ((lo & 6u) != 6u) return false;
    if (!__get_cpuid_count(7, 0, &a, &b, &c, &d)) return false;
    return (b & bit_AVX2) != 0;
#else
    return false;
#endif
}

}  // namespace vg
