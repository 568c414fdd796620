// vg_path: the polyline behind a point-to-point distance.
//
// The point-to-point search (vg_distance.cpp) says how its best distance was found and
// leaves its labels, with each label's parent node, in the workspace. The path replays
// that: a chain of legs, each inside one second-layer patch between two nodes (or an
// endpoint, or the point where the searches met across a mesh edge). A leg across a whole
// first-layer patch (an overlay edge, the shortest node path through that patch's second
// layer) is expanded again by a small A* over that second layer. Each second-layer leg is
// then traced on the surface down the stored distance field of its far end
// (vg_path_trace.h), so the traced polyline is about as long as the sum the search added
// up; pulled taut through the faces it crosses (vg_path_taut.h), it comes close to the
// geodesic.
#include "vg_fan.h"
#include "vg_lower_bound.h"
#include "vg_path_taut.h"
#include "vg_path_trace.h"
#include "vg_point_to_point.h"
#include "vg_query.h"
#include "vg_search.h"

namespace {

using namespace vg;

// Leg ends that are not nodes.
constexpr uint32_t kAtSource = 0xFFFFFFFEu, kAtTarget = 0xFFFFFFFDu;
constexpr uint32_t kAtCrossingForward = 0xFFFFFFFCu, kAtCrossingBackward = 0xFFFFFFFBu;

// How far past its overlay entry the expand of an overlay leg looks: the second-layer
// entries along the way are rounded too (half a step each), a few times finer.
constexpr float kExpandSlack = 2e-3f;

class PathBuilder {
public:
    PathBuilder(const vg_graph& g, vg_workspace& ws, const Meeting& m, PathWriter& w)
        : g_(g), ws_(ws), m_(m), w_(w), maxLegs_(maxPathLegs(g.nodeCount)) {}

    bool build() {
        w_.endpoint(g_, m_.s);
        switch (m_.kind) {
        case Meeting::kSame: return true;
        case Meeting::kSegment: w_.endpoint(g_, m_.t); return true;
        case Meeting::kFan: return fan();
        case Meeting::kPatch: return leg(kAtSource, kAtTarget, m_.patch) && finish();
        case Meeting::kNode: return forwardLegs(m_.node) && backwardLegs(m_.node) && finish();
        case Meeting::kCrossing: return crossing() && finish();
        }
        return false;
    }

private:
    const vg_graph& g_;
    vg_workspace& ws_;
    const Meeting& m_;
    PathWriter& w_;
    const uint64_t maxLegs_;
    uint64_t legCount_ = 0;
    Endpoint crossForward_{}, crossBackward_{};

    bool leg(uint32_t from, uint32_t to, uint32_t via) {
        if (legCount_ >= maxLegs_) return false;
        ws_.pathLegs[legCount_++] = PathLeg{from, to, via};
        return true;
    }

    // Legs from the source to node n along the forward labels' parents.
    bool forwardLegs(uint32_t n) {
        const Frontier& F = ws_.forward;
        uint32_t count = 0;
        for (uint32_t c = n;; c = F.route[c].parent) {
            if (count > g_.nodeCount) return false;  // a parent cycle would be a defect
            ws_.pathNodes[count++] = c;
            if (F.route[c].parent == kNone) break;
        }
        const uint32_t first = ws_.pathNodes[count - 1];
        if (F.route[first].via != kNone && !leg(kAtSource, first, F.route[first].via)) return false;
        for (uint32_t i = count - 1; i > 0; --i)
            if (!leg(ws_.pathNodes[i], ws_.pathNodes[i - 1], F.route[ws_.pathNodes[i - 1]].via)) return false;
        return true;
    }

    // Legs from node n to the target along the backward labels' parents.
    bool backwardLegs(uint32_t n) {
        const Frontier& B = ws_.backward;
        uint32_t c = n;
        for (uint32_t count = 0; B.route[c].parent != kNone; ++count) {
            if (count > g_.nodeCount || !leg(c, B.route[c].parent, B.route[c].via)) return false;
            c = B.route[c].parent;
        }
        return B.route[c].via == kNone || leg(c, kAtTarget, B.route[c].via);
    }

