// Timing helpers for the evaluation and benchmark commands: a stopwatch and percentiles.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

namespace vorogeo::tools {

class Stopwatch {
public:
    Stopwatch() : start_(std::chrono::steady_clock::now()) {}
    double seconds() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }

private:
    std::chrono::steady_clock::time_point start_;
};

// Nearest-rank percentile (p in [0, 100]) of the values; 0 for an empty set.
inline double percentile(std::vector<double> values, double p) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    size_t rank = size_t(std::ceil(p / 100.0 * double(values.size())));
    rank = std::min(std::max<size_t>(rank, 1), values.size());
    return values[rank - 1];
}

// The machine's own timing noise at one duration: a fixed chain of arithmetic calibrated to
// take about `micros` microseconds, timed `runs` times. On a quiet host its p99 is close to
// its p50; a virtual machine's timer interrupts (~50 us each, every millisecond on the
// 2-core test machine, BENCHMARKS.md) lift the p99 of any work that long, queries included.
struct FixedWorkTiming {
    double p50Us, p99Us;
};
FixedWorkTiming fixedWorkTiming(double micros, int runs = 2000);

// How fast this host is, in two figures that do not depend on the code under test: a
// dependent multiply-add (the core's clock and sharing) and a dependent load from a
// random cycle over 64 MB, more than the last-level cache (its memory latency). Sessions
// run on different hosts (BENCHMARKS.md), so a figure that moved is read against these
// first. Medians of a few runs, ~0.3 s in all.
struct HostSpeed {
    double multiplyAddNs, loadNs;
};
HostSpeed hostSpeed();

// Peak resident set size of this process so far, in megabytes.
double peakRssMb();

}  // namespace vorogeo::tools
