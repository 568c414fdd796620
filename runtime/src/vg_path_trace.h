// Tracing one leg of a path inside one second-layer patch: from a start (vertex or surface
// point) down the stored distance field of the leg's other end until it is reached.
//
// Inside a face the field is |x - s| for a virtual source s in the face's plane (the same
// model as the point interpolation in vg_point.h), so the trace heads straight for s and
// leaves the face where that ray meets an edge; in the next face it recomputes s. At a
// vertex it takes the best of "along an edge" and "into a face towards its s", judged by
// the distance still to go. Exits within kSnap of an edge's end go through the vertex.
// Where the model breaks (a loop, too many steps) the leg finishes along patch edges by a
// greedy depth-first walk, which always arrives because a patch is connected.
// Internal to the runtime.
#pragma once

#include "vg_fan.h"
#include "vg_workspace.h"

namespace vg {

constexpr float kSnap = 1e-3f;  // fraction of an edge: exits this close to an end go through the vertex

// Where the path's points go: the caller's buffer while it has room, counted beyond.
struct PathWriter {
    vg_path_point* out;
    size_t capacity;
    size_t count;

    bool stored() const { return count <= capacity; }

    void put(uint32_t face, const float* w, const float* position) {
        if (count < capacity) {
            vg_path_point& p = out[count];
            p.point.face = face;
            for (int k = 0; k < 3; ++k) {
                p.point.bary[k] = w[k];
                p.position[k] = position[k];
            }
        }
        ++count;
    }
    void vertex(const vg_graph& g, uint32_t v) {
        const uint32_t h = g.vertexHalfedge[v];
        const float w[3] = {h % 3 == 0 ? 1.0f : 0.0f, h % 3 == 1 ? 1.0f : 0.0f, h % 3 == 2 ? 1.0f : 0.0f};
        put(h / 3, w, g.positions + 3 * uint64_t(v));
    }
    void endpoint(const vg_graph& g, const Endpoint& e) {
        if (e.isVertex()) vertex(g, e.vertex);
        else put(e.face, e.weight, e.position);
    }
    // The point at fraction t of edge (corner k -> corner k + 1) of face f.
    void edgePoint(const vg_graph& g, uint32_t f, uint32_t k, float t) {
        float w[3] = {0.0f, 0.0f, 0.0f}, position[3];
        w[k] = 1.0f - t;
        w[(k + 1) % 3] = t;
        const float* a = g.positions + 3 * uint64_t(g.faceVertices[3 * f + k]);
        const float* b = g.positions + 3 * uint64_t(g.faceVertices[3 * f + (k + 1) % 3]);
        for (int i = 0; i < 3; ++i) position[i] = a[i] + t * (b[i] - a[i]);
        put(f, w, position);
    }
    // Reverses points [from, count) (when they were all stored).
    void reverse(size_t from) {
        if (!stored()) return;
        for (size_t i = from, j = count; i + 1 < j; ++i) {
            --j;
            const vg_path_point x = out[i];
            out[i] = out[j];
            out[j] = x;
        }
    }
    // Drops point `at`, shifting the rest down.
    void erase(size_t at) {
        if (stored())
            for (size_t i = at; i + 1 < count; ++i) out[i] = out[i + 1];
        --count;
    }
};

// A distance field over the vertices of one second-layer patch: the row of a vertex, or
// the interpolated distances from a surface point of the patch.
struct PatchField {
    const vg_graph* g;
    uint32_t patch;
    uint32_t source;        // the source vertex, or kNone for ...
    uint32_t row;           // (its slot)
    const Endpoint* point;  // ... a source point inside the patch

