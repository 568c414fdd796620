// Kernels of the one-to-all query (vg_field_kernels.h). The row kernels: a portable
// version that unpacks four entries per 6-byte word, and an AVX2 version that unpacks
// sixteen entries from 24 bytes with one byte shuffle and works on eight at a time; each
// entry point takes all the rows of a patch, so the per-call cost is paid once per patch.
// The crossing kernel: in AVX2, eight vertices side by side, each through all the edges of
// their best node. Where the CPU has AVX-512, the row kernels lower sixteen entries at once
// (masked stores instead of blends: ~5% of an igea field, BENCHMARKS.md).
#include "vg_field_kernels.h"

#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define VG_FIELD_KERNELS_AVX2 1
#include <cpuid.h>

#include "vg_packed_avx2.h"
#define VG_AVX512 __attribute__((target("avx2,avx512f")))
#else
#define VG_FIELD_KERNELS_AVX2 0
#endif

namespace vg {
namespace {

constexpr uint32_t kChunk = 64;  // entries unpacked at a time by the portable kernels

// A run of n consecutive entries k0 .. k0 + n - 1 of a packed array that ends (one past
// its last byte) at `end`; no kernel reads at or beyond `end`.
struct PackedRun {
    const uint8_t* packed;
    const uint8_t* end;
    uint64_t k0;
    uint32_t n;
};

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

// Lowers best / from from `base` over the run (tag: what from records); its entries
// (* scale, +inf for no path) go to `entries` too when that is not null.
void lowerPortable(const PackedRun& r, float base, float scale, uint32_t tag, float* __restrict best,
                   uint32_t* __restrict from, float* __restrict entries) {
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

void decodePortable(const PackedRun& r, float scale, float* out) {
    uint32_t q[kChunk];
    for (uint32_t j0 = 0; j0 < r.n; j0 += kChunk) {
        const uint32_t m = r.n - j0 < kChunk ? r.n - j0 : kChunk;
        unpackPortable(r, r.k0 + j0, m, q);
        for (uint32_t x = 0; x < m; ++x)
            out[j0 + x] = q[x] == kNoPathQuantum ? __builtin_inff() : float(int32_t(q[x])) * scale;
    }
}

// crossing() of vg_graph.h with the source side unfolded once per edge: the target side
// unfolded, then the segment between them; +inf where either fails.
inline float crossingAt(const CrossingEdge& E, float a, float c, float e) {
    UnfoldedPoint t;
    if (!unfoldPoint(c, e, E.length, t)) return __builtin_inff();
    return crossingLength(E.source, t, E.length, a + c, E.b + e);
}

#if VG_FIELD_KERNELS_AVX2

// crossingAt for eight (edge, member) pairs in the lanes, operation for operation (with
// unfoldPoint's l * l and 0.5 / l taken from the edge): the edges' values (b, l, ll, half,
// sx, sy), e and c per lane.
VG_AVX2 inline __m256 crossingLanes(__m256 a, __m256 b, __m256 l, __m256 ll, __m256 half, __m256 sx, __m256 sy,
                                    __m256 c, __m256 e) {
    const __m256 zero = _mm256_setzero_ps();
    const __m256 cc = _mm256_mul_ps(c, c);
    const __m256 tx = _mm256_mul_ps(_mm256_add_ps(_mm256_sub_ps(cc, _mm256_mul_ps(e, e)), ll), half);
    const __m256 y2 = _mm256_sub_ps(cc, _mm256_mul_ps(tx, tx));
    const __m256 unfolds = _mm256_cmp_ps(y2, zero, _CMP_GT_OQ);
    const __m256 ty = _mm256_sqrt_ps(_mm256_blendv_ps(_mm256_set1_ps(1.0f), y2, unfolds));
    const __m256 x = _mm256_add_ps(sx, _mm256_mul_ps(_mm256_sub_ps(tx, sx), _mm256_div_ps(sy, _mm256_add_ps(sy, ty))));
    const __m256 meets = _mm256_and_ps(_mm256_cmp_ps(x, zero, _CMP_GT_OQ), _mm256_cmp_ps(x, l, _CMP_LT_OQ));
    const __m256 dx = _mm256_sub_ps(tx, sx), dy = _mm256_add_ps(ty, sy);
    const __m256 d = _mm256_sqrt_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)));
    const __m256 viaU = _mm256_add_ps(a, c), viaW = _mm256_add_ps(b, e);
    const __m256 viaNode = _mm256_div_ps(_mm256_min_ps(viaU, viaW), _mm256_set1_ps(kUnfoldSlack));  // viaU < viaW ? viaU : viaW
    const __m256 length = _mm256_max_ps(viaNode, d);  // d < viaNode ? viaNode : d
    return _mm256_blendv_ps(_mm256_set1_ps(__builtin_inff()), length, _mm256_and_ps(unfolds, meets));
}