    // The searches met across edge (v, w): each side reaches the crossing point from the
    // parent of v or w inside the patch that labelled it, whichever is shorter.
    bool crossing() {
        const Frontier& F = ws_.forward;
        const Frontier& B = ws_.backward;
        const uint32_t v = m_.node, w = m_.other;
        const uint32_t V = g_.nodeVertex[v], W = g_.nodeVertex[w];
        const float l = euclidean(g_, V, W);
        UnfoldedPoint s, t;
        float along = 0.5f;
        if (unfoldPoint(F.label[v].dist, F.label[w].dist, l, s) && unfoldPoint(B.label[v].dist, B.label[w].dist, l, t))
            along = (s.x + (t.x - s.x) * (s.y / (s.y + t.y))) / l;
        if (!(along > 0.0f && along < 1.0f)) along = 0.5f;
        uint32_t parentF, patchF, parentB, patchB;
        const bool forward = crossingSide(F, m_.s, V, W, along, crossForward_, parentF, patchF);
        const bool backward = crossingSide(B, m_.t, V, W, along, crossBackward_, parentB, patchB);
        if (!forward || !backward) {  // meet at the better end node instead
            const uint32_t n = F.label[v].dist + B.label[v].dist <= F.label[w].dist + B.label[w].dist ? v : w;
            return forwardLegs(n) && backwardLegs(n);
        }
        if (parentF == kNone ? !leg(kAtSource, kAtCrossingForward, patchF)
                             : !(forwardLegs(parentF) && leg(parentF, kAtCrossingForward, patchF)))
            return false;
        if (parentB == kNone) return leg(kAtCrossingBackward, kAtTarget, patchB);
        return leg(kAtCrossingBackward, parentB, patchB) && backwardLegs(parentB);
    }

    // One side of a crossing: the point at `along` on edge (V, W) inside the patch that
    // labelled v or w, and that label's parent (kNone: the endpoint itself).
    bool crossingSide(const Frontier& S, const Endpoint& end, uint32_t V, uint32_t W, float along, Endpoint& x,
                      uint32_t& parent, uint32_t& patch) {
        const uint32_t ends[2] = {m_.node, m_.other};
        float best = __builtin_inff();
        for (uint32_t n : ends) {
            const uint32_t via = S.route[n].via;
            if (via == kNone || (via & kFirstLayerBit)) continue;
            Endpoint here;
            if (!pointOnEdge(V, W, along, via, here)) continue;
            const uint32_t p = S.route[n].parent;
            PatchField field{&g_, via, kNone, kNone, nullptr};
            if (p != kNone) {
                field.source = g_.nodeVertex[p];
            } else if (end.isVertex()) {
                field.source = end.vertex;
            } else {
                if (end.patch != via) continue;
                field.point = &end;
            }
            if (field.source != kNone && (field.row = slotIn(g_, field.source, via)) == kNone) continue;
            const float d = (p == kNone ? 0.0f : S.label[p].dist) + distanceTo(field, here);
            if (d < best) {
                best = d;
                x = here;
                parent = p;
                patch = via;
            }
        }
        return best != __builtin_inff();
    }

    float distanceTo(const PatchField& field, const Endpoint& e) const {
        if (e.isVertex()) return field.at(e.vertex);
        return interpolate(e, field.slot(e.slot[0]), field.slot(e.slot[1]), field.slot(e.slot[2]));
    }

    // The point at fraction `along` of edge V -> W as a point of a face of `patch`.
    bool pointOnEdge(uint32_t V, uint32_t W, float along, uint32_t patch, Endpoint& out) const {
        bool found = false;
        forEachFaceAround(g_, V, [&](uint32_t f, uint32_t k) {
            if (found || g_.facePatch[f] != patch) return;
            const uint32_t* c = g_.faceVertices + 3 * uint64_t(f);
            uint32_t kw = 3;
            for (uint32_t i = 1; i < 3; ++i)
                if (c[(k + i) % 3] == W) kw = (k + i) % 3;
            if (kw == 3) return;
            vg_point p{f, {0.0f, 0.0f, 0.0f}};
            p.bary[k] = 1.0f - along;
            p.bary[kw] = along;
            found = resolvePoint(g_, p, out) == VG_OK;
        });
        return found;
    }

