// Inner rows computed at vg_open (vg_inner_rows.h). Per first-layer patch f and per 16 of
// its slots, one search over f's second-layer node graph in which a node holds 16
// distances (lane i: from the block's slot i): a row of a patch matrix, read once, lowers
// all 16. The search is label-correcting: a node leaves the queue keyed by the smallest
// lane lowered since it last relaxed, relaxes the lowered lanes, and may come back. It
// ends at the least path sums, the same bits in any order (vorogeo_inner_rows.h), which
// is what lets the runtime compute what the baker computed with another search.
#include "vg_inner_rows.h"

#include "vg_layout.h"
#include "vorogeo_inner_rows.h"

#if defined(__x86_64__)
#include <immintrin.h>
#define VG_INNER_AVX2 1
#else
#define VG_INNER_AVX2 0
#endif

namespace vg {
namespace {

constexpr uint32_t kLanes = 16;
constexpr uint32_t kMaxNodes = VG_INNER_AT_OPEN_MAX_NODES;
constexpr uint32_t kMaxChildren = VG_INNER_AT_OPEN_MAX_CHILDREN;
constexpr uint32_t kMaxChildNodes = VG_INNER_AT_OPEN_MAX_CHILD_NODES;
constexpr double kInf = __builtin_inf();

// The search's arrays in the scratch.
struct Search {
    double* dist;             // kMaxNodes x kLanes
    float* distF;             // the same in floats, for the node distances' searches
    double* key;              // per node: its queue key
    uint32_t* heap;           // binary heap of nodes
    uint32_t* heapAt;         // per node: its heap position, kNone when not queued
    uint16_t* pending;        // per node: lanes lowered since it last relaxed
    uint32_t* children;       // f's second-layer patches, increasing
    uint32_t* childBegin;     // children + 1 offsets into slotLocal
    uint32_t* slotLocal;      // per child node slot: its local node, kNone when none
    uint32_t* extraNode;      // local nodes from `rows` on: slots' merged-away nodes
    uint32_t* sourceLocal;    // per slot of f: its node's local id
    uint64_t* order;          // f's slots in the order the blocks take them: (hub, slot)
    uint32_t heapSize = 0;
};

constexpr uint32_t kMaxSlots = 65536;  // vg_validate bounds a first-layer patch's slots by this
constexpr size_t kScratchAlign = 64;

// Lays the search out in L: measures (L.base null) or carves.
Search layOut(Layout& L) {
    Search s;
    s.dist = L.take<double>(uint64_t(kMaxNodes) * kLanes);
    s.distF = L.take<float>(uint64_t(kMaxNodes) * kLanes);
    s.key = L.take<double>(kMaxNodes);
    s.heap = L.take<uint32_t>(kMaxNodes);
    s.heapAt = L.take<uint32_t>(kMaxNodes);
    s.pending = L.take<uint16_t>(kMaxNodes);
    s.children = L.take<uint32_t>(kMaxChildren);
    s.childBegin = L.take<uint32_t>(uint64_t(kMaxChildren) + 1);
    s.slotLocal = L.take<uint32_t>(kMaxChildNodes);
    s.extraNode = L.take<uint32_t>(kMaxNodes);
    s.sourceLocal = L.take<uint32_t>(kMaxSlots);
    s.order = L.take<uint64_t>(kMaxSlots);
    return s;
}

// The queue: a binary heap by (key, node), a node at most once, its key lowered in place.
bool before(const Search& s, uint32_t a, uint32_t b) { return s.key[a] < s.key[b] || (s.key[a] == s.key[b] && a < b); }

void siftUp(Search& s, uint32_t at) {
    const uint32_t node = s.heap[at];
    while (at > 0) {
        const uint32_t up = (at - 1) / 2;
        if (!before(s, node, s.heap[up])) break;
        s.heap[at] = s.heap[up];
        s.heapAt[s.heap[at]] = at;
        at = up;
    }
    s.heap[at] = node;
    s.heapAt[node] = at;
}

void queue(Search& s, uint32_t node, double key) {
    if (s.heapAt[node] != kNone) {
        if (!(key < s.key[node])) return;
        s.key[node] = key;
        siftUp(s, s.heapAt[node]);
        return;
    }
    s.key[node] = key;
    s.heap[s.heapSize] = node;
    siftUp(s, s.heapSize++);
}

uint32_t pop(Search& s) {
    const uint32_t top = s.heap[0];
    s.heapAt[top] = kNone;
    const uint32_t last = s.heap[--s.heapSize];
    if (s.heapSize == 0) return top;
    uint32_t at = 0;
    for (;;) {
        uint32_t child = 2 * at + 1;
        if (child >= s.heapSize) break;
        if (child + 1 < s.heapSize && before(s, s.heap[child + 1], s.heap[child])) ++child;
        if (!before(s, s.heap[child], last)) break;
        s.heap[at] = s.heap[child];
        s.heapAt[s.heap[at]] = at;
        at = child;
    }
    s.heap[at] = last;
    s.heapAt[last] = at;
    return top;
}

// Sorts a[0, n) increasing (heapsort: no allocation, n log n at worst).
void sortKeys(uint64_t* a, uint32_t n) {
    auto down = [a](uint32_t at, uint32_t size) {
        for (;;) {
            uint32_t child = 2 * at + 1;
            if (child >= size) return;
            if (child + 1 < size && a[child + 1] > a[child]) ++child;
            if (!(a[child] > a[at])) return;
            const uint64_t t = a[at];
            a[at] = a[child];
            a[child] = t;
            at = child;
        }
    };
    for (uint32_t i = n / 2; i-- > 0;) down(i, n);
    for (uint32_t end = n; end > 1; --end) {
        const uint64_t t = a[0];
        a[0] = a[end - 1];
        a[end - 1] = t;
        down(0, end - 1);
    }
}

// Writes the steps of node r's lanes [0, count) to its row of the table, lane i at column
// column[i] (vg_label_steps of the lane rounded to a float).
void writeSteps(const double* d, uint32_t count, float scale, const uint32_t* column, uint16_t* row) {
    for (uint32_t i = 0; i < count; ++i) row[column[i]] = vg_label_steps(double(float(d[i])), scale);
}

#if VG_INNER_AVX2
// The same, four lanes per instruction: the same roundings, division and floor.
__attribute__((target("avx2"))) void writeStepsAvx2(const double* d, uint32_t count, float scale,
                                                    const uint32_t* column, uint16_t* row) {
    const __m256d divisor = _mm256_set1_pd(double(scale)), half = _mm256_set1_pd(0.5),
                  top = _mm256_set1_pd(65534.0), zero = _mm256_setzero_pd(), noPath = _mm256_set1_pd(65535.0);
    int32_t steps[kLanes];
    for (uint32_t i = 0; i < kLanes; i += 4) {
        const __m256d x = _mm256_cvtps_pd(_mm256_cvtpd_ps(_mm256_loadu_pd(d + i)));
        const __m256d finite = _mm256_cmp_pd(_mm256_sub_pd(x, x), zero, _CMP_EQ_OQ);
        const __m256d y = _mm256_floor_pd(_mm256_add_pd(_mm256_div_pd(x, divisor), half));
        const __m256d capped = _mm256_blendv_pd(top, y, _mm256_cmp_pd(y, top, _CMP_LT_OQ));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(steps + i),
                         _mm256_cvttpd_epi32(_mm256_blendv_pd(noPath, capped, finite)));
    }
    for (uint32_t i = 0; i < count; ++i) row[column[i]] = uint16_t(steps[i]);
}
#endif

// The lanes' distances in T: doubles for the inner rows (the baker's numbers bit for bit),
// floats for the node distances (half the vector work; they are rounded to 16-bit steps).
inline double* laneDistances(Search& s, double) { return s.dist; }
inline float* laneDistances(Search& s, float) { return s.distF; }

// Lowers node `to`'s lanes to source + w where that is lower; queues it if any is.
template <class T>
inline void lowerScalar(Search& s, const T* source, T w, uint32_t to) {
    T* d = laneDistances(s, T()) + uint64_t(to) * kLanes;
    uint32_t lowered = 0;
    T key = T(kInf);
    for (uint32_t i = 0; i < kLanes; ++i) {
        const T c = source[i] + w;
        if (c < d[i]) {
            d[i] = c;
            lowered |= 1u << i;
            key = c < key ? c : key;
        }
    }
    if (lowered == 0) return;
    s.pending[to] = uint16_t(s.pending[to] | lowered);
    queue(s, to, double(key));
}

// Relaxes one matrix row (`n` packed 12-bit quanta from index `row`, column `self` being
// the node itself) from the lanes `source` (+inf in lanes that do not relax).
template <class T>
void relaxRowScalar(Search& s, const uint8_t* packed, uint64_t row, uint32_t n, uint32_t self, T scale,
                    const uint32_t* to, const T* source) {
    for (uint32_t j = 0; j < n; ++j) {
        const uint32_t q = quantum(packed, row + j);
        if (j == self || q == kNoPathQuantum || to[j] == kNone) continue;
        lowerScalar(s, source, T(q) * scale, to[j]);
    }
}

#if VG_INNER_AVX2
// The same sums and comparisons, four lanes per instruction.
__attribute__((target("avx2"))) void relaxRowAvx2(Search& s, const uint8_t* packed, uint64_t row, uint32_t n,
                                                  uint32_t self, double scale, const uint32_t* to,
                                                  const double* source) {
    const __m256d s0 = _mm256_loadu_pd(source), s1 = _mm256_loadu_pd(source + 4), s2 = _mm256_loadu_pd(source + 8),
                  s3 = _mm256_loadu_pd(source + 12);
    const __m256d inf = _mm256_set1_pd(kInf);
    for (uint32_t j = 0; j < n; ++j) {
        const uint32_t q = quantum(packed, row + j);
        if (j == self || q == kNoPathQuantum || to[j] == kNone) continue;
        const __m256d w = _mm256_set1_pd(double(q) * scale);
        double* d = s.dist + uint64_t(to[j]) * kLanes;
        const __m256d c0 = _mm256_add_pd(s0, w), c1 = _mm256_add_pd(s1, w), c2 = _mm256_add_pd(s2, w),
                      c3 = _mm256_add_pd(s3, w);
        const __m256d d0 = _mm256_loadu_pd(d), d1 = _mm256_loadu_pd(d + 4), d2 = _mm256_loadu_pd(d + 8),
                      d3 = _mm256_loadu_pd(d + 12);
        const __m256d m0 = _mm256_cmp_pd(c0, d0, _CMP_LT_OQ), m1 = _mm256_cmp_pd(c1, d1, _CMP_LT_OQ),
                      m2 = _mm256_cmp_pd(c2, d2, _CMP_LT_OQ), m3 = _mm256_cmp_pd(c3, d3, _CMP_LT_OQ);
        const uint32_t lowered = uint32_t(_mm256_movemask_pd(m0)) | (uint32_t(_mm256_movemask_pd(m1)) << 4) |
                                 (uint32_t(_mm256_movemask_pd(m2)) << 8) | (uint32_t(_mm256_movemask_pd(m3)) << 12);
        if (lowered == 0) continue;
        _mm256_storeu_pd(d, _mm256_blendv_pd(d0, c0, m0));
        _mm256_storeu_pd(d + 4, _mm256_blendv_pd(d1, c1, m1));
        _mm256_storeu_pd(d + 8, _mm256_blendv_pd(d2, c2, m2));
        _mm256_storeu_pd(d + 12, _mm256_blendv_pd(d3, c3, m3));
        // The key: the least lowered lane.
        __m256d k = _mm256_min_pd(_mm256_min_pd(_mm256_blendv_pd(inf, c0, m0), _mm256_blendv_pd(inf, c1, m1)),
                                  _mm256_min_pd(_mm256_blendv_pd(inf, c2, m2), _mm256_blendv_pd(inf, c3, m3)));
        const __m128d half = _mm_min_pd(_mm256_castpd256_pd128(k), _mm256_extractf128_pd(k, 1));
        const double key = _mm_cvtsd_f64(_mm_min_sd(half, _mm_unpackhi_pd(half, half)));
        s.pending[to[j]] = uint16_t(s.pending[to[j]] | lowered);
        queue(s, to[j], key);
    }
}

// The float lanes: eight per instruction.
__attribute__((target("avx2"))) void relaxRowAvx2(Search& s, const uint8_t* packed, uint64_t row, uint32_t n,
                                                  uint32_t self, float scale, const uint32_t* to,
                                                  const float* source) {
    const __m256 s0 = _mm256_loadu_ps(source), s1 = _mm256_loadu_ps(source + 8);
    const __m256 inf = _mm256_set1_ps(__builtin_inff());
    for (uint32_t j = 0; j < n; ++j) {
        const uint32_t q = quantum(packed, row + j);
        if (j == self || q == kNoPathQuantum || to[j] == kNone) continue;
        const __m256 w = _mm256_set1_ps(float(q) * scale);
        float* d = s.distF + uint64_t(to[j]) * kLanes;
        const __m256 c0 = _mm256_add_ps(s0, w), c1 = _mm256_add_ps(s1, w);
        const __m256 d0 = _mm256_loadu_ps(d), d1 = _mm256_loadu_ps(d + 8);
        const __m256 m0 = _mm256_cmp_ps(c0, d0, _CMP_LT_OQ), m1 = _mm256_cmp_ps(c1, d1, _CMP_LT_OQ);
        const uint32_t lowered = uint32_t(_mm256_movemask_ps(m0)) | (uint32_t(_mm256_movemask_ps(m1)) << 8);
        if (lowered == 0) continue;
        _mm256_storeu_ps(d, _mm256_blendv_ps(d0, c0, m0));
        _mm256_storeu_ps(d + 8, _mm256_blendv_ps(d1, c1, m1));
        const __m256 k = _mm256_min_ps(_mm256_blendv_ps(inf, c0, m0), _mm256_blendv_ps(inf, c1, m1));
        const __m128 half = _mm_min_ps(_mm256_castps256_ps128(k), _mm256_extractf128_ps(k, 1));
        const __m128 quarter = _mm_min_ps(half, _mm_movehl_ps(half, half));
        const float key = _mm_cvtss_f32(_mm_min_ss(quarter, _mm_shuffle_ps(quarter, quarter, 1)));
        s.pending[to[j]] = uint16_t(s.pending[to[j]] | lowered);
        queue(s, to[j], double(key));
    }
}
#endif

// First-layer patch f's search graph: its children (second-layer patches), their node
// slots' local nodes, and the local nodes themselves: f's inner rows, then each slot whose
// node is merged away. VG_ERR_CORRUPT_CONTENT past the format's limits or for a slot node
// that no inner row holds.
struct PatchGraph {
    uint32_t f;
    const uint32_t* rowNode;  // the inner rows' nodes, increasing
    uint32_t rows, nodes, childCount;
};

vg_status prepareGraph(const vg_graph& g, uint32_t f, Search& s, PatchGraph& pg) {
    const Patch& first = g.first[f];
    const uint32_t K = first.slotCount;
    pg.f = f;
    pg.rowNode = g.hubInnerNode + g.hubInnerBegin[f];
    pg.rows = g.hubInnerBegin[f + 1] - g.hubInnerBegin[f];
    uint32_t childCount = 0, childNodes = 0;
    s.childBegin[0] = 0;
    for (uint32_t q = 0; q < g.secondCount; ++q) {
        if (g.second[q].parent != f) continue;
        const Patch& p = g.second[q];
        if (childCount == kMaxChildren || p.nodeCount > kMaxChildNodes - childNodes) return VG_ERR_CORRUPT_CONTENT;
        s.children[childCount] = q;
        for (uint32_t j = 0; j < p.nodeCount; ++j)
            s.slotLocal[childNodes + j] = sortedIndex(pg.rowNode, pg.rows, g.slots[p.slotBegin + j]);
        childNodes += p.nodeCount;
        s.childBegin[++childCount] = childNodes;
    }
    pg.childCount = childCount;
    // The blocks take the slots by hub number: a tree node's hubs follow its separator, so
    // neighbours share a block, their lanes drop together and fewer nodes relax twice (igea:
    // 879,479 nodes taken from the queue instead of 1,140,366 in slot order, for 763,785
    // node visits).
    uint32_t nodes = pg.rows;
    if (pg.rows > kMaxNodes) return VG_ERR_CORRUPT_CONTENT;
    for (uint32_t k = 0; k < K; ++k) {
        const uint32_t b = g.slots[first.slotBegin + k];
        const uint32_t hub = g.nodeHub[b];
        s.order[k] = (uint64_t(hub) << 32) | k;
        if (nodeActive(g, b)) {
            s.sourceLocal[k] = sortedIndex(pg.rowNode, pg.rows, b);
            if (s.sourceLocal[k] == kNone) return VG_ERR_CORRUPT_CONTENT;
            continue;
        }
        if (nodes == kMaxNodes) return VG_ERR_CORRUPT_CONTENT;
        s.sourceLocal[k] = nodes;
        s.extraNode[nodes++ - pg.rows] = b;
    }
    pg.nodes = nodes;
    sortKeys(s.order, K);
    return VG_OK;
}

// One search over pg's graph from `count` (at most kLanes) local nodes, lane i from
// sources[i]: the lanes' distances (laneDistances) hold the least path sums in T when it
// returns.
template <class T>
void searchFrom(const vg_graph& g, const PatchGraph& pg, Search& s, const uint32_t* sources, uint32_t count, bool avx2) {
#if !VG_INNER_AVX2
    (void)avx2;
#endif
    T source[kLanes];
    T* dist = laneDistances(s, T());
    for (uint64_t i = 0; i < uint64_t(pg.nodes) * kLanes; ++i) dist[i] = T(kInf);
    for (uint32_t n = 0; n < pg.nodes; ++n) {
        s.pending[n] = 0;
        s.heapAt[n] = kNone;
    }
    s.heapSize = 0;
    for (uint32_t i = 0; i < count; ++i) {
        const uint32_t local = sources[i];
        dist[uint64_t(local) * kLanes + i] = T(0);
        s.pending[local] = uint16_t(s.pending[local] | (1u << i));
        queue(s, local, 0.0);
    }
    while (s.heapSize > 0) {
        const uint32_t u = pop(s);
        const uint32_t relax = s.pending[u];
        s.pending[u] = 0;
        const T* du = dist + uint64_t(u) * kLanes;
        for (uint32_t i = 0; i < kLanes; ++i) source[i] = (relax >> i) & 1u ? du[i] : T(kInf);
        const uint32_t node = u < pg.rows ? pg.rowNode[u] : s.extraNode[u - pg.rows];
        for (uint32_t m = g.nodeSecondBegin[node]; m < g.nodeSecondBegin[node + 1]; ++m) {
            const Membership& ms = g.nodeSecond[m];
            const Patch& p = g.second[ms.patch];
            if (p.parent != pg.f) continue;
            const uint32_t c = sortedIndex(s.children, pg.childCount, ms.patch);
            const uint32_t* to = s.slotLocal + s.childBegin[c];
            const uint64_t row = nodeRowStart(p, ms.slot);
#if VG_INNER_AVX2
            if (avx2) {  // vg_open has asked the CPU
                relaxRowAvx2(s, g.secondDistances, row, p.nodeCount, ms.slot, T(p.scale), to, source);
                continue;
            }
#endif
            relaxRowScalar(s, g.secondDistances, row, p.nodeCount, ms.slot, T(p.scale), to, source);
        }
    }
}

// Patch f's inner table: a search per block of up to kLanes slots, written out in steps.
vg_status patchRows(const vg_graph& g, uint32_t f, Search& s, bool avx2) {
    const uint32_t K = g.first[f].slotCount;
    const uint32_t rows = g.hubInnerBegin[f + 1] - g.hubInnerBegin[f];
    uint16_t* table = const_cast<uint16_t*>(g.hubInner) + g.hubInnerMatrixBegin[f];
    // The blob stores zeros here: anything else is a corrupt blob, not something to overwrite.
    for (uint64_t e = 0; e < uint64_t(rows) * K; ++e)
        if (table[e] != 0) return VG_ERR_CORRUPT_CONTENT;
    PatchGraph pg;
    const vg_status st = prepareGraph(g, f, s, pg);
    if (st != VG_OK) return st;

    uint32_t column[kLanes], sources[kLanes];
    for (uint32_t k0 = 0; k0 < K; k0 += kLanes) {
        const uint32_t count = K - k0 < kLanes ? K - k0 : kLanes;
        for (uint32_t i = 0; i < count; ++i) {
            column[i] = uint32_t(s.order[k0 + i]);
            sources[i] = s.sourceLocal[column[i]];
        }
        searchFrom<double>(g, pg, s, sources, count, avx2);
        for (uint32_t r = 0; r < rows; ++r) {
            const double* d = s.dist + uint64_t(r) * kLanes;
#if VG_INNER_AVX2
            if (avx2) {
                writeStepsAvx2(d, count, g.hubLabelScale, column, table + uint64_t(r) * K);
                continue;
            }
#endif
            writeSteps(d, count, g.hubLabelScale, column, table + uint64_t(r) * K);
        }
    }
    return VG_OK;
}

}  // namespace

