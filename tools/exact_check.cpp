#include "exact_check.h"

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include <tbb/task_arena.h>

#include "timing.h"
#include "parallel.h"

namespace vorogeo::tools {

namespace {

struct ErrorAccumulator {
    size_t count = 0, failures = 0;
    double maxRel = 0, sumRel = 0, maxAbs = 0;
    bool add(double value, double reference, const Tolerance& tol) {
        ++count;
        const double rel = relativeError(value, reference);
        const double abs = (std::isinf(value) || std::isinf(reference))
                               ? (value == reference ? 0.0 : INFINITY)
                               : std::fabs(value - reference);
        if (!agrees(value, reference, tol)) ++failures;
        // Near-zero references are judged by the absolute rule only.
        const bool relCounts = !(reference <= tol.absTol / tol.relTol) || std::isinf(rel);
        const double r = relCounts ? rel : 0.0;
        sumRel += std::isfinite(r) ? r : 0.0;
        maxAbs = std::max(maxAbs, abs);
        const bool worst = count == 1 || r > maxRel;  // true: this is the new worst value
        maxRel = std::max(maxRel, r);
        return worst;
    }
};

}  // namespace

const char* engineName(ExactEngine engine) { return engine == ExactEngine::Mmp ? "mmp" : "wavefront"; }

bool parseEngine(const std::string& name, ExactEngine& engine) {
    if (name == "wavefront") engine = ExactEngine::Wavefront;
    else if (name == "mmp") engine = ExactEngine::Mmp;
    else return false;
    return true;
}

void ExactRunner::run(ExactEngine engine, const ExactGeodesic& geo, uint32_t source, std::vector<double>& distances,
                      ExactStats* stats) {
    if (engine == ExactEngine::Wavefront) {
        wavefront_.run(geo, {source}, distances, stats);
        return;
    }
    ExactQuery q;
    q.sources.push_back(GeodesicSource::atVertex(source));
    mmp_.run(geo, q, distances, stats);
}

PairCheckResult checkPairs(const ExactGeodesic& geo, const std::vector<DistancePair>& pairs,
                           const Tolerance& tol, int threads, ExactEngine engine) {
    std::map<uint32_t, std::vector<size_t>> bySource;
    for (size_t i = 0; i < pairs.size(); ++i) {
        if (pairs[i].source >= geo.vertexCount() || pairs[i].target >= geo.vertexCount())
            throw std::invalid_argument("pair " + std::to_string(i + 1) + " (" + std::to_string(pairs[i].source) +
                                        "," + std::to_string(pairs[i].target) + ") refers to a vertex outside the mesh (" +
                                        std::to_string(geo.vertexCount()) + " vertices)");
        bySource[pairs[i].source].push_back(i);
    }
    std::vector<std::pair<uint32_t, const std::vector<size_t>*>> work;
    for (const auto& kv : bySource) work.push_back({kv.first, &kv.second});

    std::vector<double> computed(pairs.size());
    std::vector<double> seconds(work.size());
    std::vector<uint64_t> windows(work.size());
    PerThread<ExactRunner> runners;
    PerThread<std::vector<double>> fields;
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
        parallelFor(work.size(), [&](size_t i) {
            std::vector<double>& dist = fields.local();
            ExactStats stats;
            Stopwatch clock;
            runners.local().run(engine, geo, work[i].first, dist, &stats);
            seconds[i] = clock.seconds();
            windows[i] = stats.windowsCreated;
            for (size_t p : *work[i].second) computed[p] = dist[pairs[p].target];
        });
    });

    PairCheckResult r;
    ErrorAccumulator acc;
    for (size_t i = 0; i < pairs.size(); ++i) {
        if (acc.add(computed[i], pairs[i].distance, tol)) {
            r.worst = pairs[i];
            r.worstValue = computed[i];
        }
    }
    r.pairs = acc.count;
    r.sources = work.size();
    r.failures = acc.failures;
    r.maxRelError = acc.maxRel;
    r.meanRelError = acc.count ? acc.sumRel / double(acc.count) : 0.0;
    r.maxAbsError = acc.maxAbs;
    r.sourceSeconds = seconds;
    for (uint64_t w : windows) r.windows += w;
    return r;
}

FieldCheckResult checkField(const ExactGeodesic& geo, uint32_t source, const std::vector<double>& reference,
                            const Tolerance& tol, ExactEngine engine) {
    if (reference.size() != geo.vertexCount())
        throw std::invalid_argument("field has " + std::to_string(reference.size()) + " values but the mesh has " +
                                    std::to_string(geo.vertexCount()) + " vertices");
    ExactRunner runner;
    std::vector<double> dist;
    Stopwatch clock;
    runner.run(engine, geo, source, dist);
    FieldCheckResult r;
    r.seconds = clock.seconds();
    ErrorAccumulator acc;
    for (uint32_t v = 0; v < reference.size(); ++v)
        if (acc.add(dist[v], reference[v], tol)) r.worstVertex = v;
    r.values = acc.count;
    r.failures = acc.failures;
    r.maxRelError = acc.maxRel;
    r.meanRelError = acc.count ? acc.sumRel / double(acc.count) : 0.0;
    r.maxAbsError = acc.maxAbs;
    return r;
}

}  // namespace vorogeo::tools
