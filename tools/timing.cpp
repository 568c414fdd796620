#include "timing.h"

#include <sys/resource.h>

#include <cstdint>
#include <random>

namespace vorogeo::tools {

namespace {

// A dependent chain of multiply-adds: each step waits for the one before, so the time is
// the same from run to run unless the host takes the processor away.
double chain(long steps) {
    volatile double seed = 1.0;
    double x = seed;
    for (long i = 0; i < steps; ++i) x = x * 0.9999999 + 1e-7;
    return x;
}

}  // namespace

FixedWorkTiming fixedWorkTiming(double micros, int runs) {
    volatile double sink = 0.0;
    long steps = 1000;
    for (int i = 0; i < 20; ++i) {  // calibrate: the median of a few runs, scaled to the target
        std::vector<double> t;
        for (int k = 0; k < 5; ++k) {
            Stopwatch w;
            sink = sink + chain(steps);
            t.push_back(w.seconds() * 1e6);
        }
        const double median = percentile(t, 50), ratio = median > 0 ? micros / median : 16.0;
        steps = std::max(1L, long(double(steps) * std::min(ratio, 16.0)));
        if (ratio > 0.5 && ratio < 2.0) break;  // close: the last scaling is the fine one
    }
    std::vector<double> us;
    for (int i = 0; i < runs; ++i) {
        Stopwatch w;
        sink = sink + chain(steps);
        us.push_back(w.seconds() * 1e6);
    }
    return FixedWorkTiming{percentile(us, 50), percentile(us, 99)};
}

HostSpeed hostSpeed() {
    constexpr long kSteps = 2000000;
    volatile double sink = 0.0;
    std::vector<double> multiplyAdd;
    for (int i = 0; i < 5; ++i) {
        Stopwatch w;
        sink = sink + chain(kSteps);
        multiplyAdd.push_back(w.seconds() * 1e9 / double(kSteps));
    }
    // One cycle through all the cache lines of 64 MB in a shuffled order, each line holding
    // the index of the next: every load waits for the one before, and the hardware
    // prefetchers cannot guess the next line.
    constexpr size_t kLines = (size_t(64) << 20) / 64, kWordsPerLine = 64 / sizeof(uint64_t);
    std::vector<uint32_t> order(kLines);
    for (size_t i = 0; i < kLines; ++i) order[i] = uint32_t(i);
    std::mt19937_64 random(1);
    for (size_t i = kLines - 1; i > 0; --i) std::swap(order[i], order[size_t(random() % (i + 1))]);
    std::vector<uint64_t> lines(kLines * kWordsPerLine);
    for (size_t i = 0; i < kLines; ++i) lines[size_t(order[i]) * kWordsPerLine] = order[(i + 1) % kLines];
    constexpr long kLoads = 1000000;
    std::vector<double> load;
    uint64_t at = 0;
    for (int i = 0; i < 3; ++i) {
        Stopwatch w;
        for (long k = 0; k < kLoads; ++k) at = lines[at * kWordsPerLine];
        load.push_back(w.seconds() * 1e9 / double(kLoads));
    }
    sink = sink + double(at);
    return HostSpeed{percentile(multiplyAdd, 50), percentile(load, 50)};
}

double peakRssMb() {
    struct rusage usage {};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / 1024.0;  // Linux reports kilobytes
}

}  // namespace vorogeo::tools
