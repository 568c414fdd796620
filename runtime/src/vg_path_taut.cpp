#include "vg_path_taut.h"

namespace vg {

namespace {

// Where a path point lies: on a vertex, on an edge (a half-edge of its face) or inside a face.
struct Spot {
    enum Kind : uint32_t { kVertex, kEdge, kFace } kind;
    uint32_t id;
};

constexpr float kZeroWeight = 1e-6f;
constexpr double kWorthAnotherPass = 0.05;  // radians

Spot locate(const vg_graph& g, const vg_path_point& p) {
    uint32_t zero = 3, zeros = 0;
    for (uint32_t k = 0; k < 3; ++k) {
        if (p.point.bary[k] >= 1.0f - kZeroWeight) return Spot{Spot::kVertex, g.faceVertices[3 * uint64_t(p.point.face) + k]};
        if (p.point.bary[k] <= kZeroWeight) {
            zero = k;
            ++zeros;
        }
    }
    if (zeros == 1) return Spot{Spot::kEdge, 3 * p.point.face + (zero + 1) % 3};  // the edge opposite corner `zero`
    return Spot{Spot::kFace, p.point.face};
}

bool faceHolds(const vg_graph& g, uint32_t face, const Spot& s) {
    switch (s.kind) {
    case Spot::kVertex: return cornerOf(g, face, s.id) != 3;
    case Spot::kEdge: return face == s.id / 3 || (g.faceTwin[s.id] != kNone && face == g.faceTwin[s.id] / 3);
    case Spot::kFace: return face == s.id;
    }
    return false;
}

struct Vec {
    double x, y, z;
};
Vec vertexAt(const vg_graph& g, uint32_t v) {
    const float* p = g.positions + 3 * uint64_t(v);
    return Vec{p[0], p[1], p[2]};
}
Vec pointAt(const vg_path_point& p) { return Vec{p.position[0], p.position[1], p.position[2]}; }
Vec minus(Vec a, Vec b) { return Vec{a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot(Vec a, Vec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double norm(Vec a) { return __builtin_sqrt(dot(a, a)); }

// Angle at the origin between directions a and b (0 when either is zero).
double angleBetween(Vec a, Vec b) {
    const double la = norm(a), lb = norm(b);
    if (!(la > 0.0) || !(lb > 0.0)) return 0.0;
    double c = dot(a, b) / (la * lb);
    c = c > 1.0 ? 1.0 : (c < -1.0 ? -1.0 : c);
    return __builtin_acos(c);
}

double cross2(const double* o, const double* a, const double* b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

class Corridor {
public:
    Corridor(const vg_graph& g, vg_workspace& ws, uint64_t capacity)
        : g_(g), portals_(ws.pathPortals), capacity_(capacity) {}

    // Lays face f into the plane as the corridor's first face.
    bool start(uint32_t f) {
        FaceFrame fr;
        if (!faceFrame(g_, f, fr)) return false;
        face_ = f;
        corner_[0][0] = corner_[0][1] = corner_[1][1] = 0.0;
        corner_[1][0] = fr.x1;
        corner_[2][0] = fr.x2;
        corner_[2][1] = fr.y2;
        return true;
    }

    uint32_t face() const { return face_; }
    uint64_t count() const { return count_; }

    // Crosses half-edge h of the current face into the face beyond, unfolding it.
    bool cross(uint32_t h) {
        const uint32_t twin = g_.faceTwin[h];
        if (twin == kNone || count_ >= capacity_) return false;
        const uint32_t k = h % 3;
        Portal& p = portals_[count_++];
        p.halfedge = h;
        p.rightVertex = g_.faceVertices[h];
        p.leftVertex = g_.faceVertices[nextHalfedge(h)];
        p.right[0] = corner_[k][0];
        p.right[1] = corner_[k][1];
        p.left[0] = corner_[(k + 1) % 3][0];
        p.left[1] = corner_[(k + 1) % 3][1];
        // The face beyond: its half-edge j runs left -> right, its third corner lies to
        // the left of that direction.
        const uint32_t f = twin / 3, j = twin % 3;
        const uint32_t third = g_.faceVertices[3 * uint64_t(f) + (j + 2) % 3];
        const Vec l = vertexAt(g_, p.leftVertex), r = vertexAt(g_, p.rightVertex), x = vertexAt(g_, third);
        const double d2 = dot(minus(l, r), minus(l, r)), a2 = dot(minus(x, l), minus(x, l));
        const double b2 = dot(minus(x, r), minus(x, r));
        const double d = __builtin_sqrt(d2);
        if (!(d > 0.0)) return false;
        // The portal's plane length (d up to rounding): the unit vector along it.
        const double ux = (p.right[0] - p.left[0]) / d, uy = (p.right[1] - p.left[1]) / d;
        const double along = (a2 - b2 + d2) / (2.0 * d);
        const double h2 = a2 - along * along;
        const double up = h2 > 0.0 ? __builtin_sqrt(h2) : 0.0;
        corner_[j][0] = p.left[0];
        corner_[j][1] = p.left[1];
        corner_[(j + 1) % 3][0] = p.right[0];
        corner_[(j + 1) % 3][1] = p.right[1];
        corner_[(j + 2) % 3][0] = p.left[0] + along * ux - up * uy;
        corner_[(j + 2) % 3][1] = p.left[1] + along * uy + up * ux;
        face_ = f;
        return true;
    }

    // A raw point in the current face's plane (every vertex it is weighted on is a corner).
    bool planar(const vg_path_point& p, double* out) const {
        out[0] = out[1] = 0.0;
        for (uint32_t k = 0; k < 3; ++k) {
            const float w = p.point.bary[k];
            if (w <= kZeroWeight) continue;
            const uint32_t c = cornerOf(g_, face_, g_.faceVertices[3 * uint64_t(p.point.face) + k]);
            if (c == 3) return false;
            out[0] += double(w) * corner_[c][0];
            out[1] += double(w) * corner_[c][1];
        }
        return true;
    }

private:
    const vg_graph& g_;
    Portal* portals_;
    const uint64_t capacity_;
    uint64_t count_ = 0;
    uint32_t face_ = kNone;
    double corner_[3][2] = {};
};

// Turning around vertex v from face `from` in direction `dir` (0: across the edge leaving
// v, 1: across the edge entering v) to the first face holding `next`: the faces passed
// and the angle swept from direction `in` (at v, in `from`) to direction `out`.
struct FanWalk {
    uint32_t faces;
    double angle;
    bool ok;
};

FanWalk walkFan(const vg_graph& g, uint32_t v, uint32_t from, uint32_t dir, const Spot& next, Vec in, Vec out) {
    const Vec pv = vertexAt(g, v);
    uint32_t f = from;
    double angle = 0.0;
    for (uint32_t step = 0; step < 4096; ++step) {
        const uint32_t k = cornerOf(g, f, v);
        if (k == 3) break;
        const uint32_t* c = g.faceVertices + 3 * uint64_t(f);
        const Vec exitSpoke = minus(vertexAt(g, c[dir == 0 ? (k + 1) % 3 : (k + 2) % 3]), pv);
        const Vec entrySpoke = minus(vertexAt(g, c[dir == 0 ? (k + 2) % 3 : (k + 1) % 3]), pv);
        if (step > 0 && faceHolds(g, f, next)) return FanWalk{step, angle + angleBetween(entrySpoke, out), true};
        angle += step == 0 ? angleBetween(in, exitSpoke) : angleBetween(entrySpoke, exitSpoke);
        const uint32_t h = 3 * f + (dir == 0 ? k : (k + 2) % 3);
        const uint32_t t = g.faceTwin[h];
        if (t == kNone || t / 3 == from) break;
        f = t / 3;
    }
    return FanWalk{0, 0.0, false};
}

// Builds the corridor of the raw path and lays the start point into its plane: false when
// consecutive points share no face.
bool buildCorridor(const vg_graph& g, const vg_path_point* raw, size_t count, Corridor& c, double* start) {
    Spot here = locate(g, raw[0]), next = locate(g, raw[1]);
    uint32_t first = kNone;
    const uint32_t f0 = raw[0].point.face;
    if (faceHolds(g, f0, next)) {
        first = f0;
    } else if (here.kind == Spot::kEdge && g.faceTwin[here.id] != kNone && faceHolds(g, g.faceTwin[here.id] / 3, next)) {
        first = g.faceTwin[here.id] / 3;
    } else if (here.kind == Spot::kVertex) {
        forEachFaceAround(g, here.id, [&](uint32_t f, uint32_t) {
            if (first == kNone && faceHolds(g, f, next)) first = f;
        });
    }
    if (first == kNone || !c.start(first) || !c.planar(raw[0], start)) return false;
    for (size_t i = 1; i + 1 < count; ++i) {
        here = next;
        next = locate(g, raw[i + 1]);
        const uint32_t cur = c.face();
        if (faceHolds(g, cur, next)) continue;  // the step stays in the current face
        if (here.kind == Spot::kEdge) {
            if (!c.cross(here.id / 3 == cur ? here.id : g.faceTwin[here.id])) return false;
        } else if (here.kind == Spot::kVertex) {
            const Vec pv = vertexAt(g, here.id);
            const Vec in = minus(pointAt(raw[i - 1]), pv), out = minus(pointAt(raw[i + 1]), pv);
            const FanWalk w0 = walkFan(g, here.id, cur, 0, next, in, out);
            const FanWalk w1 = walkFan(g, here.id, cur, 1, next, in, out);
            if (!w0.ok && !w1.ok) return false;
            const uint32_t dir = w0.ok && (!w1.ok || w0.angle <= w1.angle) ? 0 : 1;
            const uint32_t steps = dir == 0 ? w0.faces : w1.faces;
            for (uint32_t s = 0; s < steps; ++s) {
                const uint32_t k = cornerOf(g, c.face(), here.id);
                if (!c.cross(3 * c.face() + (dir == 0 ? k : (k + 2) % 3))) return false;
            }
        } else {
            return false;
        }
        if (!faceHolds(g, c.face(), next)) return false;
    }
    return true;
}

}  // namespace

bool pullTaut(const vg_graph& g, vg_workspace& ws, const vg_path_point* raw, size_t count, PathWriter& out,
              double& length, bool& bendable) {
    if (count < 2) return false;
    const uint64_t capacity = maxPortals(g.faceCount);
    Corridor corridor(g, ws, capacity);
    double start[2], end[2];
    if (!buildCorridor(g, raw, count, corridor, start) || !corridor.planar(raw[count - 1], end)) return false;
    const uint64_t m = corridor.count();
    const Portal* P = ws.pathPortals;
    Apex* A = ws.pathApexes;
    uint64_t apexes = 0;
    A[apexes++] = Apex{{start[0], start[1]}, 0, kNone};

    // The funnel: apex, and the left and right rays' ends with the portals they came from.
    double apex[2] = {start[0], start[1]}, fl[2] = {start[0], start[1]}, fr[2] = {start[0], start[1]};
    uint64_t ai = 0, li = 0, ri = 0;
    auto atApex = [&](const double* q) { return q[0] == apex[0] && q[1] == apex[1]; };
    auto portalLeft = [&](uint64_t i) { return i <= m && i > 0 ? P[i - 1].left : end; };
    auto portalRight = [&](uint64_t i) { return i <= m && i > 0 ? P[i - 1].right : end; };
    for (uint64_t i = 1; i <= m + 1; ++i) {
        const double* L = portalLeft(i);
        const double* R = portalRight(i);
        if (cross2(apex, fr, R) >= 0.0) {  // the right ray narrows
            if (atApex(fr) || cross2(apex, fl, R) < 0.0) {
                fr[0] = R[0], fr[1] = R[1], ri = i;
            } else {  // it crosses the left ray: the path bends around the left end
                if (li > m) break;  // the end itself
                A[apexes++] = Apex{{fl[0], fl[1]}, uint32_t(li), P[li - 1].leftVertex};
                apex[0] = fl[0], apex[1] = fl[1], ai = li;
                fr[0] = fl[0], fr[1] = fl[1], ri = li = ai;
                i = ai;
                continue;
            }
        }
        if (cross2(apex, fl, L) <= 0.0) {  // the left ray narrows
            if (atApex(fl) || cross2(apex, fr, L) > 0.0) {
                fl[0] = L[0], fl[1] = L[1], li = i;
            } else {
                if (ri > m) break;
                A[apexes++] = Apex{{fr[0], fr[1]}, uint32_t(ri), P[ri - 1].rightVertex};
                apex[0] = fr[0], apex[1] = fr[1], ai = ri;
                fl[0] = fr[0], fl[1] = fr[1], li = ri = ai;
                i = ai;
                continue;
            }
        }
    }
    A[apexes++] = Apex{{end[0], end[1]}, uint32_t(m + 1), kNone};

    // Another pass can only help where the path bends round a vertex whose other side
    // is shorter: there the angle left over, total minus the corridor's side (pi plus
    // the bend), is below pi. On a flat or convex vertex any bend qualifies; a pass is
    // worth it where the shortfall is more than kWorthAnotherPass (the length it saves
    // grows with the square of the shortfall).
    bendable = false;
    for (uint64_t s = 1; s + 1 < apexes && !bendable; ++s) {
        const double ux = A[s].at[0] - A[s - 1].at[0], uy = A[s].at[1] - A[s - 1].at[1];
        const double wx = A[s + 1].at[0] - A[s].at[0], wy = A[s + 1].at[1] - A[s].at[1];
        const double cr = ux * wy - uy * wx;
        const double bend = __builtin_atan2(cr < 0.0 ? -cr : cr, ux * wx + uy * wy);
        bool closed = true;
        double total = 0.0;
        const uint32_t v = A[s].vertex;
        const Vec pv = vertexAt(g, v);
        forEachFaceAround(g, v, [&](uint32_t f, uint32_t k) {
            const uint32_t* c = g.faceVertices + 3 * uint64_t(f);
            total += angleBetween(minus(vertexAt(g, c[(k + 1) % 3]), pv), minus(vertexAt(g, c[(k + 2) % 3]), pv));
            if (g.faceTwin[3 * f + k] == kNone) closed = false;  // the fan ends at a boundary
        });
        constexpr double kPi = 3.14159265358979323846;
        if (closed && total - (kPi + bend) < kPi - kWorthAnotherPass) bendable = true;
    }

    // Emit: the start, then per straight stretch its portal crossings and its far corner.
    length = 0.0;
    float last[3] = {raw[0].position[0], raw[0].position[1], raw[0].position[2]};
    uint32_t lastVertex = kNone;
    auto emitted = [&](const float* position) {
        const float dx = position[0] - last[0], dy = position[1] - last[1], dz = position[2] - last[2];
        length += __builtin_sqrt(double(dx) * dx + double(dy) * dy + double(dz) * dz);
        last[0] = position[0], last[1] = position[1], last[2] = position[2];
    };
    out.put(raw[0].point.face, raw[0].point.bary, raw[0].position);
    for (uint64_t s = 0; s + 1 < apexes; ++s) {
        const Apex& a = A[s];
        const Apex& b = A[s + 1];
        for (uint64_t i = uint64_t(a.portal) + 1; i < b.portal; ++i) {
            const Portal& p = P[i - 1];
            const bool touches = (a.vertex != kNone && (p.leftVertex == a.vertex || p.rightVertex == a.vertex)) ||
                                 (b.vertex != kNone && (p.leftVertex == b.vertex || p.rightVertex == b.vertex));
            if (touches) continue;
            // Where segment a -> b meets the portal right -> left.
            const double dx = b.at[0] - a.at[0], dy = b.at[1] - a.at[1];
            const double ex = p.left[0] - p.right[0], ey = p.left[1] - p.right[1];
            const double den = dx * ey - dy * ex;
            double t = den != 0.0 ? (dx * (a.at[1] - p.right[1]) - dy * (a.at[0] - p.right[0])) / den : 0.5;
            t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
            out.edgePoint(g, p.halfedge / 3, p.halfedge % 3, float(t));
            lastVertex = kNone;
            const float* pa = g.positions + 3 * uint64_t(p.rightVertex);
            const float* pb = g.positions + 3 * uint64_t(p.leftVertex);
            float x[3];
            for (int k = 0; k < 3; ++k) x[k] = pa[k] + float(t) * (pb[k] - pa[k]);
            emitted(x);
        }
        if (b.vertex != kNone) {
            if (b.vertex == lastVertex) continue;
            out.vertex(g, b.vertex);
            lastVertex = b.vertex;
            emitted(g.positions + 3 * uint64_t(b.vertex));
        }
    }
    const vg_path_point& e = raw[count - 1];
    out.put(e.point.face, e.point.bary, e.position);
    emitted(e.position);
    return true;
}

}  // namespace vg
