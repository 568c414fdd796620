// Multi-source all-destinations distances (thesis 3.7.2): one search over the second layer
// everywhere (every patch must be reached, so the overlay saves nothing), then every
// other vertex takes the best of its patch's nodes plus the stored entry, and the
// unfolded crossing of the border edges at that best node (as vg_distance does where its
// two searches meet).
#include "vg_query.h"
#include "vg_field_kernels.h"
#include "vg_search.h"

namespace {

using namespace vg;

// The search's labels, kept per second-layer node slot (slotBegin-based, vg_workspace.h's
// slotDist) and nowhere else, so that a patch's come from a few consecutive lines instead
// of a line per node.
struct SlotLabels {
    const float* dist;        // +inf: none; -inf: a merged-away node
    const uint32_t* source;   // its nearest source
    const uint8_t* through;   // 1 where it came through this patch's own row
    explicit SlotLabels(const vg_workspace& ws) : dist(ws.slotDist), source(ws.slotSource), through(ws.slotThrough) {}
};

// The path to an interior vertex may cross the border on an edge next to its best node
// rather than at the node. The source side of each such edge (its unfolded source point)
// is the same for every vertex of the patch, so it is computed once per edge here, for
// the nodes that are some vertex's best; then each vertex takes the edges of its best node
// (lowerByCrossings). Crossing edges join nodes of the best node's source, so the nearest
// source stays.
void unfoldAtBestNodes(const vg_graph& g, uint32_t patchIndex, vg_workspace& ws, uint32_t reached) {
    const Patch& p = g.second[patchIndex];
    const uint32_t interior = p.slotCount - p.nodeCount, stride = entriesStride(interior);
    const uint32_t* bestNode = ws.patchBestNode;
    // The interior slots grouped by their best node (a counting sort).
    uint32_t* memberBegin = ws.patchMemberBegin;
    for (uint32_t r = 0; r <= reached; ++r) memberBegin[r] = 0;
    for (uint32_t j = 0; j < interior; ++j)
        if (bestNode[j] != kNone) ++memberBegin[bestNode[j] + 1];
    for (uint32_t r = 0; r < reached; ++r) memberBegin[r + 1] += memberBegin[r];
    uint32_t* members = ws.patchMembers;
    for (uint32_t j = 0; j < interior; ++j)
        if (bestNode[j] != kNone) members[memberBegin[bestNode[j]]++] = j;
    for (uint32_t r = reached; r > 0; --r) memberBegin[r] = memberBegin[r - 1];  // back to the starts
    memberBegin[0] = 0;

    // Each best node's edges to nodes reached from the same source, unfolded, then its
    // members lowered through them. A node's edges are found by where they start
    // (slotFirstEdge), so the edges of the nodes that are nobody's best are not read.
    const uint32_t patchEnd = patchEdgesEnd(g, patchIndex);
    const uint32_t* firstEdge = ws.slotFirstEdge + p.slotBegin;
    CrossingEdge* edges = ws.patchEdges;
    uint32_t decoded = reached;  // rows in patchEntries: the reached nodes', then those decoded here
    for (uint32_t r = 0; r < reached; ++r) {
        if (memberBegin[r] == memberBegin[r + 1]) continue;
        const uint32_t u = ws.patchNodeSlot[r], origin = ws.slotOrigin[u];
        const float a = ws.patchNodeDistance[r];
        const uint32_t end = u + 1 < p.nodeCount ? firstEdge[u + 1] : patchEnd;
        uint32_t count = 0;
        for (uint32_t e = firstEdge[u]; e < end && count < kMaxPatchEdges; ++e) {
            const PatchEdge& E = g.secondEdges[e];
            const float b = ws.slotLabel[E.to], l = E.length;
            UnfoldedPoint source;
            // (An unlabelled node has no source: kNone, unlike any best node's.)
            if (ws.slotOrigin[E.to] != origin || !unfoldPoint(a, b, l, source)) continue;
            if (ws.slotEntries[E.to] == kNone) {
                ws.slotEntries[E.to] = decoded;
                decodeRow(g.avx2, g, p.scale, interiorRowStart(p, E.to), interior,
                          ws.patchEntries + uint64_t(decoded++) * stride);
            }
            edges[count++] = CrossingEdge{ws.slotEntries[E.to] * stride, b, l, l * l, 0.5f / l, source};
        }
        if (count > 0)
            lowerByCrossings(g.avx2, ws.patchEntries, a, ws.patchEntries + uint64_t(r) * stride, edges, count,
                             members + memberBegin[r], memberBegin[r + 1] - memberBegin[r], ws.patchBest);
    }
}

// The reached active nodes of patch `patchIndex` (whose labels are final once the search is
// done) into the workspace's per-patch lists (patchNodeSlot, patchNodeDistance,
// patchNodeRow, slotEntries) and the labels and sources of all its node slots (slotLabel,
// slotOrigin); their number.
uint32_t reachedNodes(const vg_graph& g, uint32_t patchIndex, const SlotLabels& labels, vg_workspace& ws) {
    const Patch& p = g.second[patchIndex];
    const float* dist = labels.dist + p.slotBegin;
    const uint32_t* source = labels.source + p.slotBegin;
    const uint8_t* through = labels.through + p.slotBegin;
    uint32_t reached = 0;
    for (uint32_t i = 0; i < p.nodeCount; ++i) {
        const float d = dist[i];
        const bool usable = d < __builtin_inff() && d > -__builtin_inff();  // labelled, active
        ws.slotLabel[i] = usable ? d : __builtin_inff();
        ws.slotOrigin[i] = usable ? source[i] : kNone;
        ws.slotEntries[i] = kNone;
        // A node labelled through this patch's own row is no better start than the node
        // it came from (patch distances obey the triangle inequality): skip it.
        if (usable && !through[i]) {
            ws.patchNodeSlot[reached] = i;
            ws.slotEntries[i] = reached;
            ws.patchNodeDistance[reached] = ws.slotLabel[i];
            ws.patchNodeRow[reached] = interiorRowStart(p, i);
            ++reached;
        }
    }
    return reached;
}

// Asks the memory system for the lines of [begin, end).
template <typename T>
inline void prefetchRange(const T* begin, const T* end) {
    const uintptr_t e = uintptr_t(end);
    for (uintptr_t x = uintptr_t(begin) & ~uintptr_t(63); x < e; x += 64)
        __builtin_prefetch(reinterpret_cast<const void*>(x));
}

// Merged-away nodes (slots before the interior ones) of the patch take the best of its
// `reached` nodes too (they lie in several patches: the first patch giving the best wins).
void fillMergedAwayFrom(const vg_graph& g, uint32_t patchIndex, const vg_workspace& ws, uint32_t reached, float* out,
                        uint32_t* nearest) {
    const Patch& p = g.second[patchIndex];
    const uint32_t* slots = g.slots + p.slotBegin;
    for (uint32_t j = 0; j < p.nodeCount; ++j) {
        const uint32_t n = slots[j];
        if (nodeActive(g, n)) continue;
        float& o = out[g.nodeVertex[n]];
        for (uint32_t r = 0; r < reached; ++r) {
            const float d = ws.patchNodeDistance[r] + entry(p, g.secondDistances, ws.patchNodeSlot[r], j);
            if (d < o) {
                o = d;
                if (nearest) nearest[g.nodeVertex[n]] = ws.slotOrigin[ws.patchNodeSlot[r]];
            }
        }
    }
}

// Vertices of one patch that are not active nodes: best over its reached active nodes.
// `mergedAway` false leaves its merged-away nodes (which other patches share) to the caller.
void fillPatch(const vg_graph& g, uint32_t patchIndex, const SlotLabels& labels, vg_workspace& ws, float* out,
               uint32_t* nearest, uint32_t noSource, bool mergedAway) {
    const Patch& p = g.second[patchIndex];
    const uint32_t* slots = g.slots + p.slotBegin;
    const uint32_t interior = p.slotCount - p.nodeCount;
    float* best = ws.patchBest;
    uint32_t* bestNode = ws.patchBestNode;
    // The output entries of the patch's vertices lie all over the output array, out of the
    // cache by now: asked for here, they arrive while the rows are read.
    for (uint32_t j = 0; j < interior; ++j) __builtin_prefetch(out + slots[p.nodeCount + j], 1);
    for (uint32_t j = 0; j < interior; ++j) {
        best[j] = __builtin_inff();
        bestNode[j] = kNone;
    }
    const uint32_t reached = reachedNodes(g, patchIndex, labels, ws);
    // The crossings read the patch's edge list and edge index a node at a time, each read
    // waiting for its own line: asked for here, they arrive while the rows are lowered
    // (igea's field: 1.05x on one thread, 1.04x on two, BENCHMARKS.md).
    prefetchRange(g.secondEdges + p.edgeBegin, g.secondEdges + patchEdgesEnd(g, patchIndex));
    prefetchRange(ws.slotFirstEdge + p.slotBegin, ws.slotFirstEdge + p.slotBegin + p.nodeCount);
    if (mergedAway) fillMergedAwayFrom(g, patchIndex, ws, reached, out, nearest);
    lowerFromRows(g.avx2, g, p.scale, ws.patchNodeRow, ws.patchNodeDistance, nullptr, reached, interior, best,
                  bestNode, ws.patchEntries, entriesStride(interior), &ws.drip);
    unfoldAtBestNodes(g, patchIndex, ws, reached);
    // This patch is the only one to write its interior vertices (vg_open checks it), and
    // nothing wrote them before.
    for (uint32_t j = 0; j < interior; ++j) {
        const uint32_t v = slots[p.nodeCount + j];
        out[v] = best[j];
        if (nearest) nearest[v] = bestNode[j] != kNone ? ws.slotOrigin[ws.patchNodeSlot[bestNode[j]]] : noSource;
    }
}

// The merged-away nodes of every patch, in patch order (after a fill that left them).
void fillMergedAway(const vg_graph& g, vg_workspace& ws, float* out, uint32_t* nearest) {
    const SlotLabels labels(ws);
    for (uint32_t i = 0; i < g.secondCount; ++i)
        if (ws.parallel.activeNodes[i] < g.second[i].nodeCount)
            fillMergedAwayFrom(g, i, ws, reachedNodes(g, i, labels, ws), out, nearest);
}

// The search's distances of the nodes, a chunk per step (each node once, at its own vertex).
constexpr uint32_t kNodesPerStep = 256;

// Each node's label is read at its first slot (the search keeps it only there, not in the
// node arrays). A node without a label (unreached, or merged away: the fills give it its
// distance) starts at +inf and no source, as beginField leaves the nodes' vertices to this.
void writeNodes(const vg_graph& g, const SlotLabels& labels, uint32_t first, float* out, uint32_t* nearest,
                uint32_t noSource) {
    const uint32_t end = g.nodeCount - first < kNodesPerStep ? g.nodeCount : first + kNodesPerStep;
    for (uint32_t n = first; n < end; ++n) {
        float d = __builtin_inff();
        uint32_t source = noSource;
        // (A node in no second-layer patch, which only a crafted blob has, is never labelled.)
        if (nodeActive(g, n) && g.nodeSecondBegin[n] < g.nodeSecondBegin[n + 1]) {
            const Membership& m = g.nodeSecond[g.nodeSecondBegin[n]];
            const uint32_t k = g.second[m.patch].slotBegin + m.slot;
            if (labels.dist[k] < __builtin_inff()) d = labels.dist[k], source = labels.source[k];
        }
        out[g.nodeVertex[n]] = d;
        if (nearest) nearest[g.nodeVertex[n]] = source;
    }
}

// The search visits a patch at a time rather than a node at a time. A node-by-node
// Dijkstra relaxes each of a patch's ~55 rows at a different moment, and by then the
// patch's matrix has left the cache; here a patch is taken from a queue ordered by the
// smallest label it has not yet relaxed, and relaxes all such labels together (a
// label-correcting search: a node may be relaxed again through a patch when its label
// drops later; the labels end at the same shortest paths, up to the 12-bit rounding of
// the entries, and an igea field is 1.13-1.27x faster, BENCHMARKS.md).

// Active node v's label became d, from source `source`, through patch `via` (kNone: a
// seed): each of v's slots takes it (where its patch's visit and fill read it), and every
// other patch of v must relax it; `via` need not, as its own row gave it (patch distances
// obey the triangle inequality).
inline void announce(const vg_graph& g, vg_workspace& ws, uint32_t v, float d, uint32_t source, uint32_t via) {
    for (uint32_t m = g.nodeSecondBegin[v]; m < g.nodeSecondBegin[v + 1]; ++m) {
        const uint32_t patch = g.nodeSecond[m].patch, k = g.second[patch].slotBegin + g.nodeSecond[m].slot;
        ws.slotDist[k] = d;
        ws.slotSource[k] = source;
        ws.slotThrough[k] = patch == via;
        if (patch == via) ws.slotSent[k] = d;
        else ws.patchQueue.offer(patch, d);
    }
}

// vg_distance_field_parallel's bookkeeping (ParallelFill, vg_workspace.h). Active node v
// has its first label: each of its patches counts it, and a patch whose active nodes now
// all have labels waits in `pending` under the largest (labels only drop, so a key that
// is no longer the largest is still an upper bound of it).
void countLabelled(const vg_graph& g, ParallelFill& P, const vg_workspace& ws, uint32_t v) {
    for (uint32_t m = g.nodeSecondBegin[v]; m < g.nodeSecondBegin[v + 1]; ++m) {
        const uint32_t patch = g.nodeSecond[m].patch;
        if (++P.labelledNodes[patch] != P.activeNodes[patch]) continue;
        const Patch& p = g.second[patch];
        float largest = 0.0f;  // (a merged-away slot's -inf is never the largest)
        for (uint32_t j = 0; j < p.nodeCount; ++j)
            if (ws.slotDist[p.slotBegin + j] > largest) largest = ws.slotDist[p.slotBegin + j];
        heapSiftUp(P.pending, P.pendingCount++, HeapEntry{largest, patch}, [&](uint32_t i, HeapEntry e) { P.pending[i] = e; });
    }
}

// Appends patch i to the ready list (not yet visible to the tasks).
inline void markReady(ParallelFill& P, uint32_t i, uint32_t& length) {
    P.readyPatches[length++] = i;
    P.labelledNodes[i] = kNone;
}

// Makes the pending patches whose largest label is at most `finalBelow` ready, and tells the
// tasks (the release store: the labels they will read were written before it).
void publishFinal(ParallelFill& P, float finalBelow) {
    uint32_t length = P.readyCount;
    while (P.pendingCount > 0 && P.pending[0].key <= finalBelow) {
        markReady(P, P.pending[0].node, length);
        const HeapEntry last = P.pending[--P.pendingCount];
        if (P.pendingCount > 0) heapSiftDown(P.pending, P.pendingCount, 0, last, [&](uint32_t i, HeapEntry e) { P.pending[i] = e; });
    }
    if (length == P.readyCount) return;
    P.readyCount = length;
    __atomic_store_n(&P.published, length, __ATOMIC_RELEASE);
}

// Starts the search from the seeded labels (in the node heap of the forward frontier);
// with `P`, counts the seeded active nodes for it.
void beginPatchSearch(const vg_graph& g, vg_workspace& ws, ParallelFill* P) {
    for (uint32_t i = 0; i < g.secondCount; ++i) {
        ws.patchQueue.position[i] = kNone;
        const Patch& p = g.second[i];
        for (uint32_t k = p.slotBegin; k < p.slotBegin + p.nodeCount; ++k) ws.slotSent[k] = ws.slotDist[k] = ws.slotBlank[k];
    }
    ws.patchQueue.size = 0;
    Frontier& f = ws.forward;
    while (!f.empty()) {
        const uint32_t u = f.pop().node;
        const Route& r = f.route[u];
        if (nodeActive(g, u)) {
            announce(g, ws, u, f.label[u].dist, r.origin, r.via);
            if (P != nullptr) countLabelled(g, *P, ws, u);
        } else {
            // A merged-away seed takes no label in the search (its patches' fills give it
            // one), but its patches' nodes take labels from its rows.
            for (uint32_t m = g.nodeSecondBegin[u]; m < g.nodeSecondBegin[u + 1]; ++m)
                if (g.nodeSecond[m].patch != r.via) ws.patchQueue.offer(g.nodeSecond[m].patch, f.label[u].dist);
        }
    }
}

// Relaxes, inside patch `patchIndex`, every node label it has not relaxed yet (each such
// source lowers the others by its row); the nodes whose labels drop tell their other
// patches. Every node ends at the smallest label + entry, from the first source in slot
// order that gives it.
void visitPatch(const vg_graph& g, uint32_t patchIndex, vg_workspace& ws, ParallelFill* P) {
    const Patch& p = g.second[patchIndex];
    const uint32_t n = p.nodeCount;
    const uint32_t* slots = g.slots + p.slotBegin;
    const float* dist = ws.slotDist + p.slotBegin;  // (-inf: merged away; it never takes a label)
    float* sent = ws.slotSent + p.slotBegin;        // (-inf there too: it is never a source)
    float* best = ws.patchBest;            // per node slot: the best found here
    uint32_t* from = ws.patchBestNode;     // ... and the source slot whose row gave it
    uint32_t* sources = ws.patchNodeSlot;  // the sources' slots, labels and rows
    float* labels = ws.patchNodeDistance;
    uint64_t* rows = ws.patchNodeRow;
    // Where its label drops, announce reads a node's patch list, far from the last one
    // read: asked for now, while the rows are read (igea's field: 1.03x).
    for (uint32_t j = 0; j < n; ++j) __builtin_prefetch(g.nodeSecond + g.nodeSecondBegin[slots[j]]);
    // (Sixteen slots at a time where the CPU can: the branch per slot was mispredicted
    // often, ~a quarter of the slots being sources; igea's field 1.04-1.06x.)
    const uint32_t sourceCount = scanSources(g.avx512, dist, sent, best, from, n, sources, labels);
    for (uint32_t k = 0; k < sourceCount; ++k) rows[k] = nodeRowStart(p, sources[k]);
    lowerFromRows(g.avx2, g, p.scale, rows, labels, sources, sourceCount, n, best, from, nullptr, 0, &ws.drip);
    const uint32_t changedCount = changedSlots(g.avx512, from, n, ws.patchChanged);
    for (uint32_t i = 0; i < changedCount; ++i) {
        const uint32_t j = ws.patchChanged[i];
        const uint32_t v = slots[j], source = ws.slotSource[p.slotBegin + from[j]];
        const bool first = !(dist[j] < __builtin_inff());  // (before announce writes it)
        announce(g, ws, v, best[j], source, patchIndex);
        if (P != nullptr && first) countLabelled(g, *P, ws, v);
    }
}

// Entries [first, first + count) of the second-layer matrices, to be asked for while this
// step's rows are read: the block the next search step or fill step reads (igea's field:
// 1.05x with the blob out of the caches, 1.09x in them; a share per row rather than all at
// once: PrefetchDrip).
inline void prefetchEntries(const vg_graph& g, vg_workspace& ws, uint64_t first, uint64_t count) {
    ws.drip.set(g.secondDistances + ((3 * first) >> 1), g.secondDistances + ((3 * (first + count)) >> 1) + 1);
}

// The node x other block of patch i, which its fill reads.
inline void prefetchFillBlock(const vg_graph& g, vg_workspace& ws, uint32_t i) {
    const Patch& q = g.second[i];
    prefetchEntries(g, ws, interiorRowStart(q, 0), uint64_t(q.nodeCount) * (q.slotCount - q.nodeCount));
}

// One step of the search: the patch with the smallest key visited, the likely next one's
// node x node block, node ids and sent labels (its visit's first reads) asked for meanwhile.
inline void visitNextPatch(const vg_graph& g, vg_workspace& ws, ParallelFill* P) {
    const uint32_t patch = ws.patchQueue.pop();
    ws.drip.clear();
    if (!ws.patchQueue.empty()) {
        const Patch& q = g.second[ws.patchQueue.heap[0].node];
        prefetchEntries(g, ws, q.matrixBegin, uint64_t(q.nodeCount) * q.nodeCount);
        prefetchRange(g.slots + q.slotBegin, g.slots + q.slotBegin + q.nodeCount);
        prefetchRange(ws.slotSent + q.slotBegin, ws.slotSent + q.slotBegin + q.nodeCount);
    }
    visitPatch(g, patch, ws, P);
}

enum Phase : uint32_t { Search = 0, Nodes = 1, Fill = 2, Direct = 3, Done = 4 };

// Source i of the query as an endpoint; false for a vertex used by no face.
bool sourceEndpoint(const vg_graph& g, const FieldSlice& s, size_t i, Endpoint& e) {
    if (s.points) return resolvePoint(g, s.points[i], e) == VG_OK;  // checked by beginField
    if (g.vertexPatch[s.sources[i]] == kNone) return false;
    e = vertexEndpoint(g, s.sources[i]);
    return true;
}

// Checks the arguments, clears the outputs and seeds the search from the sources (vertex
// ids, or surface points when `points` is given).
vg_status beginField(const vg_graph* graph, vg_workspace* workspace, const uint32_t* sources, const vg_point* points,
                     size_t source_count, float* out_distances, uint32_t* out_nearest, bool parallel = false) {
    const vg_status st = vg::checkQuery(graph, workspace, out_distances);
    if (st != VG_OK) return st;
    if (source_count > 0 && sources == nullptr && points == nullptr) return VG_ERR_INVALID_ARGUMENT;
    if (source_count >= kNone) return VG_ERR_INVALID_ARGUMENT;
    const vg_graph& g = *graph;
    for (size_t i = 0; i < source_count; ++i) {
        Endpoint e;
        if (points ? resolvePoint(g, points[i], e) != VG_OK : sources[i] >= g.vertexCount)
            return points ? VG_ERR_INVALID_POINT : VG_ERR_INVALID_VERTEX;
    }

    vg_workspace& ws = *workspace;
    const uint32_t gen = beginQuery(ws);
    // Only the vertices that no step writes start here: writeNodes writes every node's
    // vertex, and its home patch's fill every other used vertex (vg_open checks that these
    // are all, each once). So the calling thread does not take every line of the outputs
    // only for the fill tasks to take them back (igea's field on two threads: 1.03x).
    if (g.unusedVertexCount > 0)
        for (uint32_t v = 0; v < g.vertexCount; ++v) {
            if (g.vertexPatch[v] != kNone) continue;
            out_distances[v] = __builtin_inff();
            if (out_nearest) out_nearest[v] = uint32_t(source_count);
        }
    ws.slice = FieldSlice{gen, Search, 0, points ? nullptr : sources, points, source_count, out_distances, out_nearest};
    auto key = [](uint32_t, float dv) { return dv; };
    auto none = [](uint32_t, float) {};
    for (size_t i = 0; i < source_count; ++i) {
        Endpoint e;
        if (sourceEndpoint(g, ws.slice, i, e)) seedEndpoint(g, e, uint32_t(i), ws.forward, key, none);
    }
    ParallelFill* P = parallel ? &ws.parallel : nullptr;
    if (P != nullptr) {
        for (uint32_t i = 0; i < g.secondCount; ++i) P->labelledNodes[i] = 0;
        P->pendingCount = P->readyCount = P->published = P->claimed = P->arrivals = 0;
    }
    beginPatchSearch(g, ws, P);
    return VG_OK;
}

// Runs up to `budget` units of the query begun by beginField, stopping early on reaching
// phase `stop`; true once it is complete.
bool advanceField(const vg_graph& g, vg_workspace& ws, uint64_t budget, uint32_t stop = Done) {
    FieldSlice& s = ws.slice;
    float* out = s.out;
    uint32_t* nearest = s.nearest;
    for (; budget > 0 && s.phase < stop; --budget) {
        if (s.phase == Search) {
            if (!ws.patchQueue.empty()) {
                visitNextPatch(g, ws, nullptr);
                continue;
            }
            s.phase = Nodes;
            s.next = 0;
        } else if (s.phase == Nodes) {
            if (s.next < g.nodeCount) {
                writeNodes(g, SlotLabels(ws), s.next, out, nearest, uint32_t(s.sourceCount));
                s.next += kNodesPerStep;
                continue;
            }
            s.phase = Fill;
            s.next = 0;
        } else if (s.phase == Fill) {
            if (s.next < g.secondCount) {
                ws.drip.clear();
                if (s.next + 1 < g.secondCount) prefetchFillBlock(g, ws, s.next + 1);
                fillPatch(g, s.next++, SlotLabels(ws), ws, out, nearest, uint32_t(s.sourceCount), true);
                continue;
            }
            s.phase = Direct;
            s.next = 0;
        } else if (s.phase == Direct) {
            // A source's own patches also hold the direct entries: paths that touch no node.
            if (s.next < s.sourceCount) {
                const uint32_t i = s.next++;
                Endpoint e;
                if (!sourceEndpoint(g, s, i, e)) continue;
                forEachEndpointPatch(g, e, [&](uint32_t patch, uint32_t, auto&& dist) {
                    const Patch& p = g.second[patch];
                    for (uint32_t j = 0; j < p.slotCount; ++j) {
                        const uint32_t id = g.slots[p.slotBegin + j];
                        const uint32_t v = j < p.nodeCount ? g.nodeVertex[id] : id;
                        const float d = dist(j);
                        if (d < out[v]) {
                            out[v] = d;
                            if (nearest) nearest[v] = i;
                        }
                    }
                });
                continue;
            }
            // Sources last, so that a vertex listed twice (or a tie at distance 0) names
            // its first listing.
            for (size_t i = s.sourceCount; i-- > 0;) {
                Endpoint e;
                const uint32_t v = s.points ? (resolvePoint(g, s.points[i], e) == VG_OK ? e.vertex : kNone) : s.sources[i];
                if (v == kNone) continue;
                out[v] = 0.0f;
                if (nearest) nearest[v] = uint32_t(i);
            }
            s.phase = Done;
        }
    }
    return s.phase == Done;
}

// vg_distance_field_parallel's tasks. The first to start runs the search on the query's
// workspace, telling which patches are ready as it goes (publishFinal), then fills too;
// the others fill ready patches meanwhile, each with a workspace of its own as scratch (the
// n-th to start takes the n-th workspace), in the order the patches became ready. A task
// waits only for patches that a running search has still to make ready, so any scheduler
// does: one that runs the tasks in turn runs the search, then all the fill, in the first.
struct FieldTasks {
    const vg_graph* graph;
    vg_workspace* const* workspaces;
    uint32_t count;
};

inline void pause() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
}