// Eight of a node's members side by side (lanes past the last one masked off), each
// lane going through all of the node's edges: an edge's values are broadcast and only w's
// row entry is gathered per edge, and a member's best is written once, after its lowest
// crossing. (With (edge, member) pairs in the lanes, three gathers and a write per pair,
// the kernel took 1.3-1.8 ms of an igea field against 0.7-1.0: BENCHMARKS.md.)
VG_AVX2 void lowerByCrossingsAvx2(const float* rows, float a, const float* c, const CrossingEdge* edges,
                                  uint32_t edgeCount, const uint32_t* members, uint32_t memberCount, float* best) {
    const __m256 va = _mm256_set1_ps(a), inf = _mm256_set1_ps(__builtin_inff());
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    for (uint32_t m0 = 0; m0 < memberCount; m0 += 8) {
        const __m256i live = _mm256_cmpgt_epi32(_mm256_set1_epi32(int32_t(memberCount - m0)), lane);
        const __m256 liveMask = _mm256_castsi256_ps(live);
        const __m256i j = _mm256_maskload_epi32(reinterpret_cast<const int*>(members + m0), live);
        const __m256 vc = _mm256_mask_i32gather_ps(_mm256_setzero_ps(), c, j, liveMask, 4);
        __m256 lowest = inf;
        for (uint32_t k = 0; k < edgeCount; ++k) {
            const CrossingEdge& E = edges[k];
            const __m256 ve = _mm256_mask_i32gather_ps(inf, rows + E.row, j, liveMask, 4);
            const __m256 length = crossingLanes(va, _mm256_set1_ps(E.b), _mm256_set1_ps(E.length),
                                                _mm256_set1_ps(E.lengthSquared), _mm256_set1_ps(E.halfInverse),
                                                _mm256_set1_ps(E.source.x), _mm256_set1_ps(E.source.y), vc, ve);
            lowest = _mm256_min_ps(lowest, length);
        }
        alignas(32) float len[8];
        alignas(32) uint32_t slot[8];
        _mm256_store_ps(len, lowest);
        _mm256_store_si256(reinterpret_cast<__m256i*>(slot), j);
        const uint32_t n = memberCount - m0 < 8 ? memberCount - m0 : 8;
        for (uint32_t i = 0; i < n; ++i) best[slot[i]] = len[i] < best[slot[i]] ? len[i] : best[slot[i]];
    }
}

// Lanes [0, n - j0) of a block of sixteen from j0.
VG_AVX512 inline __mmask16 laneMask(uint32_t j0, uint32_t n) {
    return n - j0 >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << (n - j0)) - 1u);
}

// The slot numbers j0 .. j0 + 15, one per lane.
VG_AVX512 inline __m512i slotsFrom(uint32_t j0) {
    return _mm512_add_epi32(_mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15),
                            _mm512_set1_epi32(int32_t(j0)));
}

// scanSources sixteen slots at a time: a comparison gives the sources' lanes, which a
// register compress packs in slot order (the compress to memory is slow on some CPUs).
VG_AVX512 uint32_t scanSourcesAvx512(const float* dist, float* sent, float* best, uint32_t* from, uint32_t n,
                                     uint32_t* sources, float* labels) {
    const __m512i none = _mm512_set1_epi32(int32_t(kNone));
    uint32_t count = 0;
    for (uint32_t j0 = 0; j0 < n; j0 += 16) {
        const __mmask16 live = laneMask(j0, n);
        const __m512 d = _mm512_maskz_loadu_ps(live, dist + j0);
        _mm512_mask_storeu_ps(best + j0, live, d);
        _mm512_mask_storeu_epi32(from + j0, live, none);
        const __mmask16 lower = _mm512_mask_cmp_ps_mask(live, d, _mm512_maskz_loadu_ps(live, sent + j0), _CMP_LT_OQ);
        _mm512_mask_storeu_ps(sent + j0, lower, d);
        _mm512_storeu_si512(sources + count, _mm512_maskz_compress_epi32(lower, slotsFrom(j0)));
        _mm512_storeu_ps(labels + count, _mm512_maskz_compress_ps(lower, d));
        count += uint32_t(__builtin_popcount(lower));
    }
    return count;
}

