// A query's scratch memory, carved out of caller memory once: per-node labels and an
// indexed binary heap for each search direction, per-patch and per-vertex marks. Labels
// are valid only where their stamp equals the current generation, so a query never
// clears arrays (one increment per query; a full reset once every 2^32 queries).
#pragma once

#include "vg_field_kernels.h"
#include "vg_point.h"

namespace vg {

constexpr uint32_t kFirstLayerBit = 0x80000000u;

struct Portal;  // vg_path_taut.h
struct Apex;

constexpr uint32_t kMaxPatchSlots = 65536;  // slots per patch (vertex slots are 16-bit)
constexpr uint32_t kMaxPatchEdges = 4096;  // crossing edges of one best node (more are skipped)
constexpr uint32_t kTargetChunk = 2048;    // surface-point targets resolved at once (k-nearest)

struct Potential {
    float value;
    uint32_t stamp;
};

struct HeapEntry {
    float key;
    uint32_t node;  // a node id, or a patch id in the PatchQueue
};

// The binary min-heap moves shared by the Frontier and the PatchQueue; place(i, e) stores
// e at heap[i] and records where its id now sits.
template <class Place>
inline void heapSiftUp(HeapEntry* heap, uint32_t i, HeapEntry e, Place&& place) {
    while (i > 0) {
        const uint32_t parent = (i - 1) / 2;
        if (!(e.key < heap[parent].key)) break;
        place(i, heap[parent]);
        i = parent;
    }
    place(i, e);
}
template <class Place>
inline void heapSiftDown(HeapEntry* heap, uint32_t size, uint32_t i, HeapEntry e, Place&& place) {
    for (;;) {
        uint32_t child = 2 * i + 1;
        if (child >= size) break;
        if (child + 1 < size && heap[child + 1].key < heap[child].key) ++child;
        if (!(heap[child].key < e.key)) break;
        place(i, heap[child]);
        i = child;
    }
    place(i, e);
}

// Hub-label queries (vg_hub_labels.cpp): a block of kHubBlock hubs of the common tree path
// that a query reads, as the start of its column matrix in hubColumns and the hubs
// [lo, hi) of its tree node's subtree (the matrix's rows, kHubBlock entries each).
struct HubBlockRef {
    uint64_t base;
    uint32_t lo, hi;
    uint32_t pathIndex;  // the block's place on a tree path from the root (its exit lists' index)
    // The most a query's target side may add to the source's distance to one of the
    // block's hubs and still stay within the upper bound (+inf: read the block whatever it is).
    float targetRoom;
    // Lower bounds of the paths through the block's hubs: from s to t, and from the hubs to
    // t (0 without block bounds); from the block's sphere alone until `landmarks` is kNone,
    // else its block number, to tighten them with its landmark ranges (hubBlockRanges).
    float throughBound, toTargetBound;
    uint32_t landmarks;
};
// A first-layer node through which a query endpoint enters the labels: its hub, its slot
// in the endpoint's first-layer patch, and the endpoint's distance to it in label steps.
struct HubExit {
    uint32_t hub, slot;
    uint16_t steps;
};

// A node's label in one search direction: what every relaxation reads (kept small so
// that more of them stay in cache) ...
struct Label {
    float dist;
    uint32_t stamp;    // == generation when the label belongs to the current query
};
// ... and what only a label change needs.
struct Route {
    uint32_t via;      // patch whose row gave the label (first layer: | kFirstLayerBit)
    uint32_t heapPos;  // kNone when not in the heap
    uint32_t origin;   // which source the label comes from (multi-source fields)
    uint32_t parent;   // node whose row gave the label, kNone when seeded from an endpoint
};

// One leg of a path: from node to node (or an endpoint marker, vg_path.cpp) inside
// second-layer patch `via`, or across first-layer patch `via | kFirstLayerBit`.
struct PathLeg {
    uint32_t from, to, via;
};

// One search direction: tentative distances and the queue of open nodes.
struct Frontier {
    Label* label;
    Route* route;
    HeapEntry* heap;
    uint32_t size;
    uint32_t generation;

    bool labelled(uint32_t u) const { return label[u].stamp == generation; }
    // True when d would lower u's label (or u has none in this query).
    bool better(uint32_t u, float d) const { return label[u].stamp != generation || d < label[u].dist; }
    bool empty() const { return size == 0; }
    float topKey() const { return size ? heap[0].key : __builtin_inff(); }

    // Sets u's label to d (queue key `key`), reached through the row of patch `from` of
    // node `parent` from source `origin`; the caller checked better(u, d).
    void improve(uint32_t u, float d, float key, uint32_t from, uint32_t origin, uint32_t parent) {
        Label& l = label[u];
        Route& r = route[u];
        const bool queued = l.stamp == generation && r.heapPos != kNone;
        l.stamp = generation;
        l.dist = d;
        r.via = from;
        r.origin = origin;
        r.parent = parent;
        siftUp(queued ? r.heapPos : size++, HeapEntry{key, u});  // decrease, or (re)open
    }

