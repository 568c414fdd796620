// Distance functions of windows (geodesic_exact.h, geodesic_wavefront.h): a window's
// (pseudo-)source unfolded to (sx, sy) in its edge's frame, sigma the distance at that source.
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>

namespace vorogeo {

inline double windowDistance(double sx, double sy, double sigma, double x) {
    double dx = x - sx;
    return sigma + std::sqrt(dx * dx + sy * sy);
}

// Points in (lo, hi) where two window distance functions may be equal: roots of the
// quadratic obtained by squaring twice. Spurious roots only add harmless split points.
inline int crossings(double wx, double wy, double ws, double ex, double ey, double es, double lo,
              double hi, double out[2]) {
    // Shift to the interval start to keep the squared terms small.
    wx -= lo;
    ex -= lo;
    const double span = hi - lo;
    const double c = es - ws;
    const double alpha = 2.0 * (ex - wx);
    const double beta = wx * wx + wy * wy - ex * ex - ey * ey - c * c;
    const double qa = alpha * alpha - 4.0 * c * c;
    const double qb = 2.0 * alpha * beta + 8.0 * c * c * ex;
    const double qc = beta * beta - 4.0 * c * c * (ex * ex + ey * ey);
    double r[2];
    int n = 0;
    const double scale = std::fabs(qb) * span + std::fabs(qc) + 1e-300;
    if (std::fabs(qa) * span * span <= 1e-14 * scale) {
        if (qb != 0.0) r[n++] = -qc / qb;
    } else {
        // Equal sigmas give an exact double root that rounding can push to a slightly
        // negative discriminant: clamp, since an extra split point costs nothing.
        const double disc = std::max(qb * qb - 4.0 * qa * qc, 0.0);
        const double sq = std::sqrt(disc);
        const double q = -0.5 * (qb + (qb >= 0 ? sq : -sq));
        if (q != 0.0) {
            r[n++] = q / qa;
            r[n++] = qc / q;
        } else {
            r[n++] = 0.0;
        }
    }
    int m = 0;
    for (int i = 0; i < n; ++i)
        if (r[i] > 0.0 && r[i] < span && std::isfinite(r[i])) out[m++] = r[i] + lo;
    if (m == 2 && out[0] > out[1]) std::swap(out[0], out[1]);
    return m;
}

}  // namespace vorogeo