// The search to its end; then every patch not yet ready (unreached nodes, or still
// pending) becomes so, and the nodes' own distances are written.
void searchPublishing(const vg_graph& g, vg_workspace& ws) {
    ParallelFill& P = ws.parallel;
    while (!ws.patchQueue.empty()) {
        publishFinal(P, ws.patchQueue.heap[0].key);
        visitNextPatch(g, ws, &P);
    }
    uint32_t length = P.readyCount;
    for (uint32_t i = 0; i < g.secondCount; ++i)
        if (P.labelledNodes[i] != kNone) markReady(P, i, length);
    P.readyCount = length;
    __atomic_store_n(&P.published, length, __ATOMIC_RELEASE);
    // (The nodes' entries after that, so that no task waits for them.)
    for (uint32_t first = 0; first < g.nodeCount; first += kNodesPerStep)
        writeNodes(g, SlotLabels(ws), first, ws.slice.out, ws.slice.nearest, uint32_t(ws.slice.sourceCount));
}

// Index i of the ready list once the search has published it.
inline uint32_t readyPatch(const ParallelFill& P, uint32_t i) {
    while (__atomic_load_n(&P.published, __ATOMIC_ACQUIRE) <= i) pause();
    return P.readyPatches[i];
}

void fieldTask(void* context, uint32_t) {
    FieldTasks& t = *static_cast<FieldTasks*>(context);
    vg_workspace& query = *t.workspaces[0];
    ParallelFill& P = query.parallel;
    const uint32_t arrival = __atomic_fetch_add(&P.arrivals, 1u, __ATOMIC_RELAXED);
    if (arrival >= t.count) return;  // (a scheduler calling more tasks than asked)
    const vg_graph& g = *t.graph;
    vg_workspace& scratch = *t.workspaces[arrival];
    if (arrival == 0) searchPublishing(g, query);
    // What the fill reads of the query's workspace, copied once: the search goes on writing
    // next to it.
    const SlotLabels labels(query);
    float* const out = query.slice.out;
    uint32_t* const nearest = query.slice.nearest;
    const uint32_t noSource = uint32_t(query.slice.sourceCount);
    const uint32_t* const ready = P.readyPatches;
    const uint32_t total = g.secondCount;
    uint32_t next = __atomic_fetch_add(&P.claimed, 1u, __ATOMIC_RELAXED);
    uint32_t patch = next < total ? readyPatch(P, next) : kNone;
    while (patch != kNone) {
        // The next claim's block asked for while this patch fills, when it is ready already.
        next = __atomic_fetch_add(&P.claimed, 1u, __ATOMIC_RELAXED);
        const bool more = next < total;
        scratch.drip.clear();
        if (more && __atomic_load_n(&P.published, __ATOMIC_ACQUIRE) > next) prefetchFillBlock(g, scratch, ready[next]);
        fillPatch(g, patch, labels, scratch, out, nearest, noSource, false);
        patch = more ? readyPatch(P, next) : kNone;
    }
}