    bool fan() {
        const uint32_t v = m_.vertex;
        if (m_.way == 2) {
            w_.vertex(g_, v);
            w_.endpoint(g_, m_.t);
            return true;
        }
        FanCrossing crossings[kMaxFan];
        uint32_t count = 0;
        if (fanSegment(g_, v, m_.s, m_.t, m_.way == 0, crossings, &count) == __builtin_inff()) return false;
        for (uint32_t r = 0; r < count; ++r) {
            const FanCrossing& c = crossings[r];
            const uint32_t kv = cornerOf(g_, c.face, v), kf = cornerOf(g_, c.face, c.far);
            const float t = c.along / euclidean(g_, v, c.far);
            // edgePoint runs from corner k to k + 1: pick the direction of (v, far) in this face
            if ((kv + 1) % 3 == kf) w_.edgePoint(g_, c.face, kv, t < 1.0f ? t : 1.0f);
            else w_.edgePoint(g_, c.face, kf, t < 1.0f ? 1.0f - t : 0.0f);
        }
        w_.endpoint(g_, m_.t);
        return true;
    }

    // Expands first-layer legs, then traces every leg.
    bool finish() {
        uint64_t steps = 0;
        for (uint64_t i = 0; i < legCount_; ++i) {
            const PathLeg& L = ws_.pathLegs[i];
            if (!(L.via & kFirstLayerBit)) {
                if (steps >= maxLegs_) return false;
                ws_.pathSteps[steps++] = L;
            } else if (!expand(L, steps)) {
                return false;
            }
        }
        for (uint64_t i = 0; i < steps; ++i)
            if (!trace(ws_.pathSteps[i])) return false;
        return true;
    }

    // The distance an overlay leg stands for: its entry in the first-layer matrix (+inf if
    // either end is not a node of that patch).
    float overlayDistance(uint32_t first, uint32_t from, uint32_t to) const {
        uint32_t slotFrom = kNone, slotTo = kNone;
        for (uint32_t m = g_.nodeFirstBegin[from]; m < g_.nodeFirstBegin[from + 1]; ++m)
            if (g_.nodeFirst[m].patch == first) slotFrom = g_.nodeFirst[m].slot;
        for (uint32_t m = g_.nodeFirstBegin[to]; m < g_.nodeFirstBegin[to + 1]; ++m)
            if (g_.nodeFirst[m].patch == first) slotTo = g_.nodeFirst[m].slot;
        if (slotFrom == kNone || slotTo == kNone) return __builtin_inff();
        const Patch& p = g_.first[first];
        const uint32_t q = quantum(g_.firstDistances, p.matrixBegin + uint64_t(slotFrom) * p.slotCount + slotTo);
        return q == kNoPathQuantum ? __builtin_inff() : float(q) * p.scale + 0.5f * p.scale;
    }

    // The second-layer node path of an overlay leg: A* from its start over the second-layer
    // patches of its first-layer patch, stopped at its end. The overlay entry says how long
    // that path is, so nodes whose lower bound (straight line, then landmarks) exceeds it
    // are never queued; should rounding leave the end unreached, it runs again unbounded.
    bool expand(const PathLeg& L, uint64_t& steps) {
        const uint32_t first = L.via & ~kFirstLayerBit;
        const float overlay = overlayDistance(first, L.from, L.to);
        return expandWithin(L, overlay * (1.0f + kExpandSlack), steps) ||
               (overlay != __builtin_inff() && expandWithin(L, __builtin_inff(), steps));
    }