VG_AVX512 uint32_t changedSlotsAvx512(const uint32_t* from, uint32_t n, uint32_t* out) {
    const __m512i none = _mm512_set1_epi32(int32_t(kNone));
    uint32_t count = 0;
    for (uint32_t j0 = 0; j0 < n; j0 += 16) {
        const __mmask16 changed = _mm512_mask_cmpneq_epi32_mask(laneMask(j0, n), _mm512_loadu_si512(from + j0), none);
        _mm512_storeu_si512(out + count, _mm512_maskz_compress_epi32(changed, slotsFrom(j0)));
        count += uint32_t(__builtin_popcount(changed));
    }
    return count;
}

VG_AVX2 inline Unpacker unpackerFor(const PackedRun& r) { return unpackerAt(r.packed, r.k0); }

// True when every block of the run stays before the end of the packed array (a block
// reads 28 bytes: two 16-byte loads, 12 apart).
VG_AVX2 inline bool runFits(const Unpacker& u, const PackedRun& r) {
    const uint32_t blocks = (r.n + 15) / 16;
    return blocks == 0 || u.p + 24 * uint64_t(blocks - 1) + 28 <= r.end;
}

// Sixteen entries as two vectors of eight 32-bit quanta.
VG_AVX2 inline void unpack16(Unpacker& u, __m256i* q) {
    const __m256i words = unpackWords(u);
    q[0] = _mm256_cvtepu16_epi32(_mm256_castsi256_si128(words));
    q[1] = _mm256_cvtepu16_epi32(_mm256_extracti128_si256(words, 1));
}

// Entries x .. x + 7 (quanta q) lower best / from from `base`, and go to entries when that
// is not null. The arrays are read and written whole vectors at a time, so the lanes past
// the run write into the caller's slack (vg_field_kernels.h): masks would cost more.
VG_AVX2 inline void lowerStep(__m256i q, uint32_t x, __m256 base, __m256 scale, __m256i tag, float* best,
                              uint32_t* from, float* entries) {
    const __m256 e = _mm256_mul_ps(_mm256_cvtepi32_ps(q), scale);
    const __m256i none = _mm256_cmpeq_epi32(q, _mm256_set1_epi32(int32_t(kNoPathQuantum)));
    if (entries) _mm256_storeu_ps(entries + x, _mm256_blendv_ps(e, _mm256_set1_ps(__builtin_inff()), _mm256_castsi256_ps(none)));
    const __m256 v = _mm256_add_ps(base, e);
    const __m256 cur = _mm256_loadu_ps(best + x);
    const __m256i lower = _mm256_andnot_si256(none, _mm256_castps_si256(_mm256_cmp_ps(v, cur, _CMP_LT_OQ)));
    _mm256_storeu_ps(best + x, _mm256_blendv_ps(cur, v, _mm256_castsi256_ps(lower)));
    __m256i* f = reinterpret_cast<__m256i*>(from + x);
    _mm256_storeu_si256(f, _mm256_blendv_epi8(_mm256_loadu_si256(f), tag, lower));
}

// Lowers best / from over the whole run from `base`; false (nothing done) when the run's
// blocks would read past the packed array.
VG_AVX2 bool lowerRunAvx2(const PackedRun& run, float base, float scale, uint32_t tag, float* best, uint32_t* from,
                          float* entries) {
    Unpacker u = unpackerFor(run);
    if (!runFits(u, run)) return false;
    const __m256 b = _mm256_set1_ps(base), s = _mm256_set1_ps(scale);
    const __m256i t = _mm256_set1_epi32(int32_t(tag));
    for (uint32_t x = 0; x < run.n; x += 16) {
        __m256i q[2];
        unpack16(u, q);
        lowerStep(q[0], x, b, s, t, best, from, entries);
        if (x + 8 < run.n) lowerStep(q[1], x + 8, b, s, t, best, from, entries);
    }
    return true;
}

