// Error and metric statistics of runtime distances, shared by `vorogeo eval`, `vorogeo
// bench` and the tests.
#pragma once

#include <cstdint>
#include <vector>

#include "golden.h"
#include "runtime_graph.h"

namespace vorogeo::tools {

struct PairError {
    uint32_t source = 0, target = 0;
    double exact = 0, value = 0, rel = 0;
};

struct AccuracyReport {
    size_t pairs = 0;                // pairs with a finite exact distance (and distinct ends)
    size_t infiniteMismatches = 0;   // one side finite, the other infinite
    size_t overOnePercent = 0;
    double meanRel = 0, medianRel = 0, p99Rel = 0, maxRel = 0;
    std::vector<PairError> worst;    // up to 5, largest first
    double p50Us = 0, p90Us = 0, p99Us = 0;  // point-to-point query time
};

// Relative errors of `values` against `pairs[i].distance` (pairs at distance 0 count as
// exact when the value is 0 too). Fills everything but the timings.
AccuracyReport errorStatistics(const std::vector<DistancePair>& pairs, const std::vector<double>& values);

// Queries every pair with vg_distance (timed one by one) and compares.
AccuracyReport measureAccuracy(const RuntimeWorkspace& ws, const std::vector<DistancePair>& pairs);

struct MetricReport {
    size_t symmetryPairs = 0, symmetryViolations = 0;
    double maxSymmetryRel = 0;
    size_t triples = 0, triangleViolations = 0;
    double maxTriangleExcess = 0;  // largest d(a,c) - d(a,b) - d(b,c), in mesh units
};

// Symmetry d(a,b) = d(b,a) and triangle inequality d(a,c) <= d(a,b) + d(b,c) on random
// triples of vertices (deterministic for a seed).
MetricReport checkMetric(const RuntimeWorkspace& ws, uint32_t vertexCount, size_t triples, uint64_t seed);

}  // namespace vorogeo::tools
