// vg_workspace_size / vg_workspace_init: one layout function computes the size and, given
// memory, assigns the arrays, so the two can never disagree.
#include "vg_workspace.h"

#include "vg_path_taut.h"
#include "vg_field_kernels.h"
#include "vg_endpoint_table.h"
#include "vg_huge_pages.h"
#include "vg_hub_labels.h"
#include "vg_layout.h"
#include "vg_patch_pairs.h"

#include <string.h>

namespace {

constexpr size_t kAlign = 64;  // a cache line: a block's landmark ranges are one (blockRangeStride)
using vg::kMaxPatchSlots;
using vg::Layout;

// One past the last node slot of any second-layer patch.
uint64_t secondNodeSlotEnd(const vg_graph& g) {
    uint64_t end = 0;
    for (uint32_t i = 0; i < g.secondCount; ++i) {
        const uint64_t e = uint64_t(g.second[i].slotBegin) + g.second[i].nodeCount;
        if (e > end) end = e;
    }
    return end;
}

// Floats for one patch's decoded node rows over its interior slots (vg_field.cpp), plus the
// kernels' slack. At most n (S - n) rounded up, under 2^31 for S <= 65536 slots, so the
// crossing kernel's 32-bit offsets into it never overflow.
uint64_t patchEntriesCapacity(const vg_graph& g) {
    uint64_t most = 0;
    for (uint32_t i = 0; i < g.secondCount; ++i) {
        const vg::Patch& p = g.second[i];
        const uint64_t need = uint64_t(p.nodeCount) * vg::entriesStride(p.slotCount - p.nodeCount);
        if (need > most) most = need;
    }
    return most + vg::kRowSlack;
}

uint64_t firstSlotCount(const vg_graph& g) {
    uint64_t n = 0;
    for (uint32_t p = 0; p < g.firstCount; ++p) n += g.first[p].slotCount;
    return n;
}

// Blocks of kHubBlock hubs over every tree node (each node's hubs in whole blocks).
uint64_t hubBlockCount(const vg_graph& g) {
    uint64_t n = 0;
    for (uint32_t t = 0; t < g.hubTreeCount; ++t) n += vg::hubBlocksOf(g.hubTree[t]);
    return n;
}

void assign(const vg_graph& g, Layout& L, vg_workspace* ws) {
    vg_workspace* w = L.take<vg_workspace>(1);
    const uint64_t N = g.nodeCount, V = g.vertexCount;
    vg_workspace tmp;
    vg_workspace& o = ws ? *w : tmp;
    vg::Frontier* const frontiers[2] = {&o.forward, &o.backward};
    for (vg::Frontier* f : frontiers) {
        f->label = L.take<vg::Label>(N);
        f->route = L.take<vg::Route>(N);
        f->heap = L.take<vg::HeapEntry>(N);
        f->size = 0;
        f->generation = 0;
    }
    o.potential = L.take<vg::Potential>(N);
    o.nodeRecords = L.take<float>(N * (3 + uint64_t(g.landmarkCount)));
    o.detail = L.take<uint32_t>(g.firstCount);
    o.patchTargets = L.take<uint32_t>(g.secondCount);
    o.patchStamp = L.take<uint32_t>(g.secondCount);
    o.vertexNextTarget = L.take<uint32_t>(V);
    o.vertexTargetIndex = L.take<uint32_t>(V);
    o.vertexStamp = L.take<uint32_t>(V);
    // The row kernels read and write whole vectors up to kRowSlack entries past a patch.
    o.patchNodeDistance = L.take<float>(kMaxPatchSlots + vg::kRowSlack);
    o.patchNodeSlot = L.take<uint32_t>(kMaxPatchSlots + vg::kRowSlack);
    o.patchNodeRow = L.take<uint64_t>(kMaxPatchSlots);
    o.patchBest = L.take<float>(kMaxPatchSlots + vg::kRowSlack);
    o.patchBestNode = L.take<uint32_t>(kMaxPatchSlots + vg::kRowSlack);
    o.slotLabel = L.take<float>(kMaxPatchSlots);
    o.slotOrigin = L.take<uint32_t>(kMaxPatchSlots);
    o.patchEdges = L.take<vg::CrossingEdge>(vg::kMaxPatchEdges);
    o.slotFirstEdge = L.take<uint32_t>(secondNodeSlotEnd(g));
    o.patchMemberBegin = L.take<uint32_t>(kMaxPatchSlots + 1);
    o.patchMembers = L.take<uint32_t>(kMaxPatchSlots);
    o.slotEntries = L.take<uint32_t>(kMaxPatchSlots);
    o.patchEntries = L.take<float>(patchEntriesCapacity(g));
    o.patchQueue.position = L.take<uint32_t>(g.secondCount);
    o.patchQueue.heap = L.take<vg::HeapEntry>(g.secondCount);
    o.patchQueue.size = 0;
    o.patchChanged = L.take<uint32_t>(kMaxPatchSlots + vg::kRowSlack);
    o.slotSent = L.take<float>(secondNodeSlotEnd(g));
    o.slotDist = L.take<float>(secondNodeSlotEnd(g));
    o.slotSource = L.take<uint32_t>(secondNodeSlotEnd(g));
    o.slotThrough = L.take<uint8_t>(secondNodeSlotEnd(g));
    o.slotBlank = L.take<float>(secondNodeSlotEnd(g));
    o.parallel.activeNodes = L.take<uint32_t>(g.secondCount);
    o.parallel.labelledNodes = L.take<uint32_t>(g.secondCount);
    o.parallel.readyPatches = L.take<uint32_t>(g.secondCount);
    o.parallel.pending = L.take<vg::HeapEntry>(g.secondCount);
    o.targetEndpoints = L.take<vg::Endpoint>(vg::kTargetChunk);
    o.pathNodes = L.take<uint32_t>(N + 1);
    o.pathLegs = L.take<vg::PathLeg>(vg::maxPathLegs(N));
    o.pathSteps = L.take<vg::PathLeg>(vg::maxPathLegs(N));
    o.pathRaw = L.take<vg_path_point>(vg::maxRawPathPoints(g.faceCount));
    o.pathTaut = L.take<vg_path_point>(vg::maxRawPathPoints(g.faceCount));
    o.pathPortals = L.take<vg::Portal>(vg::maxPortals(g.faceCount));
    o.pathApexes = L.take<vg::Apex>(vg::maxPortals(g.faceCount) + 2);
    const uint64_t pathBlocks = g.hubTreeCount ? g.hubMaxPath / vg::kHubBlock + g.hubTreeCount : 0;
    const uint64_t patchSlots = g.hubTreeCount ? vg::largestFirstPatch(g) : 0;
    o.hubSteps = L.take<uint16_t>(pathBlocks * vg::kHubBlock);
    o.hubExitSteps = L.take<uint16_t>((patchSlots + 1) * vg::kHubBlock);
    o.hubExits = L.take<vg::HubExit>(2 * (patchSlots + 1));
    o.hubExitHubs = L.take<uint32_t>(2 * (patchSlots + 1));
    o.hubSubtreeEnd = L.take<uint32_t>(g.hubTreeCount);
    o.hubSlotSteps = L.take<uint16_t>(uint64_t(g.hubTreeCount ? vg::largestFirstPatch(g) : 0) + 16);
    o.hubTargetSlotSteps = L.take<uint16_t>(uint64_t(g.hubTreeCount ? vg::largestFirstPatch(g) : 0) + 16);
    o.hubSlotCost = L.take<float>(2 * uint64_t(g.hubTreeCount ? vg::largestFirstPatch(g) + vg::kRecordLanes : 0));
    o.hubBlockBegin = L.take<uint32_t>(uint64_t(g.hubTreeCount) + 1);
    o.hubBlockSpheres = L.take<float>(g.hubBlockBounds ? 4 * hubBlockCount(g) : 0);
    o.hubBlockRanges = L.take<uint16_t>(g.hubBlockBounds ? vg::blockRangeStride(g.landmarkCount) * hubBlockCount(g) : 0);
    o.hubSlotRecordBegin = L.take<uint32_t>(g.hubTreeCount ? uint64_t(g.firstCount) + 1 : 0);
    // Each patch's candidates start a group of kRecordLanes (padded with kNone slots).
    const uint64_t candidates = g.hubTreeCount ? firstSlotCount(g) + uint64_t(g.firstCount) * vg::kRecordLanes : 0;
    o.hubSlotOrder = L.take<uint32_t>(candidates);
    o.hubSlotHub = L.take<uint32_t>(candidates);
    o.hubSlotPositions = L.take<float>(candidates * 3);
    o.hubSlotLandmarks = L.take<uint16_t>(candidates * uint64_t(g.landmarkCount));
    o.hubBlocks = L.take<vg::HubBlockRef>(pathBlocks);
    o.hubBlocksAbove = L.take<uint32_t>(g.hubTreeCount);
    // kRowBuffers blocks' rows of one side: every exit once, or each of its patches' lists.
    o.hubBlockRowsEach = g.hubTreeCount ? uint64_t(vg::kMaxSidePatches) * (patchSlots + 1) : 0;
    o.hubBlockRows = L.take<uint16_t>(vg::kRowBuffers * o.hubBlockRowsEach);
    o.hubPatchReach = L.take<float>(g.hubTreeCount ? g.secondCount : 0);
    o.hubInnerRowOfSlot = L.take<uint32_t>(g.hubTreeCount ? secondNodeSlotEnd(g) : 0);
    o.hubPatchSteps = L.take<uint16_t>(g.hubTreeCount ? vg::endpointColumnStride(uint32_t(vg::largestSecondPatchNodes(g))) : 0);
    o.pairListCapacity = g.hubTreeCount ? vg::patchPairListCapacity(g) : 0;
    o.pairSlotCapacity = g.hubTreeCount ? vg::patchPairSlotCapacity(g) : 0;
    o.pairRanks = L.take<uint32_t>(2 * uint64_t(o.pairListCapacity));
    o.pairSeeds = L.take<float>(2 * uint64_t(o.pairListCapacity));
    o.pairDistances = L.take<float>(2 * uint64_t(o.pairListCapacity));
    o.pairIndexOfRank = L.take<uint32_t>(o.pairListCapacity);
    o.pairSlotIndex = L.take<uint32_t>(2 * uint64_t(o.pairSlotCapacity));
    o.endpointTable = nullptr;
    o.graph = &g;
    o.generation = 0;
    o.slice = vg::FieldSlice{0, 0, 0, nullptr, nullptr, 0, nullptr, nullptr};
}

void clearStamps(vg_workspace& ws) {
    const vg_graph& g = *ws.graph;
    for (uint32_t n = 0; n < g.nodeCount; ++n) {
        ws.forward.label[n].stamp = 0;
        ws.backward.label[n].stamp = 0;
        ws.potential[n].stamp = 0;
    }
    memset(ws.detail, 0, sizeof(uint32_t) * g.firstCount);
    memset(ws.patchStamp, 0, sizeof(uint32_t) * g.secondCount);
    memset(ws.vertexStamp, 0, sizeof(uint32_t) * g.vertexCount);
}

// The A* bounds read a node's position and landmark distances together: one record per
// node, decoded once per workspace instead of gathered from three arrays per query.
void fillNodeRecords(const vg_graph& g, float* records) {
    const uint32_t K = g.landmarkCount, stride = 3 + K;
    for (uint32_t n = 0; n < g.nodeCount; ++n) {
        float* r = records + uint64_t(n) * stride;
        const float* p = g.positions + 3 * uint64_t(g.nodeVertex[n]);
        r[0] = p[0];
        r[1] = p[1];
        r[2] = p[2];
        const uint16_t* q = g.nodeLandmarks + uint64_t(n) * K;
        for (uint32_t k = 0; k < K; ++k)
            r[3 + k] = q[k] == vg::kLandmarkUnreachable ? __builtin_inff() : float(q[k]) * g.landmarkScale[k];
    }
}

// Each block's bounds as a query reads them. Its sphere (the record's first four fields)
// side by side with the other blocks', so that the first bounds of a tree path's blocks are
// a few cache lines. Its landmark ranges in landmark steps (vg_workspace.h): the low end
// rounded down and the high end up, so that the steps times the scale, as the query
// computes it, never narrow the blob's range (which the baker writes as its hubs' steps
// times the scale: the same steps come back); a range without ends (or NaN) keeps no
// bound (0, kNoRangeEnd).
void fillHubBlockBounds(const vg_graph& g, float* spheres, uint16_t* ranges) {
    if (g.hubBlockBounds == nullptr) return;
    const uint32_t L = g.landmarkCount, stride = vg::blockRangeStride(L);
    const uint64_t record = 4 + 2 * uint64_t(L), blocks = hubBlockCount(g);
    for (uint64_t b = 0; b < blocks; ++b) {
        const float* in = g.hubBlockBounds + b * record;
        for (uint32_t k = 0; k < 4; ++k) spheres[4 * b + k] = in[k];
        uint16_t* out = ranges + b * stride;
        for (uint32_t k = 0; k < stride; ++k) out[k] = 0;
        for (uint32_t k = 0; k < L; ++k) {
            const float lo = in[4 + 2 * k], hi = in[5 + 2 * k];
            const float scale = g.landmarkScale[k];
            uint32_t loSteps = 0, hiSteps = vg::kNoRangeEnd;
            if (scale > 0.0f && lo > 0.0f) {  // also false for NaN
                const double x = double(lo) / double(scale);
                loSteps = x < 65534.0 ? uint32_t(x) : 65534u;
                while (loSteps > 0 && float(loSteps) * scale > lo) --loSteps;
                // The largest such step: a range the baker wrote as steps times the scale
                // comes back as those steps (the quotient may fall just below them).
                while (loSteps < 65534u && float(loSteps + 1) * scale <= lo) ++loSteps;
            }
            if (scale > 0.0f && hi >= 0.0f && hi < 65534.0f * scale) {
                hiSteps = uint32_t(double(hi) / double(scale)) + 1;
                while (hiSteps > 0 && float(hiSteps - 1) * scale >= hi) --hiSteps;
                while (hiSteps < vg::kNoRangeEnd && float(hiSteps) * scale < hi) ++hiSteps;
            }
            out[k] = uint16_t(loSteps);
            out[L + k] = uint16_t(hiSteps);
        }
    }
}

// The hub blocks come per tree node in tree order; a query finds a node's first by this.
void fillHubBlockBegin(const vg_graph& g, uint32_t* begin) {
    if (g.hubTreeCount == 0) return;
    begin[0] = 0;
    for (uint32_t t = 0; t < g.hubTreeCount; ++t)
        begin[t + 1] = begin[t] + uint32_t(vg::hubBlocksOf(g.hubTree[t]));
}

// The hub-label query bounds every first-layer slot of an endpoint's patch that is a hub
// (its exits): per patch their slot numbers in hub order, so that the label rows are read
// forward, their hub numbers (one run to read, not a slot and then a node per exit), and
// their node records side by side in groups of kRecordLanes, field by field
// (vg_workspace.h), so that the bounds of a group are one vector step. Each patch starts a
// group; the slots that pad its last group are kNone.
void fillHubSlotRecords(const vg_graph& g, uint32_t* begin, uint32_t* order, uint32_t* hubs, float* positions,
                        uint16_t* landmarks) {
    const uint32_t L = g.landmarkCount;
    uint32_t next = 0;
    auto hubOf = [&](uint32_t p, uint32_t k) { return g.nodeHub[g.slots[g.first[p].slotBegin + k]]; };
    for (uint32_t p = 0; p < g.firstCount; ++p) {
        begin[p] = next;
        for (uint32_t k = 0; k < g.first[p].slotCount; ++k) {
            const uint32_t hub = hubOf(p, k);
            if (hub == vg::kNone) continue;
            uint32_t i = next++;  // insertion: the slots come in node order, mostly in hub order too
            for (; i > begin[p] && hubOf(p, order[i - 1]) > hub; --i) order[i] = order[i - 1];
            order[i] = k;
        }
        for (; next % vg::kRecordLanes != 0; ++next) order[next] = vg::kNone;
        for (uint32_t i = begin[p]; i < next; ++i) {
            const uint32_t node = order[i] == vg::kNone ? vg::kNone : g.slots[g.first[p].slotBegin + order[i]];
            hubs[i] = node == vg::kNone ? vg::kNone : g.nodeHub[node];
            const float* p = node == vg::kNone ? nullptr : g.positions + 3 * uint64_t(g.nodeVertex[node]);
            for (uint32_t a = 0; a < 3; ++a) vg::slotPosition(positions, i, a) = p ? p[a] : 0.0f;
            for (uint32_t k = 0; k < L; ++k)
                vg::slotLandmark(landmarks, L, i, k) = node == vg::kNone ? 0 : g.hubLandmarks[uint64_t(hubs[i]) * L + k];
        }
    }
    begin[g.firstCount] = next;
}

// An unfolded crossing next to a label query's target undercuts a node path by less than
// the crossed node edge (vg_hub_labels.cpp): per second-layer patch the longest node edge
// at its active nodes, so that a query bounds that by one read per patch.
void fillHubPatchReach(const vg_graph& g, float* reach) {
    for (uint32_t p = 0; p < g.secondCount; ++p) {
        float longest = 0.0f;
        for (uint32_t j = 0; j < g.second[p].nodeCount; ++j) {
            const uint32_t u = g.slots[g.second[p].slotBegin + j];
            if (!vg::nodeActive(g, u)) continue;
            for (uint32_t e = g.nodeEdgeBegin[u]; e < g.nodeEdgeBegin[u + 1]; ++e) {
                const float l = vg::euclidean(g, g.nodeVertex[u], g.nodeVertex[g.nodeEdge[e]]);
                longest = l > longest ? l : longest;
            }
        }
        reach[p] = longest;
    }
}

// Where each node slot's patch edges start: they come in order of their first slot
// (vg_validate.cpp), so a slot's edges run to the next slot's first, and the last slot's
// to the patch's end. The fill then reads only the edges of the nodes that are some
// vertex's best instead of scanning all of a patch's (igea's field on one thread:
// 1.07x, BENCHMARKS.md).
void fillSlotFirstEdges(const vg_graph& g, uint32_t* first) {
    for (uint32_t i = 0; i < g.secondCount; ++i) {
        const vg::Patch& p = g.second[i];
        uint32_t e = p.edgeBegin;
        const uint32_t end = vg::patchEdgesEnd(g, i);
        for (uint32_t j = 0; j < p.nodeCount; ++j) {
            while (e < end && g.secondEdges[e].from < j) ++e;
            first[p.slotBegin + j] = e;
        }
    }
}

// Which inner row (vg_hub_labels.cpp) each node slot's node has in its patch's first-layer
// patch: the query then finds an endpoint's rows without searching the sorted node lists.
void fillHubInnerRows(const vg_graph& g, uint32_t* rowOfSlot) {
    for (uint32_t p = 0; p < g.secondCount; ++p) {
        const vg::Patch& patch = g.second[p];
        for (uint32_t j = 0; j < patch.nodeCount; ++j)
            rowOfSlot[patch.slotBegin + j] = vg::innerRow(g, patch.parent, g.slots[patch.slotBegin + j]);
    }
}

}  // namespace

