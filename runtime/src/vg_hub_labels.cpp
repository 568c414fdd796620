#include "vg_hub_labels.h"

#include "vg_endpoint_table.h"
#include "vg_lower_bound.h"

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
// The smallest of a vector's lanes: 16 label steps, or 8 floats (not NaN).
VG_AVX2_TARGET inline uint16_t lanesMinimum(__m256i x) {
    return uint16_t(_mm_cvtsi128_si32(_mm_minpos_epu16(_mm_min_epu16(_mm256_castsi256_si128(x), _mm256_extracti128_si256(x, 1)))));
}
VG_AVX2_TARGET inline float lanesMinimum(__m256 x) {
    __m128 half = _mm_min_ps(_mm256_castps256_ps128(x), _mm256_extractf128_ps(x, 1));
    half = _mm_min_ps(half, _mm_movehl_ps(half, half));
    return _mm_cvtss_f32(_mm_min_ss(half, _mm_shuffle_ps(half, half, 1)));
}

// A row whose length is no multiple of 16 ends with one more vector over its last 16
// entries, overlapping the one before: taking a minimum twice changes nothing, and the
// scalar loop it replaces was a quarter of the kernel's work on igea's rows (~310).
VG_AVX2_TARGET inline void lowerSteps16(uint16_t* d, const uint16_t* steps, __m256i b) {
    const __m256i x = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(steps));
    const __m256i y = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(d));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(d), _mm256_min_epu16(y, _mm256_adds_epu16(x, b)));
}

VG_AVX2_TARGET void lowerStepsAvx2(uint16_t* d, const uint16_t* steps, uint32_t n, uint16_t base) {
    if (n < 16) return lowerSteps(d, steps, n, base);
    const __m256i b = _mm256_set1_epi16(short(base));
    uint32_t k = 0;
    for (; k + 16 <= n; k += 16) lowerSteps16(d + k, steps + k, b);
    if (k < n) lowerSteps16(d + n - 16, steps + n - 16, b);
}

VG_AVX2_TARGET void meetSteps16(const uint16_t* d, const uint16_t* steps, __m256i& best) {
    const __m256i x = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(steps));
    const __m256i y = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(d));
    best = _mm256_min_epu16(best, _mm256_adds_epu16(x, y));
}

VG_AVX2_TARGET uint16_t meetStepsAvx2(const uint16_t* d, const uint16_t* steps, uint32_t n) {
    if (n < 16) return meetSteps(d, steps, n);
    __m256i best = _mm256_set1_epi16(-1);
    uint32_t k = 0;
    for (; k + 16 <= n; k += 16) meetSteps16(d + k, steps + k, best);
    if (k < n) meetSteps16(d + n - 16, steps + n - 16, best);
    return lanesMinimum(best);
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

}  // namespace

bool hubInPatch(const vg_graph& g, uint32_t node, uint32_t first) {
    for (uint32_t m = g.nodeFirstBegin[node]; m < g.nodeFirstBegin[node + 1]; ++m)
        if (g.nodeFirst[m].patch == first) return true;
    return false;
}

namespace {

bool shareFirstPatch(const vg_graph& g, const Side& a, const Side& b) {
    if (a.hub == kNone && b.hub == kNone) return a.first == b.first;
    if (a.hub == kNone) return hubInPatch(g, b.node, a.first);
    if (b.hub == kNone) return hubInPatch(g, a.node, b.first);
    for (uint32_t m = g.nodeFirstBegin[a.node]; m < g.nodeFirstBegin[a.node + 1]; ++m)
        if (hubInPatch(g, b.node, g.nodeFirst[m].patch)) return true;
    return false;
}

const uint16_t* innerRowData(const vg_graph& g, uint32_t first, uint32_t row) {
    return g.hubInner + g.hubInnerMatrixBegin[first] + uint64_t(row) * g.first[first].slotCount;
}

// Calls f(node, distance, inner row) for the active nodes of x's second-layer patches (not
// x itself) with x's row entry to each, where there is a path, and the node's inner row in
// the patches' first-layer patch (kNone if it has none).
template <class F>
void forEachRowNode(const vg_graph& g, const vg_workspace& ws, uint32_t x, F&& f) {
    forEachPatchOf(g, x, [&](uint32_t patch, uint32_t slot) {
        const Patch& p = g.second[patch];
        for (uint32_t j = 0; j < p.nodeCount; ++j) {
            const uint32_t n = g.slots[p.slotBegin + j];
            if (j == slot || !nodeActive(g, n)) continue;
            const uint32_t q = quantum(g.secondDistances, entryIndex(p, slot, j));
            if (q != kNoPathQuantum) f(n, float(q) * p.scale, ws.hubInnerRowOfSlot[p.slotBegin + j]);
        }
    });
}

// v[k]: the distance inside the side's first-layer patch from vertex x to its k-th slot
// (a first-layer node), in label steps: x's patch rows to the active nodes of its patches,
// then their inner rows (an active node is an inner row itself).
void innerSteps(const vg_graph& g, const vg_workspace& ws, uint32_t x, const Side& side, uint16_t* v) {
    const uint32_t first = side.first, K = g.first[first].slotCount;
    for (uint32_t k = 0; k < K; ++k) v[k] = kNoStep;
    if (side.node != kNone && nodeActive(g, side.node)) {
        const uint32_t r = innerRow(g, first, side.node);
        if (r != kNone) lowerStepsOn(g, v, innerRowData(g, first, r), K, 0);
        return;
    }
    if (side.node == kNone && ws.endpointTable != nullptr) {  // the same steps, worked out once
        const uint16_t* row = endpointVertexRow(g, *ws.endpointTable, x);
        for (uint32_t k = 0; k < K; ++k) v[k] = row[k];
        return;
    }
    // x's row entries lie a matrix column apart, a cache line each: they are gathered first,
    // in a loop of independent loads that the processor overlaps, and only then the inner
    // rows taken (one row after each entry would leave one miss outstanding at a time).
    constexpr uint32_t kChunk = 64;
    uint16_t bases[kChunk];
    uint32_t rows[kChunk], count = 0;
    auto flush = [&] {
        for (uint32_t i = 0; i < count; ++i) lowerStepsOn(g, v, innerRowData(g, first, rows[i]), K, bases[i]);
        count = 0;
    };
    forEachRowNode(g, ws, x, [&](uint32_t, float d, uint32_t r) {
        const uint16_t base = toSteps(d, g.hubLabelScale);
        if (base == kNoStep || r == kNone) return;
        const uint16_t* row = innerRowData(g, first, r);
        for (uint32_t k = 0; k < K; k += 32) __builtin_prefetch(row + k);
        bases[count] = base;
        rows[count++] = r;
        if (count == kChunk) flush();
    });
    flush();
}

uint16_t lanesMinimum(const uint16_t* lanes) {
    uint16_t best = kNoStep;
    for (uint32_t j = 0; j < kHubBlock; ++j) best = lanes[j] < best ? lanes[j] : best;
    return best;
}

// w[slot]: the source's distance to each exit of the target side that the bounds kept, the
// best over its 16 lanes in acc (one per exit); the others stay as they are.
void exitDistances(const HubExit* exits, uint32_t count, const uint16_t* acc, uint16_t* w) {
    for (uint32_t e = 0; e < count; ++e)
        if (exits[e].steps != kNoStep) w[exits[e].slot] = lanesMinimum(acc + uint64_t(e) * kHubBlock);
}

#if VG_HUB_AVX2
VG_AVX2_TARGET void exitDistancesAvx2(const HubExit* exits, uint32_t count, const uint16_t* acc, uint16_t* w) {
    for (uint32_t e = 0; e < count; ++e)
        if (exits[e].steps != kNoStep)
            w[exits[e].slot] = lanesMinimum(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(acc + uint64_t(e) * kHubBlock)));
}
#endif

void exitDistancesOn(const vg_graph& g, const HubExit* exits, uint32_t count, const uint16_t* acc, uint16_t* w) {
#if VG_HUB_AVX2
    if (g.avx2) return exitDistancesAvx2(exits, count, acc, w);
#endif
    exitDistances(exits, count, acc, w);
}

// Whether no path within the upper bound passes block r, whose nearest hub the source
// reaches in `nearest` steps (kNoStep: none): the target side then reads none of its rows.
// The source's distances come from its exits within the bound, so a path through a hub
// past them is longer than the bound too.
inline bool outOfRoom(const vg_graph& g, const HubBlockRef& r, uint16_t nearest) {
    return nearest == kNoStep || float(nearest) * g.hubLabelScale > r.targetRoom;
}

// The label kernels over column blocks (16 lanes: one block's hubs). Each block r of the
// common path has one row per hub of its tree node's subtree; an exit e's row is
// columns + r.base + (e.hub - r.lo) * kHubBlock, for r.lo <= e.hub < r.hi.
inline bool inBlock(const HubBlockRef& r, uint32_t hub) { return hub >= r.lo && hub < r.hi; }
inline const uint16_t* columnRow(const vg_graph& g, const HubBlockRef& r, uint32_t hub) {
    return g.hubColumns + r.base + uint64_t(hub - r.lo) * kHubBlock;
}
uint32_t blocksOf(const HubTreeNode& node) { return uint32_t(hubBlocksOf(node)); }
// Block b of tree node x: its matrix has a row per hub of x's subtree.
HubBlockRef blockRef(const vg_graph& g, const vg_workspace& ws, uint32_t x, uint32_t b) {
    const uint32_t lo = g.hubTree[x].hubBegin, hi = ws.hubSubtreeEnd[x];
    return HubBlockRef{g.hubColumnBegin[x] + uint64_t(b) * kHubBlock * (hi - lo), lo, hi, ws.hubBlocksAbove[x] + b,
                       __builtin_inff(), 0.0f, 0.0f, kNone};
}

