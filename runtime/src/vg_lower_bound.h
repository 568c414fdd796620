// Lower bounds on the distance between a node and a query endpoint, for the A* search:
// the straight line, and the landmark bounds |d(L, v) - d(L, x)| (stored node distances
// are rounded down to a step of the landmark's scale, hence the two-step margin).
#pragma once

#include "vg_point.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace vg {

// out[k] = min(out[k], q[k] * scale[k] + offset) for the k < K whose q[k] is not
// kLandmarkUnreachable: a node's landmark steps offered to an endpoint. Four lanes at a
// time with SSE2 (every x86-64), the same product and sum per lane as the scalar loop, so
// the same bits.
inline void lowerLandmarkDistances(const uint16_t* q, const float* scale, uint32_t K, float offset, float* out) {
    uint32_t k = 0;
#if defined(__SSE2__)
    const __m128 add = _mm_set1_ps(offset);
    const __m128i none = _mm_set1_epi32(kLandmarkUnreachable), zero = _mm_setzero_si128();
    for (; k + 4 <= K; k += 4) {
        const __m128i steps = _mm_unpacklo_epi16(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(q + k)), zero);
        const __m128 d = _mm_add_ps(_mm_mul_ps(_mm_cvtepi32_ps(steps), _mm_loadu_ps(scale + k)), add);
        const __m128 skip = _mm_castsi128_ps(_mm_cmpeq_epi32(steps, none));
        const __m128 old = _mm_loadu_ps(out + k);
        // d where it is a path and lower, else the old value.
        const __m128 take = _mm_andnot_ps(skip, _mm_cmplt_ps(d, old));
        _mm_storeu_ps(out + k, _mm_or_ps(_mm_and_ps(take, d), _mm_andnot_ps(take, old)));
    }
#endif
    for (; k < K; ++k) {
        if (q[k] == kLandmarkUnreachable) continue;
        const float d = float(q[k]) * scale[k] + offset;
        if (d < out[k]) out[k] = d;
    }
}

// d(L, x) for every landmark: an active node's own values, any other vertex's best over
// the active nodes of its patches (+inf where no landmark path exists).
inline void landmarkDistances(const vg_graph& g, uint32_t x, float* out) {
    const uint32_t K = g.landmarkCount;
    for (uint32_t k = 0; k < K; ++k) out[k] = __builtin_inff();
    auto take = [&](uint32_t node, float offset) {
        lowerLandmarkDistances(g.nodeLandmarks + uint64_t(node) * K, g.landmarkScale, K, offset, out);
    };
    const uint32_t node = vertexNode(g, x);
    if (node != kNone && nodeActive(g, node)) {
        take(node, 0.0f);
        return;
    }
    forEachPatchOf(g, x, [&](uint32_t patch, uint32_t slot) {
        const Patch& p = g.second[patch];
        for (uint32_t j = 0; j < p.nodeCount; ++j) {
            const uint32_t n = g.slots[p.slotBegin + j];
            if (!nodeActive(g, n)) continue;
            const float e = entry(p, g.secondDistances, slot, j);
            if (e != __builtin_inff()) take(n, e);
        }
    });
}

// The same for any endpoint: a surface point through its patch's active nodes.
inline void landmarkDistances(const vg_graph& g, const Endpoint& e, float* out) {
    if (e.isVertex()) {
        landmarkDistances(g, e.vertex, out);
        return;
    }
    const uint32_t K = g.landmarkCount;
    for (uint32_t k = 0; k < K; ++k) out[k] = __builtin_inff();
    const Patch& p = g.second[e.patch];
    for (uint32_t j = 0; j < p.nodeCount; ++j) {
        const uint32_t n = g.slots[p.slotBegin + j];
        if (!nodeActive(g, n)) continue;
        const float offset = pointToSlot(g, e, j);
        if (offset == __builtin_inff()) continue;
        lowerLandmarkDistances(g.nodeLandmarks + uint64_t(n) * K, g.landmarkScale, K, offset, out);
    }
}

// A lower bound of d(a, b) from their landmark distances (0 without landmarks).
inline float landmarkBound(const vg_graph& g, const float* la, const float* lb) {
    float best = 0.0f;
    for (uint32_t k = 0; k < g.landmarkCount; ++k) {
        if (la[k] == __builtin_inff() || lb[k] == __builtin_inff()) continue;
        const float d = __builtin_fabsf(la[k] - lb[k]) - 2.0f * g.landmarkScale[k];
        if (d > best) best = d;
    }
    return best;
}

// The straight-line distance between a node's record (position, then its landmark
// distances, see vg_workspace.cpp) and position x.
inline float recordDistance(const float* record, const float* xPosition) {
    const float dx = record[0] - xPosition[0], dy = record[1] - xPosition[1], dz = record[2] - xPosition[2];
    return __builtin_sqrtf(dx * dx + dy * dy + dz * dz);
}

// The best of `straight` (a lower bound of d(node, x)) and the landmark bounds from the
// node's record and x's landmark distances (each within `slack` beyond the tables' own
// rounding, which two landmark steps cover).
inline float withLandmarks(const vg_graph& g, const float* record, const float* xLandmarks, float straight,
                           float slack = 0.0f) {
    float best = straight;
    uint32_t k = 0;
#if defined(__SSE2__)
    // Four landmarks at a time, each lane keeping its own best; the largest of the lanes
    // is then the scalar loop's answer (a maximum does not depend on the order).
    const __m128 sign = _mm_set1_ps(-0.0f), inf = _mm_set1_ps(__builtin_inff()), extra = _mm_set1_ps(slack);
    __m128 lanes = _mm_set1_ps(straight);
    for (; k + 4 <= g.landmarkCount; k += 4) {
        const __m128 diff = _mm_sub_ps(_mm_loadu_ps(record + 3 + k), _mm_loadu_ps(xLandmarks + k));
        const __m128 margin = _mm_add_ps(_mm_mul_ps(_mm_set1_ps(2.0f), _mm_loadu_ps(g.landmarkScale + k)), extra);
        const __m128 d = _mm_sub_ps(_mm_andnot_ps(sign, diff), margin);
        const __m128 take = _mm_and_ps(_mm_cmpgt_ps(d, lanes), _mm_cmpneq_ps(d, inf));
        lanes = _mm_or_ps(_mm_and_ps(take, d), _mm_andnot_ps(take, lanes));
    }
    alignas(16) float lane[4];
    _mm_store_ps(lane, lanes);
    for (float x : lane) best = x > best ? x : best;
#endif
    for (; k < g.landmarkCount; ++k) {
        // +inf on either side (no landmark path) gives inf - inf or an infinite
        // difference; neither passes the comparison below as a finite bound.
        const float d = __builtin_fabsf(record[3 + k] - xLandmarks[k]) - (2.0f * g.landmarkScale[k] + slack);
        if (d > best && d != __builtin_inff()) best = d;
    }
    return best;
}

// A lower bound of d(node, x) from the node's record and x's position and landmark distances.
inline float nodeBound(const vg_graph& g, const float* record, const float* xPosition, const float* xLandmarks) {
    return withLandmarks(g, record, xLandmarks, recordDistance(record, xPosition));
}

}  // namespace vg