    // The A* of expand, queueing only nodes whose key stays within `bound`; appends the
    // chain's legs to pathSteps, or leaves them as they were and returns false.
    bool expandWithin(const PathLeg& L, float bound, uint64_t& steps) {
        const uint32_t first = L.via & ~kFirstLayerBit, goal = L.to;
        beginQuery(ws_);
        Frontier& F = ws_.forward;
        const uint32_t stride = 3 + g_.landmarkCount;
        const float* goalRecord = ws_.nodeRecords + uint64_t(goal) * stride;
        auto key = [&](uint32_t n, float dn) {
            const float* r = ws_.nodeRecords + uint64_t(n) * stride;
            const float straight = recordDistance(r, goalRecord);
            if (dn + straight > bound) return __builtin_inff();  // the cheap bound first
            const float k = dn + withLandmarks(g_, r, goalRecord + 3, straight);
            return k > bound ? __builtin_inff() : k;
        };
        auto none = [](uint32_t, float) {};
        const float startKey = key(L.from, 0.0f);
        if (startKey == __builtin_inff()) return false;
        F.improve(L.from, 0.0f, startKey, kNone, 0, kNone);
        while (!F.empty()) {
            const uint32_t u = F.pop().node;
            if (u == goal) break;
            const float du = F.label[u].dist;
            for (uint32_t m = g_.nodeSecondBegin[u]; m < g_.nodeSecondBegin[u + 1]; ++m) {
                const uint32_t patch = g_.nodeSecond[m].patch;
                // Not the row of the patch that labelled u (as in relaxNode: it cannot do better).
                if (g_.second[patch].parent == first && patch != F.route[u].via)
                    relaxSecondRow(g_, patch, g_.nodeSecond[m].slot, du, 0, u, F, key, none);
            }
        }
        if (!F.labelled(goal)) return false;
        uint32_t count = 0;
        for (uint32_t c = goal; c != L.from; c = F.route[c].parent) {
            if (count > g_.nodeCount || F.route[c].parent == kNone) return false;
            ws_.pathNodes[count++] = c;
        }
        if (steps + count > maxLegs_) return false;
        uint32_t prev = L.from;
        for (uint32_t i = count; i > 0; --i) {
            const uint32_t n = ws_.pathNodes[i - 1];
            ws_.pathSteps[steps++] = PathLeg{prev, n, F.route[n].via};
            prev = n;
        }
        return true;
    }

    Endpoint endpointOf(uint32_t end) const {
        switch (end) {
        case kAtSource: return m_.s;
        case kAtTarget: return m_.t;
        case kAtCrossingForward: return crossForward_;
        case kAtCrossingBackward: return crossBackward_;
        }
        return vertexEndpoint(g_, g_.nodeVertex[end]);
    }

    // Traces one second-layer leg from its start to its end (appending the points after the
    // start): down the field of the end when that is a vertex, else up the field of the
    // start, reversed.
    bool trace(const PathLeg& L) {
        const Endpoint a = endpointOf(L.from), b = endpointOf(L.to);
        PatchField field{&g_, L.via, kNone, kNone, nullptr};
        const bool reversed = !b.isVertex();
        const Endpoint& source = reversed ? a : b;
        if (source.isVertex()) {
            field.source = source.vertex;
            field.row = slotIn(g_, source.vertex, L.via);
            if (field.row == kNone) return false;
        } else {
            if (source.patch != L.via) return false;
            field.point = &source;
        }
        const size_t before = w_.count;
        // Through the margins first; where that fails, again inside the patches only.
        bool traced = false;
        for (int attempt = 0; attempt < 2 && !traced; ++attempt) {
            w_.count = before;
            LegTracer tracer(g_, ws_, field, w_, attempt == 0);
            traced = tracer.run(reversed ? b : a);
        }
        if (!traced) return false;
        if (reversed) {
            // Traced b .. a (a already written last time): turn it round, drop a, end at b.
            if (w_.count > before) {
                w_.reverse(before);
                w_.erase(before);
            }
            w_.endpoint(g_, b);
        }
        return true;
    }
};

}  // namespace