// The exits (in hub order) with a row in block r: [*begin, *end), found by bisection, so
// that the kernels loop over them alone (most exits of a deep block's side lie above it).
inline uint32_t firstExitFrom(const HubExit* exits, uint32_t count, uint32_t hub) {
    uint32_t lo = 0, hi = count;
    while (lo < hi) {
        const uint32_t mid = (lo + hi) / 2;
        if (exits[mid].hub < hub) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}
inline void exitsInBlock(const HubExit* exits, uint32_t count, const HubBlockRef& r, uint32_t* begin, uint32_t* end) {
    *begin = firstExitFrom(exits, count, r.lo);
    *end = *begin + firstExitFrom(exits + *begin, count - *begin, r.hi);
}

// The exits of one query side, and which of them have rows in a block: every exit whose
// hub the block's rows cover or, where the blob has exit lists, those that the lists of
// the side's second-layer patches name for the block (baker/hub_exit_lists.h: the others
// are never the best way from the patch to any of the block's hubs, nor from them back).
// With lists, `exits` holds every exit candidate of the side's first-layer patch in hub
// order (the lists' indices), those ruled out by the bounds with steps kNoStep; without,
// only the others.
struct SideRows {
    const HubExit* exits;
    const uint32_t* keptHubs;  // per exit its hub where the bounds kept it (steps < kNoStep), else kNone
    uint32_t count;
    uint32_t listCount;  // 0: no lists
    uint32_t listStart[kMaxSidePatches];  // per patch of the side: its first list in hubExitListBegin
};

// Indices into side.exits of the exits whose rows block r reads, into out; their number.
// An entry whose hub the block has no row for is skipped: no list reads past a matrix.
uint32_t blockRows(const vg_graph& g, const SideRows& side, const HubBlockRef& r, uint16_t* out) {
    uint32_t n = 0;
    if (side.listCount == 0) {
        uint32_t begin, end;
        exitsInBlock(side.exits, side.count, r, &begin, &end);
        for (uint32_t e = begin; e < end; ++e) out[n++] = uint16_t(e);
        return n;
    }
    if (side.count == 0) return 0;  // (the branch-free loop reads side.keptHubs[0])
    const uint32_t span = r.hi - r.lo;
    for (uint32_t i = 0; i < side.listCount; ++i) {
        const uint32_t list = side.listStart[i] + r.pathIndex;
        // Branch-free: whether the bounds kept an exit is a coin toss to the predictor. A
        // dropped exit's hub is kNone, outside every block (one unsigned comparison).
        for (uint32_t m = g.hubExitListBegin[list]; m < g.hubExitListBegin[list + 1]; ++m) {
            const uint16_t e = g.hubExitLists[m];
            const uint32_t hub = side.keptHubs[e < side.count ? e : 0];
            out[n] = e;
            n += uint32_t(e < side.count) & uint32_t(hub - r.lo < span);
        }
    }
    return n;
}

// d[16 i + j]: the source's distance to hub j of block i, the best over its exits (the
// exit's steps plus its row). `rows`: scratch for one block's exits.
void sourceColumns(const vg_graph& g, const SideRows& side, const HubBlockRef* blocks, uint32_t blockCount,
                   uint16_t* rows, uint16_t* d) {
    for (uint32_t i = 0; i < blockCount; ++i) {
        uint16_t* acc = d + uint64_t(i) * kHubBlock;
        for (uint32_t j = 0; j < kHubBlock; ++j) acc[j] = kNoStep;
        const uint32_t n = blockRows(g, side, blocks[i], rows);
        for (uint32_t m = 0; m < n; ++m) {
            const HubExit& e = side.exits[rows[m]];
            lowerSteps(acc, columnRow(g, blocks[i], e.hub), kHubBlock, e.steps);
        }
    }
}

// acc[16 e + j]: the source's distance through hub j of some block to target exit e, the
// best over the blocks (its lanes' minimum is the source's distance to the exit).
void targetColumns(const vg_graph& g, const uint16_t* d, const SideRows& side, const HubBlockRef* blocks,
                   uint32_t blockCount, uint16_t* rows, uint16_t* acc) {
    for (uint64_t k = 0; k < uint64_t(side.count) * kHubBlock; ++k) acc[k] = kNoStep;
    for (uint32_t i = 0; i < blockCount; ++i) {
        const uint16_t* di = d + uint64_t(i) * kHubBlock;
        if (outOfRoom(g, blocks[i], lanesMinimum(di))) continue;
        const uint32_t n = blockRows(g, side, blocks[i], rows);
        for (uint32_t m = 0; m < n; ++m) {
            const uint16_t* row = columnRow(g, blocks[i], side.exits[rows[m]].hub);
            uint16_t* a = acc + uint64_t(rows[m]) * kHubBlock;
            for (uint32_t j = 0; j < kHubBlock; ++j) {
                const uint16_t c = saturatingSum(di[j], row[j]);
                a[j] = c < a[j] ? c : a[j];
            }
        }
    }
}

#if VG_HUB_AVX2
// Asks for the rows of the n exits in rows[] in block r.
void prefetchRows(const vg_graph& g, const HubBlockRef& r, const SideRows& side, const uint16_t* rows, uint32_t n) {
    for (uint32_t m = 0; m < n; ++m)
        _mm_prefetch(reinterpret_cast<const char*>(columnRow(g, r, side.exits[rows[m]].hub)), _MM_HINT_T0);
}

// The rows of one side that the next blocks read, found and asked for kRowLookahead blocks
// ahead (kRowBuffers buffers in turn, each hubBlockRowsEach entries of the workspace).
struct RowsAhead {
    uint16_t* buffers;
    uint64_t each;
    uint32_t count[kRowBuffers];
    uint16_t* rows(uint32_t block) { return buffers + (block % kRowBuffers) * each; }
    uint32_t& countOf(uint32_t block) { return count[block % kRowBuffers]; }
    // Asks for the exit lists of block i (its rows come kRowLookahead blocks later).
    void askLists(const vg_graph& g, const SideRows& side, const HubBlockRef* blocks, uint32_t i) const {
        for (uint32_t p = 0; p < side.listCount; ++p) {
            const uint32_t list = side.listStart[p] + blocks[i].pathIndex;
            const char* from = reinterpret_cast<const char*>(g.hubExitLists + g.hubExitListBegin[list]);
            const char* to = reinterpret_cast<const char*>(g.hubExitLists + g.hubExitListBegin[list + 1]);
            for (; from < to; from += 64) __builtin_prefetch(from);
            __builtin_prefetch(to - 1);
        }
    }
    // Block i's rows, or none when `read` is false (the block is skipped).
    void find(const vg_graph& g, const SideRows& side, const HubBlockRef* blocks, uint32_t i, bool read) {
        countOf(i) = read ? blockRows(g, side, blocks[i], rows(i)) : 0;
        prefetchRows(g, blocks[i], side, rows(i), countOf(i));
    }
};

// The same numbers as sourceColumns.
VG_AVX2_TARGET void sourceColumnsAvx2(const vg_graph& g, const SideRows& side, const HubBlockRef* blocks,
                                      uint32_t blockCount, RowsAhead& ahead, uint16_t* d) {
    for (uint32_t i = 0; i < 2 * kRowLookahead && i < blockCount; ++i) ahead.askLists(g, side, blocks, i);
    for (uint32_t i = 0; i < kRowLookahead && i < blockCount; ++i) ahead.find(g, side, blocks, i, true);
    for (uint32_t i = 0; i < blockCount; ++i) {
        if (i + 2 * kRowLookahead < blockCount) ahead.askLists(g, side, blocks, i + 2 * kRowLookahead);
        if (i + kRowLookahead < blockCount) ahead.find(g, side, blocks, i + kRowLookahead, true);
        const HubBlockRef& r = blocks[i];
        const uint16_t* rows = ahead.rows(i);
        __m256i acc = _mm256_set1_epi16(-1);
        for (uint32_t m = 0, n = ahead.countOf(i); m < n; ++m) {
            const HubExit& e = side.exits[rows[m]];
            const __m256i row = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(columnRow(g, r, e.hub)));
            acc = _mm256_min_epu16(acc, _mm256_adds_epu16(row, _mm256_set1_epi16(short(e.steps))));
        }
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(d + uint64_t(i) * kHubBlock), acc);
    }
}

// Whether the target side reads block i (outOfRoom), from the source's distances d.
VG_AVX2_TARGET inline bool blockRead(const vg_graph& g, const uint16_t* d, const HubBlockRef* blocks, uint32_t i) {
    return !outOfRoom(g, blocks[i], lanesMinimum(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(d + uint64_t(i) * kHubBlock))));
}

// The same numbers as targetColumns; whether a block is read is known from d before any of
// them is, so the rows of skipped blocks are neither found nor asked for.
VG_AVX2_TARGET void targetColumnsAvx2(const vg_graph& g, const uint16_t* d, const SideRows& side,
                                      const HubBlockRef* blocks, uint32_t blockCount, RowsAhead& ahead,
                                      uint16_t* acc) {
    const __m256i none = _mm256_set1_epi16(-1);
    for (uint32_t e = 0; e < side.count; ++e) _mm256_storeu_si256(reinterpret_cast<__m256i*>(acc + uint64_t(e) * kHubBlock), none);
    for (uint32_t i = 0; i < 2 * kRowLookahead && i < blockCount; ++i) ahead.askLists(g, side, blocks, i);
    for (uint32_t i = 0; i < kRowLookahead && i < blockCount; ++i) ahead.find(g, side, blocks, i, blockRead(g, d, blocks, i));
    for (uint32_t i = 0; i < blockCount; ++i) {
        if (i + 2 * kRowLookahead < blockCount) ahead.askLists(g, side, blocks, i + 2 * kRowLookahead);
        if (i + kRowLookahead < blockCount)
            ahead.find(g, side, blocks, i + kRowLookahead, blockRead(g, d, blocks, i + kRowLookahead));
        const HubBlockRef& r = blocks[i];
        const __m256i di = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(d + uint64_t(i) * kHubBlock));
        const uint16_t* rows = ahead.rows(i);
        for (uint32_t m = 0, n = ahead.countOf(i); m < n; ++m) {
            const __m256i row = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(columnRow(g, r, side.exits[rows[m]].hub)));
            __m256i* a = reinterpret_cast<__m256i*>(acc + uint64_t(rows[m]) * kHubBlock);
            _mm256_storeu_si256(a, _mm256_min_epu16(_mm256_loadu_si256(a), _mm256_adds_epu16(row, di)));
        }
    }
}
#endif

void sourceColumnsOn(const vg_graph& g, const vg_workspace& ws, const SideRows& side, const HubBlockRef* blocks,
                     uint32_t blockCount, uint16_t* d) {
#if VG_HUB_AVX2
    if (g.avx2) {
        RowsAhead ahead{ws.hubBlockRows, ws.hubBlockRowsEach, {}};
        return sourceColumnsAvx2(g, side, blocks, blockCount, ahead, d);
    }
#endif
    sourceColumns(g, side, blocks, blockCount, ws.hubBlockRows, d);
}