    float slot(uint32_t j) const {
        if (point) return pointToSlot(*g, *point, j);
        return entry(g->second[patch], g->secondDistances, row, j);
    }
    float at(uint32_t v) const {
        const uint32_t j = slotIn(*g, v, patch);
        return j == kNone ? __builtin_inff() : slot(j);
    }
    // The same source's field in another patch that holds it (a vertex source only).
    bool moveTo(uint32_t other) {
        if (point) return other == patch;
        const uint32_t j = slotIn(*g, source, other);
        if (j == kNone) return false;
        patch = other;
        row = j;
        return true;
    }
    // At a vertex from which the source is one straight step (itself, or a corner of its face).
    bool reachedAt(uint32_t v) const {
        if (!point) return v == source;
        const uint32_t* c = g->faceVertices + 3 * uint64_t(point->face);
        return c[0] == v || c[1] == v || c[2] == v;
    }
};

// Calls f(face, corner) for every face around used vertex v (v is corner `corner` of it).
template <class F>
inline void forEachFaceAround(const vg_graph& g, uint32_t v, F&& f) {
    const uint32_t h0 = g.vertexHalfedge[v];
    if (h0 == kNone) return;
    uint32_t h = h0;
    for (uint32_t guard = 0; guard < 4096; ++guard) {  // a manifold fan closes or ends at a boundary
        f(h / 3, h % 3);
        const uint32_t across = g.faceTwin[prevHalfedge(h)];
        if (across == kNone || across == h0) return;
        h = across;
    }
}

// A face laid into its plane: corner 0 at the origin, corner 1 at (x1, 0), corner 2 at (x2, y2).
struct FaceFrame {
    float x1, x2, y2;
    void corner(uint32_t k, float* q) const {
        q[0] = k == 0 ? 0.0f : (k == 1 ? x1 : x2);
        q[1] = k == 2 ? y2 : 0.0f;
    }
};

inline bool faceFrame(const vg_graph& g, uint32_t f, FaceFrame& fr) {
    const uint32_t* c = g.faceVertices + 3 * uint64_t(f);
    const float* a = g.positions + 3 * uint64_t(c[0]);
    const float* b = g.positions + 3 * uint64_t(c[1]);
    const float* d = g.positions + 3 * uint64_t(c[2]);
    const float e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const float u[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    fr.x1 = __builtin_sqrtf(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    if (!(fr.x1 > 0.0f)) return false;
    fr.x2 = (u[0] * e[0] + u[1] * e[1] + u[2] * e[2]) / fr.x1;
    const float y2 = u[0] * u[0] + u[1] * u[1] + u[2] * u[2] - fr.x2 * fr.x2;
    if (!(y2 > 0.0f)) return false;
    fr.y2 = __builtin_sqrtf(y2);
    return true;
}

// The virtual source of corner distances D in the face's plane (see the top of the file).
inline bool virtualSource(const FaceFrame& fr, const float* D, float* s) {
    s[0] = (fr.x1 * fr.x1 + D[0] * D[0] - D[1] * D[1]) / (2.0f * fr.x1);
    s[1] = (fr.x2 * fr.x2 + fr.y2 * fr.y2 + D[0] * D[0] - D[2] * D[2] - 2.0f * fr.x2 * s[0]) / (2.0f * fr.y2);
    return s[0] - s[0] == 0.0f && s[1] - s[1] == 0.0f;  // finite
}

// Where the ray p + l (s - p), l > 0, meets edge k (corner k -> k + 1): fraction t along
// the edge and l; false when it misses the edge (beyond a small tolerance).
inline bool rayHitsEdge(const FaceFrame& fr, const float* p, const float* s, uint32_t k, float& t, float& l) {
    float a[2], b[2];
    fr.corner(k, a);
    fr.corner((k + 1) % 3, b);
    const float ux = s[0] - p[0], uy = s[1] - p[1], ex = b[0] - a[0], ey = b[1] - a[1];
    const float rx = a[0] - p[0], ry = a[1] - p[1];
    const float det = ex * uy - ux * ey;
    if (!(__builtin_fabsf(det) > 0.0f)) return false;
    l = (ex * ry - ey * rx) / det;
    t = (ux * ry - uy * rx) / det;
    return l > 0.0f && t >= -1e-4f && t <= 1.0f + 1e-4f;
}

// Along edge (a, b) of length lab at fraction t, from distances da, db: the point model's
// distance (d^2 - |x|^2 linear along the edge).
inline float alongEdge(float da, float db, float lab, float t) {
    const float sq = (1.0f - t) * da * da + t * db * db - t * (1.0f - t) * lab * lab;
    return sq > 0.0f ? __builtin_sqrtf(sq) : 0.0f;
}

// Point s in the frame of face f, seen across f's edge k (corners k -> k + 1) from face g,
// where that edge is g's edge j (running the other way): the same point in g's frame with
// g unfolded into f's plane (g's third corner on the far side of the edge).
inline void unfoldAcross(const FaceFrame& ff, uint32_t k, const FaceFrame& fg, uint32_t j, const float* s, float* out) {
    float af[2], bf[2], cf[2], ag[2], bg[2], cg[2];
    ff.corner(k, af);
    ff.corner((k + 1) % 3, bf);
    ff.corner((k + 2) % 3, cf);
    fg.corner((j + 1) % 3, ag);  // f's corner k is g's corner j + 1
    fg.corner(j, bg);
    fg.corner((j + 2) % 3, cg);
    const float ef[2] = {bf[0] - af[0], bf[1] - af[1]}, eg[2] = {bg[0] - ag[0], bg[1] - ag[1]};
    const float lf = ef[0] * ef[0] + ef[1] * ef[1];
    const float d[2] = {s[0] - af[0], s[1] - af[1]};
    const float along = (d[0] * ef[0] + d[1] * ef[1]) / lf, across = (ef[0] * d[1] - ef[1] * d[0]) / lf;
    const float sideF = ef[0] * (cf[1] - af[1]) - ef[1] * (cf[0] - af[0]);
    const float sideG = eg[0] * (cg[1] - ag[1]) - eg[1] * (cg[0] - ag[0]);
    const float acrossG = (sideF > 0.0f) == (sideG > 0.0f) ? -across : across;
    out[0] = ag[0] + along * eg[0] - acrossG * eg[1];
    out[1] = ag[1] + along * eg[1] + acrossG * eg[0];
}

class LegTracer {
public:
    // `throughMargins`: where the field's way leaves every patch that holds its source, go
    // on straight (the stored rows were computed on each patch plus a ring of faces).
    LegTracer(const vg_graph& g, vg_workspace& ws, const PatchField& field, PathWriter& w, bool throughMargins)
        : g_(g), ws_(ws), f_(field), w_(w), throughMargins_(throughMargins) {}

    // Emits the points after `start` up to the field's source (a vertex, or the source
    // point itself); false if no way was found.
    bool run(const Endpoint& start) {
        uint64_t budget = stepsFor(f_.patch);
        uint32_t vtx = kNone, face = kNone;
        float bary[3] = {0.0f, 0.0f, 0.0f};
        uint32_t entered = 3;  // edge of `face` the trace came in through (3: none)
        if (start.isVertex()) {
            if (slotIn(g_, start.vertex, f_.patch) == kNone) return false;
            vtx = start.vertex;
        } else {
            if (g_.facePatch[start.face] != f_.patch) return false;
            face = start.face;
            for (int k = 0; k < 3; ++k) {
                bary[k] = start.weight[k];
                if (bary[k] == 0.0f) entered = uint32_t(k + 1) % 3;
            }
        }
        const uint32_t gen = beginQuery(ws_);
        for (uint64_t step = 0; step < budget; ++step) {
            const uint32_t patch = f_.patch;
            if (vtx != kNone) {
                if (f_.reachedAt(vtx)) return finishAt();
                ws_.vertexStamp[vtx] = gen;
                if (!leaveVertex(vtx, gen, face, entered, bary)) return walkEdges(vtx);
            } else {
                if (f_.point && face == f_.point->face) {
                    w_.endpoint(g_, *f_.point);
                    return true;
                }
                const uint32_t* c = g_.faceVertices + 3 * uint64_t(face);
                for (uint32_t k = 0; k < 3; ++k)
                    if (c[k] == f_.source) {
                        w_.vertex(g_, c[k]);
                        return true;
                    }
                vtx = crossFace(face, entered, bary);
                if (vtx == kNone && face == kNone) return false;
                if (vtx != kNone && ws_.vertexStamp[vtx] == gen) return walkEdges(vtx);
            }
            if (f_.patch != patch) budget += stepsFor(f_.patch);
        }
        if (vtx == kNone) {
            vtx = bestCorner(face, bary);
            if (vtx == kNone) return false;
            w_.vertex(g_, vtx);
        }
        return walkEdges(vtx);
    }

private:
    const vg_graph& g_;
    vg_workspace& ws_;
    PatchField f_;  // moves to a neighbouring patch where the path leaves this one
    PathWriter& w_;
    const bool throughMargins_;
    uint32_t switches_ = 0;
    static constexpr uint32_t kMaxSwitches = 64;
    // Straight on outside the field's patches, towards virtual source straightSource_ (in the
    // current face's frame), for at most kMaxStraightFaces faces in a row.
    bool straight_ = false;
    float straightSource_[2] = {0.0f, 0.0f};
    uint32_t straightFaces_ = 0;
    static constexpr uint32_t kMaxStraightFaces = 32;

    // Continues straight into face `next` (across `edge` of the current face, frame fr) towards s.
    bool goStraight(const FaceFrame& fr, uint32_t edge, uint32_t next, const float* s) {
        FaceFrame fg;
        if (!throughMargins_ || straightFaces_ >= kMaxStraightFaces || !faceFrame(g_, next / 3, fg)) return false;
        unfoldAcross(fr, edge, fg, next % 3, s, straightSource_);
        straight_ = true;
        ++straightFaces_;
        return true;
    }

    uint64_t stepsFor(uint32_t patch) const { return 4 * uint64_t(g_.second[patch].slotCount) + 64; }

    // The field at vertex v, remembering the last few: consecutive faces share two corners,
    // and each fresh lookup reads a row entry that is rarely in cache.
    static constexpr uint32_t kRecent = 4;
    uint32_t recentVertex_[kRecent] = {kNone, kNone, kNone, kNone};
    float recentValue_[kRecent] = {};
    uint32_t recentPatch_ = kNone, recentNext_ = 0;
    float fieldAt(uint32_t v) {
        if (recentPatch_ != f_.patch) {
            for (uint32_t i = 0; i < kRecent; ++i) recentVertex_[i] = kNone;
            recentPatch_ = f_.patch;
        }
        for (uint32_t i = 0; i < kRecent; ++i)
            if (recentVertex_[i] == v) return recentValue_[i];
        const float d = f_.at(v);
        recentVertex_[recentNext_] = v;
        recentValue_[recentNext_] = d;
        recentNext_ = (recentNext_ + 1) % kRecent;
        return d;
    }

    bool finishAt() {
        if (f_.point) w_.endpoint(g_, *f_.point);  // straight across the point's face
        return true;
    }

    bool inPatch(uint32_t face, uint32_t patch) const { return face != kNone && g_.facePatch[face] == patch; }

    // The face across half-edge h, or kNone at a boundary.
    uint32_t across(uint32_t h) const { return g_.faceTwin[h]; }

    // Follows the path into `patch`: the source's field there, if the patch holds the source.
    bool enter(uint32_t patch) {
        if (patch == f_.patch) return true;
        if (switches_ >= kMaxSwitches || !f_.moveTo(patch)) return false;
        ++switches_;
        return true;
    }

    // The corner of `face` with the least straight step plus field distance (kNone if none is reachable).
    uint32_t bestCorner(uint32_t face, const float* bary) const {
        const uint32_t* c = g_.faceVertices + 3 * uint64_t(face);
        float p[3] = {0.0f, 0.0f, 0.0f};
        for (int k = 0; k < 3; ++k)
            for (int i = 0; i < 3; ++i) p[i] += bary[k] * g_.positions[3 * uint64_t(c[k]) + i];
        uint32_t best = kNone;
        float bestEst = __builtin_inff();
        for (int k = 0; k < 3; ++k) {
            const float est = distance3(p, g_.positions + 3 * uint64_t(c[k])) + f_.at(c[k]);
            if (est < bestEst) {
                bestEst = est;
                best = c[k];
            }
        }
        return best;
    }

    // One step inside `face` from the point at `bary`: to the next face (updates face,
    // entered, bary; returns kNone) or to a vertex (returns it, emitted). face = kNone on failure.
    uint32_t crossFace(uint32_t& face, uint32_t& entered, float* bary) {
        const uint32_t* c = g_.faceVertices + 3 * uint64_t(face);
        FaceFrame fr{};
        float D[3] = {0.0f, 0.0f, 0.0f}, s[2] = {straightSource_[0], straightSource_[1]};
        bool ok = faceFrame(g_, face, fr);
        if (!straight_) {
            for (int k = 0; k < 3; ++k) {
                D[k] = fieldAt(c[k]);
                ok = ok && D[k] != __builtin_inff();
            }
            ok = ok && virtualSource(fr, D, s);
        }
        uint32_t exitEdge = 3;
        float exitT = 0.0f;
        if (ok) {
            float q1[2], q2[2];
            fr.corner(1, q1);
            fr.corner(2, q2);
            const float p[2] = {bary[1] * q1[0] + bary[2] * q2[0], bary[1] * q1[1] + bary[2] * q2[1]};
            float bestL = __builtin_inff();
            for (uint32_t k = 0; k < 3; ++k) {
                float t, l;
                if (k == entered || !rayHitsEdge(fr, p, s, k, t, l) || !(l < bestL)) continue;
                bestL = l;
                exitEdge = k;
                exitT = t < 0.0f ? 0.0f : (t > 1.0f ? 1.0f : t);
            }
        }
        if (straight_) return straightStep(face, entered, bary, fr, exitEdge, exitT, s);
        if (exitEdge == 3) return toVertex(bestCorner(face, bary), face);
        const uint32_t a = c[exitEdge], b = c[(exitEdge + 1) % 3];
        if (exitT < kSnap) return toVertex(a, face);
        if (exitT > 1.0f - kSnap) return toVertex(b, face);
        const uint32_t next = across(3 * face + exitEdge);
        if (next != kNone && !enter(g_.facePatch[next / 3]) && goStraight(fr, exitEdge, next, s)) {
            w_.edgePoint(g_, face, exitEdge, exitT);
            moveAcross(face, entered, bary, next, exitT);
            return kNone;
        }
        if (next == kNone || g_.facePatch[next / 3] != f_.patch) {
            // The straight way leaves the field's patches (or the mesh): round by the better end.
            const float lab = euclidean(g_, a, b);
            return toVertex(exitT * lab + D[exitEdge] <= (1.0f - exitT) * lab + D[(exitEdge + 1) % 3] ? a : b, face);
        }
        w_.edgePoint(g_, face, exitEdge, exitT);
        moveAcross(face, entered, bary, next, exitT);
        return kNone;
    }

    // The point at fraction t of `face`'s exit edge, as a point of face `next` across it.
    static void moveAcross(uint32_t& face, uint32_t& entered, float* bary, uint32_t next, float t) {
        face = next / 3;
        entered = next % 3;
        bary[0] = bary[1] = bary[2] = 0.0f;
        bary[entered] = t;  // the twin runs the other way
        bary[(entered + 1) % 3] = 1.0f - t;
    }

    // A step of the straight mode (outside the field's patches): on to the next face, back
    // to the field where the way re-enters a patch holding it, into a patch vertex it
    // passes; face = kNone (failure) where it runs off the mesh or more than
    // kMaxStraightFaces faces.
    uint32_t straightStep(uint32_t& face, uint32_t& entered, float* bary, const FaceFrame& fr, uint32_t exitEdge,
                          float exitT, const float* s) {
        if (exitEdge == 3) {
            face = kNone;
            return kNone;
        }
        const uint32_t* c = g_.faceVertices + 3 * uint64_t(face);
        const uint32_t a = c[exitEdge], b = c[(exitEdge + 1) % 3];
        const uint32_t snapTo = exitT < kSnap ? a : (exitT > 1.0f - kSnap ? b : kNone);
        if (snapTo != kNone && slotIn(g_, snapTo, f_.patch) != kNone) {
            straight_ = false;
            straightFaces_ = 0;
            return toVertex(snapTo, face);
        }
        if (exitT < 1e-4f) exitT = 1e-4f;  // passing a vertex outside the field's patches: just beside it
        if (exitT > 1.0f - 1e-4f) exitT = 1.0f - 1e-4f;
        const uint32_t next = across(3 * face + exitEdge);
        if (next == kNone) {
            face = kNone;
            return kNone;
        }
        if (enter(g_.facePatch[next / 3])) {
            straight_ = false;
            straightFaces_ = 0;
        } else if (!goStraight(fr, exitEdge, next, s)) {
            face = kNone;
            return kNone;
        }
        w_.edgePoint(g_, face, exitEdge, exitT);
        moveAcross(face, entered, bary, next, exitT);
        return kNone;
    }

    uint32_t toVertex(uint32_t v, uint32_t& face) {
        if (v == kNone) {
            face = kNone;
            return kNone;
        }
        w_.vertex(g_, v);
        return v;
    }

    // Where the ray from vertex v (corner k of face f, frame fr) towards s leaves f's wedge
    // at v, turns around v through faces outside the field's patches until the ray runs
    // into one of them: that face g, the edge e opposite v, the fraction t on it, s in g's
    // frame. False when the ray stays in f, reaches a face of the field's patches (its own
    // candidate) or a boundary.
    bool marginFace(uint32_t v, uint32_t f, uint32_t k, const FaceFrame& fr, const float* s, uint32_t& g, uint32_t& e,
                    float& t, float* sg) const {
        FaceFrame cur = fr;
        uint32_t face = f, kk = k;
        float sc[2] = {s[0], s[1]};
        for (uint32_t turn = 0; turn < 16; ++turn) {
            float q[2], a[2], b[2];
            cur.corner(kk, q);
            cur.corner((kk + 1) % 3, a);
            cur.corner((kk + 2) % 3, b);
            const float dx = sc[0] - q[0], dy = sc[1] - q[1];
            const float pastA = (a[0] - q[0]) * dy - (a[1] - q[1]) * dx;  // >= 0: counter-clockwise of a
            const float beforeB = dx * (b[1] - q[1]) - dy * (b[0] - q[0]);  // >= 0: clockwise of b
            if (pastA >= 0.0f && beforeB >= 0.0f) {
                if (face == f) return false;
                float l;
                e = (kk + 1) % 3;
                if (!rayHitsEdge(cur, q, sc, e, t, l)) return false;
                t = t < 1e-4f ? 1e-4f : (t > 1.0f - 1e-4f ? 1.0f - 1e-4f : t);
                g = face;
                sg[0] = sc[0];
                sg[1] = sc[1];
                return true;
            }
            const uint32_t h = 3 * face + (pastA < 0.0f ? kk : (kk + 2) % 3);  // edge (v, a) or (b, v)
            const uint32_t tw = g_.faceTwin[h];
            if (tw == kNone) return false;
            PatchField probe = f_;
            if (probe.moveTo(g_.facePatch[tw / 3])) return false;
            FaceFrame next;
            if (!faceFrame(g_, tw / 3, next)) return false;
            float sn[2];
            unfoldAcross(cur, h % 3, next, tw % 3, sc, sn);
            face = tw / 3;
            cur = next;
            kk = cornerOf(g_, face, v);
            if (kk == 3) return false;
            sc[0] = sn[0];
            sc[1] = sn[1];
        }
        return false;
    }

    // From vertex v: along an edge to a neighbour, or into a face towards its virtual
    // source, in any patch around v that holds the field's source (a path between patch
    // nodes may cut through a neighbouring patch: the stored rows were computed on the
    // patch plus a margin); false when every way leads back to visited vertices.
    bool leaveVertex(uint32_t& v, uint32_t gen, uint32_t& face, uint32_t& entered, float* bary) {
        const float* pv = g_.positions + 3 * uint64_t(v);
        float bestEst = __builtin_inff();
        uint32_t toNeighbour = kNone, toFace = kNone, exitEdge = 0, bestPatch = f_.patch;
        float exitT = 0.0f, bestSource[2] = {0.0f, 0.0f};
        // Candidates: a neighbour vertex, or the point at fraction t of edge e of face f
        // (with the virtual source in f's frame); the least estimated length wins.
        auto offerNeighbour = [&](float est, uint32_t n, uint32_t patch) {
            if (!(est < bestEst)) return;
            bestEst = est;
            toNeighbour = n;
            toFace = kNone;
            bestPatch = patch;
        };
        auto offerFace = [&](float est, uint32_t f, uint32_t e, float t, const float* src, uint32_t patch) {
            if (!(est < bestEst)) return;
            bestEst = est;
            toNeighbour = kNone;
            toFace = f;
            exitEdge = e;
            exitT = t;
            bestPatch = patch;
            bestSource[0] = src[0];
            bestSource[1] = src[1];
        };
        forEachPatchOf(g_, v, [&](uint32_t patch, uint32_t) {
            PatchField fq = f_;
            if (patch != f_.patch && (switches_ >= kMaxSwitches || !fq.moveTo(patch))) return;
            const float dv = fq.at(v);
            forEachFaceAround(g_, v, [&](uint32_t f, uint32_t k) {
                if (!inPatch(f, patch)) return;
                const uint32_t* c = g_.faceVertices + 3 * uint64_t(f);
                const uint32_t a = c[(k + 1) % 3], b = c[(k + 2) % 3];
                const float da = fq.at(a), db = fq.at(b);
                const uint32_t ends[2] = {a, b};
                const float dist[2] = {da, db};
                for (int i = 0; i < 2; ++i) {
                    if (dist[i] == __builtin_inff() || ws_.vertexStamp[ends[i]] == gen) continue;
                    offerNeighbour(euclidean(g_, v, ends[i]) + dist[i], ends[i], patch);
                }
                if (da == __builtin_inff() || db == __builtin_inff() || dv == __builtin_inff()) return;
                const uint32_t e = (k + 1) % 3;  // the edge opposite v
                const uint32_t beyond = across(3 * f + e);
                PatchField probe = fq;
                if (beyond == kNone ||
                    (!throughMargins_ && (switches_ + 2 > kMaxSwitches || !probe.moveTo(g_.facePatch[beyond / 3]))))
                    return;
                FaceFrame fr;
                if (!faceFrame(g_, f, fr)) return;
                float D[3], s[2], q[2], t, l;
                D[k] = dv;
                D[(k + 1) % 3] = da;
                D[(k + 2) % 3] = db;
                if (!virtualSource(fr, D, s)) return;
                fr.corner(k, q);
                if (throughMargins_) {
                    // The way may leave v outside the field's patches: turn around v to the face it enters.
                    uint32_t g2, e2;
                    float t2, s2[2];
                    if (marginFace(v, f, k, fr, s, g2, e2, t2, s2))
                        offerFace(__builtin_sqrtf((s[0] - q[0]) * (s[0] - q[0]) + (s[1] - q[1]) * (s[1] - q[1])), g2, e2,
                                  t2, s2, patch);
                }
                if (!rayHitsEdge(fr, q, s, e, t, l) || !(t > kSnap && t < 1.0f - kSnap)) return;
                const float* pa = g_.positions + 3 * uint64_t(a);
                const float* pb = g_.positions + 3 * uint64_t(b);
                float x[3];
                for (int i = 0; i < 3; ++i) x[i] = pa[i] + t * (pb[i] - pa[i]);
                offerFace(distance3(pv, x) + alongEdge(da, db, distance3(pa, pb), t), f, e, t, s, patch);
            });
        });
        if (toNeighbour == kNone && toFace == kNone) return false;
        enter(bestPatch);
        if (toNeighbour != kNone) {
            w_.vertex(g_, toNeighbour);
            v = toNeighbour;
            return true;
        }
        // Into the face: its exit edge is crossed at once, into a patch holding the field or
        // straight on (checked above: one of the two is possible).
        const uint32_t next = across(3 * toFace + exitEdge);
        if (!enter(g_.facePatch[next / 3])) {
            FaceFrame fr;
            if (!faceFrame(g_, toFace, fr) || !goStraight(fr, exitEdge, next, bestSource)) return false;
        }
        w_.edgePoint(g_, toFace, exitEdge, exitT);
        moveAcross(face, entered, bary, next, exitT);
        v = kNone;
        return true;
    }

    // Greedy depth-first walk along edges of the field's patch from v (nearest unvisited
    // neighbour first, back up at dead ends), then emits the walk.
    bool walkEdges(uint32_t v) {
        const uint32_t gen = beginQuery(ws_);
        uint32_t* stack = ws_.patchBestNode;  // kMaxPatchSlots entries, more than a patch has vertices
        uint32_t top = 0;
        stack[top++] = v;
        ws_.vertexStamp[v] = gen;
        while (top > 0 && !f_.reachedAt(stack[top - 1])) {
            const uint32_t u = stack[top - 1];
            uint32_t next = kNone;
            float nextD = __builtin_inff();
            forEachFaceAround(g_, u, [&](uint32_t f, uint32_t k) {
                if (!inPatch(f, f_.patch)) return;
                for (uint32_t i = 1; i < 3; ++i) {
                    const uint32_t n = g_.faceVertices[3 * uint64_t(f) + (k + i) % 3];
                    if (ws_.vertexStamp[n] == gen) continue;
                    const float d = f_.at(n);
                    if (d < nextD) {
                        nextD = d;
                        next = n;
                    }
                }
            });
            if (next == kNone) {
                --top;
                continue;
            }
            if (top == 65536) return false;
            ws_.vertexStamp[next] = gen;
            stack[top++] = next;
        }
        if (top == 0) return false;
        for (uint32_t i = 1; i < top; ++i) w_.vertex(g_, stack[i]);
        return finishAt();
    }
};

}  // namespace vg
