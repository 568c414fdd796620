#include "runtime_stats.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>

#include "timing.h"

namespace vorogeo::tools {

AccuracyReport errorStatistics(const std::vector<DistancePair>& pairs, const std::vector<double>& values) {
    AccuracyReport r;
    std::vector<double> rels;
    std::vector<PairError> all;
    for (size_t i = 0; i < pairs.size(); ++i) {
        const double exact = pairs[i].distance, value = values[i];
        if (std::isinf(exact) || std::isinf(value)) {
            if (std::isinf(exact) != std::isinf(value)) ++r.infiniteMismatches;
            continue;
        }
        const double rel = exact > 0 ? std::fabs(value - exact) / exact : (value == 0 ? 0.0 : 1.0);
        rels.push_back(rel);
        all.push_back({pairs[i].source, pairs[i].target, exact, value, rel});
        if (rel > 0.01) ++r.overOnePercent;
    }
    r.pairs = rels.size();
    if (rels.empty()) return r;
    double sum = 0;
    for (double e : rels) sum += e;
    r.meanRel = sum / double(rels.size());
    r.medianRel = percentile(rels, 50);
    r.p99Rel = percentile(rels, 99);
    r.maxRel = *std::max_element(rels.begin(), rels.end());
    const size_t k = std::min<size_t>(5, all.size());
    std::partial_sort(all.begin(), all.begin() + k, all.end(),
                      [](const PairError& a, const PairError& b) { return a.rel > b.rel; });
    r.worst.assign(all.begin(), all.begin() + k);
    return r;
}

AccuracyReport measureAccuracy(const RuntimeWorkspace& ws, const std::vector<DistancePair>& pairs) {
    std::vector<double> values(pairs.size()), micros(pairs.size());
    for (size_t i = 0; i < pairs.size(); ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        values[i] = ws.distance(pairs[i].source, pairs[i].target);
        micros[i] = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    }
    AccuracyReport r = errorStatistics(pairs, values);
    r.p50Us = percentile(micros, 50);
    r.p90Us = percentile(micros, 90);
    r.p99Us = percentile(micros, 99);
    return r;
}

MetricReport checkMetric(const RuntimeWorkspace& ws, uint32_t vertexCount, size_t triples, uint64_t seed) {
    MetricReport r;
    std::mt19937_64 rng(seed ^ 0x5EEDull);
    std::uniform_int_distribution<uint32_t> pick(0, vertexCount - 1);
    for (size_t i = 0; i < triples; ++i) {
        const uint32_t a = pick(rng), b = pick(rng), c = pick(rng);
        const double ab = ws.distance(a, b), ba = ws.distance(b, a), bc = ws.distance(b, c), ac = ws.distance(a, c);
        ++r.symmetryPairs;
        if (ab != ba) {
            ++r.symmetryViolations;
            if (std::isfinite(ab) && std::isfinite(ba))
                r.maxSymmetryRel = std::max(r.maxSymmetryRel, std::fabs(ab - ba) / std::max(ab, ba));
            else
                r.maxSymmetryRel = INFINITY;
        }
        if (std::isinf(ab) || std::isinf(bc)) continue;  // the inequality holds trivially
        ++r.triples;
        const double excess = ac - (ab + bc);
        if (excess > 0) {
            ++r.triangleViolations;
            r.maxTriangleExcess = std::max(r.maxTriangleExcess, excess);
        }
    }
    return r;
}

}  // namespace vorogeo::tools