void targetColumnsOn(const vg_graph& g, const vg_workspace& ws, const uint16_t* d, const SideRows& side,
                     const HubBlockRef* blocks, uint32_t blockCount, uint16_t* acc) {
#if VG_HUB_AVX2
    if (g.avx2) {
        RowsAhead ahead{ws.hubBlockRows, ws.hubBlockRowsEach, {}};
        return targetColumnsAvx2(g, d, side, blocks, blockCount, ahead, acc);
    }
#endif
    targetColumns(g, d, side, blocks, blockCount, ws.hubBlockRows, acc);
}

// Asks for what a query will read of side x's exit lists on the common tree path (down to
// `lca`): the first lists of each of x's patches, in one run. A list is a few dozen bytes
// somewhere in megabytes, so each would otherwise be a miss of its own. `stage` 0 asks for
// the list offsets, 1 (later, once they have arrived) for the lists.
void prefetchExitLists(const vg_graph& g, const vg_workspace& ws, uint32_t x, const Side& side, uint32_t lca,
                       int stage) {
    if (g.hubExitLists == nullptr || side.hub != kNone) return;
    const uint32_t lists = ws.hubBlocksAbove[lca] + blocksOf(g.hubTree[lca]);
    forEachPatchOf(g, x, [&](uint32_t patch, uint32_t) {
        const uint32_t* begin = g.hubExitListBegin + g.hubExitPatchBegin[patch];
        const char* from = stage == 0 ? reinterpret_cast<const char*>(begin)
                                      : reinterpret_cast<const char*>(g.hubExitLists + begin[0]);
        const char* to = stage == 0 ? reinterpret_cast<const char*>(begin + lists + 1)
                                    : reinterpret_cast<const char*>(g.hubExitLists + begin[lists]);
        for (const char* p = from; p < to + 64; p += 64) __builtin_prefetch(p);
    });
}

// The exits of side x: a hub itself, or the slots of its first-layer patch that are hubs,
// reached (v[k], the side's distance to slot k, not kNoStep) and with a lower bound
// (cost, per exit candidate) within `upper`; in hub order, so that a block's rows are read
// forward. With `lists` (and exit lists in the blob, and x on at most kMaxSidePatches
// second-layer patches), every candidate, the others with steps kNoStep, and x's patches'
// lists (SideRows).
SideRows sideRows(const vg_graph& g, const vg_workspace& ws, uint32_t x, const Side& side, const uint16_t* v,
                  const float* cost, float upper, bool lists, HubExit* exits, uint32_t* keptHubs) {
    SideRows r{exits, keptHubs, 0, 0, {}};
    if (side.hub != kNone) {
        exits[0] = HubExit{side.hub, 0, 0};
        keptHubs[0] = side.hub;
        r.count = 1;
        return r;
    }
    if (lists && g.hubExitLists != nullptr) {
        uint32_t patches = 0;
        forEachPatchOf(g, x, [&](uint32_t patch, uint32_t) {
            if (patches < kMaxSidePatches) r.listStart[patches] = g.hubExitPatchBegin[patch];
            ++patches;
        });
        r.listCount = patches <= kMaxSidePatches ? patches : 0;
    }
    const uint32_t begin = ws.hubSlotRecordBegin[side.first], end = ws.hubSlotRecordBegin[side.first + 1];
    for (uint32_t c = begin; c < end; ++c) {
        const uint32_t k = ws.hubSlotOrder[c];
        if (k == kNone) continue;  // the group's padding, after the candidates
        const bool usable = v[k] != kNoStep && !(cost[c - begin] > upper);
        if (usable || r.listCount > 0) {
            keptHubs[r.count] = usable ? ws.hubSlotHub[c] : kNone;
            exits[r.count++] = HubExit{ws.hubSlotHub[c], k, usable ? v[k] : kNoStep};
        }
    }
    return r;
}

// Which first-layer nodes of an endpoint's patch a query reads. A node n of s's patch can
// only carry a shortest path to t if d(s, n) + d(n, t) is at most the answer, and d(n, t)
// is at least the straight line and the landmark bounds: the labels of the other nodes
// are never read. The landmark bounds hold in the labels' own metric (baker/hub_landmarks.h)
// up to the rounding they allow for; the straight line, a bound of the geodesic, is below
// a label distance only by the labels' rounding (steps, the patches' quanta), which this
// factor covers.
constexpr float kBoundShrink = 0.98f;
// The bounds (the straight line, and landmark distances taken over node paths) and the
// upper bound describe node paths. Next to t the answer may be an unfolded crossing of a
// node edge (u, x) instead, shorter than the better of its two node paths by less than
// the edge's length: with p where the segment meets the edge, d(s, u) + d(u, t) <= |s'p| +
// |pu| + |up| + |pt'|, so the node path through the nearer end is at most 2 |up| <= |ux|
// longer. So every test allows the longest node edge next to t (nodeEdgeReach) on top of
// the upper bound, and the pruned reads answer as the full reads do. The upper bound also
// gets one label step (t's side rounds its row distances to steps, the answer does not)
// and this factor for the float sums.
constexpr float kUpperSlack = 1.001f;
// The relative float error allowed for an unfolded crossing against its geometric length
// (the unfolding takes square roots of differences), when deciding it cannot win.
constexpr float kCrossingMargin = 1.001f;

struct EndpointBounds {
    const float* position;
    float landmarks[kMaxLandmarks];
    float slack;  // how far a landmark distance may be off beyond the landmark tables' rounding
};

// An exit candidate's landmark distance from its record's steps, as the node records have it.
inline float landmarkStepsDistance(const vg_graph& g, uint32_t k, uint16_t steps) {
    return steps == kLandmarkUnreachable ? __builtin_inff() : float(steps) * g.landmarkScale[k];
}

#if VG_HUB_AVX2
// The same for the eight candidates of a group at once (the same product, exact).
VG_AVX2_TARGET inline __m256 landmarkStepsDistances(const uint16_t* steps, float scale) {
    const __m256i wide = _mm256_cvtepu16_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(steps)));
    const __m256 d = _mm256_mul_ps(_mm256_cvtepi32_ps(wide), _mm256_set1_ps(scale));
    const __m256 none = _mm256_castsi256_ps(_mm256_cmpeq_epi32(wide, _mm256_set1_epi32(kLandmarkUnreachable)));
    return _mm256_blendv_ps(d, _mm256_set1_ps(__builtin_inff()), none);
}
#endif

// x's distance to candidate c of its patch (v: to each slot, in label steps); +inf for
// the padding and for slots it does not reach.
inline float slotStepsDistance(const vg_graph& g, const vg_workspace& ws, const uint16_t* v, uint32_t c) {
    const uint32_t slot = ws.hubSlotOrder[c];
    return slot == kNone || v[slot] == kNoStep ? __builtin_inff() : float(v[slot]) * g.hubLabelScale;
}

// out[k]: the best over candidates [begin, end) of x's distance to the candidate plus the
// candidate's distance to landmark k. A group of kRecordLanes candidates at a time, lane by
// lane (their records lie field by field).
void landmarksThroughGroups(const vg_graph& g, const vg_workspace& ws, uint32_t begin, uint32_t end,
                            const uint16_t* v, float* out) {
    float best[kMaxLandmarks][kRecordLanes];
    for (uint32_t k = 0; k < g.landmarkCount; ++k)
        for (uint32_t j = 0; j < kRecordLanes; ++j) best[k][j] = __builtin_inff();
    for (uint32_t c = begin; c < end; c += kRecordLanes) {
        float d[kRecordLanes];
        for (uint32_t j = 0; j < kRecordLanes; ++j) d[j] = slotStepsDistance(g, ws, v, c + j);
        const uint16_t* group = ws.hubSlotLandmarks + uint64_t(c) * g.landmarkCount;
        for (uint32_t k = 0; k < g.landmarkCount; ++k) {
            const uint16_t* field = group + k * kRecordLanes;
            for (uint32_t j = 0; j < kRecordLanes; ++j) {
                const float through = d[j] + landmarkStepsDistance(g, k, field[j]);
                best[k][j] = through < best[k][j] ? through : best[k][j];
            }
        }
    }
    for (uint32_t k = 0; k < g.landmarkCount; ++k) {
        out[k] = __builtin_inff();
        for (uint32_t j = 0; j < kRecordLanes; ++j) out[k] = best[k][j] < out[k] ? best[k][j] : out[k];
    }
}

#if VG_HUB_AVX2
// The same numbers, a group's eight lanes in one register (a minimum is exact, so the
// order of the final reduction does not matter; no sum here is NaN).
VG_AVX2_TARGET void landmarksThroughGroupsAvx2(const vg_graph& g, const vg_workspace& ws, uint32_t begin,
                                               uint32_t end, const uint16_t* v, float* out) {
    static_assert(kRecordLanes == 8, "one AVX2 register of floats per group");
    __m256 best[kMaxLandmarks];
    for (uint32_t k = 0; k < g.landmarkCount; ++k) best[k] = _mm256_set1_ps(__builtin_inff());
    for (uint32_t c = begin; c < end; c += kRecordLanes) {
        alignas(32) float d[kRecordLanes];
        for (uint32_t j = 0; j < kRecordLanes; ++j) d[j] = slotStepsDistance(g, ws, v, c + j);
        const __m256 vd = _mm256_load_ps(d);
        const uint16_t* group = ws.hubSlotLandmarks + uint64_t(c) * g.landmarkCount;
        for (uint32_t k = 0; k < g.landmarkCount; ++k)
            best[k] = _mm256_min_ps(_mm256_add_ps(vd, landmarkStepsDistances(group + k * kRecordLanes, g.landmarkScale[k])),
                                    best[k]);
    }
    for (uint32_t k = 0; k < g.landmarkCount; ++k) out[k] = lanesMinimum(best[k]);
}
#endif

// x's landmark distances through the first-layer nodes of its patch: the best of x's
// distance to each (v, in label steps) plus its landmark distance in the labels' metric
// (the blob's hub landmarks, baker/hub_landmarks.h). Every label path from x leaves
// through one of them, and l(x) so defined keeps |l(h) - l(x)| at most x's label distance
// to any hub h: l(h) <= l(a) + d(a, h) for the node a that x's path to h leaves by, and
// l(a) <= l(b) + v[a] + v[b] for the node b that gives l(x) (the patch's matrix entry
// between them is at most the way through x), up to the rounding kLandmarkSlackSteps
// allows. A landmark inside the patch needs no exception. The nodes' records are the exit
// bounds' (read anyway), where the row nodes' landmark records would be one scattered
// read each.
void landmarksThroughSlots(const vg_graph& g, const vg_workspace& ws, uint32_t first, const uint16_t* v, float* out) {
    const uint32_t begin = ws.hubSlotRecordBegin[first], end = ws.hubSlotRecordBegin[first + 1];
#if VG_HUB_AVX2
    if (g.avx2) landmarksThroughGroupsAvx2(g, ws, begin, end, v, out);
    else
#endif
        landmarksThroughGroups(g, ws, begin, end, v, out);
}