namespace vg {

uint32_t beginQuery(vg_workspace& ws) {
    if (++ws.generation == 0) {  // wrapped: old stamps could collide with new generations
        clearStamps(ws);
        ws.generation = 1;
    }
    ws.forward.reset(ws.generation);
    ws.backward.reset(ws.generation);
    return ws.generation;
}

}  // namespace vg

namespace {

// Bytes the arrays take from the aligned start of a workspace's memory.
size_t layoutBytes(const vg_graph& g) {
    Layout L{nullptr, kAlign};
    assign(g, L, nullptr);
    return L.used;
}

}  // namespace

extern "C" size_t vg_workspace_size(const vg_graph* graph) {
    if (graph == nullptr) return 0;
    return layoutBytes(*graph) + kAlign - 1;  // the start is aligned within the memory given
}

extern "C" vg_status vg_workspace_init(const vg_graph* graph, void* memory, size_t memory_size,
                                       vg_workspace** out_workspace) {
    if (out_workspace == nullptr) return VG_ERR_INVALID_ARGUMENT;
    *out_workspace = nullptr;
    if (graph == nullptr || memory == nullptr) return VG_ERR_INVALID_ARGUMENT;
    const size_t used = layoutBytes(*graph);
    if (memory_size < used + kAlign - 1) return VG_ERR_BUFFER_TOO_SMALL;  // vg_workspace_size
    vg::adviseHugePages(memory, memory_size);  // before the first write (vg_huge_pages.h)
    unsigned char* base = reinterpret_cast<unsigned char*>(
        (reinterpret_cast<uintptr_t>(memory) + kAlign - 1) & ~uintptr_t(kAlign - 1));
    // Every page written once here, not first by some query: a page's first write is a
    // fault (on a huge page, 2 MB cleared: about 1 ms on igea's test machine), which would
    // land on the first queries of a workspace as latency spikes.
    memset(base, 0, used);
    Layout L{base, kAlign};
    vg_workspace* ws = reinterpret_cast<vg_workspace*>(base);
    assign(*graph, L, ws);
    clearStamps(*ws);
    fillNodeRecords(*graph, ws->nodeRecords);
    fillHubBlockBegin(*graph, ws->hubBlockBegin);
    fillHubBlockBounds(*graph, ws->hubBlockSpheres, ws->hubBlockRanges);
    for (uint32_t t = 0; t < graph->hubTreeCount; ++t) {
        ws->hubSubtreeEnd[t] = vg::hubSubtreeEnd(graph->hubTree, graph->hubTreeCount, graph->hubCount, t);
        const uint32_t parent = graph->hubTree[t].parent;  // preorder: filled before t
        ws->hubBlocksAbove[t] = parent == vg::kNone ? 0 : ws->hubBlocksAbove[parent] + ws->hubBlockBegin[parent + 1] - ws->hubBlockBegin[parent];
    }
    if (graph->hubTreeCount) {
        fillHubSlotRecords(*graph, ws->hubSlotRecordBegin, ws->hubSlotOrder, ws->hubSlotHub,
                           ws->hubSlotPositions, ws->hubSlotLandmarks);
        fillHubPatchReach(*graph, ws->hubPatchReach);
        fillHubInnerRows(*graph, ws->hubInnerRowOfSlot);
        for (uint32_t r = 0; r < ws->pairListCapacity; ++r) ws->pairIndexOfRank[r] = vg::kNone;
    }
    fillSlotFirstEdges(*graph, ws->slotFirstEdge);
    for (uint32_t i = 0; i < graph->secondCount; ++i) {
        const vg::Patch& p = graph->second[i];
        uint32_t active = 0;
        for (uint32_t j = 0; j < p.nodeCount; ++j) {
            const bool on = vg::nodeActive(*graph, graph->slots[p.slotBegin + j]);
            ws->slotBlank[p.slotBegin + j] = on ? __builtin_inff() : -__builtin_inff();
            active += on ? 1 : 0;
        }
        ws->parallel.activeNodes[i] = active;
    }
    ws->searchMode = VG_SEARCH_HUB_LABELS;
    *out_workspace = ws;
    return VG_OK;
}

extern "C" vg_status vg_workspace_set_search(vg_workspace* workspace, vg_search_mode mode) {
    if (workspace == nullptr) return VG_ERR_INVALID_ARGUMENT;
    if (mode != VG_SEARCH_DIRECTED && mode != VG_SEARCH_BIDIRECTIONAL && mode != VG_SEARCH_HUB_LABELS)
        return VG_ERR_INVALID_ARGUMENT;
    workspace->searchMode = mode;
    return VG_OK;
}
