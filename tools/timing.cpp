#include "timing.h"

#include <sys/resource.h>

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

double peakRssMb() {
    struct rusage usage {};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / 1024.0;  // Linux reports kilobytes
}

}  // namespace vorogeo::tools