// How far an endpoint's landmark distances may be off beyond the landmark steps' rounding,
// in label steps: the labels and inner rows are rounded to steps (half a step each, two
// on a side's way to a hub), the first-layer entries to their patches' quanta (about a
// label step on the shared meshes) and the label metric's distances summed in floats.
constexpr float kLandmarkSlackSteps = 4.0f;

// An endpoint's position and landmark distances in the labels' metric: a hub's own
// (baker/hub_landmarks.h), else through its patch's first-layer nodes (v: its distances to
// them).
void endpointBounds(const vg_graph& g, const vg_workspace& ws, uint32_t x, const Side& side, const uint16_t* v,
                    EndpointBounds& b) {
    b.position = g.positions + 3 * uint64_t(x);
    b.slack = kLandmarkSlackSteps * g.hubLabelScale;
    if (side.node == kNone && ws.endpointTable != nullptr) {  // the same numbers, worked out once
        const float* own = ws.endpointTable->vertexLandmarks + uint64_t(x) * g.landmarkCount;
        for (uint32_t k = 0; k < g.landmarkCount; ++k) b.landmarks[k] = own[k];
        return;
    }
    if (side.hub == kNone) {
        landmarksThroughSlots(g, ws, side.first, v, b.landmarks);
        return;
    }
    for (uint32_t k = 0; k < g.landmarkCount; ++k)
        b.landmarks[k] = landmarkStepsDistance(g, k, g.hubLandmarks[uint64_t(side.hub) * g.landmarkCount + k]);
}

// A block's bounds as the query reads them: its sphere (centre, radius) and its landmark
// ranges in steps (the workspace's copies, vg_workspace.h).
struct BlockBounds {
    const float* sphere;
    const uint16_t* ranges;
};
inline BlockBounds blockBounds(const vg_graph& g, const vg_workspace& ws, uint32_t block) {
    return BlockBounds{ws.hubBlockSpheres + 4 * uint64_t(block),
                       ws.hubBlockRanges + uint64_t(blockRangeStride(g.landmarkCount)) * block};
}

// A range end in landmark steps as a distance (the same product in every kernel).
inline float rangeLow(const vg_graph& g, const uint16_t* ranges, uint32_t k) {
    return float(ranges[k]) * g.landmarkScale[k];
}
inline float rangeHigh(const vg_graph& g, const uint16_t* ranges, uint32_t k) {
    const uint16_t q = ranges[g.landmarkCount + k];
    return q == kNoRangeEnd ? __builtin_inff() : float(q) * g.landmarkScale[k];
}

// A lower bound of d(x, h) for the hubs h of a block (its sphere, shrunk, and landmark
// ranges).
float blockBoundTo(const vg_graph& g, const BlockBounds& block, const EndpointBounds& x) {
    const float* c = block.sphere;
    const float dx = c[0] - x.position[0], dy = c[1] - x.position[1], dz = c[2] - x.position[2];
    float best = (__builtin_sqrtf(dx * dx + dy * dy + dz * dz) - c[3]) * kBoundShrink;
    for (uint32_t k = 0; k < g.landmarkCount; ++k) {
        const float lo = rangeLow(g, block.ranges, k), hi = rangeHigh(g, block.ranges, k), d = x.landmarks[k];
        if (d == __builtin_inff()) continue;
        const float below = lo - d, above = d - hi;
        const float b = (below > above ? below : above) - (2.0f * g.landmarkScale[k] + x.slack);
        if (b > best) best = b;  // a range without ends [0, +inf) never is a positive one
    }
    return best > 0.0f ? best : 0.0f;
}

#if VG_HUB_AVX2
// The landmark part of blockBoundTo eight landmarks at a time, one lane each.
struct LandmarkLanes {
    alignas(32) float distance[kMaxLandmarks];   // the endpoint's; +inf: no bound (or no landmark)
    alignas(32) float allowance[kMaxLandmarks];  // two landmark steps and the endpoint's slack
    alignas(32) float scale[kMaxLandmarks];      // the landmarks' step lengths
};

void landmarkLanes(const vg_graph& g, const EndpointBounds& x, LandmarkLanes& out) {
    const uint32_t groups = (g.landmarkCount + 7) / 8 * 8;
    for (uint32_t k = 0; k < groups; ++k) {
        const bool real = k < g.landmarkCount;
        out.distance[k] = real ? x.landmarks[k] : __builtin_inff();
        out.allowance[k] = real ? 2.0f * g.landmarkScale[k] + x.slack : 0.0f;
        out.scale[k] = real ? g.landmarkScale[k] : 0.0f;
    }
}

// The same numbers as blockBoundTo: the same operations on each landmark, and a maximum.
// A partial last group reads past its landmarks' low and high ends, inside the block's
// entries (blockRangeStride); those lanes have no distance and count for nothing.
VG_AVX2_TARGET float blockBoundToAvx2(const vg_graph& g, const BlockBounds& block, const EndpointBounds& x,
                                      const LandmarkLanes& lanes) {
    const float* c = block.sphere;
    const float dx = c[0] - x.position[0], dy = c[1] - x.position[1], dz = c[2] - x.position[2];
    const float sphere = (__builtin_sqrtf(dx * dx + dy * dy + dz * dz) - c[3]) * kBoundShrink;
    const __m256 inf = _mm256_set1_ps(__builtin_inff()), none = _mm256_set1_ps(-__builtin_inff());
    const __m256i noEnd = _mm256_set1_epi32(kNoRangeEnd);
    __m256 best = none;
    for (uint32_t k = 0; k < g.landmarkCount; k += 8) {
        const __m256 scale = _mm256_load_ps(lanes.scale + k);
        const __m256i loSteps = _mm256_cvtepu16_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(block.ranges + k)));
        const __m256i hiSteps = _mm256_cvtepu16_epi32(
            _mm_loadu_si128(reinterpret_cast<const __m128i*>(block.ranges + g.landmarkCount + k)));
        const __m256 lo = _mm256_mul_ps(_mm256_cvtepi32_ps(loSteps), scale);
        const __m256 hi = _mm256_blendv_ps(_mm256_mul_ps(_mm256_cvtepi32_ps(hiSteps), scale), inf,
                                           _mm256_castsi256_ps(_mm256_cmpeq_epi32(hiSteps, noEnd)));
        const __m256 d = _mm256_load_ps(lanes.distance + k);
        const __m256 below = _mm256_sub_ps(lo, d), above = _mm256_sub_ps(d, hi);
        const __m256 wider = _mm256_blendv_ps(above, below, _mm256_cmp_ps(below, above, _CMP_GT_OQ));
        const __m256 b = _mm256_sub_ps(wider, _mm256_load_ps(lanes.allowance + k));
        best = _mm256_max_ps(best, _mm256_blendv_ps(b, none, _mm256_cmp_ps(d, inf, _CMP_EQ_OQ)));
    }
    const __m128 half = _mm_max_ps(_mm256_castps256_ps128(best), _mm256_extractf128_ps(best, 1));
    const __m128 quarter = _mm_max_ps(half, _mm_movehl_ps(half, half));
    const float landmarks = _mm_cvtss_f32(_mm_max_ss(quarter, _mm_shuffle_ps(quarter, quarter, 1)));
    const float bound = landmarks > sphere ? landmarks : sphere;
    return bound > 0.0f ? bound : 0.0f;
}
#endif

// Both endpoints' bounds as the block bounds take them (with AVX2, the landmarks in lanes),
// and the workspace the blocks' bounds are read from.
struct PathBounds {
    const EndpointBounds* s;
    const EndpointBounds* t;
    const vg_workspace* ws;
#if VG_HUB_AVX2
    LandmarkLanes lanesS, lanesT;
#endif
};

void preparePathBounds(const vg_graph& g, const vg_workspace& ws, const EndpointBounds& bs, const EndpointBounds& bt,
                       PathBounds& out) {
    out.s = &bs;
    out.t = &bt;
    out.ws = &ws;
#if VG_HUB_AVX2
    if (g.avx2) {
        landmarkLanes(g, bs, out.lanesS);
        landmarkLanes(g, bt, out.lanesT);
    }
#else
    (void)g;
#endif
}

// A lower bound of d(x, h) for the hubs h of a block from its sphere alone (at most
// blockBoundTo's: the same sphere term, without the landmark ranges).
inline float sphereBoundTo(const float* sphere, const float* x) {
    const float dx = sphere[0] - x[0], dy = sphere[1] - x[1], dz = sphere[2] - x[2];
    const float d = __builtin_sqrtf(dx * dx + dy * dy + dz * dz) - sphere[3];
    return d > 0.0f ? d : 0.0f;
}

// Block r's bounds from its sphere and landmark ranges, once.
void tighten(const vg_graph& g, const PathBounds& b, HubBlockRef& r) {
    if (r.landmarks == kNone) return;
    const BlockBounds block = blockBounds(g, *b.ws, r.landmarks);
#if VG_HUB_AVX2
    if (g.avx2) {
        r.toTargetBound = blockBoundToAvx2(g, block, *b.t, b.lanesT);
        r.throughBound = blockBoundToAvx2(g, block, *b.s, b.lanesS) + r.toTargetBound;
        r.landmarks = kNone;
        return;
    }
#endif
    r.toTargetBound = blockBoundTo(g, block, *b.t);
    r.throughBound = blockBoundTo(g, block, *b.s) + r.toTargetBound;
    r.landmarks = kNone;
}

// Asks for block r's landmark ranges (one cache line up to 16 landmarks), unless they were
// read already.
inline void prefetchBounds(const vg_graph& g, const PathBounds& b, const HubBlockRef& r) {
    if (r.landmarks == kNone) return;
    const uint32_t stride = blockRangeStride(g.landmarkCount);
    const char* ranges = reinterpret_cast<const char*>(b.ws->hubBlockRanges + uint64_t(stride) * r.landmarks);
    for (uint32_t at = 0; at < stride * 2; at += 64) __builtin_prefetch(ranges + at);
}

// Whether a path from s to t through block r's hubs may be no longer than `upper`: its
// sphere bound first, its landmark ranges only if that passes.
inline bool mayPass(const vg_graph& g, const PathBounds& b, HubBlockRef& r, float upper) {
    if (r.throughBound >= upper) return false;
    tighten(g, b, r);
    return r.throughBound < upper;
}