    HeapEntry pop() {
        const HeapEntry top = heap[0];
        route[top.node].heapPos = kNone;
        const HeapEntry last = heap[--size];
        if (size > 0) siftDown(0, last);
        return top;
    }

    void reset(uint32_t gen) {
        generation = gen;
        size = 0;
    }

private:
    void place(uint32_t i, HeapEntry e) {
        heap[i] = e;
        route[e.node].heapPos = i;
    }
    void siftUp(uint32_t i, HeapEntry e) {
        heapSiftUp(heap, i, e, [this](uint32_t j, HeapEntry x) { place(j, x); });
    }
    void siftDown(uint32_t i, HeapEntry e) {
        heapSiftDown(heap, size, i, e, [this](uint32_t j, HeapEntry x) { place(j, x); });
    }
};

// The second-layer patches whose nodes have labels not yet relaxed through them, by the
// smallest such label (one-to-all: the search visits a patch at a time, vg_field.cpp).
struct PatchQueue {
    uint32_t* position;  // per patch: index in heap, kNone when not queued
    HeapEntry* heap;     // (smallest unrelaxed label, patch)
    uint32_t size;

    bool empty() const { return size == 0; }
    // Queues `patch` with key k, or lowers its key to k.
    void offer(uint32_t patch, float k) {
        if (position[patch] == kNone) siftUp(size++, HeapEntry{k, patch});
        else if (k < heap[position[patch]].key) siftUp(position[patch], HeapEntry{k, patch});
    }
    uint32_t pop() {
        const uint32_t top = heap[0].node;
        position[top] = kNone;
        const HeapEntry last = heap[--size];
        if (size > 0) siftDown(0, last);
        return top;
    }

private:
    void place(uint32_t i, HeapEntry e) {
        heap[i] = e;
        position[e.node] = i;
    }
    void siftUp(uint32_t i, HeapEntry e) {
        heapSiftUp(heap, i, e, [this](uint32_t j, HeapEntry x) { place(j, x); });
    }
    void siftDown(uint32_t i, HeapEntry e) {
        heapSiftDown(heap, size, i, e, [this](uint32_t j, HeapEntry x) { place(j, x); });
    }
};

// vg_distance_field_parallel's shared state, in the query's workspace: the search tells
// which patches' node labels are final (each patch once, in readyPatches), and the tasks
// fill them from there while it goes on. A label at most the patch queue's smallest key
// can no longer drop (every later label is some relaxed label plus an entry), so a patch
// is ready once all its active nodes have labels and the largest is below that key.
struct alignas(64) ParallelFill {  // (whole lines: the fields after it stay off the counters')
    uint32_t* activeNodes;   // per second-layer patch: its active nodes (set at workspace init)
    uint32_t* labelledNodes; // ... how many of them have labels; kNone once it is ready
    uint32_t* readyPatches;  // the patches in the order they became ready
    HeapEntry* pending;      // patches whose active nodes all have labels, by the largest then
    uint32_t pendingCount;
    uint32_t readyCount;     // readyPatches' length, the search's own copy
    // The shared counters, each on a cache line of its own: a line that one core writes and
    // another reads moves between them each time, and the search must not pay for the tasks'
    // claims, nor for a waiting task's reads, in the fields above that it uses throughout.
    alignas(64) uint32_t published;  // readyPatches' length (atomic: written by the search, read by tasks)
    alignas(64) uint32_t claimed;    // the next readyPatches index a task takes (atomic)
    uint32_t arrivals;               // tasks started (atomic): the first runs the search
};

// A one-to-all query in progress (vg_distance_field_begin / _step). It is live while its
// generation is the workspace's: any other query on the workspace abandons it.
struct FieldSlice {
    uint32_t generation;  // 0: none started
    uint32_t phase;       // 0: search, 1: node distances, 2: fill patches, 3: sources' own patches, 4: done
    uint32_t next;        // next node (Nodes), patch (Fill) or source (Direct)
    const uint32_t* sources;  // vertex sources, or NULL ...
    const vg_point* points;   // ... for surface-point sources
    size_t sourceCount;
    float* out;
    uint32_t* nearest;
};

}  // namespace vg