void runInTurn(void*, uint32_t count, vg_task task, void* context) {
    for (uint32_t i = 0; i < count; ++i) task(context, i);
}

}  // namespace

namespace {

// vg_distance_field_parallel from vertex sources, or from surface points when `points` is given.
vg_status fieldParallel(const vg_graph* graph, vg_workspace* const* workspaces, uint32_t workspace_count,
                        const uint32_t* sources, const vg_point* points, size_t source_count, float* out_distances,
                        uint32_t* out_nearest, vg_parallel_for parallel_for, void* user_context) {
    if (workspaces == nullptr || workspace_count == 0) return VG_ERR_INVALID_ARGUMENT;
    for (uint32_t i = 0; i < workspace_count; ++i) {
        if (workspaces[i] == nullptr) return VG_ERR_INVALID_ARGUMENT;
        if (graph != nullptr && workspaces[i]->graph != graph) return VG_ERR_WRONG_WORKSPACE;
        for (uint32_t j = 0; j < i; ++j)
            if (workspaces[j] == workspaces[i]) return VG_ERR_INVALID_ARGUMENT;
    }
    const vg_status st =
        beginField(graph, workspaces[0], sources, points, source_count, out_distances, out_nearest, true);
    if (st != VG_OK) return st;
    const vg_graph& g = *graph;
    vg_workspace& ws = *workspaces[0];
    for (uint32_t i = 1; i < workspace_count; ++i) beginQuery(*workspaces[i]);  // ends their sliced queries
    FieldTasks tasks{graph, workspaces, workspace_count};
    (parallel_for != nullptr ? parallel_for : runInTurn)(user_context, workspace_count, fieldTask, &tasks);
    fillMergedAway(g, ws, out_distances, out_nearest);
    ws.slice.phase = Direct;
    ws.slice.next = 0;
    advanceField(g, ws, ~uint64_t(0));
    return VG_OK;
}

}  // namespace

