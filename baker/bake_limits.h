// Limits of a bake, checked before the long work starts: the memory the bake will need
// (against BakeOptions::maxMemoryBytes) and the size of the flatbuffer (flatbuffers'
// offsets are 32-bit, so a blob holds less than 2 GiB). Both are estimated from the
// vertex count and the patch sizes with models fitted to measured bakes (BENCHMARKS.md);
// the flatbuffer size is checked again, exactly, before serialising, and the memory is
// watched during the bake.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "bake.h"
#include "hub_labels.h"

namespace vorogeo {

// A bake refused or stopped because it would exceed a limit; the message names the limit
// and what to change.
class BakeLimitError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// flatbuffers::FLATBUFFERS_MAX_BUFFER_SIZE: the largest buffer 32-bit offsets address.
constexpr uint64_t kMaxFlatbufferBytes = 0x7FFFFFFFull;

struct BakeEstimate {
    uint64_t peakBytes = 0;        // resident memory at the bake's peak (conservative)
    uint64_t flatbufferBytes = 0;  // the blob's flatbuffer before compression
};

// `vertices` = vertices used by faces.
BakeEstimate estimateBake(uint64_t vertices, const BakeOptions& options);

// Throws BakeLimitError when the estimate breaks a limit.
void checkBakeLimits(uint64_t vertices, const BakeOptions& options);

// Throws BakeLimitError when a flatbuffer of `bytes` cannot be built.
void checkFlatbufferSize(uint64_t bytes, uint64_t vertices);

// Throws BakeLimitError when hub labels of `sizes` cannot be added to a graph flatbuffer of
// `graphBytes` bytes (the 2 GiB limit), or when building them would take the process over
// options.maxMemoryBytes (if set). Checked once the label stage knows its sizes, seconds
// into a stage that takes most of a large bake.
void checkHubLabelLimits(uint64_t graphBytes, const HubLabelSizes& sizes, uint64_t vertices,
                         const BakeOptions& options, uint64_t residentNow);

// Throws BakeLimitError when the process's resident memory is above options.maxMemoryBytes
// (if set); `stage` names where the bake was.
void checkMemoryDuringBake(const BakeOptions& options, const char* stage);

// Resident memory of this process now, 0 where the platform does not tell.
uint64_t residentBytes();

// "1.5 GiB", "320 MiB": sizes in messages.
std::string formatBytes(uint64_t bytes);

}  // namespace vorogeo
