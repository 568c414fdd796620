#include "hub_exit_lists.h"

#include <algorithm>

#include "parallel.h"
#include "vorogeo_generated.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define VG_EXIT_LISTS_AVX2 1
#else
#define VG_EXIT_LISTS_AVX2 0
#endif

namespace vorogeo {

namespace {

constexpr uint32_t kNo = UINT32_MAX;

// The exits of one first-layer patch in hub order: hub number and slot.
struct Exit {
    uint32_t hub, slot;
};

// For inner row `inner` (one entry per slot of the first-layer patch) and the block
// matrix `block` (kHubBlock entries per hub of the tree node's subtree, from hub `lo`):
// per lane, the first exit among exits[begin, end) with the smallest saturated sum
// inner + label, into best (kNoExit where every sum is "no path").
constexpr uint16_t kNoExit = 0xFFFF;

void bestExits(const uint16_t* inner, const uint16_t* block, uint32_t lo, const Exit* exits, uint32_t begin,
               uint32_t end, uint16_t* best) {
    uint32_t low[kHubBlock];
    for (uint32_t j = 0; j < kHubBlock; ++j) low[j] = kHubUnreachable, best[j] = kNoExit;
    for (uint32_t c = begin; c < end; ++c) {
        const uint16_t* row = block + uint64_t(exits[c].hub - lo) * kHubBlock;
        const uint32_t base = inner[exits[c].slot];
        for (uint32_t j = 0; j < kHubBlock; ++j) {
            const uint32_t sum = std::min<uint32_t>(base + row[j], kHubUnreachable);
            if (sum < low[j]) low[j] = sum, best[j] = uint16_t(c);
        }
    }
}

#if VG_EXIT_LISTS_AVX2
// The same sixteen lanes at once (saturating 16-bit sums, a strict unsigned "less" that
// keeps the first exit of a tie): the same exits.
__attribute__((target("avx2"))) void bestExitsAvx2(const uint16_t* inner, const uint16_t* block, uint32_t lo,
                                                   const Exit* exits, uint32_t begin, uint32_t end, uint16_t* best) {
    __m256i low = _mm256_set1_epi16(-1), arg = _mm256_set1_epi16(-1);  // 65535: none
    for (uint32_t c = begin; c < end; ++c) {
        const __m256i row = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(block + uint64_t(exits[c].hub - lo) * kHubBlock));
        const __m256i sum = _mm256_adds_epu16(row, _mm256_set1_epi16(short(inner[exits[c].slot])));
        const __m256i lower = _mm256_min_epu16(sum, low);
        const __m256i improved = _mm256_andnot_si256(_mm256_cmpeq_epi16(lower, low), _mm256_set1_epi16(-1));
        arg = _mm256_blendv_epi8(arg, _mm256_set1_epi16(short(c)), improved);
        low = lower;
    }
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(best), arg);
}
#endif

}  // namespace

