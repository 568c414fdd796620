// Pairs inside one first-layer patch (vg_patch_pairs.h). The labels answer the paths that
// leave a first-layer patch; a pair inside one was searched instead, twice (vg_distance.cpp:
// from each end, as a short pair), which made these ~3% of igea's random pairs about half
// of its slowest 1%. The endpoint table holds the distances between the patch's nodes over
// its second layer, so the two ends' patch nodes meet in one pass over a small block of
// them: the distance from s to each node around t, and from t to each node around s. The
// pair then meets next to t and next to s as the directed search meets next to its target
// (through a node, or across a node edge unfolded). The paths that leave the patch and come
// back are the labels' (hubLeavingDistance), read only where they could be shorter: a
// hub end's always, others' only when both ends' steps to the patch border add up to less
// than the best inside. The answer is the shortest of these and the local answers
// (vg_point_to_point.h). On igea's golden pairs of this kind it is closer to the exact
// distance than the searches were (BENCHMARKS.md).
#include "vg_patch_pairs.h"

#include "vg_endpoint_table.h"
#include "vg_hub_labels.h"
#include "vg_point_to_point.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define VG_PAIRS_AVX2 1
#else
#define VG_PAIRS_AVX2 0
#endif

namespace vg {

namespace {

constexpr uint16_t kNoPathStep = 65535;
// The labels' answer for a leaving path sums rounded steps (each off by up to half a
// step, a few of them) and entries: it is trusted to stay above the ends' border steps
// less this many steps, and above that less this share.
constexpr float kBorderRoundingSteps = 4.0f;
constexpr float kBorderMargin = 1.01f;

bool isHub(const vg_graph& g, uint32_t v) {
    const uint32_t node = vertexNode(g, v);
    return node != kNone && g.nodeHub[node] != kNone;
}

// The first-layer patch that holds every second-layer patch of vertex v, kNone when v is
// unused, a hub (a first-layer node, on the borders of two or more) or on patches of two.
uint32_t enclosingFirstPatch(const vg_graph& g, uint32_t v) {
    if (g.vertexPatch[v] == kNone || isHub(g, v)) return kNone;
    const uint32_t first = g.second[g.vertexPatch[v]].parent;
    bool inside = true;
    forEachPatchOf(g, v, [&](uint32_t patch, uint32_t) { inside &= g.second[patch].parent == first; });
    return inside ? first : kNone;
}

// One end's patch nodes, each once: its place in the node distances, the end's entry to
// it (the smallest over the end's patches, 0 at the end itself) and the other end's
// distance to it; and per node slot of each of the end's patches its place in these lists.
struct EndNodes {
    uint32_t* rank;
    float* seed;
    float* distance;
    uint32_t* indexOfRank;  // kNone everywhere between queries
    uint32_t* slotIndex;
    uint32_t patch[kMaxSidePatches], slotOffset[kMaxSidePatches];
    uint32_t count, patchCount;
};

// Lists end x's nodes; false (lists left empty) when x lies on more patches, or more node
// slots, than the workspace holds.
bool listEndNodes(const vg_graph& g, const vg_endpoint_table& table, uint32_t x, uint32_t first, uint32_t slotCapacity,
                  EndNodes& end) {
    end.count = 0;
    end.patchCount = 0;
    uint32_t offset = 0;
    bool fits = true;
    // An interior vertex's entries are a row of the table; a node's, its own matrix row.
    const bool node = vertexNode(g, x) != kNone;
    forEachPatchOf(g, x, [&](uint32_t patch, uint32_t slot) {
        const Patch& p = g.second[patch];
        if (p.parent != first) return;  // a hub's patches on the other side of the border
        if (!fits || end.patchCount == kMaxSidePatches || p.nodeCount > slotCapacity - offset) {
            fits = false;
            return;
        }
        end.patch[end.patchCount] = patch;
        end.slotOffset[end.patchCount++] = offset;
        const uint16_t* entries = node ? nullptr : endpointVertexEntries(g, table, x);
        for (uint32_t j = 0; j < p.nodeCount; ++j) {
            const uint32_t rank = table.nodeRank[p.slotBegin + j];
            const uint32_t q = node ? (j == slot ? 0u : quantum(g.secondDistances, nodeRowStart(p, slot) + j)) : entries[j];
            if (rank == kNone || q == kNoPathQuantum) {
                end.slotIndex[offset + j] = kNone;
                continue;
            }
            const float d = float(q) * p.scale;
            uint32_t i = end.indexOfRank[rank];
            if (i == kNone) {
                i = end.count++;
                end.indexOfRank[rank] = i;
                end.rank[i] = rank;
                end.seed[i] = d;
            } else if (d < end.seed[i]) {
                end.seed[i] = d;
            }
            end.slotIndex[offset + j] = i;
        }
        offset += p.nodeCount;
    });
    for (uint32_t i = 0; i < end.count; ++i) end.indexOfRank[end.rank[i]] = kNone;
    if (!fits) end.count = 0;
    return fits;
}

// The block's rows come from memory (a first-layer patch's node distances are ~1.4 MB on
// igea, and a pair reads ~80 rows of them): each row's cache lines that hold t's columns
// are asked for kRowsAhead rows before the row is read, so that their misses overlap.
// t's columns by their 32-entry chunk: a chunk spans at most two lines of a row.
constexpr uint32_t kRowsAhead = 8;
constexpr uint32_t kMaxChunks = 64;

// t's distinct column chunks (at most kMaxChunks; beyond that only the first are asked for).
uint32_t columnChunks(const EndNodes& t, uint32_t* chunks) {
    uint32_t count = 0;
    for (uint32_t k = 0; k < t.count; ++k) {
        const uint32_t c = t.rank[k] >> 5;
        bool seen = false;
        for (uint32_t x = 0; x < count; ++x) seen |= chunks[x] == c;
        if (!seen && count < kMaxChunks) chunks[count++] = c;
    }
    return count;
}

inline void prefetchRow(const uint16_t* row, const uint32_t* chunks, uint32_t count) {
    for (uint32_t x = 0; x < count; ++x) {
        __builtin_prefetch(row + (uint64_t(chunks[x]) << 5));
        __builtin_prefetch(row + (uint64_t(chunks[x]) << 5) + 31);
    }
}

// The distances from each end to the other end's nodes, in one pass over the block of the
// node distances that joins them (rows of s's nodes, columns of t's): t.distance[k] =
// min over i of s.seed[i] + D(i, k), s.distance[i] = min over k of t.seed[k] + D(i, k).
void crossDistances(const uint16_t* distances, uint64_t rows, float scale, EndNodes& s, EndNodes& t) {
    uint32_t chunks[kMaxChunks];
    const uint32_t chunkCount = columnChunks(t, chunks);
    for (uint32_t i = 0; i < s.count && i < kRowsAhead; ++i) prefetchRow(distances + uint64_t(s.rank[i]) * rows, chunks, chunkCount);
    for (uint32_t k = 0; k < t.count; ++k) t.distance[k] = __builtin_inff();
    for (uint32_t i = 0; i < s.count; ++i) {
        if (i + kRowsAhead < s.count) prefetchRow(distances + uint64_t(s.rank[i + kRowsAhead]) * rows, chunks, chunkCount);
        const uint16_t* row = distances + uint64_t(s.rank[i]) * rows;
        const float si = s.seed[i];
        float fromT = __builtin_inff();
        for (uint32_t k = 0; k < t.count; ++k) {
            const uint16_t q = row[t.rank[k]];
            if (q == kNoPathStep) continue;
            const float w = float(q) * scale;
            const float viaS = si + w, viaT = t.seed[k] + w;
            t.distance[k] = viaS < t.distance[k] ? viaS : t.distance[k];
            fromT = viaT < fromT ? viaT : fromT;
        }
        s.distance[i] = fromT;
    }
}

#if VG_PAIRS_AVX2
// The same, eight of t's nodes at a time: the same products and sums, and minima, which
// do not depend on their order, so the same bits. t's lists are padded to whole vectors
// (rank 0, entry +inf: those lanes add nothing to s's distances; theirs are not read).
__attribute__((target("avx2"))) void crossDistancesAvx2(const uint16_t* distances, uint64_t rows, float scale,
                                                        EndNodes& s, EndNodes& t) {
    const uint32_t padded = (t.count + 7) & ~7u;
    for (uint32_t k = t.count; k < padded; ++k) {
        t.rank[k] = 0;
        t.seed[k] = __builtin_inff();
    }
    const __m256 inf = _mm256_set1_ps(__builtin_inff()), vscale = _mm256_set1_ps(scale);
    const __m256i low = _mm256_set1_epi32(0xFFFF), none = _mm256_set1_epi32(kNoPathStep);
    for (uint32_t k = 0; k < padded; k += 8) _mm256_storeu_ps(t.distance + k, inf);
    uint32_t chunks[kMaxChunks];
    const uint32_t chunkCount = columnChunks(t, chunks);
    for (uint32_t i = 0; i < s.count && i < kRowsAhead; ++i) prefetchRow(distances + uint64_t(s.rank[i]) * rows, chunks, chunkCount);
    for (uint32_t i = 0; i < s.count; ++i) {
        if (i + kRowsAhead < s.count) prefetchRow(distances + uint64_t(s.rank[i + kRowsAhead]) * rows, chunks, chunkCount);
        // Two bytes past a row's last entry are read with it (the table pads its matrices).
        const int* row = reinterpret_cast<const int*>(distances + uint64_t(s.rank[i]) * rows);
        const __m256 si = _mm256_set1_ps(s.seed[i]);
        __m256 fromT = inf;
        for (uint32_t k = 0; k < padded; k += 8) {
            const __m256i at = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(t.rank + k));
            const __m256i q = _mm256_and_si256(_mm256_i32gather_epi32(row, at, 2), low);
            const __m256 noPath = _mm256_castsi256_ps(_mm256_cmpeq_epi32(q, none));
            const __m256 w = _mm256_mul_ps(_mm256_cvtepi32_ps(q), vscale);
            const __m256 viaS = _mm256_blendv_ps(_mm256_add_ps(si, w), inf, noPath);
            const __m256 viaT = _mm256_blendv_ps(_mm256_add_ps(_mm256_loadu_ps(t.seed + k), w), inf, noPath);
            _mm256_storeu_ps(t.distance + k, _mm256_min_ps(_mm256_loadu_ps(t.distance + k), viaS));
            fromT = _mm256_min_ps(fromT, viaT);
        }
        const __m128 half = _mm_min_ps(_mm256_castps256_ps128(fromT), _mm256_extractf128_ps(fromT, 1));
        const __m128 quarter = _mm_min_ps(half, _mm_movehl_ps(half, half));
        s.distance[i] = _mm_cvtss_f32(_mm_min_ss(quarter, _mm_shuffle_ps(quarter, quarter, 1)));
    }
}
#endif

// The meeting next to one end, as the directed search meets next to its target: through
// each of `near`'s nodes, the other end's distance plus this end's entry, and across each
// node edge of near's patches between two of them, unfolded (vg_graph.h crossing: the
// other end's distances on the source side).
float meetNear(const vg_graph& g, const EndNodes& near) {
    float best = __builtin_inff();
    for (uint32_t i = 0; i < near.count; ++i) {
        const float d = near.distance[i] + near.seed[i];
        best = d < best ? d : best;
    }
    // A crossing is never below its better node path over kUnfoldSlack (crossingLength):
    // only the edges whose bound is under the best so far can lower it (most are far from
    // the shortest path, and an unfolding costs two square roots and two divisions).
    for (uint32_t c = 0; c < near.patchCount; ++c) {
        const uint32_t* index = near.slotIndex + near.slotOffset[c];
        const uint32_t end = patchEdgesEnd(g, near.patch[c]);
        for (uint32_t e = g.second[near.patch[c]].edgeBegin; e < end; ++e) {
            const PatchEdge& E = g.secondEdges[e];
            const uint32_t u = index[E.from], w = index[E.to];
            if (u == kNone || w == kNone) continue;
            const float viaU = near.distance[u] + near.seed[u], viaW = near.distance[w] + near.seed[w];
            if (!((viaU < viaW ? viaU : viaW) / kUnfoldSlack < best)) continue;
            const float d = crossing(near.distance[u], near.distance[w], near.seed[u], near.seed[w], E.length);
            best = d < best ? d : best;
        }
    }
    return best;
}

}  // namespace

