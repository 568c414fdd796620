// One revision's hub-label stage behind a small C interface, for scripts/ab-hub-labels.sh:
// the script builds this file against each revision's baker into a shared library of its
// own (symbols kept local), so that the driver can time two revisions' label stages in
// turns on the same graph buffer.
#include "hub_labels.h"
#include "vorogeo_generated.h"

#include <tbb/task_arena.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <vector>

namespace {

// FNV-1a over the bytes of a table, so that two builds' tables compare without keeping both.
void mix(uint64_t& h, const void* data, size_t bytes) {
    const unsigned char* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
}

template <class T>
void mix(uint64_t& h, const std::vector<T>& v) {
    const uint64_t n = v.size();
    mix(h, &n, sizeof n);
    mix(h, v.data(), v.size() * sizeof(T));
}

}  // namespace

#define ABH_EXPORT extern "C" __attribute__((visibility("default")))

// computeHubLabels on `threads` threads over the graph buffer [flatbuffer, + bytes): its
// seconds, and a hash of every table it made into `hash`. Negative with the reason in
// `error` when the buffer does not verify or the stage throws.
ABH_EXPORT double abh_labels(const uint8_t* flatbuffer, size_t bytes, int threads, uint64_t* hash, char* error,
                             size_t errorSize) {
    try {
        const std::vector<uint8_t> buffer(flatbuffer, flatbuffer + bytes);
        flatbuffers::Verifier verifier(buffer.data(), buffer.size());
        if (!vorogeo::fb::VerifyGraphBuffer(verifier)) {
            std::snprintf(error, errorSize, "the graph buffer does not verify");
            return -1;
        }
        vorogeo::HubLabels labels;
        const auto start = std::chrono::steady_clock::now();
        tbb::task_arena arena(threads);
        arena.execute([&] { labels = vorogeo::computeHubLabels(buffer); });
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        uint64_t h = 1469598103934665603ull;
        mix(h, &labels.labelScale, sizeof labels.labelScale);
        mix(h, labels.nodeHub);
        mix(h, labels.columnBegin);
        mix(h, labels.columns);
        mix(h, labels.innerNode);
        mix(h, labels.inner);
        mix(h, labels.landmarks);
        mix(h, labels.blockBounds);
        mix(h, labels.exitListBegin);
        mix(h, labels.exitLists);
        *hash = h;
        return seconds;
    } catch (const std::exception& e) {
        std::snprintf(error, errorSize, "%s", e.what());
        return -1;
    }
}
