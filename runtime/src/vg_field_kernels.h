// The inner loops of the one-to-all query: rows of a second-layer patch matrix (packed
// 12-bit entries, vg_graph.h) against arrays of distances, and the unfolded crossings of
// a patch's border edges. Each kernel has a portable
// version and, on x86-64, an AVX2 version picked at run time (vg_graph::avx2, set by
// vg_open from the CPU). Both give the same bits: a value is always base + q * scale with
// the product rounded before the sum (no fused multiply-add), a minimum is the same in
// any order, and ties go to the first row or entry either way.
#pragma once

#include <stdint.h>

#include "vg_graph.h"

namespace vg {

// The caller's arrays (best, from, src) have this many entries past the n the kernel is
// given: the vector versions read and write whole vectors there, leaving them as they were.
constexpr uint32_t kRowSlack = 16;

// Patch p's node x node block for the sources src[a] < +inf (the last at slot `last`;
// +inf elsewhere): for every node b, best[b] = min(best[b], src[a] + d(a, b)) over the
// sources a != b, and from[b] = the first such a in slot order where that lowers it.
// `scratch` holds last + 1 floats.
void relaxNodeBlock(bool avx2, const vg_graph& g, const Patch& p, uint32_t last, const float* src, float* scratch,
                    float* best, uint32_t* from);

// The same for one source a at distance du: its column above the diagonal, then its row.
void relaxNodeSource(bool avx2, const vg_graph& g, const Patch& p, uint32_t a, float du, float* best, uint32_t* from);

// Patch p's interior slots from `count` rows (rows[r]: packed index of row r's first
// interior entry, bases[r] its start distance): best[j] = min(best[j], bases[r] + entry)
// and from[j] = the first r that lowers it. Row r's entries (entry * scale, +inf for no
// path) go to entries + r * stride as well, for the crossings (stride >= the interior
// count, and kRowSlack entries of slack after the last row).
void lowerInteriorFromRows(bool avx2, const vg_graph& g, const Patch& p, const uint64_t* rows, const float* bases,
                           uint32_t count, float* best, uint32_t* from, float* entries, uint32_t stride);

// Floats between decoded rows of `interior` entries: whole vectors.
inline uint32_t interiorStride(uint32_t interior) { return (interior + 7) & ~7u; }

// One row's interior entries the same way, into out (with kRowSlack entries of slack).
void decodeInteriorRow(bool avx2, const vg_graph& g, const Patch& p, uint64_t row, float* out);

// Crossings of border edges next to the vertices' best nodes, gathered per patch (arrays
// of kCrossingChunk entries): per crossing, the distances a = d(s, u), b = d(s, w),
// c = d(t, u), e = d(t, w) (+inf for no path), the edge length l with l * l and 0.5 / l
// (as crossing() in vg_graph.h computes them), the source point unfolded once per edge,
// and t's interior slot.
constexpr uint32_t kCrossingChunk = 256;  // eleven arrays of 1 KB: all in the L1 cache, in different sets
struct CrossingBatch {
    float *a, *b, *c, *e, *l, *ll, *half, *sx, *sy, *length;
    uint32_t* vertex;
    uint32_t count;
};

// A border edge (u, w) of the patch being filled, from a vertex's best node u to a
// neighbour node w reached from the same source, unfolded once for the whole patch.
struct CrossingEdge {
    const float* entries;  // w's decoded row over the interior slots
    float b, length;       // d(s, w) and |uw|
    UnfoldedPoint source;
};

// length[i] for the whole batch: crossing() of vg_graph.h, the same operations in the same
// order (so the same bits), written without branches so that it vectorises; +inf where the
// segment misses the edge or does not unfold.
void crossBatch(bool avx2, CrossingBatch& batch);

// True when this CPU and operating system run AVX2 code (x86-64 only).
bool cpuHasAvx2();

}  // namespace vg