// Every block of the common tree path (from the root down to tree node `lca`, in the order
// their matrices lie in), with lower bounds from their spheres when `bounded` (and the blob
// has block bounds; tighten() adds the landmark ranges). Returns their number; *meetCount:
// how many of the first ones lie at tree node `meetNode` or above, the blocks a hub-to-hub
// meeting between hubs below it can read.
uint32_t pathBlocks(const vg_graph& g, vg_workspace& ws, uint32_t lca, const PathBounds& bounds, bool bounded,
                    uint32_t meetNode, uint32_t* meetCount) {
    HubBlockRef* out = ws.hubBlocks;
    uint32_t count = 0, belowMeet = 0;
    bounded = bounded && g.hubBlockBounds != nullptr;
    // From the common node up to the root, each node's blocks last to first, reversed at the
    // end.
    for (uint32_t x = lca; x != kNone; x = g.hubTree[x].parent) {
        if (x == meetNode) belowMeet = count;
        for (uint32_t b = blocksOf(g.hubTree[x]); b-- > 0;) {
            HubBlockRef r = blockRef(g, ws, x, b);
            if (bounded) {
                const float* sphere = ws.hubBlockSpheres + 4 * uint64_t(ws.hubBlockBegin[x] + b);
                r.toTargetBound = sphereBoundTo(sphere, bounds.t->position) * kBoundShrink;
                r.throughBound = sphereBoundTo(sphere, bounds.s->position) * kBoundShrink + r.toTargetBound;
                r.landmarks = ws.hubBlockBegin[x] + b;
            }
            out[count++] = r;
        }
    }
    for (uint32_t i = 0, j = count; i + 1 < j; ++i, --j) {
        const HubBlockRef r = out[i];
        out[i] = out[j - 1];
        out[j - 1] = r;
    }
    *meetCount = meetNode == kNone ? 0 : count - belowMeet;
    return count;
}

// Keeps the blocks (of pathBlocks, bounded) whose hubs may lie on a path from s to t no
// longer than `upper`, each with the room its target side has. Returns their number.
uint32_t blocksWithin(const vg_graph& g, const PathBounds& bounds, HubBlockRef* blocks, uint32_t count,
                      float upper) {
    if (upper == __builtin_inff()) return count;
    uint32_t kept = 0;
    // The landmark ranges of the next 2 kRowLookahead blocks whose spheres pass (as in
    // hubToHub): one miss each otherwise. `asked`: those asked for and not yet reached.
    uint32_t scan = 0, asked = 0;
    for (uint32_t i = 0; i < count; ++i) {
        for (; asked < 2 * kRowLookahead && scan < count; ++scan)
            if (!(blocks[scan].throughBound > upper)) {
                prefetchBounds(g, bounds, blocks[scan]);
                ++asked;
            }
        HubBlockRef& r = blocks[i];
        if (r.throughBound > upper) continue;
        --asked;  // (every block that passes here was asked for: scan is past it)
        tighten(g, bounds, r);
        if (r.throughBound > upper) continue;
        blocks[kept] = r;
        blocks[kept++].targetRoom = upper - r.toTargetBound;
    }
    return kept;
}

}  // namespace

// (vg_hub_labels.h) The most an unfolded crossing next to t can undercut a node path.
float nodeEdgeReach(const vg_graph& g, const vg_workspace& ws, uint32_t t) {
    float reach = 0.0f;
    forEachPatchOf(g, t, [&](uint32_t patch, uint32_t) {
        reach = ws.hubPatchReach[patch] > reach ? ws.hubPatchReach[patch] : reach;
    });
    return reach;
}

namespace {

// cost[c]: a lower bound of the paths from the endpoint through its patch's c-th exit
// candidate (a slot that is a hub, in hub order) to the other endpoint; +inf where the
// endpoint does not reach it (or c pads the last group). Returns the slot of the smallest,
// the likeliest exit (kNone if none). The portable and AVX2 versions give the same numbers.
uint32_t likeliestExit(const vg_workspace& ws, uint32_t begin, uint32_t end, const float* cost) {
    uint32_t best = kNone;
    float bestCost = __builtin_inff();
    for (uint32_t c = begin; c < end; ++c) {
        const float x = cost[c - begin];
        if (x == __builtin_inff()) continue;
        if (best == kNone || x < bestCost) {
            best = ws.hubSlotOrder[c];
            bestCost = x;
        }
    }
    return best;
}

uint32_t exitCosts(const vg_graph& g, const vg_workspace& ws, uint32_t first, const uint16_t* v,
                   const EndpointBounds& other, float* cost) {
    const uint32_t begin = ws.hubSlotRecordBegin[first], end = ws.hubSlotRecordBegin[first + 1];
    float record[3 + kMaxLandmarks];
    for (uint32_t c = begin; c < end; ++c) {
        const uint32_t k = ws.hubSlotOrder[c];
        float& out = cost[c - begin];
        out = __builtin_inff();
        if (k == kNone || v[k] == kNoStep) continue;
        for (uint32_t a = 0; a < 3; ++a) record[a] = slotPosition(ws.hubSlotPositions, c, a);
        for (uint32_t i = 0; i < g.landmarkCount; ++i)
            record[3 + i] = landmarkStepsDistance(g, i, slotLandmark(ws.hubSlotLandmarks, g.landmarkCount, c, i));
        const float straight = recordDistance(record, other.position) * kBoundShrink;
        out = float(v[k]) * g.hubLabelScale + withLandmarks(g, record, other.landmarks, straight, other.slack);
    }
    return likeliestExit(ws, begin, end, cost);
}

#if VG_HUB_AVX2
// The same slot (the first candidate of the smallest finite cost): the minimum over whole
// groups, then the first lane that holds it.
VG_AVX2_TARGET uint32_t likeliestExitAvx2(const vg_workspace& ws, uint32_t begin, uint32_t end, const float* cost) {
    __m256 low = _mm256_set1_ps(__builtin_inff());
    for (uint32_t c = begin; c < end; c += kRecordLanes) low = _mm256_min_ps(low, _mm256_loadu_ps(cost + (c - begin)));
    const float least = lanesMinimum(low);
    if (!(least < __builtin_inff())) return kNone;
    const __m256 target = _mm256_set1_ps(least);
    for (uint32_t c = begin; c < end; c += kRecordLanes) {
        const int hit = _mm256_movemask_ps(_mm256_cmp_ps(_mm256_loadu_ps(cost + (c - begin)), target, _CMP_EQ_OQ));
        if (hit != 0) return ws.hubSlotOrder[c + uint32_t(__builtin_ctz(unsigned(hit)))];
    }
    return kNone;
}

// The same, a group of kRecordLanes candidates at a time: the straight line and each
// landmark's bound (a landmark the other endpoint does not reach is no bound; an infinite
// difference never is one) as lanes, the same operations in the same order as withLandmarks.
VG_AVX2_TARGET uint32_t exitCostsAvx2(const vg_graph& g, const vg_workspace& ws, uint32_t first, const uint16_t* v,
                                      const EndpointBounds& other, float* cost) {
    static_assert(kRecordLanes == 8, "one AVX2 register of floats per group");
    const uint32_t begin = ws.hubSlotRecordBegin[first], end = ws.hubSlotRecordBegin[first + 1];
    const __m256 inf = _mm256_set1_ps(__builtin_inff()), absMask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
    const __m256 px = _mm256_set1_ps(other.position[0]), py = _mm256_set1_ps(other.position[1]),
                 pz = _mm256_set1_ps(other.position[2]);
    const __m256 scale = _mm256_set1_ps(g.hubLabelScale), shrink = _mm256_set1_ps(kBoundShrink);
    for (uint32_t c = begin; c < end; c += kRecordLanes) {
        const float* group = ws.hubSlotPositions + uint64_t(c) * 3;
        const uint16_t* landmarks = ws.hubSlotLandmarks + uint64_t(c) * g.landmarkCount;
        alignas(32) float steps[kRecordLanes];
        for (uint32_t j = 0; j < kRecordLanes; ++j) {
            const uint32_t k = ws.hubSlotOrder[c + j];
            steps[j] = k == kNone || v[k] == kNoStep ? __builtin_inff() : float(v[k]);
        }
        const __m256 dx = _mm256_sub_ps(_mm256_loadu_ps(group), px);
        const __m256 dy = _mm256_sub_ps(_mm256_loadu_ps(group + kRecordLanes), py);
        const __m256 dz = _mm256_sub_ps(_mm256_loadu_ps(group + 2 * kRecordLanes), pz);
        __m256 best = _mm256_mul_ps(_mm256_sqrt_ps(_mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)),
                                                                 _mm256_mul_ps(dz, dz))),
                                    shrink);
        for (uint32_t k = 0; k < g.landmarkCount; ++k) {
            const __m256 rk = landmarkStepsDistances(landmarks + k * kRecordLanes, g.landmarkScale[k]);
            const __m256 d = _mm256_sub_ps(_mm256_and_ps(_mm256_sub_ps(rk, _mm256_set1_ps(other.landmarks[k])), absMask),
                                           _mm256_set1_ps(2.0f * g.landmarkScale[k] + other.slack));
            const __m256 take = _mm256_and_ps(_mm256_cmp_ps(d, best, _CMP_GT_OQ), _mm256_cmp_ps(d, inf, _CMP_NEQ_OQ));
            best = _mm256_blendv_ps(best, d, take);
        }
        const __m256 s = _mm256_load_ps(steps);
        const __m256 out = _mm256_add_ps(_mm256_mul_ps(s, scale), best);
        _mm256_storeu_ps(cost + (c - begin), _mm256_blendv_ps(out, inf, _mm256_cmp_ps(s, inf, _CMP_EQ_OQ)));
    }
    return likeliestExitAvx2(ws, begin, end, cost);
}
#endif

uint32_t exitCostsOn(const vg_graph& g, const vg_workspace& ws, uint32_t first, const uint16_t* v,
                     const EndpointBounds& other, float* cost) {
#if VG_HUB_AVX2
    if (g.avx2) return exitCostsAvx2(g, ws, first, v, other, cost);
#endif
    return exitCosts(g, ws, first, v, other, cost);
}

// The smallest of first-layer patch `first`'s exit costs (exitCostsOn's; +inf: none).
float leastCost(const vg_workspace& ws, uint32_t first, const float* cost) {
    float least = __builtin_inff();
    for (uint32_t c = 0; c < ws.hubSlotRecordBegin[first + 1] - ws.hubSlotRecordBegin[first]; ++c)
        least = cost[c] < least ? cost[c] : least;
    return least;
}