size_t innerRowsScratchSize() {
    Layout L{nullptr, kScratchAlign};
    layOut(L);
    return L.used;
}

vg_status computeInnerRows(const vg_graph& g, bool avx2, void* scratch) {
    Layout L{static_cast<unsigned char*>(scratch), kScratchAlign};
    Search s = layOut(L);
    for (uint32_t f = 0; f < g.firstCount; ++f) {
        const vg_status st = patchRows(g, f, s, avx2);
        if (st != VG_OK) return st;
    }
    return VG_OK;
}

bool searchFits(const vg_graph& g, uint32_t f) {
    uint64_t children = 0, childNodes = 0;
    for (uint32_t q = 0; q < g.secondCount; ++q)
        if (g.second[q].parent == f) {
            ++children;
            childNodes += g.second[q].nodeCount;
        }
    uint64_t nodes = g.hubInnerBegin[f + 1] - g.hubInnerBegin[f];
    for (uint32_t k = 0; k < g.first[f].slotCount; ++k) nodes += !nodeActive(g, g.slots[g.first[f].slotBegin + k]);
    return children <= kMaxChildren && childNodes <= kMaxChildNodes && nodes <= kMaxNodes;
}

vg_status computeNodeDistances(const vg_graph& g, uint32_t f, bool avx2, void* scratch, const uint32_t* order,
                               float* out) {
    Layout L{static_cast<unsigned char*>(scratch), kScratchAlign};
    Search s = layOut(L);
    PatchGraph pg;
    const vg_status st = prepareGraph(g, f, s, pg);
    if (st != VG_OK) return st;
    uint32_t sources[kLanes];
    for (uint32_t a0 = 0; a0 < pg.rows; a0 += kLanes) {
        const uint32_t count = pg.rows - a0 < kLanes ? pg.rows - a0 : kLanes;
        for (uint32_t i = 0; i < count; ++i) sources[i] = order[a0 + i];
        searchFrom<float>(g, pg, s, sources, count, avx2);
        for (uint32_t b = 0; b < pg.rows; ++b)
            for (uint32_t i = 0; i < count; ++i) out[uint64_t(sources[i]) * pg.rows + b] = s.distF[uint64_t(b) * kLanes + i];
    }
    return VG_OK;
}

}  // namespace vg