void computeHubExitLists(const std::vector<uint8_t>& flatbuffer, HubLabels& labels, bool allowAvx2) {
    labels.exitPatchBegin.clear();
    labels.exitListBegin.clear();
    labels.exitLists.clear();
    const fb::Graph* g = fb::GetGraph(flatbuffer.data());
    const uint32_t firstCount = g->first_patches()->size(), secondCount = g->second_patches()->size();
    const uint32_t T = uint32_t(labels.tree.size()), H = labels.hubCount;
    if (T == 0) return;
    auto slotNode = [&](uint64_t k) { return g->slots()->Get(uint32_t(k)); };

    // Per first-layer patch its exits in hub order (the runtime's candidate order).
    std::vector<std::vector<Exit>> exits(firstCount);
    for (uint32_t p = 0; p < firstCount; ++p) {
        const fb::PatchRecord& r = *g->first_patches()->Get(p);
        for (uint32_t k = 0; k < r.slot_count(); ++k) {
            const uint32_t hub = labels.nodeHub[slotNode(uint64_t(r.slot_begin()) + k)];
            if (hub != kNo) exits[p].push_back(Exit{hub, k});
        }
        std::sort(exits[p].begin(), exits[p].end(), [](const Exit& a, const Exit& b) { return a.hub < b.hub; });
        if (exits[p].size() >= 0xFFFF) return;  // no 16-bit index: no lists
    }
    // Tree geometry: each node's subtree hubs [hubBegin, end), blocks, and the blocks of
    // its proper ancestors (its first list's index on any path through it).
    std::vector<uint32_t> subtreeEnd(T), blocks(T), blocksAbove(T);
    for (uint32_t t = 0; t < T; ++t) subtreeEnd[t] = t + 1;
    for (uint32_t t = T; t-- > 1;)
        subtreeEnd[labels.tree[t].parent] = std::max(subtreeEnd[labels.tree[t].parent], subtreeEnd[t]);
    for (uint32_t t = 0; t < T; ++t) {
        blocks[t] = (labels.tree[t].hubCount + kHubBlock - 1) / kHubBlock;
        const uint32_t parent = labels.tree[t].parent;
        blocksAbove[t] = parent == kNo ? 0 : blocksAbove[parent] + blocks[parent];
    }
    auto hubEnd = [&](uint32_t t) { return subtreeEnd[t] < T ? labels.tree[subtreeEnd[t]].hubBegin : H; };

    // Inner row of each active node of a first-layer patch (innerNode is sorted per patch).
    auto innerRowOf = [&](uint32_t p, uint32_t node) -> uint32_t {
        const auto b = labels.innerNode.begin() + labels.innerBegin[p], e = labels.innerNode.begin() + labels.innerBegin[p + 1];
        const auto it = std::lower_bound(b, e, node);
        return it != e && *it == node ? uint32_t(it - b) : kNo;
    };

#if VG_EXIT_LISTS_AVX2
    const bool avx2 = allowAvx2 && __builtin_cpu_supports("avx2");
#else
    (void)allowAvx2;
#endif
    std::vector<std::vector<uint32_t>> children(firstCount);  // per first-layer patch, increasing
    for (uint32_t q = 0; q < secondCount; ++q) children[g->second_patches()->Get(q)->parent()].push_back(q);
    std::vector<std::vector<uint32_t>> listEnds(secondCount);  // per patch: each list's end within its part
    std::vector<std::vector<uint16_t>> lists(secondCount);
    // Per first-layer patch P: each inner row's best exits per block of P's tree path once
    // (a node lies in two or more second-layer patches, whose lists all need its exits),
    // then each second-layer patch's lists as the union over its nodes' rows.
    parallelFor(firstCount, [&](size_t pIndex) {
        const uint32_t p = uint32_t(pIndex);
        if (children[p].empty()) return;
        const uint32_t K = g->first_patches()->Get(p)->slot_count();
        const uint32_t R = labels.innerBegin[p + 1] - labels.innerBegin[p];
        const uint16_t* innerMatrix = labels.inner.data() + labels.innerMatrixBegin[p];
        const std::vector<Exit>& ex = exits[p];
        struct PathBlock {
            const uint16_t* block;
            uint32_t lo, begin, end;
        };
        std::vector<PathBlock> pathBlocks;  // root first, a tree node's blocks in order
        std::vector<uint32_t> path;
        for (uint32_t t = labels.firstLeaf[p]; t != kNo; t = labels.tree[t].parent) path.push_back(t);
        std::reverse(path.begin(), path.end());
        for (uint32_t t : path) {
            const uint32_t lo = labels.tree[t].hubBegin, hi = hubEnd(t);
            auto byHub = [](const Exit& e, uint32_t hub) { return e.hub < hub; };
            const uint32_t begin = uint32_t(std::lower_bound(ex.begin(), ex.end(), lo, byHub) - ex.begin());
            const uint32_t end = uint32_t(std::lower_bound(ex.begin(), ex.end(), hi, byHub) - ex.begin());
            for (uint32_t b = 0; b < blocks[t]; ++b) {
                const uint16_t* block = labels.columns.data() + labels.columnBegin[t] + uint64_t(b) * kHubBlock * (hi - lo);
                pathBlocks.push_back(PathBlock{block, lo, begin, end});
            }
        }
        // best: per block and inner row, the best exit of each lane.
        const size_t B = pathBlocks.size();
        std::vector<uint16_t> best(B * R * kHubBlock);
        for (size_t k = 0; k < B; ++k) {
            const PathBlock& pb = pathBlocks[k];
            for (uint32_t r = 0; r < R; ++r) {
                const uint16_t* inner = innerMatrix + uint64_t(r) * K;
                uint16_t* out = best.data() + (k * R + r) * kHubBlock;
#if VG_EXIT_LISTS_AVX2
                if (avx2) {
                    bestExitsAvx2(inner, pb.block, pb.lo, ex.data(), pb.begin, pb.end, out);
                    continue;
                }
#endif
                bestExits(inner, pb.block, pb.lo, ex.data(), pb.begin, pb.end, out);
            }
        }
        std::vector<uint8_t> needed(ex.size());
        std::vector<uint32_t> rows;  // the inner rows of q's active nodes
        for (uint32_t q : children[p]) {
            const fb::PatchRecord& sp = *g->second_patches()->Get(q);
            rows.clear();
            for (uint32_t j = 0; j < sp.node_count(); ++j) {
                const uint32_t node = slotNode(uint64_t(sp.slot_begin()) + j);
                if ((g->node_flags()->Get(node) & 1u) != 0) continue;  // merged away: not a row node
                const uint32_t r = innerRowOf(p, node);
                if (r != kNo) rows.push_back(r);
            }
            for (size_t k = 0; k < B; ++k) {
                std::fill(needed.begin(), needed.end(), 0);
                for (uint32_t r : rows) {
                    const uint16_t* lanes = best.data() + (k * R + r) * kHubBlock;
                    for (uint32_t j = 0; j < kHubBlock; ++j)
                        if (lanes[j] != kNoExit) needed[lanes[j]] = 1;
                }
                for (uint32_t c = pathBlocks[k].begin; c < pathBlocks[k].end; ++c)
                    if (needed[c]) lists[q].push_back(uint16_t(c));
                listEnds[q].push_back(uint32_t(lists[q].size()));
            }
        }
    });

    labels.exitPatchBegin.assign(1, 0);
    labels.exitListBegin.assign(1, 0);
    for (uint32_t q = 0; q < secondCount; ++q) {
        const uint32_t offset = uint32_t(labels.exitLists.size());
        for (uint32_t e : listEnds[q]) labels.exitListBegin.push_back(offset + e);
        labels.exitLists.insert(labels.exitLists.end(), lists[q].begin(), lists[q].end());
        labels.exitPatchBegin.push_back(uint32_t(labels.exitListBegin.size() - 1));
    }
}

}  // namespace vorogeo