extern "C" vg_status vg_path(const vg_graph* graph, vg_workspace* workspace, const vg_point* source,
                             const vg_point* target, vg_path_point* out_points, size_t capacity, size_t* out_count,
                             float* out_distance) {
    const vg_status st = vg::checkQuery(graph, workspace, out_count);
    if (st != VG_OK) return st;
    *out_count = 0;
    if (out_distance == nullptr || source == nullptr || target == nullptr || (out_points == nullptr && capacity != 0))
        return VG_ERR_INVALID_ARGUMENT;
    *out_distance = __builtin_inff();
    vg::Endpoint s, t;
    if (vg::resolvePoint(*graph, *source, s) != VG_OK || vg::resolvePoint(*graph, *target, t) != VG_OK)
        return VG_ERR_INVALID_POINT;
    // Traced into the workspace, pulled taut (vg_path_taut.h), copied to the caller's
    // buffer; a path too long for the workspace is traced again straight into the
    // caller's buffer and returned as traced.
    // Always the bidirectional search: its meeting point lies between the two ends, and
    // the route traced from there pulls taut closer to the geodesic (on a plane, within
    // 0.04% of the straight segment against 0.11% from the directed search's meeting at
    // the target's patch).
    vg::Meeting meeting;
    const float d = vg::pointToPoint(*graph, *workspace, s, t, __builtin_inff(), VG_SEARCH_BIDIRECTIONAL, &meeting);
    *out_distance = d;
    if (meeting.kind == vg::Meeting::kUnreached) return VG_OK;
    const size_t rawCapacity = size_t(vg::maxRawPathPoints(graph->faceCount));
    vg::PathWriter raw{workspace->pathRaw, rawCapacity, 0};
    if (!PathBuilder(*graph, *workspace, meeting, raw).build()) return VG_ERR_PATH_FAILED;
    vg::PathWriter writer{out_points, capacity, 0};
    double length = 0.0;
    if (raw.stored()) {
        // Each pass lays the corridor along the previous pass's path: where that bends
        // round a vertex, the side of the smaller angle (a first pass has only the traced
        // path's directions to go by).
        vg::PathWriter passes[2] = {raw, vg::PathWriter{workspace->pathTaut, rawCapacity, 0}};
        uint32_t cur = 0;
        length = vg::polylineLength(raw.out, raw.count);
        for (uint32_t pass = 0; pass < vg::kTautPasses; ++pass) {
            vg::PathWriter& next = passes[1 - cur];
            next.count = 0;
            double l = 0.0;
            bool bendable = false;
            if (!vg::pullTaut(*graph, *workspace, passes[cur].out, passes[cur].count, next, l, bendable) ||
                !next.stored() || !(l < length))
                break;
            const bool enough = !bendable || (pass > 0 && l > length * (1.0 - vg::kTautGain));
            length = l;
            cur = 1 - cur;
            if (enough) break;
        }
        // Pulled taut in the search's own direction, so that both directions of a query
        // give the same polyline.
        const size_t n = passes[cur].count;
        for (size_t i = 0; i < n; ++i) {
            const vg_path_point& p = passes[cur].out[meeting.swapped ? n - 1 - i : i];
            writer.put(p.point.face, p.point.bary, p.position);
        }
    } else {
        vg::Meeting again;
        vg::pointToPoint(*graph, *workspace, s, t, __builtin_inff(), VG_SEARCH_BIDIRECTIONAL, &again);
        if (!PathBuilder(*graph, *workspace, again, writer).build()) return VG_ERR_PATH_FAILED;
        if (again.swapped) writer.reverse(0);
        length = __builtin_inff();  // not measured (maybe not even stored): the distance stays the search's
    }
    // The distance that comes with a path is the length of that path (it is what a caller
    // will walk, and closer to the geodesic than the search's estimate on average).
    if (length != __builtin_inff()) *out_distance = float(length);
    *out_count = writer.count;
    return writer.count > capacity && out_points != nullptr ? VG_ERR_BUFFER_TOO_SMALL : VG_OK;
}