// lowerRunAvx2 sixteen entries at a time: the same operations per entry, so the same
// bits; a lane is written only where it lowers (masked stores rather than a blend of the
// old values), and nothing past the run.
VG_AVX512 bool lowerRunAvx512(const PackedRun& run, float base, float scale, uint32_t tag, float* best, uint32_t* from,
                              float* entries) {
    Unpacker u = unpackerFor(run);
    if (!runFits(u, run)) return false;
    const __m512 b = _mm512_set1_ps(base), s = _mm512_set1_ps(scale), inf = _mm512_set1_ps(__builtin_inff());
    const __m512i t = _mm512_set1_epi32(int32_t(tag)), none = _mm512_set1_epi32(int32_t(kNoPathQuantum));
    for (uint32_t x = 0; x < run.n; x += 16) {
        const __mmask16 live = run.n - x >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << (run.n - x)) - 1u);
        // (The zero-masking forms: GCC 12 warns about the plain ones' undefined fill.)
        const __m512i q = _mm512_maskz_cvtepu16_epi32(live, unpackWords(u));
        const __m512 e = _mm512_mul_ps(_mm512_maskz_cvtepi32_ps(live, q), s);
        const __mmask16 path = _mm512_mask_cmpneq_epi32_mask(live, q, none);
        if (entries) _mm512_mask_storeu_ps(entries + x, live, _mm512_mask_mov_ps(inf, path, e));
        const __m512 v = _mm512_add_ps(b, e);
        const __mmask16 lower = _mm512_mask_cmp_ps_mask(path, v, _mm512_loadu_ps(best + x), _CMP_LT_OQ);
        _mm512_mask_storeu_ps(best + x, lower, v);
        _mm512_mask_storeu_epi32(from + x, lower, t);
    }
    return true;
}

VG_AVX2 void lowerFromRowsAvx2(const vg_graph& g, float scale, const uint64_t* rows, const float* bases,
                               const uint32_t* tags, uint32_t count, uint32_t n, float* best, uint32_t* from,
                               float* entries, uint32_t stride, PrefetchDrip* drip) {
    // The rows lie apart in the patch matrix, mostly out of the cache: ask for all of them
    // before the first is used, so that their loads overlap (igea's field: 1.14x).
    for (uint32_t r = 0; r < count; ++r) {
        const uintptr_t b = uintptr_t(g.secondDistances + ((3 * rows[r]) >> 1));
        const uintptr_t e = uintptr_t(g.secondDistances + ((3 * (rows[r] + n)) >> 1));
        for (uintptr_t x = b; x < e + 63; x += 64) __builtin_prefetch(reinterpret_cast<const void*>(x));
    }
    const uint32_t share = drip != nullptr ? drip->share(count) : 0;
    for (uint32_t r = 0; r < count; ++r) {
        if (share > 0) drip->issue(share);
        const PackedRun run{g.secondDistances, g.secondDistancesEnd, rows[r], n};
        const uint32_t tag = tags ? tags[r] : r;
        float* kept = entries ? entries + uint64_t(r) * stride : nullptr;
        const bool done = g.avx512 ? lowerRunAvx512(run, bases[r], scale, tag, best, from, kept)
                                   : lowerRunAvx2(run, bases[r], scale, tag, best, from, kept);
        if (!done) lowerPortable(run, bases[r], scale, tag, best, from, kept);
    }
}

// Entries x .. x + 7 (quanta q) as floats into out + x, +inf for no path.
VG_AVX2 inline void decodeStep(__m256i q, uint32_t x, __m256 scale, float* out) {
    const __m256 e = _mm256_mul_ps(_mm256_cvtepi32_ps(q), scale);
    const __m256i none = _mm256_cmpeq_epi32(q, _mm256_set1_epi32(int32_t(kNoPathQuantum)));
    _mm256_storeu_ps(out + x, _mm256_blendv_ps(e, _mm256_set1_ps(__builtin_inff()), _mm256_castsi256_ps(none)));
}

VG_AVX2 bool decodeAvx2(const PackedRun& run, float scale, float* out) {
    Unpacker u = unpackerFor(run);
    if (!runFits(u, run)) return false;
    const __m256 s = _mm256_set1_ps(scale);
    for (uint32_t x = 0; x < run.n; x += 16) {
        __m256i q[2];
        unpack16(u, q);
        decodeStep(q[0], x, s, out);
        // Not the second eight past the run, as lowerRunAvx2: a row's decoded entries end
        // within its stride (entriesStride), so rows may be decoded in any order.
        if (x + 8 < run.n) decodeStep(q[1], x + 8, s, out);
    }
    return true;
}

#endif

}  // namespace