struct vg_workspace {
    const vg_graph* graph;
    uint32_t generation;
    vg_search_mode searchMode;     // point-to-point search (vg_workspace_set_search)
    vg::Frontier forward, backward;
    float landmarkSource[vg::kMaxLandmarks];  // d(L, source) and d(L, target) of the current query
    float landmarkTarget[vg::kMaxLandmarks];
    vg::Potential* potential;      // per node: A* potential of the current query
    float* nodeRecords;            // per node: position, then d(L, node) per landmark (+inf: none)
    uint32_t* detail;  // per first-layer patch: searched through its second layer
    uint32_t* patchTargets;        // per second-layer patch: first target vertex (vg_nearest)
    uint32_t* patchStamp;
    uint32_t* vertexNextTarget;    // per vertex: next target in the same patch
    uint32_t* vertexTargetIndex;   // per vertex: its first index in the caller's target list
    uint32_t* vertexStamp;
    // vg_distance_field, per patch: in the search its sources, in the fill its reached nodes
    float* patchNodeDistance;      // ... their labels (65536 entries and the kernels' slack),
    uint32_t* patchNodeSlot;       // ... their slots (with the kernels' slack too),
    uint64_t* patchNodeRow;        // ... the packed index of their row (node or interior part);
    float* patchBest;              // per node slot (search) or interior slot (fill): best so far
    uint32_t* patchBestNode;       // ... and the source slot or reached node that gave it
    float* slotLabel;              // per node slot of one patch: its label (+inf: none, or merged away)
    uint32_t* slotOrigin;          // ... and the source it came from
    vg::CrossingEdge* patchEdges;  // one node's crossing edges
    uint32_t* slotFirstEdge;       // per second-layer node slot: its first patch edge (filled at init)
    uint32_t* patchMemberBegin;    // per reached node of one patch: first interior slot it is best for ...
    uint32_t* patchMembers;        // ... in these lists
    uint32_t* slotEntries;         // per node slot of one patch: its row in patchEntries, else kNone
    float* patchEntries;           // node rows over a patch's interior slots, decoded (entriesStride apart)
    vg::PatchQueue patchQueue;     // one-to-all search: patches with news ...
    uint32_t* patchChanged;        // ... a visit's node slots whose labels dropped (and kRowSlack),
    float* slotSent;               // ... and per node slot: the label last relaxed through that patch,
    float* slotDist;               // ... its node's label (+inf: none yet), which announce writes to
                                   //     all the node's slots so that a visit or fill reads a patch's
                                   //     labels from consecutive lines (-inf in both: merged away);
                                   //     the search keeps its labels only here, not in `forward`,
    uint32_t* slotSource;          // ... the label's source,
    uint8_t* slotThrough;          // ... 1 where it came through this patch's own row,
    float* slotBlank;              // ... and what slotSent and slotDist start a query at (at init)
    vg::ParallelFill parallel;     // vg_distance_field_parallel, on the query's workspace
    vg::PrefetchDrip drip;         // the one-to-all query's next patch block, asked for while this one runs
    vg::Endpoint* targetEndpoints; // kTargetChunk resolved targets (vg_point_k_nearest)
    uint32_t* pathNodes;           // N + 1: a node chain being read off (vg_path)
    vg::PathLeg* pathLegs;         // kMaxPathLegs(N): the route's legs, then ...
    vg::PathLeg* pathSteps;        // ... with first-layer legs expanded into second-layer ones
    vg_path_point* pathRaw;        // maxRawPathPoints(F): the traced path, before it is pulled taut,
    vg_path_point* pathTaut;       // and as many for the passes that pull it taut
    vg::Portal* pathPortals;       // maxPortals(F): the corridor of faces it runs through
    vg::Apex* pathApexes;          // maxPortals(F) + 2: the taut path's corners
    vg::FieldSlice slice;          // the time-sliced one-to-all query, if one was started
    uint16_t* hubSteps;            // hub labels: the source's distance to the hubs of each block read,
    uint16_t* hubExitSteps;        // ... the source's distance through each target exit, per block lane,
    vg::HubExit* hubExits;         // ... both endpoints' exits (a patch's slots each, hub order),
    uint32_t* hubExitHubs;         // ... and per exit its hub where the bounds kept it, else kNone,
    uint32_t* hubSubtreeEnd;       // ... per tree node the end of its subtree's hubs (filled at init),
    uint16_t* hubSlotSteps;        // ... an endpoint's to each first-layer node of its patch,
    uint16_t* hubTargetSlotSteps;  // ... the target's to each first-layer node of its patch,
    float* hubSlotCost;            // ... both endpoints' lower bounds through each (per side a patch
                                   //     padded to a whole group of kRecordLanes),
    uint32_t* hubBlockBegin;       // ... per tree node its first block (T + 1, filled at init),
    float* hubBlockSpheres;        // ... per block its bounding sphere (centre, radius; filled at
                                   //     init from the block bounds, which hold them 112 bytes apart),
    uint16_t* hubBlockRanges;      // ... per block its landmark ranges in landmark steps, widened
                                   //     outward (blockRangeStride entries a block: every low end,
                                   //     then every high end; 65535 high: none; filled at init),
    uint32_t* hubSlotRecordBegin;  // ... per first-layer patch (+ 1) its first exit candidate,
    uint32_t* hubSlotOrder;        // ... per patch its slots that are hubs, in hub order (kNone pads),
    uint32_t* hubSlotHub;          // ... their hub numbers (kNone pads),
    float* hubSlotPositions;       // ... and their nodes' positions and landmark distances (the
    uint16_t* hubSlotLandmarks;    //     blob's hub landmarks) by groups of kRecordLanes
                                   //     (slotPosition, slotLandmark; all five filled at init),
    vg::HubBlockRef* hubBlocks;    // ... and the blocks of the common tree path a query reads,
    uint32_t* hubBlocksAbove;      // ... per tree node the blocks of its proper ancestors (filled at init),
    uint16_t* hubBlockRows;        // ... a side's exits with rows in a block, for the block at hand and
    uint64_t hubBlockRowsEach;     //     kRowLookahead more (kRowBuffers parts of this many entries),
    float* hubPatchReach;          // ... per second-layer patch its longest node edge (filled at init)
    uint32_t* hubInnerRowOfSlot;   // ... per node slot of a second-layer patch its node's inner row in
                                   //     the patch's first-layer patch, kNone if none (filled at init)
    uint16_t* hubPatchSteps;       // ... the source's distance to each node of t's patch (with a table),
    const vg_endpoint_table* endpointTable;  // ... the table its label queries read, if any
    // A pair inside one first-layer patch (vg_patch_pairs.cpp, with a table): two lists of
    // pairListCapacity each, of an end's nodes (their places in the node distances, the
    // end's entries and the other end's distances), per place its index in a list (kNone
    // between queries), and two of pairSlotCapacity: per node slot of the end's patches.
    uint32_t* pairRanks;
    float* pairSeeds;
    float* pairDistances;
    uint32_t* pairIndexOfRank;
    uint32_t* pairSlotIndex;
    uint32_t pairListCapacity, pairSlotCapacity;
};

