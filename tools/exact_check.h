// Checks the exact engine against reference distances (golden pairs and fields) and times
// its single-source runs. Shared by `vorogeo exact` and the tests.
#pragma once

#include <string>
#include <vector>

#include "geodesic_exact.h"
#include "geodesic_wavefront.h"
#include "golden.h"

namespace vorogeo::tools {

// Which exact engine answers: both give the exact vertex distances.
enum class ExactEngine { Wavefront, Mmp };
const char* engineName(ExactEngine engine);
// Parses "wavefront" or "mmp"; false for anything else.
bool parseEngine(const std::string& name, ExactEngine& engine);

// One single-source all-destinations run with the chosen engine; each thread keeps one
// (the workspaces of both engines, reused between runs).
class ExactRunner {
public:
    void run(ExactEngine engine, const ExactGeodesic& geo, uint32_t source, std::vector<double>& distances,
             ExactStats* stats = nullptr);

private:
    ExactWorkspace mmp_;
    WavefrontWorkspace wavefront_;
};

struct PairCheckResult {
    size_t pairs = 0, sources = 0, failures = 0;
    double maxRelError = 0, meanRelError = 0, maxAbsError = 0;
    DistancePair worst{};     // the pair with the largest relative error
    double worstValue = 0;    // what the engine computed for it
    std::vector<double> sourceSeconds;  // one single-source all-destinations run per source
    uint64_t windows = 0;               // windows created over all runs
};

// One all-destinations run per distinct source, in parallel on `threads` workers
// (0: all cores). Throws std::invalid_argument for indices outside the mesh.
PairCheckResult checkPairs(const ExactGeodesic& geo, const std::vector<DistancePair>& pairs,
                           const Tolerance& tol, int threads, ExactEngine engine = ExactEngine::Wavefront);

struct FieldCheckResult {
    size_t values = 0, failures = 0;
    double maxRelError = 0, meanRelError = 0, maxAbsError = 0;
    uint32_t worstVertex = 0;
    double seconds = 0;
};
// Compares the field of `source` with one value per vertex.
FieldCheckResult checkField(const ExactGeodesic& geo, uint32_t source, const std::vector<double>& reference,
                            const Tolerance& tol, ExactEngine engine = ExactEngine::Wavefront);

}  // namespace vorogeo::tools
