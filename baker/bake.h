// The whole bake (thesis Algorithm 1): partition, patch geodesics, first-layer overlay,
// pruning, and the blob. One call from a prepared mesh to the bytes of a .vgeo file.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "graph_prune.h"
#include "mesh.h"

namespace vorogeo {

struct BakeOptions {
    uint32_t n1 = 0;              // first-layer patches; 0 = automatic (about 3,000 vertices each)
    uint32_t n2 = 0;              // second-layer patches per first-layer patch; 0 = automatic (about 100 vertices each)
    double delta = -1;            // pruning threshold, fraction of the bounding-box diagonal; < 0 = automatic
    uint64_t seed = 1;
    uint32_t marginRings = 1;     // rings of faces around a patch for its geodesics
    bool exactFirstLayer = false; // first-layer distances by exact runs (thesis) instead of composed
    bool compress = true;         // zstd frames, else the flatbuffer as is (zero-copy)
    bool compact = false;         // with compress: prediction-coded distances, ~2x smaller, ~1.6x the open time
    // zstd level, 1-22; 0 = automatic (automaticLevel below).
    int compressionLevel = 0;
    uint32_t landmarks = 12;      // A* landmarks stored in the blob (0: straight-line bound only)
    bool hubLabels = false;       // hub labels for microsecond point-to-point queries (hub_labels.h)
    // With compact and hubLabels: the inner rows left out, vg_open computes them
    // (schema/vorogeo_inner_rows.h): igea's blob 41 bytes per vertex smaller, its open ~0.4 s longer.
    bool innerRowsAtOpen = false;
    uint64_t maxMemoryBytes = 0;  // refuse up front / stop when a bake needs more (0: no limit)
};

// The automatic zstd level for a payload of `payloadBytes`: 9 for plain quanta, which
// hardly compress anyway. For coded blobs the optimal-parse levels pay, at a time that
// grows with the payload: 19 up to 32 MiB (a few seconds); 17 up to 1 GiB (igea's
// labelled 109 MB: 1.3% more bytes than 19 in 0.55x its time, 36.5 -> 20.2 s on one
// thread); 11 above (16 and up cost 5-11x the time of 11 for 8-12% fewer bytes, and igea
// x16's 4.3 GB took 5.4 of its bake's 20.4 minutes at 17). BENCHMARKS.md has the figures.
int automaticLevel(bool coded, uint64_t payloadBytes);

// The automatic pruning threshold (fraction of the bounding-box diagonal).
constexpr double kDefaultDelta = 0.0;

struct BakeStage {
    std::string name;
    double seconds = 0;
};

struct BakeReport {
    uint32_t vertices = 0, faces = 0;
    double delta = 0, deltaAbsolute = 0, deltaSecond = 0;
    double bboxDiagonal = 0;
    std::vector<BakeStage> stages;
    size_t firstPatches = 0, secondPatches = 0;
    uint64_t firstBorder = 0, firstInterior = 0;   // Bv / Iv summed over first-layer patches
    uint64_t secondBorder = 0, secondInterior = 0; // the same over second-layer patches
    PruneStats firstPrune, secondPrune;
    uint64_t sourceRuns = 0;
    double quantisationMaxAbs = 0;  // largest absolute error added by 12-bit distances
    size_t flatbufferBytes = 0, blobBytes = 0;
    bool compressed = true;
    bool compact = false;           // distances prediction-coded (format 5, flag bit 1)
    bool innerRowsAtOpen = false;   // inner rows left to the readers (flag bit 2)
    uint64_t hubs = 0, hubTreeNodes = 0, hubLabelEntries = 0, hubInnerEntries = 0;  // bake --hub-labels
};

using BakeProgress = std::function<void(const char* stage, double fraction)>;

// Bakes a prepared mesh (connectivity built). Throws std::invalid_argument for bad options
// (naming the option and the allowed range), BakeLimitError (bake_limits.h) when the blob
// or the memory would exceed a limit (checked before the work starts, and memory again at
// every progress step), std::runtime_error if the mesh cannot be baked.
std::vector<uint8_t> bakeMesh(const Mesh& mesh, const BakeOptions& options, BakeReport& report,
                              const BakeProgress& progress = BakeProgress());

}  // namespace vorogeo
