#include "triangulate.h"

#include <cmath>

namespace vorogeo {
namespace {

constexpr uint32_t kMaxEarClippingVertices = 2000;

struct P2 {
    double u, v;
};

double cross2(P2 a, P2 b, P2 c) { return (b.u - a.u) * (c.v - a.v) - (b.v - a.v) * (c.u - a.u); }

// p inside or on triangle abc, which is counter-clockwise.
bool inTriangle(P2 p, P2 a, P2 b, P2 c) {
    return cross2(a, b, p) >= 0 && cross2(b, c, p) >= 0 && cross2(c, a, p) >= 0;
}

}  // namespace

bool triangulatePolygon(const std::vector<Vec3>& positions, const uint32_t* poly, uint32_t n, std::vector<Tri>& out) {
    if (n == 3) {
        out.push_back({poly[0], poly[1], poly[2]});
        return true;
    }
    // Newell's normal is robust for non-planar polygons; project along its largest axis,
    // choosing 2D axes so that the polygon winds counter-clockwise in the plane.
    Vec3 normal;
    for (uint32_t i = 0; i < n; ++i) {
        const Vec3& a = positions[poly[i]];
        const Vec3& b = positions[poly[(i + 1) % n]];
        normal.x += (a.y - b.y) * (a.z + b.z);
        normal.y += (a.z - b.z) * (a.x + b.x);
        normal.z += (a.x - b.x) * (a.y + b.y);
    }
    const double ax = std::fabs(normal.x), ay = std::fabs(normal.y), az = std::fabs(normal.z);
    std::vector<P2> p(n);
    for (uint32_t i = 0; i < n; ++i) {
        const Vec3& q = positions[poly[i]];
        if (az >= ax && az >= ay) p[i] = normal.z >= 0 ? P2{q.x, q.y} : P2{q.y, q.x};
        else if (ax >= ay) p[i] = normal.x >= 0 ? P2{q.y, q.z} : P2{q.z, q.y};
        else p[i] = normal.y >= 0 ? P2{q.z, q.x} : P2{q.x, q.z};
    }

    std::vector<uint32_t> left(n);
    for (uint32_t i = 0; i < n; ++i) left[i] = i;
    // Ear clipping is quadratic: huge polygons (never seen in real meshes) get a fan.
    bool earsOnly = ax + ay + az > 0 && n <= kMaxEarClippingVertices;
    uint32_t i = 0, misses = 0;
    while (earsOnly && left.size() > 3) {
        const uint32_t m = uint32_t(left.size());
        const uint32_t ia = left[(i + m - 1) % m], ib = left[i % m], ic = left[(i + 1) % m];
        bool ear = cross2(p[ia], p[ib], p[ic]) > 0;
        for (uint32_t k = 0; ear && k < m; ++k) {
            const uint32_t j = left[k];
            if (j == ia || j == ib || j == ic) continue;
            ear = !inTriangle(p[j], p[ia], p[ib], p[ic]);
        }
        if (ear) {
            out.push_back({poly[ia], poly[ib], poly[ic]});
            left.erase(left.begin() + (i % m));
            misses = 0;
        } else if (++misses > m) {
            earsOnly = false;
        } else {
            ++i;
        }
    }
    for (size_t k = 1; k + 1 < left.size(); ++k) out.push_back({poly[left[0]], poly[left[k]], poly[left[k + 1]]});
    return earsOnly;
}

}  // namespace vorogeo