extern "C" vg_status vg_distance_field_parallel(const vg_graph* graph, vg_workspace* const* workspaces,
                                                uint32_t workspace_count, const uint32_t* sources,
                                                size_t source_count, float* out_distances, uint32_t* out_nearest,
                                                vg_parallel_for parallel_for, void* user_context) {
    return fieldParallel(graph, workspaces, workspace_count, sources, nullptr, source_count, out_distances,
                         out_nearest, parallel_for, user_context);
}

extern "C" vg_status vg_point_distance_field_parallel(const vg_graph* graph, vg_workspace* const* workspaces,
                                                      uint32_t workspace_count, const vg_point* sources,
                                                      size_t source_count, float* out_distances,
                                                      uint32_t* out_nearest, vg_parallel_for parallel_for,
                                                      void* user_context) {
    if (source_count > 0 && sources == nullptr) return VG_ERR_INVALID_ARGUMENT;
    return fieldParallel(graph, workspaces, workspace_count, nullptr, sources, source_count, out_distances,
                         out_nearest, parallel_for, user_context);
}

extern "C" vg_status vg_distance_field_nearest(const vg_graph* graph, vg_workspace* workspace,
                                               const uint32_t* sources, size_t source_count, float* out_distances,
                                               uint32_t* out_nearest) {
    const vg_status st = beginField(graph, workspace, sources, nullptr, source_count, out_distances, out_nearest);
    if (st != VG_OK) return st;
    advanceField(*graph, *workspace, ~uint64_t(0));
    return VG_OK;
}

