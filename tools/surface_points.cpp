#include "surface_points.h"

#include <algorithm>
#include <random>

#include "parallel.h"

namespace vorogeo::tools {

std::vector<SurfacePoint> randomSurfacePoints(const Mesh& mesh, size_t count, uint64_t seed) {
    std::vector<double> cumulative(mesh.faceCount());
    double total = 0;
    for (uint32_t f = 0; f < mesh.faceCount(); ++f) {
        const Vec3 a = mesh.positions[mesh.faces[f][0]], b = mesh.positions[mesh.faces[f][1]],
                   c = mesh.positions[mesh.faces[f][2]];
        total += 0.5 * length(cross(b - a, c - a));
        cumulative[f] = total;
    }
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<SurfacePoint> points(count);
    for (SurfacePoint& p : points) {
        const double at = unit(rng) * total;
        p.face = uint32_t(std::min<size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), at) - cumulative.begin(),
                                           mesh.faceCount() - 1));
        double u = unit(rng), v = unit(rng);
        if (u + v > 1) {  // fold the square onto the triangle: uniform in area
            u = 1 - u;
            v = 1 - v;
        }
        p.bary[0] = 1 - u - v;
        p.bary[1] = u;
        p.bary[2] = v;
    }
    return points;
}

std::vector<PointPair> exactPointPairs(const Mesh& mesh, size_t count, size_t perSource, uint64_t seed) {
    perSource = std::max<size_t>(1, perSource);
    const size_t sources = (count + perSource - 1) / perSource;
    const std::vector<SurfacePoint> points = randomSurfacePoints(mesh, sources + count, seed);
    std::vector<PointPair> pairs(count);
    for (size_t i = 0; i < count; ++i) {
        pairs[i].source = points[i / perSource];
        pairs[i].target = points[sources + i];
    }
    const ExactGeodesic geo(mesh);
    PerThread<ExactWorkspace> workspaces;
    parallelFor(sources, [&](size_t s) {
        ExactWorkspace& ws = workspaces.local();
        ExactQuery q;
        q.sources.push_back(GeodesicSource::atPoint(points[s]));
        std::vector<double> dist;
        ws.run(geo, q, dist);
        for (size_t i = s * perSource; i < std::min(count, (s + 1) * perSource); ++i)
            pairs[i].distance = ws.distanceAt(pairs[i].target, dist);
    });
    return pairs;
}

vg_point toRuntimePoint(const SurfacePoint& p) {
    vg_point out;
    out.face = p.face;
    for (int k = 0; k < 3; ++k) out.bary[k] = float(p.bary[k]);
    return out;
}

}  // namespace vorogeo::tools
