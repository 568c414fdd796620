// The distance function of a window and its minimum, shared by both exact engines (geodesic_exact.h,
// geodesic_wavefront.h): its (pseudo-)source unfolded to (sx, sy) in its edge's frame,
// sigma the distance at that source.
#pragma once

#include <algorithm>
#include <cmath>

namespace vorogeo {

inline double windowDistance(double sx, double sy, double sigma, double x) {
    double dx = x - sx;
    return sigma + std::sqrt(dx * dx + sy * sy);
}

// Smallest distance of a window over its extent.
inline double windowMin(double b0, double b1, double sx, double sy, double sigma) {
    double x = std::min(std::max(sx, b0), b1);
    return windowDistance(sx, sy, sigma, x);
}

}  // namespace vorogeo