extern "C" vg_status vg_distance_field(const vg_graph* graph, vg_workspace* workspace, const uint32_t* sources,
                                       size_t source_count, float* out_distances) {
    return vg_distance_field_nearest(graph, workspace, sources, source_count, out_distances, nullptr);
}

extern "C" vg_status vg_distance_field_begin(const vg_graph* graph, vg_workspace* workspace, const uint32_t* sources,
                                             size_t source_count, float* out_distances, uint32_t* out_nearest) {
    return beginField(graph, workspace, sources, nullptr, source_count, out_distances, out_nearest);
}

extern "C" vg_status vg_distance_field_step(const vg_graph* graph, vg_workspace* workspace, uint32_t max_steps,
                                            int* out_done) {
    if (out_done == nullptr || graph == nullptr || workspace == nullptr) return VG_ERR_INVALID_ARGUMENT;
    *out_done = 0;
    if (workspace->graph != graph) return VG_ERR_WRONG_WORKSPACE;
    const vg::FieldSlice& s = workspace->slice;
    if (s.generation == 0 || s.generation != workspace->generation) return VG_ERR_NO_SLICED_QUERY;
    *out_done = advanceField(*graph, *workspace, max_steps) ? 1 : 0;
    return VG_OK;
}

extern "C" vg_status vg_point_distance_field(const vg_graph* graph, vg_workspace* workspace, const vg_point* sources,
                                             size_t source_count, float* out_distances, uint32_t* out_nearest) {
    if (source_count > 0 && sources == nullptr) return VG_ERR_INVALID_ARGUMENT;
    const vg_status st = beginField(graph, workspace, nullptr, sources, source_count, out_distances, out_nearest);
    if (st != VG_OK) return st;
    advanceField(*graph, *workspace, ~uint64_t(0));
    return VG_OK;
}