uint32_t patchPairListCapacity(const vg_graph& g) { return (largestInnerRows(g) + 7) & ~7u; }

uint32_t patchPairSlotCapacity(const vg_graph& g) { return kMaxSidePatches * uint32_t(largestSecondPatchNodes(g)); }

bool patchPairDistance(const vg_graph& g, vg_workspace& ws, uint32_t s, uint32_t t, float maxDistance, float* out) {
    const vg_endpoint_table* table = ws.endpointTable;
    if (table == nullptr || g.hubTreeCount == 0 || s == t) return false;
    // Both inside one first-layer patch, or one of them a hub on its border.
    uint32_t first = enclosingFirstPatch(g, s);
    bool hubEnd = false;
    if (first == kNone) {
        first = enclosingFirstPatch(g, t);
        if (first == kNone || g.vertexPatch[s] == kNone || !isHub(g, s) || !hubInPatch(g, vertexNode(g, s), first)) return false;
        hubEnd = true;
    } else if (enclosingFirstPatch(g, t) != first) {
        if (g.vertexPatch[t] == kNone || !isHub(g, t) || !hubInPatch(g, vertexNode(g, t), first)) return false;
        hubEnd = true;
    }
    // A patch whose node distances the table does not keep (too large for their search).
    const uint64_t rows = g.hubInnerBegin[first + 1] - g.hubInnerBegin[first];
    if (rows > 0 && table->nodeDistanceBegin[first + 1] == table->nodeDistanceBegin[first]) return false;
    float best = __builtin_inff();
    // One order for both directions, so that d(s, t) and d(t, s) are the same number.
    if (t < s) {
        const uint32_t x = s;
        s = t;
        t = x;
    }
    const uint32_t lists = ws.pairListCapacity, slots = ws.pairSlotCapacity;
    EndNodes S{ws.pairRanks, ws.pairSeeds, ws.pairDistances, ws.pairIndexOfRank, ws.pairSlotIndex, {}, {}, 0, 0};
    EndNodes T{ws.pairRanks + lists, ws.pairSeeds + lists, ws.pairDistances + lists, ws.pairIndexOfRank,
               ws.pairSlotIndex + slots, {}, {}, 0, 0};
    if (!listEndNodes(g, *table, s, first, slots, S) || !listEndNodes(g, *table, t, first, slots, T)) return false;
    const uint16_t* distances = table->nodeDistances + table->nodeDistanceBegin[first];
#if VG_PAIRS_AVX2
    if (g.avx2)
        crossDistancesAvx2(distances, rows, table->nodeDistanceScale[first], S, T);
    else
#endif
        crossDistances(distances, rows, table->nodeDistanceScale[first], S, T);

    Meeting local;
    const float nearby = nearbyDistance(g, vertexEndpoint(g, s), vertexEndpoint(g, t), local);
    best = nearby < best ? nearby : best;
    // Next to t the search from s meets t's entries; next to s, the one from t meets s's.
    const float nearT = meetNear(g, T), nearS = meetNear(g, S);
    best = nearT < best ? nearT : best;
    best = nearS < best ? nearS : best;
    // The paths that leave the patch and come back are the labels' (hubLeavingDistance).
    // Each reaches the patch's border from both ends first, and the labels' meeting next to
    // t undercuts such a node path by less than a node edge next to t (a crossing is at
    // least its better node path less its edge); so where the border steps less that are
    // longer than the best inside (with a margin for the steps' rounding), the labels are
    // not read: they could not lower it.
    bool leave = hubEnd;
    if (!hubEnd) {
        const uint32_t steps = uint32_t(hubBorderSteps(g, ws, s)) + hubBorderSteps(g, ws, t);
        const float reachS = nodeEdgeReach(g, ws, s), reachT = nodeEdgeReach(g, ws, t);
        const float border = (float(steps) - kBorderRoundingSteps) * g.hubLabelScale - (reachS > reachT ? reachS : reachT);
        leave = !(best * kBorderMargin < border);
    }
    float leaving = __builtin_inff();
    if (leave && hubLeavingDistance(g, ws, s, t, best, &leaving)) best = leaving < best ? leaving : best;
    if (best == __builtin_inff()) return false;  // no path at all: the search says so
    *out = best <= maxDistance ? best : __builtin_inff();
    return true;
}

}  // namespace vg
