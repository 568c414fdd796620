// Transparent huge pages for the caller's large buffers. A query reads a few thousand
// scattered cache lines of a graph that spans tens or hundreds of megabytes; with 4 KB
// pages nearly each of them also misses the TLB, and under virtualisation every such miss
// is a two-level page walk. Backing the graph and the workspace with 2 MB pages removes
// most of that (BENCHMARKS.md: "Huge pages"). Internal to the runtime.
#pragma once

#include <stddef.h>

namespace vg {

// Asks the kernel (Linux: madvise MADV_HUGEPAGE) to back the whole 2 MB pages inside
// [memory, memory + size) with huge pages. A hint only: nothing about the memory's
// contents, ownership or lifetime changes, and where the system has no such thing, or
// refuses, nothing happens. It takes effect for pages not yet touched.
void adviseHugePages(void* memory, size_t size);

}  // namespace vg