// The upper bound's hub-to-hub part: the labels' distance between hubs a and b (their best
// sum over the hubs of the first `count` blocks, those of their tree nodes' common ancestor
// and above), in steps, on top of `base`. A block is read only while the path through it
// could still beat the best sum so far (its lower bounds below it, the sphere's first;
// every block when `everyBlock`), the likeliest block by its sphere first: on igea x16 a
// few tens of ~390 blocks. A sum through a skipped block is at least its lower bound, so the bound
// is the same as from every block, up to the rounding the block pruning allows for anyway.
uint16_t hubToHub(const vg_graph& g, const PathBounds& bounds, HubBlockRef* blocks, uint32_t count, uint32_t a,
                  uint32_t b, uint16_t base, bool everyBlock) {
    uint16_t best = kNoStep;
    auto bestDistance = [&] { return best == kNoStep ? __builtin_inff() : float(best) * g.hubLabelScale; };
    auto meet = [&](uint32_t i) {
        const uint16_t m = saturatingSum(base, meetStepsOn(g, columnRow(g, blocks[i], a), columnRow(g, blocks[i], b), kHubBlock));
        best = m < best ? m : best;
    };
    uint32_t likeliest = 0;
    for (uint32_t i = 1; i < count; ++i)
        if (blocks[i].throughBound < blocks[likeliest].throughBound) likeliest = i;
    if (count > 0) meet(likeliest);
    // Only the blocks whose sphere passes can be met (the best only drops), a fraction of the
    // path on the larger graphs (~110 of ~390 on igea x16). Their landmark ranges are asked
    // for 2 kRowLookahead of them ahead, and a block's two rows once those bounds let it
    // pass, kRowLookahead ahead: each is a miss of its own (mostly from memory there), and
    // one after the other they were most of this loop's time. A block is met or skipped on
    // the same bounds and best sum as when taken one at a time (tighten() only computes,
    // and a block tightened early and skipped later would have been skipped then too), so
    // the result is the same.
    auto passes = [&](uint32_t i) { return i != likeliest && (everyBlock || mayPass(g, bounds, blocks[i], bestDistance())); };
    constexpr uint32_t kRing = 2 * kRowLookahead;
    uint32_t ring[kRing];
    uint32_t scan = 0, found = 0, asked = 0, done = 0;  // candidates: found >= asked >= done
    for (;;) {
        for (; found < done + kRing && scan < count; ++scan) {
            if (scan == likeliest || !(everyBlock || blocks[scan].throughBound < bestDistance())) continue;
            prefetchBounds(g, bounds, blocks[scan]);
            ring[found++ % kRing] = scan;
        }
        for (; asked < found && asked <= done + kRowLookahead; ++asked) {
            const uint32_t i = ring[asked % kRing];
            if (passes(i)) {
                __builtin_prefetch(columnRow(g, blocks[i], a));
                __builtin_prefetch(columnRow(g, blocks[i], b));
            }
        }
        if (done == found) break;
        const uint32_t i = ring[done++ % kRing];
        if (passes(i)) meet(i);
    }
    return best;
}

// The upper bound again once s's distances to the hubs of the kept blocks are known (d):
// through t's likeliest exit (hub hubT, baseT steps from t) and the best of those hubs,
// which replaces hubS by every exit of s. If that is lower, t's side reads against it (its
// exits and each block's room). `extra`: what the upper bound adds to a path's length.
float tighterUpper(const vg_graph& g, vg_workspace& ws, uint32_t blockCount, const uint16_t* d, uint32_t hubT,
                   uint16_t baseT, float extra, float upper) {
    uint16_t best = kNoStep;
    for (uint32_t i = 0; i < blockCount; ++i)  // all asked for first: one miss each
        if (inBlock(ws.hubBlocks[i], hubT)) __builtin_prefetch(columnRow(g, ws.hubBlocks[i], hubT));
    for (uint32_t i = 0; i < blockCount; ++i) {
        const HubBlockRef& r = ws.hubBlocks[i];
        if (!inBlock(r, hubT)) continue;
        const uint16_t m = meetStepsOn(g, d + uint64_t(i) * kHubBlock, columnRow(g, r, hubT), kHubBlock);
        best = m < best ? m : best;
    }
    best = saturatingSum(best, baseT);
    if (best == kNoStep) return upper;
    const float tighter = kUpperSlack * float(best) * g.hubLabelScale + extra;
    if (!(tighter < upper)) return upper;
    for (uint32_t i = 0; i < blockCount; ++i) ws.hubBlocks[i].targetRoom = tighter - ws.hubBlocks[i].toTargetBound;
    return tighter;
}

// The unfolded crossing of node edge (v, x) next to t, both ends met (f: from s, b: to t),
// taken into best, unless x's own turn unfolds it (xTurns: every met node gets one) or it
// cannot win: a crossing undercuts the better of its two node paths by less than `reach`
// (kUpperSlack's comment). The edge's length is asked for only past those tests.
template <class Length>
inline float unfoldNodeEdge(uint32_t v, float fv, float bv, uint32_t x, float fx, float bx, bool xTurns, float near,
                            float reach, float margin, float best, Length&& length) {
    if (xTurns && x < v && fx + bx <= near) return best;  // x's own turn unfolds it
    const float nodePath = fv + bv < fx + bx ? fv + bv : fx + bx;
    if (nodePath - reach > best * margin) return best;
    const float l = length();
    const float d = v < x ? crossing(fv, fx, bv, bx, l) : crossing(fx, fv, bx, bv, l);
    return d < best ? d : best;
}

// d[j] = min(d[j], w[k] + columns[k][j]) for the `count` exits k listed in `taken`, j below
// `stride` (a patch's columns, vg_endpoint_table.h).
void lowerColumns(uint16_t* d, const uint16_t* columns, uint32_t stride, const uint16_t* taken, uint32_t count,
                  const uint16_t* w) {
    for (uint32_t i = 0; i < count; ++i) lowerSteps(d, columns + uint64_t(taken[i]) * stride, stride, w[taken[i]]);
}

#if VG_HUB_AVX2
// The same numbers; a patch of up to 64 nodes (nearly all) keeps its minima in registers
// rather than storing and reloading them after each column.
VG_AVX2_TARGET void lowerColumnsAvx2(uint16_t* d, const uint16_t* columns, uint32_t stride, const uint16_t* taken,
                                     uint32_t count, const uint16_t* w) {
    if (stride > 64) {
        for (uint32_t i = 0; i < count; ++i) lowerStepsAvx2(d, columns + uint64_t(taken[i]) * stride, stride, w[taken[i]]);
        return;
    }
    const uint32_t vectors = stride / 16;
    __m256i acc[4];
    for (uint32_t v = 0; v < vectors; ++v) acc[v] = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(d + 16 * v));
    for (uint32_t i = 0; i < count; ++i) {
        const uint16_t* column = columns + uint64_t(taken[i]) * stride;
        const __m256i base = _mm256_set1_epi16(short(w[taken[i]]));
        for (uint32_t v = 0; v < vectors; ++v)
            acc[v] = _mm256_min_epu16(acc[v], _mm256_adds_epu16(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(column + 16 * v)), base));
    }
    for (uint32_t v = 0; v < vectors; ++v) _mm256_storeu_si256(reinterpret_cast<__m256i*>(d + 16 * v), acc[v]);
}
#endif

void lowerColumnsOn(const vg_graph& g, uint16_t* d, const uint16_t* columns, uint32_t stride, const uint16_t* taken,
                    uint32_t count, const uint16_t* w) {
#if VG_HUB_AVX2
    if (g.avx2) return lowerColumnsAvx2(d, columns, stride, taken, count, w);
#endif
    lowerColumns(d, columns, stride, taken, count, w);
}

// Which exits the meeting next to t must take, in steps: every exit k whose node path
// w[k] + vT[k] (through its best node for t, vT being t's steps) is within this. `through`
// is the best such path. The meeting looks at the nodes within `near` (the best node path
// and the reach, meetInPatch) and at their neighbours across a node edge, whose paths are
// longer by at most twice the edge (<= reach) and the entries' rounding (a patch quantum
// each, a label step each for the inner rows). A node within that has its best exit here:
// w[k] + vT[k] <= its path in steps plus half a step (t's rounded entry). The rest is slack
// for the float sums.
float exitLimit(const vg_graph& g, const Patch& p, uint16_t through, float reach) {
    const float scale = g.hubLabelScale;
    const float near = (float(through) + 0.5f) * scale * kCrossingMargin + reach;
    return ((near + 2.0f * reach + 2.0f * p.scale) * kCrossingMargin) / scale + 4.0f;
}

