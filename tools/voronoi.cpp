#include "voronoi.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <unordered_map>

#include "mesh_stats.h"

namespace vorogeo::tools {

namespace {

// Accepted seeds hashed by grid cell of side `radius`: a new dart looks at 27 cells.
class SeedGrid {
public:
    explicit SeedGrid(double cell) : cell_(cell) {}
    bool farFromAll(const Mesh& mesh, Vec3 p) const {
        const int64_t cx = coord(p.x), cy = coord(p.y), cz = coord(p.z);
        for (int64_t dx = -1; dx <= 1; ++dx)
            for (int64_t dy = -1; dy <= 1; ++dy)
                for (int64_t dz = -1; dz <= 1; ++dz) {
                    const auto it = cells_.find(key(cx + dx, cy + dy, cz + dz));
                    if (it == cells_.end()) continue;
                    for (uint32_t s : it->second)
                        if (distance(mesh.positions[s], p) < cell_) return false;
                }
        return true;
    }
    void add(const Mesh& mesh, uint32_t v) {
        const Vec3 p = mesh.positions[v];
        cells_[key(coord(p.x), coord(p.y), coord(p.z))].push_back(v);
    }

private:
    int64_t coord(double x) const { return int64_t(std::floor(x / cell_)); }
    static uint64_t key(int64_t x, int64_t y, int64_t z) {
        return (uint64_t(x) * 73856093u) ^ (uint64_t(y) * 19349663u) ^ (uint64_t(z) * 83492791u);
    }
    double cell_;
    std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
};

}  // namespace

std::vector<uint32_t> poissonDiskSeeds(const Mesh& mesh, uint32_t count, uint64_t seed, double& radius) {
    const uint32_t V = mesh.vertexCount();
    std::vector<uint32_t> order(V);
    std::iota(order.begin(), order.end(), 0u);
    std::mt19937_64 rng(seed);
    std::shuffle(order.begin(), order.end(), rng);
    count = std::min(count, V);
    const MeshStats stats = computeStats(mesh);
    radius = 2.0 * std::sqrt(std::max(stats.area, 1e-300) / (M_PI * std::max(count, 1u)));
    for (int attempt = 0; attempt < 200; ++attempt, radius *= 0.9) {
        std::vector<uint32_t> seeds;
        SeedGrid grid(radius);
        for (uint32_t v : order) {
            if (!grid.farFromAll(mesh, mesh.positions[v])) continue;
            grid.add(mesh, v);
            seeds.push_back(v);
            if (seeds.size() == count) return seeds;
        }
    }
    radius = 0;
    return std::vector<uint32_t>(order.begin(), order.begin() + count);  // degenerate geometry
}

VoronoiResult growingSpheres(const Mesh& mesh, const vg_graph* graph, vg_workspace* workspace,
                             const std::vector<uint32_t>& seeds, double radius, double growth) {
    const uint32_t V = mesh.vertexCount();
    const uint32_t none = uint32_t(seeds.size());
    VoronoiResult r;
    r.label.assign(V, none);
    r.distance.assign(V, INFINITY);
    const MeshStats stats = computeStats(mesh);
    const double diagonal = std::max(stats.bboxDiag, 1e-300);
    std::vector<uint32_t> open(V);
    std::iota(open.begin(), open.end(), 0u);
    double inner = -1, outer = std::max(radius / 2, diagonal * 1e-3);
    while (!open.empty()) {
        ++r.rounds;
        // Every seed is within the bounding box's diagonal: the last round asks all of them.
        const bool last = outer >= diagonal;
        std::vector<uint32_t> still;
        for (uint32_t v : open) {
            for (uint32_t k = 0; k < seeds.size(); ++k) {
                const double e = distance(mesh.positions[v], mesh.positions[seeds[k]]);
                if (e <= inner || e > outer) continue;  // asked in an earlier round, or not yet covered
                float d = INFINITY;
                const bool bounded = std::isfinite(r.distance[v]);
                const vg_status st = bounded ? vg_distance_within(graph, workspace, seeds[k], v, r.distance[v], &d)
                                             : vg_distance(graph, workspace, seeds[k], v, &d);
                if (st != VG_OK) d = INFINITY;
                ++r.queries;
                r.boundedQueries += bounded;
                // Strictly nearer wins; a tie keeps the lower seed index, as a multi-source
                // field names the first listed source.
                if (d < r.distance[v] || (d == r.distance[v] && std::isfinite(d) && k < r.label[v])) {
                    r.distance[v] = d;
                    r.label[v] = k;
                }
            }
            if (!last && !(r.distance[v] <= outer)) still.push_back(v);
        }
        open.swap(still);
        inner = outer;
        outer *= 1 + growth;
    }
    return r;
}

}  // namespace vorogeo::tools