namespace vg {

// The exit candidates' node records (position, then landmark distances) are stored in groups
// of kRecordLanes candidates, field by field, so that the query bounds a group at once. The
// landmark distances stay the table's 16-bit steps (kLandmarkUnreachable: none), half the
// bytes of floats: a label query reads both endpoints' candidates with cold caches, and
// converts them exactly as the node records are filled (steps times the landmark's scale).
constexpr uint32_t kRecordLanes = 8;
// A label query side reads the exit lists of at most this many second-layer patches (an
// endpoint on more patches' borders reads every exit's rows instead).
constexpr uint32_t kMaxSidePatches = 8;
// The label kernels find a block's rows and ask for them this many blocks before they add
// them (and exit lists and landmark ranges twice as far ahead): a block's rows are a few dozen misses, its
// sums far shorter than one. One block ahead was ~6% slower at p50 on igea; 3 and 6
// measured the same (BENCHMARKS.md, session 40).
constexpr uint32_t kRowLookahead = 3;
constexpr uint32_t kRowBuffers = kRowLookahead + 1;
inline float& slotPosition(float* positions, uint64_t candidate, uint64_t axis) {
    return positions[(candidate / kRecordLanes) * kRecordLanes * 3 + axis * kRecordLanes + candidate % kRecordLanes];
}
inline uint16_t& slotLandmark(uint16_t* landmarks, uint64_t landmarkCount, uint64_t candidate, uint64_t k) {
    return landmarks[(candidate / kRecordLanes) * kRecordLanes * landmarkCount + k * kRecordLanes + candidate % kRecordLanes];
}

// A block's landmark ranges as a query reads them: one cache line (64-byte aligned) up to 16
// landmarks, where the blob's float record (sphere and ranges) spans two or three; the
// vector kernel reads eight low and eight high ends at a time, so a partial last group
// stays inside the block's entries.
inline uint32_t blockRangeStride(uint32_t landmarkCount) {
    const uint32_t need = 2 * landmarkCount + (landmarkCount % 8 ? 8 - landmarkCount % 8 : 0);
    return (need + 31) & ~31u;
}
constexpr uint16_t kNoRangeEnd = 65535;  // a high end of no range (+inf)

// Legs a path may have (its node chain plus the endpoints and a crossing, twice over for
// first-layer legs expanded into the second layer).
inline uint64_t maxPathLegs(uint64_t nodeCount) { return 2 * nodeCount + 8; }

// Starts a query: a fresh generation for every stamp array.
uint32_t beginQuery(vg_workspace& ws);

}  // namespace vg