// The meeting next to a target inside one second-layer patch (no node): s's distance to each
// node of the patch (through the first-layer nodes of t's patch that passed, w) met with
// t's row entry to it, then the unfolded crossings of the patch's node edges. The same
// numbers, in the same order, as the general meeting in hubDistance, but from slot-local
// arrays and the patch's own edge list (with its lengths), instead of the search labels
// and node edge lists, which are scattered reads all over the graph.
float meetInPatch(const vg_graph& g, vg_workspace& ws, uint32_t t, uint32_t first, const uint16_t* w, bool prune,
                  float reach, const uint16_t* vT) {
    const float inf = __builtin_inff();
    const uint32_t patch = g.vertexPatch[t], slotT = g.vertexSlot[t];
    const Patch& p = g.second[patch];
    const uint32_t K = g.first[first].slotCount;
    const uint32_t* slots = g.slots + p.slotBegin;
    float* fromS = ws.slotLabel;            // per node slot: s's distance (+inf: not met)
    float* toT = ws.patchNodeDistance;      // ... and t's (+inf: not met)
    // With an endpoint table, s's distance to every node at once from the patch's columns
    // of the exits that passed (w[k] < kNoStep), a fraction of its nodes' inner rows: the
    // same minima, as a column of kNoStep or a sum saturated to it lowers nothing.
    uint16_t* fromSteps = nullptr;
    if (ws.endpointTable != nullptr) {
        const uint32_t stride = endpointColumnStride(p.nodeCount);
        const uint16_t* columns = ws.endpointTable->patchColumns + ws.endpointTable->patchColumnBegin[patch];
        fromSteps = ws.hubPatchSteps;
        for (uint32_t j = 0; j < stride; ++j) fromSteps[j] = kNoStep;
        const uint16_t through = meetStepsOn(g, w, vT, K);  // the best node path, in steps
        if (through == kNoStep) return inf;                 // s reaches no node of the patch
        const float limit = prune ? exitLimit(g, p, through, reach) : inf;
        // The columns taken, listed without branches (whether an exit is taken is a coin
        // toss to the predictor) and asked for together (a few dozen misses, overlapped).
        uint16_t* taken = ws.hubBlockRows;  // the label kernels' row buffers: free again, and >= K
        uint32_t count = 0;
        for (uint32_t k = 0; k < K; ++k) {
            taken[count] = uint16_t(k);
            count += uint32_t(w[k] != kNoStep) & uint32_t(!(float(saturatingSum(w[k], vT[k])) > limit));
        }
        for (uint32_t i = 0; i < count; ++i) {
            const char* column = reinterpret_cast<const char*>(columns + uint64_t(taken[i]) * stride);
            for (uint32_t b = 0; b < stride * 2; b += 64) __builtin_prefetch(column + b);
        }
        lowerColumnsOn(g, fromSteps, columns, stride, taken, count, w);
    }
    const uint16_t* entriesT = ws.endpointTable ? endpointVertexEntries(g, *ws.endpointTable, t) : nullptr;
    float best = inf;
    for (uint32_t j = 0; j < p.nodeCount; ++j) {
        fromS[j] = inf;
        toT[j] = inf;
        uint32_t q, r = kNone;
        if (entriesT != nullptr) {  // (no path also where the node is not reached: the table's)
            q = entriesT[j];
        } else {
            r = ws.hubInnerRowOfSlot[p.slotBegin + j];
            if (r == kNone || !nodeActive(g, slots[j])) continue;
            q = quantum(g.secondDistances, entryIndex(p, slotT, j));
        }
        if (q == kNoPathQuantum) continue;
        toT[j] = float(q) * p.scale;
        const uint16_t steps = fromSteps ? fromSteps[j] : meetStepsOn(g, w, innerRowData(g, first, r), K);
        fromS[j] = steps == kNoStep ? inf : float(steps) * g.hubLabelScale;
        const float via = fromS[j] + toT[j];
        if (via < best) best = via;
    }
    const float margin = prune ? kCrossingMargin : inf;
    const float near = prune ? best * kCrossingMargin + reach : inf;
    const uint32_t end = patchEdgesEnd(g, patch);
    for (uint32_t e = p.edgeBegin; e < end; ++e) {
        const PatchEdge& edge = g.secondEdges[e];
        const uint32_t jv = edge.from, jx = edge.to;
        const float fv = fromS[jv], bv = toT[jv];
        if (!(fv + bv <= near) || toT[jx] == inf) continue;
        best = unfoldNodeEdge(slots[jv], fv, bv, slots[jx], fromS[jx], toT[jx], true, near, reach, margin, best,
                              [&] { return edge.length; });
    }
    return best;
}

}  // namespace

float hubEndpointLandmarks(const vg_graph& g, vg_workspace& ws, uint32_t x, float* out) {
    Side side;
    if (g.hubTreeCount == 0 || g.vertexPatch[x] == kNone || !sideOf(g, x, side)) return -1.0f;
    if (side.hub == kNone) innerSteps(g, ws, x, side, ws.hubSlotSteps);
    EndpointBounds b;
    endpointBounds(g, ws, x, side, ws.hubSlotSteps, b);
    for (uint32_t k = 0; k < g.landmarkCount; ++k) out[k] = b.landmarks[k];
    return b.slack;
}

uint32_t hubEndpointSteps(const vg_graph& g, vg_workspace& ws, uint32_t x, uint16_t* out) {
    Side side;
    if (g.hubTreeCount == 0 || g.vertexPatch[x] == kNone || !sideOf(g, x, side) || side.hub != kNone) return 0;
    innerSteps(g, ws, x, side, out);
    return g.first[side.first].slotCount;
}

float hubBlockBound(const vg_graph& g, vg_workspace& ws, uint32_t x, uint32_t block, bool sphereOnly) {
    Side side;
    if (g.hubTreeCount == 0 || g.hubBlockBounds == nullptr || g.vertexPatch[x] == kNone || !sideOf(g, x, side))
        return -1.0f;
    if (sphereOnly)
        return sphereBoundTo(ws.hubBlockSpheres + 4 * uint64_t(block), g.positions + 3 * uint64_t(x)) * kBoundShrink;
    if (side.hub == kNone) innerSteps(g, ws, x, side, ws.hubSlotSteps);
    EndpointBounds b;
    endpointBounds(g, ws, x, side, ws.hubSlotSteps, b);
    const BlockBounds bounds = blockBounds(g, ws, block);
#if VG_HUB_AVX2
    if (g.avx2) {
        LandmarkLanes lanes;
        landmarkLanes(g, b, lanes);
        return blockBoundToAvx2(g, bounds, b, lanes);
    }
#endif
    return blockBoundTo(g, bounds, b);
}

// out[k]: the best over the n (a multiple of 8) entries of d[i] + lm[k * n + i], for k below
// `count`: an endpoint's landmark distances through its patch's slots (d: its distances,
// lm: the slots' landmark distances, +inf where none). Minima of the same sums as
// landmarksThroughGroups, so the same numbers.
void landmarksThroughRows(const float* d, const float* lm, uint32_t n, uint32_t count, float* out) {
    for (uint32_t k = 0; k < count; ++k) {
        float best = __builtin_inff();
        for (uint32_t i = 0; i < n; ++i) {
            const float through = d[i] + lm[uint64_t(k) * n + i];
            best = through < best ? through : best;
        }
        out[k] = best;
    }
}

#if VG_HUB_AVX2
VG_AVX2_TARGET void landmarksThroughRowsAvx2(const float* d, const float* lm, uint32_t n, uint32_t count, float* out) {
    for (uint32_t k = 0; k < count; ++k) {
        __m256 best = _mm256_set1_ps(__builtin_inff());
        for (uint32_t i = 0; i < n; i += 8)
            best = _mm256_min_ps(_mm256_add_ps(_mm256_loadu_ps(d + i), _mm256_loadu_ps(lm + uint64_t(k) * n + i)), best);
        out[k] = lanesMinimum(best);
    }
}
#endif

void fillEndpointTable(const vg_graph& g, vg_endpoint_table& table) {
    uint64_t rowAt = 0, columnAt = 0, entryAt = 0;
    for (uint32_t q = 0; q < g.secondCount; ++q) {
        const Patch& p = g.second[q];
        const uint32_t first = p.parent, K = g.first[first].slotCount, stride = endpointColumnStride(p.nodeCount);
        table.vertexRowBegin[q] = rowAt;
        table.patchColumnBegin[q] = columnAt;
        table.vertexEntryBegin[q] = entryAt;
        // Each node's inner row (kNone: merged away, or none), found once for the patch.
        uint32_t* rows = table.nodeRows;
        uint16_t* columns = table.patchColumns + columnAt;
        for (uint64_t i = 0; i < uint64_t(K) * stride; ++i) columns[i] = kNoStep;
        for (uint32_t j = 0; j < p.nodeCount; ++j) {
            const uint32_t n = g.slots[p.slotBegin + j];
            rows[j] = nodeActive(g, n) ? innerRow(g, first, n) : kNone;
            if (rows[j] == kNone) continue;
            const uint16_t* row = innerRowData(g, first, rows[j]);
            for (uint32_t k = 0; k < K; ++k) columns[uint64_t(k) * stride + j] = row[k];
        }
        // The slots' landmark distances (+inf for a slot that is no hub and for the padding).
        const uint32_t L = g.landmarkCount, padded = (K + 7) / 8 * 8;
        float* landmarks = table.scratch;
        float* distances = table.scratch + uint64_t(L) * padded;
        for (uint32_t k = 0; k < L; ++k)
            for (uint32_t kk = 0; kk < padded; ++kk) {
                const uint32_t hub = kk < K ? g.nodeHub[g.slots[g.first[first].slotBegin + kk]] : kNone;
                landmarks[uint64_t(k) * padded + kk] =
                    hub == kNone ? __builtin_inff() : landmarkStepsDistance(g, k, g.hubLandmarks[uint64_t(hub) * L + k]);
            }
        // Each vertex's entries to the nodes (no path where a node has no row), its steps as
        // innerSteps works them out (its entry to each node with an inner row, then that
        // row, the same saturating minima), then its landmark distances as endpointBounds
        // takes them.
        for (uint32_t i = p.nodeCount; i < p.slotCount; ++i, rowAt += K) {
            uint16_t* v = table.vertexRows + rowAt;
            for (uint32_t k = 0; k < K; ++k) v[k] = kNoStep;
            for (uint32_t j = 0; j < p.nodeCount; ++j) {
                const uint32_t quanta = rows[j] == kNone ? kNoPathQuantum : quantum(g.secondDistances, entryIndex(p, i, j));
                table.vertexEntries[entryAt++] = uint16_t(quanta);
                if (quanta == kNoPathQuantum) continue;
                const uint16_t base = toSteps(float(quanta) * p.scale, g.hubLabelScale);
                if (base != kNoStep) lowerStepsOn(g, v, innerRowData(g, first, rows[j]), K, base);
            }
            for (uint32_t kk = 0; kk < padded; ++kk)
                distances[kk] = kk < K && v[kk] != kNoStep ? float(v[kk]) * g.hubLabelScale : __builtin_inff();
            float* out = table.vertexLandmarks + uint64_t(g.slots[p.slotBegin + i]) * L;
#if VG_HUB_AVX2
            if (g.avx2) landmarksThroughRowsAvx2(distances, landmarks, padded, L, out);
            else
#endif
                landmarksThroughRows(distances, landmarks, padded, L, out);
        }
        columnAt += uint64_t(K) * stride;
    }
    table.vertexRowBegin[g.secondCount] = rowAt;
    table.patchColumnBegin[g.secondCount] = columnAt;
    table.vertexEntryBegin[g.secondCount] = entryAt;
}

uint32_t innerRow(const vg_graph& g, uint32_t first, uint32_t node) {
    const uint32_t begin = g.hubInnerBegin[first];
    return sortedIndex(g.hubInnerNode + begin, g.hubInnerBegin[first + 1] - begin, node);
}

