// The inner loops of the one-to-all query: rows of a second-layer patch matrix (packed
// 12-bit entries, vg_graph.h) lowering arrays of distances, and the unfolded crossings of
// a patch's border edges. Each kernel has a portable version and, on x86-64, an AVX2
// version picked at run time (vg_graph::avx2, set by vg_open from the CPU). Both give the
// same bits: a value is always base + q * scale with the product rounded before the sum
// (no fused multiply-add), a minimum is the same in any order, and ties go to the first
// row either way.
#pragma once

#include <stdint.h>

#include "vg_graph.h"

namespace vg {

// The caller's best, from and entries arrays have this many entries past the n the
// kernel is given, which the kernels may overwrite: the vector version reads and writes
// whole vectors.
constexpr uint32_t kRowSlack = 16;

// Lines of memory asked for a share at a time while other work runs. A whole block (~100-200
// lines) asked for at once holds more misses than a core keeps in flight: the prefetches
// themselves stall, and the lines arrive no sooner (igea's field on a family-25 EPYC:
// 1.16-1.19x on one thread with the block asked for a share per row, BENCHMARKS.md).
struct PrefetchDrip {
    uintptr_t next, end;  // the next line to ask for, and the end of the range
    void set(const void* begin, const void* stop) {
        next = uintptr_t(begin) & ~uintptr_t(63);
        end = uintptr_t(stop);
    }
    void clear() { next = end = 0; }
    uint32_t lines() const { return next < end ? uint32_t((end - next + 63) >> 6) : 0u; }
    // Lines to ask for at each of `parts` steps so that all are asked for by the last.
    uint32_t share(uint32_t parts) const { return parts > 0 ? (lines() + parts - 1) / parts : 0u; }
    void issue(uint32_t count) {
        for (; count > 0 && next < end; --count, next += 64) __builtin_prefetch(reinterpret_cast<const void*>(next));
    }
};

// Lowers best[0..n) from `count` rows of patch matrix entries: row r starts at packed
// index rows[r] and at distance bases[r]; best[j] = min(best[j], bases[r] + entry) over
// the entries with a path, and from[j] = tags[r] (r when tags is null) for the first row
// that gives the minimum. When `entries` is not null, row r's entries (entry * scale,
// +inf for no path) are kept at entries + r * stride as well. With `avx2` and g.avx512,
// sixteen entries at a time (the same bits). With `drip`, its lines are asked for a share
// per row, all of them by the last row.
void lowerFromRows(bool avx2, const vg_graph& g, float scale, const uint64_t* rows, const float* bases,
                   const uint32_t* tags, uint32_t count, uint32_t n, float* best, uint32_t* from, float* entries,
                   uint32_t stride, PrefetchDrip* drip = nullptr);

// Floats between kept rows of n entries: whole vectors.
inline uint32_t entriesStride(uint32_t n) { return (n + 7) & ~7u; }

// n entries from packed index `row` the same way (entry * scale, +inf for no path), into
// out; writes nothing at or past entriesStride(n), so that rows entriesStride(n) apart
// may be decoded in any order.
void decodeRow(bool avx2, const vg_graph& g, float scale, uint64_t row, uint32_t n, float* out);

// A border edge (u, w) of the patch being filled, from a vertex's best node u to a
// neighbour node w reached from the same source, unfolded once for the whole patch: w's
// distance b from the source, the edge length l with l * l and 0.5 / l (as crossing() in
// vg_graph.h computes them), and the source point unfolded across it.
struct CrossingEdge {
    uint32_t row;  // where w's decoded interior row starts in the caller's row buffer
    float b, length, lengthSquared, halfInverse;
    UnfoldedPoint source;
};

// For the interior slots j in `members`, whose best node u is at distance a from the
// source (c: u's decoded interior row), lowers best[j] to the crossing of each of u's
// edges: crossing() of vg_graph.h with the same operations in the same order (so the
// same bits), e = rows[edge.row + j]; +inf (no change) where the segment misses the edge,
// does not unfold or e is +inf.
void lowerByCrossings(bool avx2, const float* rows, float a, const float* c, const CrossingEdge* edges,
                      uint32_t edgeCount, const uint32_t* members, uint32_t memberCount, float* best);

// The one-to-all search's scan of a patch's n node slots (labels dist, last relaxed labels
// sent): best = dist and from = kNone for every slot, and the slots whose label is below
// the one sent (sent takes it) listed in order in sources, with their labels in labels;
// their number. With `avx512` (x86-64), sixteen slots at a time without a branch per
// slot. best, from, sources and labels have kRowSlack entries past n (the vector version
// writes whole vectors).
uint32_t scanSources(bool avx512, const float* dist, float* sent, float* best, uint32_t* from, uint32_t n,
                     uint32_t* sources, float* labels);

// The slots j < n with from[j] != kNone, in order, into out (kRowSlack entries past n);
// their number. With `avx512`, sixteen at a time.
uint32_t changedSlots(bool avx512, const uint32_t* from, uint32_t n, uint32_t* out);

// True when this CPU and operating system run AVX2 code (x86-64 only).
bool cpuHasAvx2();
// True when they run AVX-512 (foundation) code as well.
bool cpuHasAvx512();

}  // namespace vg
