#include "bake_limits.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vorogeo {

namespace {

// Patch sizes the partition will aim at (partition.h: automatic n1 and n2).
void patchSizes(uint64_t vertices, const BakeOptions& o, double& firstSize, double& secondSize) {
    const double V = double(std::max<uint64_t>(1, vertices));
    const double n1 = o.n1 ? double(o.n1) : std::max(1.0, std::round(V / 3000.0));
    firstSize = V / n1;
    const double n2 = o.n2 ? double(o.n2) : std::max(1.0, std::round(firstSize / 100.0));
    secondSize = std::max(1.0, firstSize / n2);
}

}  // namespace

std::string formatBytes(uint64_t bytes) {
    char buf[64];
    const double b = double(bytes);
    if (b >= 1024.0 * 1024 * 1024) std::snprintf(buf, sizeof buf, "%.1f GiB", b / (1024.0 * 1024 * 1024));
    else if (b >= 1024.0 * 1024) std::snprintf(buf, sizeof buf, "%.0f MiB", b / (1024.0 * 1024));
    else std::snprintf(buf, sizeof buf, "%.0f KiB", b / 1024.0);
    return buf;
}

BakeEstimate estimateBake(uint64_t vertices, const BakeOptions& o) {
    double s1 = 0, s2 = 0;
    patchSizes(vertices, o, s1, s2);
    const double V = double(vertices);
    // Fitted to bakes of igea and of armadillo-50k with n1 and n2 varied (BENCHMARKS.md,
    // "Bake limits"), in terms of the requested patch sizes (the partition may split
    // patches further to make disks); the 15% margin makes both upper bounds on every
    // measured bake. Per vertex: mesh, partition and workspaces (fixed), second-layer
    // matrices (grow with the second-layer patch size), first-layer rows (first-layer size).
    const double exactFirst = o.exactFirstLayer ? 2.0 : 1.0;
    const double margin = 1.15;
    const double peakPerVertex = margin * (1700.0 + 4.5 * s2 + 0.12 * s1 * exactFirst);
    const double fbPerVertex = margin * (165.0 + 0.62 * s2 + 0.006 * s1);  // +30: whole node rows (format 4)
    BakeEstimate e;
    e.peakBytes = uint64_t(32.0 * 1024 * 1024 + V * peakPerVertex);
    e.flatbufferBytes = uint64_t(4096.0 + V * fbPerVertex);
    return e;
}

void checkBakeLimits(uint64_t vertices, const BakeOptions& o) {
    const BakeEstimate e = estimateBake(vertices, o);
    if (e.flatbufferBytes > kMaxFlatbufferBytes)
        throw BakeLimitError("the blob of this mesh (" + std::to_string(vertices) + " vertices) would be about " +
                             formatBytes(e.flatbufferBytes) +
                             ", over the 2 GiB limit of a flatbuffer; split the mesh into parts of at most " +
                             std::to_string(uint64_t(double(vertices) * double(kMaxFlatbufferBytes) /
                                                     double(e.flatbufferBytes) * 0.9)) +
                             " vertices and bake each");
    if (o.maxMemoryBytes && e.peakBytes > o.maxMemoryBytes)
        throw BakeLimitError("the bake of this mesh (" + std::to_string(vertices) + " vertices) needs about " +
                             formatBytes(e.peakBytes) + " of memory, over --max-memory " +
                             formatBytes(o.maxMemoryBytes) +
                             "; raise --max-memory, use smaller patches (--n1/--n2 larger) or split the mesh");
}

void checkFlatbufferSize(uint64_t bytes, uint64_t vertices) {
    if (bytes > kMaxFlatbufferBytes)
        throw BakeLimitError("the blob of this mesh (" + std::to_string(vertices) + " vertices) would be " +
                             formatBytes(bytes) +
                             ", over the 2 GiB limit of a flatbuffer; split the mesh into parts and bake each");
}

void checkHubLabelLimits(uint64_t graphBytes, const HubLabelSizes& sizes, uint64_t vertices, const BakeOptions& o,
                         uint64_t residentNow) {
    // 16-bit steps per entry, after the flatbuffer (schema/vorogeo_container.h); in it, a
    // 32-bit id per inner node: the least the labels add to it.
    const uint64_t entries = sizes.labelEntries + sizes.innerEntries;
    const uint64_t tableBytes = 2 * entries + 4 * sizes.innerNodes;
    if (graphBytes + 4 * sizes.innerNodes > kMaxFlatbufferBytes)
        throw BakeLimitError("with hub labels (" + std::to_string(sizes.innerNodes) +
                             " inner nodes) the flatbuffer of this mesh (" + std::to_string(vertices) +
                             " vertices) would be at least " + formatBytes(graphBytes + 4 * sizes.innerNodes) +
                             ", over the 2 GiB limit of a flatbuffer; bake without --hub-labels or split the mesh");
    // The stage holds each entry as a float while computing it, then as steps (the floats
    // freed as they are converted), and builds the labelled flatbuffer beside the graph's.
    const uint64_t stageBytes = 4 * entries + graphBytes + tableBytes;
    if (o.maxMemoryBytes && residentNow + stageBytes > o.maxMemoryBytes)
        throw BakeLimitError("the hub labels of this mesh (" + std::to_string(vertices) + " vertices) need about " +
                             formatBytes(stageBytes) + " more memory (" + formatBytes(residentNow) +
                             " resident), over --max-memory " + formatBytes(o.maxMemoryBytes) +
                             "; raise --max-memory, bake without --hub-labels or split the mesh");
}

uint64_t residentBytes() {
    // /proc/self/statm: size resident shared text lib data dt, in pages. Read with plain
    // system calls: this runs from progress callbacks on worker threads.
    const int fd = ::open("/proc/self/statm", O_RDONLY | O_CLOEXEC);
    if (fd < 0) return 0;
    char buf[128];
    const ssize_t n = ::read(fd, buf, sizeof buf - 1);
    ::close(fd);
    if (n <= 0) return 0;
    buf[n] = 0;
    unsigned long long size = 0, resident = 0;
    if (std::sscanf(buf, "%llu %llu", &size, &resident) != 2) return 0;
    const long page = ::sysconf(_SC_PAGESIZE);
    return resident * uint64_t(page > 0 ? page : 4096);
}

void checkMemoryDuringBake(const BakeOptions& o, const char* stage) {
    if (!o.maxMemoryBytes) return;
    const uint64_t now = residentBytes();
    if (now > o.maxMemoryBytes)
        throw BakeLimitError(std::string("the bake went over --max-memory ") + formatBytes(o.maxMemoryBytes) +
                             " during " + stage + " (" + formatBytes(now) +
                             " resident); raise --max-memory, use smaller patches (--n1/--n2 larger) or split the mesh");
}

}  // namespace vorogeo