void lowerFromRows(bool avx2, const vg_graph& g, float scale, const uint64_t* rows, const float* bases,
                   const uint32_t* tags, uint32_t count, uint32_t n, float* best, uint32_t* from, float* entries,
                   uint32_t stride, PrefetchDrip* drip) {
#if VG_FIELD_KERNELS_AVX2
    if (avx2) return lowerFromRowsAvx2(g, scale, rows, bases, tags, count, n, best, from, entries, stride, drip);
#endif
    (void)avx2;
    const uint32_t share = drip != nullptr ? drip->share(count) : 0;
    for (uint32_t r = 0; r < count; ++r) {
        if (share > 0) drip->issue(share);
        lowerPortable(PackedRun{g.secondDistances, g.secondDistancesEnd, rows[r], n}, bases[r], scale, tags ? tags[r] : r,
                      best, from, entries ? entries + uint64_t(r) * stride : nullptr);
    }
}

void decodeRow(bool avx2, const vg_graph& g, float scale, uint64_t row, uint32_t n, float* out) {
    const PackedRun run{g.secondDistances, g.secondDistancesEnd, row, n};
#if VG_FIELD_KERNELS_AVX2
    if (avx2 && decodeAvx2(run, scale, out)) return;
#endif
    (void)avx2;
    decodePortable(run, scale, out);
}

void lowerByCrossings(bool avx2, const float* rows, float a, const float* c, const CrossingEdge* edges,
                      uint32_t edgeCount, const uint32_t* members, uint32_t memberCount, float* best) {
#if VG_FIELD_KERNELS_AVX2
    if (avx2) return lowerByCrossingsAvx2(rows, a, c, edges, edgeCount, members, memberCount, best);
#endif
    (void)avx2;
    for (uint32_t m = 0; m < memberCount; ++m) {
        const uint32_t j = members[m];
        float lowest = best[j];
        for (uint32_t k = 0; k < edgeCount; ++k) {
            const float d = crossingAt(edges[k], a, c[j], rows[edges[k].row + j]);
            lowest = d < lowest ? d : lowest;
        }
        best[j] = lowest;
    }
}

uint32_t scanSources(bool avx512, const float* dist, float* sent, float* best, uint32_t* from, uint32_t n,
                     uint32_t* sources, float* labels) {
#if VG_FIELD_KERNELS_AVX2
    if (avx512) return scanSourcesAvx512(dist, sent, best, from, n, sources, labels);
#endif
    (void)avx512;
    uint32_t count = 0;
    for (uint32_t j = 0; j < n; ++j) {
        best[j] = dist[j];
        from[j] = kNone;
        if (dist[j] < sent[j]) {
            sent[j] = dist[j];
            sources[count] = j;
            labels[count++] = dist[j];
        }
    }
    return count;
}

uint32_t changedSlots(bool avx512, const uint32_t* from, uint32_t n, uint32_t* out) {
#if VG_FIELD_KERNELS_AVX2
    if (avx512) return changedSlotsAvx512(from, n, out);
#endif
    (void)avx512;
    uint32_t count = 0;
    for (uint32_t j = 0; j < n; ++j)
        if (from[j] != kNone) out[count++] = j;
    return count;
}

#if VG_FIELD_KERNELS_AVX2
namespace {

// The register states the OS saves (XCR0): bits 1-2 SSE and AVX, 5-7 AVX-512's.
unsigned savedStates() {
    unsigned lo, hi;
    __asm__("xgetbv" : "=a"(lo), "=d"(hi) : "c"(0));
    return lo;
}

// The extended feature flags (CPUID leaf 7, EBX), 0 where the leaf is missing.
unsigned extendedFeatures() {
    unsigned a, b, c, d;
    return __get_cpuid_count(7, 0, &a, &b, &c, &d) ? b : 0u;
}

}  // namespace
#endif

bool cpuHasAvx2() {
#if VG_FIELD_KERNELS_AVX2
    unsigned a, b, c, d;
    if (!__get_cpuid(1, &a, &b, &c, &d) || !(c & bit_OSXSAVE) || !(c & bit_AVX)) return false;
    return (savedStates() & 6u) == 6u && (extendedFeatures() & bit_AVX2) != 0;
#else
    return false;
#endif
}

bool cpuHasAvx512() {
#if VG_FIELD_KERNELS_AVX2
    return cpuHasAvx2() && (extendedFeatures() & bit_AVX512F) != 0 && (savedStates() & 0xE0u) == 0xE0u;
#else
    return false;
#endif
}

}  // namespace vg
