// Reading the golden exact-distance files of ../shared/golden (and any file in the same
// format): pairs "source,target,distance" with a header line, fields one value per line.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace vorogeo::tools {

struct DistancePair {
    uint32_t source, target;
    double distance;  // +inf where the golden file says inf
};

// Returns false and sets `error` ("FILE:LINE: problem") on a missing file or a bad line.
bool readPairs(const std::string& path, std::vector<DistancePair>& pairs, std::string& error);
bool readField(const std::string& path, std::vector<double>& values, std::string& error);

// Agreement rule of the exact engine: relative error at most relTol, or absolute error at
// most absTol (for distances near zero). Infinities agree only with infinities.
struct Tolerance {
    double relTol = 1e-6;
    double absTol = 0.0;  // set to 1e-9 * bounding-box diagonal
};
bool agrees(double value, double reference, const Tolerance& tol);
double relativeError(double value, double reference);  // 0 for equal infinities

}  // namespace vorogeo::tools
