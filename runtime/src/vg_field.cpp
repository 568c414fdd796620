// Multi-source all-destinations distances (thesis 3.7.2): one search over the second layer
// everywhere (every patch must be reached, so the overlay saves nothing), then every
// other vertex takes the best of its patch's nodes plus the stored entry, and the
// unfolded crossing of the border edges at that best node (as vg_distance does where its
// two searches meet).
#include "vg_query.h"
#include "vg_search.h"

namespace {

using namespace vg;

// Lowers best[0..n) to base + the packed row entries k0.. (interior slots of a patch),
// remembering which reached node gave each. The quanta are unpacked in chunks so that the
// conversion and comparison loop is branch-free and vectorises.
inline void lowerRow(const uint8_t* packed, uint64_t k0, uint32_t n, float base, float scale, uint32_t node,
                     float* __restrict best, uint32_t* __restrict bestNode) {
    constexpr uint32_t kChunk = 64;
    uint32_t q[kChunk];
    for (uint32_t j0 = 0; j0 < n; j0 += kChunk) {
        const uint32_t m = n - j0 < kChunk ? n - j0 : kChunk;
        unpackQuanta(packed, k0 + j0, m, q);
        float* __restrict b = best + j0;
        uint32_t* __restrict bn = bestNode + j0;
        for (uint32_t x = 0; x < m; ++x) {
            const float v = base + float(int32_t(q[x])) * scale, cur = b[x];
            const bool lower = (v < cur) & (q[x] != kNoPathQuantum);
            const uint32_t mask = 0u - uint32_t(lower);  // selects written as masks vectorise
            b[x] = lower ? v : cur;
            bn[x] = (node & mask) | (bn[x] & ~mask);
        }
    }
}

// Evaluates the gathered crossings and lowers each one's vertex to it: unfoldPoint and
// crossingLength (vg_graph.h) written as one branch-free loop, the same operations in
// the same order (so the same bits), with the failed cases masked to +inf at the end.
void evaluateCrossings(CrossingBatch& batch, float* best) {
    const float* __restrict A = batch.a;
    const float* __restrict B = batch.b;
    const float* __restrict C = batch.c;
    const float* __restrict E = batch.e;
    const float* __restrict L = batch.l;
    const float* __restrict SX = batch.sx;
    const float* __restrict SY = batch.sy;
    float* __restrict out = batch.length;
    const uint32_t n = batch.count;
    for (uint32_t i = 0; i < n; ++i) {
        const float c = C[i], e = E[i], l = L[i], sx = SX[i], sy = SY[i];
        // The target point (unfoldPoint(c, e, l)); l > 0 for every gathered edge.
        const float tx = (c * c - e * e + l * l) * (0.5f / l);
        const float y2 = c * c - tx * tx;
        const bool unfolds = y2 > 0.0f;
        const float ty = __builtin_sqrtf(unfolds ? y2 : 1.0f);
        // The segment to it (crossingLength).
        const float x = sx + (tx - sx) * (sy / (sy + ty));
        const bool meets = (x > 0.0f) & (x < l);
        const float dx = tx - sx, dy = ty + sy;
        const float d = __builtin_sqrtf(dx * dx + dy * dy);
        const float viaU = A[i] + c, viaW = B[i] + e;
        const float viaNode = (viaU < viaW ? viaU : viaW) / kUnfoldSlack;
        const float length = d < viaNode ? viaNode : d;
        out[i] = unfolds & meets ? length : __builtin_inff();
    }
    for (uint32_t i = 0; i < n; ++i) {
        float& o = best[batch.vertex[i]];
        if (out[i] < o) o = out[i];
    }
    batch.count = 0;
}

// The path to an interior vertex may cross the border on an edge next to its best node
// rather than at the node. The source side of each such edge (its unfolded source point)
// is the same for every vertex of the patch, so it is computed once per edge here, for
// the nodes that are some vertex's best. (Crossing edges join nodes of the best node's
// source, so the nearest source stays.)
void unfoldAtBestNodes(const vg_graph& g, uint32_t patchIndex, const Frontier& f, vg_workspace& ws,
                       uint32_t reached) {
    const Patch& p = g.second[patchIndex];
    const uint32_t* slots = g.slots + p.slotBegin;
    const uint32_t interior = p.slotCount - p.nodeCount;
    CrossingEdge* edges = ws.patchEdges;
    uint32_t* begin = ws.patchEdgeBegin;
    for (uint32_t r = 0; r < reached; ++r) begin[r] = 0;  // first as a flag: "is some vertex's best"
    for (uint32_t j = 0; j < interior; ++j)
        if (ws.patchBestNode[j] != kNone) begin[ws.patchBestNode[j]] = 1;
    uint32_t count = 0;
    for (uint32_t r = 0; r < reached; ++r) {
        const bool used = begin[r] != 0;
        begin[r] = count;
        if (!used) continue;
        const uint32_t u = slots[ws.patchNodeSlot[r]];
        const float a = ws.patchNodeDistance[r];
        for (uint32_t e = g.nodeEdgeBegin[u]; e < g.nodeEdgeBegin[u + 1] && count < kMaxPatchEdges; ++e) {
            const uint32_t w = g.nodeEdge[e];
            // Both ends must be reached from the same source for one unfolded path.
            if (!nodeActive(g, w) || !f.labelled(w) || f.route[w].origin != f.route[u].origin) continue;
            const uint32_t slot = ws.nodeSlotInPatch[w];
            if (slot == kNone) continue;
            const float b = f.label[w].dist, l = euclidean(g, g.nodeVertex[u], g.nodeVertex[w]);
            UnfoldedPoint source;
            if (unfoldPoint(a, b, l, source))
                edges[count++] = CrossingEdge{rowStart(p, slot) - (slot + 1) + p.nodeCount, l, b, source};
        }
    }
    begin[reached] = count;
    CrossingBatch& batch = ws.crossings;
    batch.count = 0;
    for (uint32_t j = 0; j < interior; ++j) {
        const uint32_t r = ws.patchBestNode[j];
        if (r == kNone || begin[r] == begin[r + 1]) continue;
        const float a = ws.patchNodeDistance[r];
        const float c = float(quantum(g.secondDistances, ws.patchNodeRow[r] + j)) * p.scale;
        for (uint32_t k = begin[r]; k < begin[r + 1]; ++k) {
            const CrossingEdge& E = edges[k];
            const uint32_t q = quantum(g.secondDistances, E.row + j);
            if (q == kNoPathQuantum) continue;
            if (batch.count == kCrossingChunk) evaluateCrossings(batch, ws.patchBest);
            const uint32_t i = batch.count++;
            batch.a[i] = a;
            batch.b[i] = E.b;
            batch.c[i] = c;
            batch.e[i] = float(q) * p.scale;
            batch.l[i] = E.length;
            batch.sx[i] = E.source.x;
            batch.sy[i] = E.source.y;
            batch.vertex[i] = j;
        }
    }
    evaluateCrossings(batch, ws.patchBest);
}

// Vertices of one patch that are not active nodes: best over its reached active nodes
// (whose labels are final once the search is done).
void fillPatch(const vg_graph& g, uint32_t patchIndex, const Frontier& f, vg_workspace& ws, float* out,
               uint32_t* nearest) {
    const Patch& p = g.second[patchIndex];
    const uint32_t* slots = g.slots + p.slotBegin;
    const uint32_t interior = p.slotCount - p.nodeCount;
    float* best = ws.patchBest;
    uint32_t* bestNode = ws.patchBestNode;
    for (uint32_t j = 0; j < interior; ++j) {
        best[j] = __builtin_inff();
        bestNode[j] = kNone;
    }
    uint32_t reached = 0;
    for (uint32_t i = 0; i < p.nodeCount; ++i) {
        const uint32_t n = slots[i];
        // A node labelled through this patch's own row is no better start than the node
        // it came from (patch distances obey the triangle inequality): skip it.
        if (nodeActive(g, n) && f.labelled(n) && f.route[n].via != patchIndex) {
            ws.patchNodeSlot[reached] = i;
            ws.patchNodeDistance[reached] = f.label[n].dist;
            ws.patchNodeRow[reached] = rowStart(p, i) - (i + 1) + p.nodeCount;
            ++reached;
        }
    }
    // The search's distances of the nodes this patch is home to (each node has one).
    for (uint32_t i = 0; i < p.nodeCount; ++i) {
        const uint32_t n = slots[i], v = g.nodeVertex[n];
        if (!nodeActive(g, n) || !f.labelled(n) || g.vertexPatch[v] != patchIndex) continue;
        out[v] = f.label[n].dist;
        if (nearest) nearest[v] = f.route[n].origin;
    }
    // Merged-away nodes (slots before the interior ones) take the best reached node too.
    for (uint32_t j = 0; j < p.nodeCount; ++j) {
        const uint32_t n = slots[j];
        if (nodeActive(g, n)) continue;
        float& o = out[g.nodeVertex[n]];
        for (uint32_t r = 0; r < reached; ++r) {
            const float d = ws.patchNodeDistance[r] + entry(p, g.secondDistances, ws.patchNodeSlot[r], j);
            if (d < o) {
                o = d;
                if (nearest) nearest[g.nodeVertex[n]] = f.route[slots[ws.patchNodeSlot[r]]].origin;
            }
        }
    }
    for (uint32_t r = 0; r < reached; ++r)
        lowerRow(g.secondDistances, ws.patchNodeRow[r], interior, ws.patchNodeDistance[r], p.scale, r, best, bestNode);
    for (uint32_t i = 0; i < p.nodeCount; ++i) ws.nodeSlotInPatch[slots[i]] = i;
    unfoldAtBestNodes(g, patchIndex, f, ws, reached);
    for (uint32_t i = 0; i < p.nodeCount; ++i) ws.nodeSlotInPatch[slots[i]] = kNone;
    for (uint32_t j = 0; j < interior; ++j) {
        const uint32_t v = slots[p.nodeCount + j];
        if (best[j] < out[v]) {
            out[v] = best[j];
            if (nearest) nearest[v] = f.route[slots[ws.patchNodeSlot[bestNode[j]]]].origin;
        }
    }
}

// The search visits a patch at a time rather than a node at a time. A node-by-node
// Dijkstra relaxes each of a patch's ~55 rows at a different moment, and by then the
// patch's matrix has left the cache; here a patch is taken from a queue ordered by the
// smallest label it has not yet relaxed, and relaxes all such labels together (a
// label-correcting search: a node may be relaxed again through a patch when its label
// drops later; the labels end at the same shortest paths, up to the 12-bit rounding of
// the entries, and an igea field is 1.13-1.27x faster, BENCHMARKS.md).

// Node v's label became d through patch `via` (kNone: a seed): every other patch of v must
// relax it; `via` need not, as its own row gave it (patch distances obey the triangle
// inequality).
inline void announce(const vg_graph& g, vg_workspace& ws, uint32_t v, float d, uint32_t via) {
    for (uint32_t m = g.nodeSecondBegin[v]; m < g.nodeSecondBegin[v + 1]; ++m) {
        const uint32_t patch = g.nodeSecond[m].patch;
        if (patch == via) ws.slotSent[g.second[patch].slotBegin + g.nodeSecond[m].slot] = d;
        else ws.patchQueue.offer(patch, d);
    }
}

// Starts the search from the seeded labels (in the node heap of the forward frontier).
void beginPatchSearch(const vg_graph& g, vg_workspace& ws) {
    for (uint32_t i = 0; i < g.secondCount; ++i) {
        ws.patchQueue.position[i] = kNone;
        const Patch& p = g.second[i];
        for (uint32_t j = 0; j < p.nodeCount; ++j) ws.slotSent[p.slotBegin + j] = __builtin_inff();
    }
    ws.patchQueue.size = 0;
    Frontier& f = ws.forward;
    while (!f.empty()) {
        const uint32_t u = f.pop().node;
        announce(g, ws, u, f.label[u].dist, f.route[u].via);
    }
}

// Relaxes, inside patch `patchIndex`, every node label it has not relaxed yet; the nodes
// whose labels drop tell their other patches.
void visitPatch(const vg_graph& g, uint32_t patchIndex, vg_workspace& ws) {
    Frontier& f = ws.forward;
    const Patch& p = g.second[patchIndex];
    const uint32_t n = p.nodeCount;
    const uint32_t* slots = g.slots + p.slotBegin;
    float* sent = ws.slotSent + p.slotBegin;
    float* label = ws.patchNodeDistance;  // per node slot: its label on arrival
    float* best = ws.patchBest;           // ... the best found here
    uint32_t* from = ws.patchBestNode;    // ... and the slot whose row gave it
    uint32_t* sources = ws.patchNodeSlot;
    uint32_t* q = ws.rowQuanta;
    uint32_t sourceCount = 0;
    for (uint32_t j = 0; j < n; ++j) {
        const uint32_t v = slots[j];
        const bool active = nodeActive(g, v), labelled = f.labelled(v);
        label[j] = labelled ? f.label[v].dist : __builtin_inff();
        best[j] = active ? label[j] : -__builtin_inff();  // a merged-away node never takes a label
        from[j] = kNone;
        if (active && labelled && label[j] < sent[j]) {
            sources[sourceCount++] = j;
            sent[j] = label[j];
        }
    }
    for (uint32_t k = 0; k < sourceCount; ++k) {
        const uint32_t i = sources[k];
        // Row i over the node slots: column i above the diagonal, then row i after it.
        uint64_t e = p.matrixBegin + i - 1;
        for (uint32_t j = 0; j < i; e += p.slotCount - j - 2, ++j) q[j] = quantum(g.secondDistances, e);
        q[i] = kNoPathQuantum;
        if (i + 1 < n) unpackQuanta(g.secondDistances, rowStart(p, i), n - i - 1, q + i + 1);
        const float du = label[i], scale = p.scale;
        for (uint32_t j = 0; j < n; ++j) {  // branch-free: it vectorises
            const float d = du + float(int32_t(q[j])) * scale;
            const bool lower = (d < best[j]) & (q[j] != kNoPathQuantum);
            best[j] = lower ? d : best[j];
            from[j] = lower ? i : from[j];
        }
    }
    for (uint32_t j = 0; j < n; ++j) {
        if (from[j] == kNone) continue;
        const uint32_t v = slots[j], u = slots[from[j]];
        f.label[v] = Label{best[j], f.generation};
        f.route[v] = Route{patchIndex, kNone, f.route[u].origin, u};
        announce(g, ws, v, best[j], patchIndex);
    }
}

enum Phase : uint32_t { Search = 0, Fill = 1, Direct = 2, Done = 3 };

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
                     size_t source_count, float* out_distances, uint32_t* out_nearest) {
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
    const float inf = __builtin_inff();
    for (uint32_t v = 0; v < g.vertexCount; ++v) out_distances[v] = inf;
    if (out_nearest)
        for (uint32_t v = 0; v < g.vertexCount; ++v) out_nearest[v] = uint32_t(source_count);
    ws.slice = FieldSlice{gen, Search, 0, points ? nullptr : sources, points, source_count, out_distances, out_nearest};
    auto key = [](uint32_t, float dv) { return dv; };
    auto none = [](uint32_t, float) {};
    for (size_t i = 0; i < source_count; ++i) {
        Endpoint e;
        if (sourceEndpoint(g, ws.slice, i, e)) seedEndpoint(g, e, uint32_t(i), ws.forward, key, none);
    }
    beginPatchSearch(g, ws);
    return VG_OK;
}

// Runs up to `budget` units of the query begun by beginField; true once it is complete.
bool advanceField(const vg_graph& g, vg_workspace& ws, uint64_t budget) {
    FieldSlice& s = ws.slice;
    Frontier& F = ws.forward;
    float* out = s.out;
    uint32_t* nearest = s.nearest;
    for (; budget > 0 && s.phase != Done; --budget) {
        if (s.phase == Search) {
            if (!ws.patchQueue.empty()) {
                visitPatch(g, ws.patchQueue.pop(), ws);
                continue;
            }
            s.phase = Fill;
            s.next = 0;
        } else if (s.phase == Fill) {
            if (s.next < g.secondCount) {
                fillPatch(g, s.next++, F, ws, out, nearest);
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

}  // namespace

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
