// Exact local paths between two surface points whose faces share a vertex v: the fan of
// faces around v unfolds into the plane, and a straight segment that stays inside the
// unfolded fan, going either way around v, is a path on the surface, as is the path
// through v itself. The patch interpolation (vg_point.h) assumes a field seen from one
// side of v, which fails exactly here: for two points a face or two apart it can be off
// by tens of percent, where these candidates are exact. Every candidate is the length of
// a real path, so taking the minimum with other estimates is always safe.
// Internal to the runtime.
#pragma once

#include "vg_point.h"

namespace vg {

// Corner index (0..2) of vertex v in face f, or 3.
inline uint32_t cornerOf(const vg_graph& g, uint32_t f, uint32_t v) {
    const uint32_t* c = g.faceVertices + 3 * uint64_t(f);
    return c[0] == v ? 0 : c[1] == v ? 1 : c[2] == v ? 2 : 3;
}

// Angle at vertex `at` between the directions to points a and b.
inline float angleAt(const float* at, const float* a, const float* b) {
    const float ux = a[0] - at[0], uy = a[1] - at[1], uz = a[2] - at[2];
    const float vx = b[0] - at[0], vy = b[1] - at[1], vz = b[2] - at[2];
    const float cx = uy * vz - uz * vy, cy = uz * vx - ux * vz, cz = ux * vy - uy * vx;
    return __builtin_atan2f(__builtin_sqrtf(cx * cx + cy * cy + cz * cz), ux * vx + uy * vy + uz * vz);
}

// Where a fan segment crosses one edge (v, far) of the fan: `face` is the face it leaves,
// `along` the distance from v.
struct FanCrossing {
    uint32_t face, far;
    float along;
};
constexpr uint32_t kMaxFan = 64;

// Walks the fan around v from face fs to face ft, one way round (forward: across the edge
// entering v in each face; else across the edge leaving v), and returns the straight
// segment from s to t in the unfolded fan, or +inf when the walk hits a boundary, the
// opening angle reaches pi or the segment leaves the fan. With `crossings` (kMaxFan
// entries) it also says where the segment crosses each edge, in order.
inline float fanSegment(const vg_graph& g, uint32_t v, const Endpoint& s, const Endpoint& t, bool forward,
                        FanCrossing* crossings = nullptr, uint32_t* crossingCount = nullptr) {
    const float inf = __builtin_inff();
    const float* pv = g.positions + 3 * uint64_t(v);
    // Edge rays crossed on the way, as (angle from s, length); a fan has few faces.
    float rayAngle[kMaxFan], rayLength[kMaxFan];
    uint32_t rayFace[kMaxFan], rayFar[kMaxFan];
    uint32_t rays = 0;
    uint32_t f = s.face;
    // In face f, `out` is the corner after v and `in` the corner before it; walking forward
    // leaves f across the edge (in, v), backward across (v, out).
    auto neighbours = [&](uint32_t face, uint32_t& out, uint32_t& in, uint32_t& h) {
        const uint32_t k = cornerOf(g, face, v);
        h = 3 * face + k;  // v -> out
        out = headOf(g, h);
        in = tailOf(g, prevHalfedge(h));
    };
    uint32_t out, in, h;
    neighbours(f, out, in, h);
    const float* far = g.positions + 3 * uint64_t(forward ? in : out);
    float angle = angleAt(pv, s.position, far);  // from s to the exit edge
    for (uint32_t step = 0; f != t.face; ++step) {
        if (step >= kMaxFan || !(angle < 3.14159265f)) return inf;
        rayAngle[rays] = angle;
        rayFace[rays] = f;
        rayFar[rays] = forward ? in : out;
        rayLength[rays++] = distance3(pv, far);
        const uint32_t across = forward ? g.faceTwin[prevHalfedge(h)] : g.faceTwin[h];
        if (across == kNone) return inf;
        f = across / 3;
        neighbours(f, out, in, h);
        const float* enter = far;
        far = g.positions + 3 * uint64_t(forward ? in : out);
        if (f == t.face) {
            angle += angleAt(pv, enter, t.position);
        } else {
            angle += angleAt(pv, enter, far);
        }
    }
    if (rays == 0 || !(angle < 3.14159265f)) return inf;  // same face: not a fan path
    const float rs = distance3(pv, s.position), rt = distance3(pv, t.position);
    // s at (rs, 0), t at rt (cos angle, sin angle); each crossed edge ray must meet the
    // segment within the edge.
    const float sx = rs, sy = 0.0f, tx = rt * __builtin_cosf(angle), ty = rt * __builtin_sinf(angle);
    for (uint32_t r = 0; r < rays; ++r) {
        const float ux = __builtin_cosf(rayAngle[r]), uy = __builtin_sinf(rayAngle[r]);
        // Point on the segment s + l (t - s) on the ray: cross(u, s + l (t - s)) = 0.
        const float cs = ux * sy - uy * sx, ct = ux * ty - uy * tx;
        if (!(cs - ct != 0.0f)) return inf;
        const float l = cs / (cs - ct);
        const float px = sx + l * (tx - sx), py = sy + l * (ty - sy);
        const float along = px * ux + py * uy;
        if (along > rayLength[r]) return inf;
        if (crossings) crossings[r] = FanCrossing{rayFace[r], rayFar[r], along};
    }
    if (crossingCount) *crossingCount = rays;
    const float dx = tx - sx, dy = ty - sy;
    return __builtin_sqrtf(dx * dx + dy * dy);
}

// The shortest local path between two surface points (not vertices) whose faces share a
// vertex: through the shared vertex, or straight across its fan either way; +inf when the
// faces share none. With the out parameters it says which: the vertex, and way 0 / 1 for
// the fan forward / backward, 2 through the vertex.
inline float localPath(const vg_graph& g, const Endpoint& s, const Endpoint& t, uint32_t* outVertex = nullptr,
                       uint32_t* outWay = nullptr) {
    float best = __builtin_inff();
    if (s.isVertex() || t.isVertex()) return best;
    for (int i = 0; i < 3; ++i) {
        const uint32_t v = s.corner[i];
        const uint32_t j = cornerOf(g, t.face, v);
        if (j == 3) continue;
        const float through = s.reach[i] + t.reach[j];
        auto offer = [&](float d, uint32_t way) {
            if (!(d < best)) return;
            best = d;
            if (outVertex) *outVertex = v;
            if (outWay) *outWay = way;
        };
        offer(through, 2);
        for (uint32_t way = 0; way < 2; ++way) offer(fanSegment(g, v, s, t, way == 0), way);
    }
    return best;
}

}  // namespace vg
