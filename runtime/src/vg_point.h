// Query endpoints: a mesh vertex, or a surface point (face + barycentric weights).
//
// A point inside a face takes its distances from the rows of the face's three corners in
// the face's second-layer patch. Within one face, a geodesic field from a source seen
// through an edge is d(x) = |x - s| for a virtual source s in the face's plane, so d^2 - |x|^2
// is linear over the face: interpolating it from the corners is exact for such a field,
// and it reduces, with barycentric weights w and squared edge lengths e, to
//     d(p)^2 = sum w_i d_i^2 - (w0 w1 e01 + w1 w2 e12 + w2 w0 e20).
// Where the field is not of that kind (a pseudo-source inside the face's view), the
// result is kept within the triangle inequality through the corners:
//     max_i (d_i - r_i) <= d(p) <= min_i (d_i + r_i),  r_i = |p - corner_i|.
// Internal to the runtime.
#pragma once

#include "vg_graph.h"

namespace vg {

// Barycentric weights may miss the face by this much (negative weights, sum != 1); within
// it they are clamped and renormalised, beyond it the point is rejected.
constexpr float kBaryTolerance = 1e-4f;
// A weight this close to 1 makes the point its corner vertex.
constexpr float kVertexSnap = 1e-6f;

struct Endpoint {
    uint32_t vertex;     // a mesh vertex, or kNone for a point inside a face or on an edge
    uint32_t face;       // point: its face (vertex: kNone)
    uint32_t patch;      // point: the face's second-layer patch
    uint32_t corner[3];  // point: the face's vertices
    uint32_t slot[3];    // point: their slots in `patch`
    float weight[3];     // point: barycentric weights, >= 0, summing to 1
    float edge2[3];      // point: squared lengths of edges (0,1), (1,2), (2,0)
    float reach[3];      // point: straight-line distance to each corner
    float position[3];

    bool isVertex() const { return vertex != kNone; }
};

inline void positionOf(const vg_graph& g, uint32_t v, float* out) {
    const float* p = g.positions + 3 * uint64_t(v);
    out[0] = p[0];
    out[1] = p[1];
    out[2] = p[2];
}

inline float distance3(const float* a, const float* b) {
    const float dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return __builtin_sqrtf(dx * dx + dy * dy + dz * dz);
}

inline Endpoint vertexEndpoint(const vg_graph& g, uint32_t v) {
    Endpoint e{};
    e.vertex = v;
    e.face = kNone;
    e.patch = g.vertexPatch[v];
    positionOf(g, v, e.position);
    return e;
}

// Checks and resolves a caller's point: VG_ERR_INVALID_POINT for a face out of range or
// weights that are NaN, negative or off a sum of 1 beyond kBaryTolerance.
inline vg_status resolvePoint(const vg_graph& g, const vg_point& p, Endpoint& e) {
    if (p.face >= g.faceCount) return VG_ERR_INVALID_POINT;
    float w[3], sum = 0.0f;
    for (int k = 0; k < 3; ++k) {
        w[k] = p.bary[k];
        if (!(w[k] >= -kBaryTolerance && w[k] <= 1.0f + kBaryTolerance)) return VG_ERR_INVALID_POINT;  // NaN too
        if (w[k] < 0.0f) w[k] = 0.0f;
        sum += w[k];
    }
    if (!(__builtin_fabsf(sum - 1.0f) <= kBaryTolerance) || !(sum > 0.0f)) return VG_ERR_INVALID_POINT;
    const uint32_t* c = g.faceVertices + 3 * uint64_t(p.face);
    for (int k = 0; k < 3; ++k) {
        w[k] /= sum;
        if (w[k] >= 1.0f - kVertexSnap) {
            e = vertexEndpoint(g, c[k]);
            return VG_OK;
        }
    }
    e = Endpoint{};
    e.vertex = kNone;
    e.face = p.face;
    e.patch = g.facePatch[p.face];
    float x[3][3];
    for (int k = 0; k < 3; ++k) {
        e.corner[k] = c[k];
        e.slot[k] = slotIn(g, c[k], e.patch);  // validated: never kNone
        e.weight[k] = w[k];
        positionOf(g, c[k], x[k]);
    }
    for (int i = 0; i < 3; ++i) e.position[i] = w[0] * x[0][i] + w[1] * x[1][i] + w[2] * x[2][i];
    for (int k = 0; k < 3; ++k) {
        const float d = distance3(x[k], x[(k + 1) % 3]);
        e.edge2[k] = d * d;
        e.reach[k] = distance3(e.position, x[k]);
    }
    return VG_OK;
}

// d(p) from the corner distances d0..d2 (see the top of this file); +inf when no corner
// is reachable.
inline float interpolate(const Endpoint& e, float d0, float d1, float d2) {
    const float d[3] = {d0, d1, d2};
    float lo = 0.0f, hi = __builtin_inff();
    for (int k = 0; k < 3; ++k) {
        if (d[k] == __builtin_inff()) continue;
        if (d[k] + e.reach[k] < hi) hi = d[k] + e.reach[k];
        if (d[k] - e.reach[k] > lo) lo = d[k] - e.reach[k];
    }
    if (hi == __builtin_inff()) return hi;
    if (d0 == __builtin_inff() || d1 == __builtin_inff() || d2 == __builtin_inff()) return hi;
    const float* w = e.weight;
    const float sq = w[0] * d0 * d0 + w[1] * d1 * d1 + w[2] * d2 * d2 -
                     (w[0] * w[1] * e.edge2[0] + w[1] * w[2] * e.edge2[1] + w[2] * w[0] * e.edge2[2]);
    const float r = sq > 0.0f ? __builtin_sqrtf(sq) : 0.0f;
    return r < lo ? lo : (r > hi ? hi : r);
}

// Distance from point endpoint e to slot j of its patch.
inline float pointToSlot(const vg_graph& g, const Endpoint& e, uint32_t j) {
    const Patch& p = g.second[e.patch];
    return interpolate(e, entry(p, g.secondDistances, e.slot[0], j), entry(p, g.secondDistances, e.slot[1], j),
                       entry(p, g.secondDistances, e.slot[2], j));
}

// Calls f(patch, dist) for every second-layer patch holding endpoint e, where dist(j) is
// the distance from e to slot j of that patch: a vertex's patches with its stored row, a
// point's one patch with interpolated values. For a vertex, f also gets its slot (kNone
// for a point).
template <class F>
inline void forEachEndpointPatch(const vg_graph& g, const Endpoint& e, F&& f) {
    if (e.isVertex()) {
        forEachPatchOf(g, e.vertex, [&](uint32_t patch, uint32_t slot) {
            const Patch& p = g.second[patch];
            f(patch, slot, [&](uint32_t j) { return entry(p, g.secondDistances, slot, j); });
        });
        return;
    }
    f(e.patch, kNone, [&](uint32_t j) { return pointToSlot(g, e, j); });
}

// Distance to endpoint t, inside patch `patch` that holds t (t's slot there for a
// vertex, `slotT`), given distances `from(j)` to the slots of that patch.
template <class Dist>
inline float toEndpointInPatch(const Endpoint& t, uint32_t slotT, Dist&& from) {
    if (t.isVertex()) return from(slotT);
    return interpolate(t, from(t.slot[0]), from(t.slot[1]), from(t.slot[2]));
}

// The connected component of an endpoint.
inline uint32_t endpointComponent(const vg_graph& g, const Endpoint& e) {
    return vertexComponent(g, e.isVertex() ? e.vertex : e.corner[0]);
}

}  // namespace vg