namespace {

// hubDistance once its endpoints' sides are known.
// `beaten`: a distance another method already has (+inf: none), so that only label paths
// below it matter: the reads are pruned as if the upper bound had come from it.
bool labelDistance(const vg_graph& g, vg_workspace& ws, uint32_t s, uint32_t t, Side a, Side b, float maxDistance,
                   float* out, bool prune, bool generalMeeting, bool meetEveryBlock, float* upperBound,
                   float beaten = __builtin_inff()) {
    // One order for both directions, so that d(s, t) and d(t, s) are the same number: a
    // node on the source side, whose distances to its patch's exits are its own inner row,
    // rather than on the target side, where the meeting would take the rows of all its
    // patches' nodes; else the smaller vertex id first.
    const bool sNode = a.node != kNone, tNode = b.node != kNone;
    if (sNode != tNode ? tNode : t < s) {
        const uint32_t x = s;
        s = t;
        t = x;
        const Side y = a;
        a = b;
        b = y;
    }
    const uint32_t lca = commonAncestor(g, a.tree, b.tree);
    prefetchExitLists(g, ws, s, a, lca, 0);
    prefetchExitLists(g, ws, t, b, lca, 0);
    const float scale = g.hubLabelScale;
    auto distanceOf = [&](uint16_t steps) { return steps == kNoStep ? __builtin_inff() : float(steps) * scale; };

    // Each side's distance to the first-layer nodes of its patch, the likeliest exits and
    // through them an upper bound of the answer; then only the nodes whose lower bound is
    // within it are read.
    uint16_t* vS = ws.hubSlotSteps;
    uint16_t* vT = ws.hubTargetSlotSteps;
    const uint32_t slotsS = a.hub == kNone ? g.first[a.first].slotCount : 0;
    float* costS = ws.hubSlotCost;
    float* costT = ws.hubSlotCost + slotsS + kRecordLanes;  // s's candidates pad to a whole group
    uint32_t hubS = a.hub, hubT = b.hub;
    uint16_t baseS = 0, baseT = 0;
    if (a.hub == kNone) innerSteps(g, ws, s, a, vS);
    if (b.hub == kNone) innerSteps(g, ws, t, b, vT);
    prefetchExitLists(g, ws, s, a, lca, 1);
    prefetchExitLists(g, ws, t, b, lca, 1);
    EndpointBounds boundsS, boundsT;
    endpointBounds(g, ws, s, a, vS, boundsS);
    endpointBounds(g, ws, t, b, vT, boundsT);
    if (a.hub == kNone) {
        const uint32_t k = exitCostsOn(g, ws, a.first, vS, boundsT, costS);
        hubS = k == kNone ? kNone : g.nodeHub[g.slots[g.first[a.first].slotBegin + k]];
        baseS = k == kNone ? kNoStep : vS[k];
    }
    if (b.hub == kNone) {
        const uint32_t k = exitCostsOn(g, ws, b.first, vT, boundsS, costT);
        hubT = k == kNone ? kNone : g.nodeHub[g.slots[g.first[b.first].slotBegin + k]];
        baseT = k == kNone ? kNoStep : vT[k];
    }
    const float reach = b.hub == kNone ? nodeEdgeReach(g, ws, t) : 0.0f;
    // Beaten already where every exit on either side is bounded above it: a label path is
    // at least its exits' costs, less what the meeting next to t may undercut (reach).
    if (prune && beaten != __builtin_inff()) {
        const float limit = kUpperSlack * beaten + scale + reach;
        if ((a.hub == kNone && leastCost(ws, a.first, costS) > limit) || (b.hub == kNone && leastCost(ws, b.first, costT) > limit)) {
            *out = __builtin_inff();
            return true;
        }
    }
    // The upper bound: through the likeliest exits and the labels between their hubs.
    float upper = __builtin_inff();
    const bool bounded = prune && hubS != kNone && hubT != kNone;
    uint32_t meetCount = 0;
    const uint32_t meetNode = bounded ? commonAncestor(g, treeOfHub(g, hubS), treeOfHub(g, hubT)) : kNone;
    PathBounds pathBounds;
    if (bounded) preparePathBounds(g, ws, boundsS, boundsT, pathBounds);
    uint32_t blockCount = pathBlocks(g, ws, lca, pathBounds, bounded, meetNode, &meetCount);
    if (bounded)
        upper = kUpperSlack * distanceOf(hubToHub(g, pathBounds, ws.hubBlocks, meetCount, hubS, hubT,
                                                  saturatingSum(baseS, baseT), meetEveryBlock));
    if (upper != __builtin_inff()) upper += scale + reach;
    if (prune && beaten != __builtin_inff()) {
        const float known = kUpperSlack * beaten + scale + reach;
        upper = known < upper ? known : upper;
    }
    if (upperBound) *upperBound = upper;
    if (bounded && g.hubBlockBounds != nullptr)
        blockCount = blocksWithin(g, pathBounds, ws.hubBlocks, blockCount, upper);
    const HubBlockRef* blocks = ws.hubBlocks;
    uint16_t* dS = ws.hubSteps;
    HubExit* exitsS = ws.hubExits;
    HubExit* exitsT = ws.hubExits + (slotsS > 0 ? slotsS : 1);
    // The exit lists are exact, not bounds: the full reads (the tests' reference) go without.
    const SideRows rowsS = sideRows(g, ws, s, a, vS, costS, upper, prune, exitsS, ws.hubExitHubs);
    sourceColumnsOn(g, ws, rowsS, blocks, blockCount, dS);
    if (bounded && hubT != kNone && upper != __builtin_inff())
        upper = tighterUpper(g, ws, blockCount, dS, hubT, baseT, scale + reach, upper);
    const SideRows rowsT = sideRows(g, ws, t, b, vT, costT, upper, prune, exitsT, ws.hubExitHubs + (exitsT - ws.hubExits));
    uint16_t* acc = ws.hubExitSteps;
    targetColumnsOn(g, ws, dS, rowsT, blocks, blockCount, acc);
    float best = __builtin_inff();
    if (b.hub != kNone) {
        best = distanceOf(rowsT.count == 0 ? kNoStep : lanesMinimum(acc));
    } else {
        // s's distance to each first-layer node of t's patch that passed, then to t's patch nodes.
        const uint32_t first = b.first;
        const Patch& fp = g.first[first];
        uint16_t* w = ws.hubSlotSteps;
        for (uint32_t k = 0; k < fp.slotCount; ++k) w[k] = kNoStep;
        exitDistancesOn(g, exitsT, rowsT.count, acc, w);
        if (b.node == kNone && !generalMeeting) {  // t inside one second-layer patch: the common case
            const float d = meetInPatch(g, ws, t, first, w, prune, reach, vT);
            *out = d <= maxDistance ? d : __builtin_inff();
            return true;
        }
        const uint32_t gen = beginQuery(ws);
        Frontier& F = ws.forward;
        Frontier& B = ws.backward;
        uint32_t* met = ws.patchNodeSlot;  // the nodes labelled from both sides
        uint32_t metCount = 0;
        bool everyMet = true;  // every labelled node is in met (so each gets its own turn)
        auto label = [&](uint32_t u, float fromT, uint32_t r) {
            if (!B.labelled(u)) {
                if (r == kNone) return;
                F.label[u] = Label{distanceOf(meetStepsOn(g, w, innerRowData(g, first, r), fp.slotCount)), gen};
                B.label[u] = Label{fromT, gen};
                if (metCount < kMaxPatchSlots) met[metCount++] = u;
                else everyMet = false;
            } else if (fromT < B.label[u].dist) {
                B.label[u].dist = fromT;
            }
        };
        if (b.node != kNone && nodeActive(g, b.node)) label(b.node, 0.0f, innerRow(g, first, b.node));
        forEachRowNode(g, ws, t, label);
        // Meetings at a node, then across a mesh edge between two of them (vg_distance.cpp).
        for (uint32_t i = 0; i < metCount; ++i) {
            const float via = F.label[met[i]].dist + B.label[met[i]].dist;
            if (via < best) best = via;
        }
        // A crossing undercuts the better of its two node paths by less than its edge, at
        // most `reach` (kUpperSlack's comment). So only edges at a node whose path is within
        // that of the best meeting (and a margin for the unfolding's float error) are
        // unfolded, each once, from its lower node id unless only the other end is near.
        const float margin = prune ? kCrossingMargin : __builtin_inff();
        const float near = prune && everyMet ? best * kCrossingMargin + reach : __builtin_inff();
        for (uint32_t i = 0; i < metCount; ++i) {
            const uint32_t v = met[i];
            const float fv = F.label[v].dist, bv = B.label[v].dist;
            if (!(fv + bv <= near)) continue;
            for (uint32_t e = g.nodeEdgeBegin[v]; e < g.nodeEdgeBegin[v + 1]; ++e) {
                const uint32_t x = g.nodeEdge[e];
                if (!B.labelled(x)) continue;
                best = unfoldNodeEdge(v, fv, bv, x, F.label[x].dist, B.label[x].dist, everyMet, near, reach, margin,
                                      best, [&] { return euclidean(g, g.nodeVertex[v], g.nodeVertex[x]); });
            }
        }
    }
    *out = best <= maxDistance ? best : __builtin_inff();
    return true;
}

}  // namespace

bool hubDistance(const vg_graph& g, vg_workspace& ws, uint32_t s, uint32_t t, float maxDistance, float* out,
                 bool prune, bool generalMeeting, bool meetEveryBlock, float* upperBound) {
    if (g.hubTreeCount == 0 || s == t || g.vertexPatch[s] == kNone || g.vertexPatch[t] == kNone) return false;
    Side a, b;
    if (!sideOf(g, s, a) || !sideOf(g, t, b) || shareFirstPatch(g, a, b)) return false;
    return labelDistance(g, ws, s, t, a, b, maxDistance, out, prune, generalMeeting, meetEveryBlock, upperBound);
}

bool hubLeavingDistance(const vg_graph& g, vg_workspace& ws, uint32_t s, uint32_t t, float beaten, float* out) {
    if (g.hubTreeCount == 0 || s == t || g.vertexPatch[s] == kNone || g.vertexPatch[t] == kNone) return false;
    Side a, b;
    if (!sideOf(g, s, a) || !sideOf(g, t, b) || !shareFirstPatch(g, a, b) || (a.hub != kNone && b.hub != kNone))
        return false;
    return labelDistance(g, ws, s, t, a, b, __builtin_inff(), out, true, false, false, nullptr, beaten);
}

uint16_t hubBorderSteps(const vg_graph& g, vg_workspace& ws, uint32_t x) {
    Side side;
    if (g.hubTreeCount == 0 || g.vertexPatch[x] == kNone || !sideOf(g, x, side) || side.hub != kNone) return 0;
    innerSteps(g, ws, x, side, ws.hubSlotSteps);
    const uint32_t K = g.first[side.first].slotCount;
    uint16_t least = kNoStep;
    for (uint32_t k = 0; k < K; ++k) least = ws.hubSlotSteps[k] < least ? ws.hubSlotSteps[k] : least;
    return least;
}

}  // namespace vg
