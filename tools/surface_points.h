// Random surface points and their exact distances (the exact engine with surface-point
// sources), shared by `vorogeo eval-points`, `vorogeo bench` and the tests.
#pragma once

#include <cstdint>
#include <vector>

#include "geodesic_exact.h"
#include "mesh.h"
#include "vorogeo.h"

namespace vorogeo::tools {

struct PointPair {
    SurfacePoint source, target;
    double distance = 0;  // exact
};

// `count` points uniformly distributed over the surface area (deterministic for a seed).
std::vector<SurfacePoint> randomSurfacePoints(const Mesh& mesh, size_t count, uint64_t seed);

// `count` random point pairs, `perSource` targets per source, with exact distances: one
// exact run per source, in parallel.
std::vector<PointPair> exactPointPairs(const Mesh& mesh, size_t count, size_t perSource, uint64_t seed);

// The runtime's form of a point (float weights).
vg_point toRuntimePoint(const SurfacePoint& p);

}  // namespace vorogeo::tools
