#include "voronoi_domain.h"


#include <algorithm>
#include <cmath>
#include <numeric>
#include <queue>
#include <stdexcept>
#include <unordered_map>

#include "geodesic_wavefront.h"
#include "patch_topology.h"
#include "parallel.h"

namespace vorogeo {

namespace {

// A face goes to the label of at least two of its vertices, else to the smallest one.
void assignFaces(const Mesh& m, const std::vector<uint32_t>& label, std::vector<uint32_t>& faceRegion) {
    faceRegion.resize(m.faceCount());
    for (uint32_t f = 0; f < m.faceCount(); ++f) {
        const uint32_t a = label[m.faces[f][0]], b = label[m.faces[f][1]], c = label[m.faces[f][2]];
        faceRegion[f] = (a == b || a == c) ? a : (b == c ? b : std::min({a, b, c}));
    }
}

uint32_t findRoot(std::vector<uint32_t>& parent, uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
}

// The vertex of `faces` with the smallest D (ties: smaller index).
uint32_t nearestVertex(const Mesh& m, const std::vector<double>& D, const std::vector<uint32_t>& faces) {
    uint32_t best = m.faces[faces.front()][0];
    for (uint32_t f : faces)
        for (uint32_t v : m.faces[f])
            if (D[v] < D[best] || (D[v] == D[best] && v < best)) best = v;
    return best;
}

// Keeps one face-connected piece of every region: the one at its seed, else the largest
// (ties: the piece with the smallest face). The other pieces (mostly single faces that
// touch their region only at a vertex) are handed out face by face, in rounds, to the
// edge-adjacent region whose seed is nearest to the face's centre in a straight line
// (ties: smaller region). Faces that no region can take (a component without any kept
// piece, not expected) become regions of their own.
void makeConnected(const Mesh& m, const std::vector<double>& D, std::vector<uint32_t>& faceRegion,
                   std::vector<uint32_t>& seeds) {
    const uint32_t nf = m.faceCount();
    std::vector<uint32_t> parent(nf);
    std::iota(parent.begin(), parent.end(), 0u);
    for (uint32_t f = 0; f < nf; ++f)
        for (int k = 0; k < 3; ++k) {
            const int32_t t = m.twin[3 * f + k];
            if (t < 0 || uint32_t(t / 3) < f || faceRegion[t / 3] != faceRegion[f]) continue;
            const uint32_t a = findRoot(parent, f), b = findRoot(parent, uint32_t(t / 3));
            if (a != b) parent[std::max(a, b)] = std::min(a, b);
        }
    std::vector<uint32_t> size(nf, 0);
    std::vector<uint8_t> hasSeed(nf, 0);  // per piece root: the piece holds its region's seed
    for (uint32_t f = 0; f < nf; ++f) {
        const uint32_t root = findRoot(parent, f);
        ++size[root];
        for (uint32_t v : m.faces[f]) hasSeed[root] |= v == seeds[faceRegion[f]];
    }
    std::vector<uint32_t> keep(seeds.size(), kNoRegion);  // per region: root of its kept piece
    for (uint32_t f = 0; f < nf; ++f) {
        if (findRoot(parent, f) != f) continue;  // roots are each piece's smallest face
        uint32_t& k = keep[faceRegion[f]];
        if (k == kNoRegion || hasSeed[f] > hasSeed[k] || (hasSeed[f] == hasSeed[k] && size[f] > size[k])) k = f;
    }
    std::vector<uint32_t> orphans;
    for (uint32_t f = 0; f < nf; ++f)
        if (keep[faceRegion[f]] != findRoot(parent, f)) {
            faceRegion[f] = kNoRegion;
            orphans.push_back(f);
        }
    while (!orphans.empty()) {
        std::vector<std::pair<uint32_t, uint32_t>> assigned;
        std::vector<uint32_t> still;
        for (uint32_t f : orphans) {
            const Tri& tri = m.faces[f];
            const Vec3 centre = (m.positions[tri[0]] + m.positions[tri[1]] + m.positions[tri[2]]) * (1.0 / 3);
            uint32_t best = kNoRegion;
            double bestDist = kInfinity;
            for (int k = 0; k < 3; ++k) {
                const int32_t t = m.twin[3 * f + k];
                if (t < 0 || faceRegion[t / 3] == kNoRegion) continue;
                const uint32_t r = faceRegion[t / 3];
                const double d = distance(m.positions[seeds[r]], centre);
                if (d < bestDist || (d == bestDist && r < best)) best = r, bestDist = d;
            }
            if (best == kNoRegion) still.push_back(f);
            else assigned.push_back({f, best});
        }
        if (assigned.empty()) break;
        for (const auto& [f, r] : assigned) faceRegion[f] = r;
        orphans.swap(still);
    }
    // Left-over faces: one new region per connected group.
    for (uint32_t start : orphans) {
        if (faceRegion[start] != kNoRegion) continue;
        const uint32_t r = uint32_t(seeds.size());
        std::vector<uint32_t> group{start};
        faceRegion[start] = r;
        for (size_t q = 0; q < group.size(); ++q)
            for (int k = 0; k < 3; ++k) {
                const int32_t t = m.twin[3 * group[q] + k];
                if (t >= 0 && faceRegion[t / 3] == kNoRegion) {
                    faceRegion[t / 3] = r;
                    group.push_back(uint32_t(t / 3));
                }
            }
        seeds.push_back(nearestVertex(m, D, group));
    }
}

// The vertex to seed in a region that is not a disk: its pinched vertex, else its vertex
// of largest D on a boundary loop other than the longest, else its vertex of largest D.
// kNoRegion if every candidate is already a seed.
uint32_t splitTarget(const Mesh& m, const std::vector<double>& D, const std::vector<uint32_t>& faceRegion,
                     const std::vector<uint32_t>& faces, uint32_t region, const RegionTopology& topo,
                     const std::vector<uint8_t>& isSeed) {
    if (topo.firstPinchedVertex >= 0 && !isSeed[topo.firstPinchedVertex]) return uint32_t(topo.firstPinchedVertex);
    std::vector<uint32_t> candidates;
    if (topo.boundaryLoops >= 2) {
        auto loops = regionBoundaryLoops(m, faceRegion, region);
        size_t longest = 0;
        for (size_t i = 1; i < loops.size(); ++i)
            if (loops[i].size() > loops[longest].size()) longest = i;
        for (size_t i = 0; i < loops.size(); ++i)
            if (i != longest) candidates.insert(candidates.end(), loops[i].begin(), loops[i].end());
    }
    for (int pass = 0; pass < 2; ++pass) {
        uint32_t best = kNoRegion;
        auto consider = [&](uint32_t v) {
            if (isSeed[v] || !(D[v] < kInfinity)) return;
            if (best == kNoRegion || D[v] > D[best] || (D[v] == D[best] && v < best)) best = v;
        };
        if (pass == 0) {
            for (uint32_t v : candidates) consider(v);
        } else {
            for (uint32_t f : faces)
                for (uint32_t v : m.faces[f]) consider(v);
        }
        if (best != kNoRegion) return best;
    }
    return kNoRegion;
}

// Exact geodesic distances from single seeds, each run bounded by its own distance.
struct SeedRun {
    uint32_t seed;  // index into seeds
    double bound;
};

// Runs every seed of `runs` alone (in parallel) up to its bound and lowers D / relabels
// where it is nearer; ties go to the smaller seed index, so the order of runs is free.
void applySeedRuns(const ExactGeodesic& geo, const std::vector<uint32_t>& seeds, const std::vector<SeedRun>& runs,
                   std::vector<double>& D, std::vector<uint32_t>& label) {
    std::vector<std::vector<std::pair<uint32_t, double>>> reached(runs.size());
    struct Scratch {  // reused between runs: a fresh distance array per run costs more than the run
        WavefrontWorkspace workspace;
        std::vector<double> distances;
    };
    PerThread<Scratch> scratch;
    parallelFor(runs.size(), [&](size_t i) {
        Scratch& local = scratch.local();
        const std::vector<double>& d = local.distances;
        local.workspace.run(geo, {seeds[runs[i].seed]}, local.distances, nullptr, runs[i].bound);
        for (uint32_t v = 0; v < d.size(); ++v)
            if (d[v] <= D[v] && d[v] < kInfinity) reached[i].push_back({v, d[v]});
    });
    for (size_t i = 0; i < runs.size(); ++i) {
        const uint32_t s = runs[i].seed;
        for (const auto& [v, d] : reached[i])
            if (d < D[v] || (d == D[v] && s < label[v])) D[v] = d, label[v] = s;
    }
}

// Exact geodesic Voronoi labels: label[v] = the seed index with the smallest exact
// distance D[v] (ties: smaller index). Seed s runs up to R_s, the radius of its cell in
// the edge graph (shortest edge paths are never shorter than geodesics, so every vertex
// is reached by its edge-graph seed). A vertex v is certain once every seed t that did not
// reach it is known to be farther: R_t >= D[v], or the straight-line distance |t v| >= D[v]
// (a geodesic is never shorter); seeds that fail this run again up to the D[v] needed.
void exactVoronoi(const ExactGeodesic& geo, const VertexGraph& graph, const std::vector<uint32_t>& seeds,
                  std::vector<double>& D, std::vector<uint32_t>& label) {
    const Mesh& m = geo.mesh();
    const uint32_t nv = m.vertexCount(), ns = uint32_t(seeds.size());
    // Edge-graph Voronoi cells by one multi-source Dijkstra.
    std::vector<double> edgeD(nv, kInfinity);
    std::vector<uint32_t> edgeLabel(nv, kNoRegion);
    using Item = std::pair<double, uint32_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    for (uint32_t i = 0; i < ns; ++i) {
        edgeD[seeds[i]] = 0.0;
        edgeLabel[seeds[i]] = i;
        queue.push({0.0, seeds[i]});
    }
    while (!queue.empty()) {
        const auto [d, v] = queue.top();
        queue.pop();
        if (d > edgeD[v]) continue;
        for (uint32_t i = graph.offset[v]; i < graph.offset[v + 1]; ++i) {
            const uint32_t w = graph.neighbor[i];
            const double nd = d + graph.length[i];
            if (nd < edgeD[w] || (nd == edgeD[w] && edgeLabel[v] < edgeLabel[w])) {
                edgeD[w] = nd;
                edgeLabel[w] = edgeLabel[v];
                queue.push({nd, w});
            }
        }
    }
    // A little slack so that a geodesic running exactly along edges is not cut by rounding.
    auto padded = [](double r) { return r * (1.0 + 1e-9) + 1e-300; };
    std::vector<double> bound(ns, 0.0);
    for (uint32_t v = 0; v < nv; ++v)
        if (edgeLabel[v] != kNoRegion) bound[edgeLabel[v]] = std::max(bound[edgeLabel[v]], padded(edgeD[v]));
    D.assign(nv, kInfinity);
    label.assign(nv, kNoRegion);
    std::vector<SeedRun> runs;
    for (uint32_t i = 0; i < ns; ++i) runs.push_back({i, bound[i]});
    // Seeds in a uniform grid of cells as wide as the largest first bound, to find the
    // seeds within a straight-line distance of a vertex.
    double cell = 0, minBound = kInfinity;
    for (double b : bound) cell = std::max(cell, b), minBound = std::min(minBound, b);
    if (!(cell > 0)) cell = 1.0;
    auto cellOf = [&](double x) { return int64_t(std::floor(x / cell)); };
    auto key = [](int64_t x, int64_t y, int64_t z) {
        return (uint64_t(x & 0x1FFFFF) << 42) | (uint64_t(y & 0x1FFFFF) << 21) | uint64_t(z & 0x1FFFFF);
    };
    std::unordered_map<uint64_t, std::vector<uint32_t>> grid;
    for (uint32_t t = 0; t < ns; ++t) {
        const Vec3& p = m.positions[seeds[t]];
        grid[key(cellOf(p.x), cellOf(p.y), cellOf(p.z))].push_back(t);
    }
    std::vector<double> need(ns);
    while (!runs.empty()) {
        applySeedRuns(geo, seeds, runs, D, label);
        std::fill(need.begin(), need.end(), 0.0);
        for (uint32_t v = 0; v < nv; ++v) {
            if (edgeLabel[v] == kNoRegion) continue;  // isolated, or no seed in its component
            if (!(D[v] < kInfinity)) {                // rounding beat the padding: go further
                need[edgeLabel[v]] = std::max(need[edgeLabel[v]], 2.0 * padded(edgeD[v]));
                continue;
            }
            if (D[v] <= minBound) continue;  // every seed ran at least this far
            const Vec3& p = m.positions[v];
            const double r = D[v];
            auto check = [&](uint32_t t) {
                if (bound[t] < r && distance(m.positions[seeds[t]], p) < r) need[t] = std::max(need[t], r);
            };
            const int64_t x0 = cellOf(p.x - r), x1 = cellOf(p.x + r), y0 = cellOf(p.y - r), y1 = cellOf(p.y + r),
                          z0 = cellOf(p.z - r), z1 = cellOf(p.z + r);
            if (double(x1 - x0 + 1) * double(y1 - y0 + 1) * double(z1 - z0 + 1) > double(ns)) {
                for (uint32_t t = 0; t < ns; ++t) check(t);
                continue;
            }
            for (int64_t x = x0; x <= x1; ++x)
                for (int64_t y = y0; y <= y1; ++y)
                    for (int64_t z = z0; z <= z1; ++z) {
                        const auto it = grid.find(key(x, y, z));
                        if (it != grid.end())
                            for (uint32_t t : it->second) check(t);
                    }
        }
        runs.clear();
        for (uint32_t t = 0; t < ns; ++t)
            if (need[t] > bound[t]) {
                bound[t] = padded(need[t]);
                runs.push_back({t, bound[t]});
            }
    }
    // Cannot happen (a geodesic is never longer than an edge path); kept total anyway.
    for (uint32_t v = 0; v < nv; ++v)
        if (edgeLabel[v] != kNoRegion && !(D[v] < kInfinity)) D[v] = edgeD[v], label[v] = edgeLabel[v];
}

// New seeds lower D where they are nearer. Each runs alone, bounded by the current
// largest D (no vertex can gain from a seed farther than that), so the update is exact.
void addSeeds(const ExactGeodesic& geo, const std::vector<uint32_t>& added, std::vector<double>& D,
              std::vector<uint32_t>& label, std::vector<uint32_t>& seeds) {
    double bound = 0;
    for (double d : D)
        if (d < kInfinity) bound = std::max(bound, d);
    std::vector<SeedRun> runs;
    for (uint32_t v : added) {
        runs.push_back({uint32_t(seeds.size()), bound * (1.0 + 1e-9)});
        seeds.push_back(v);
    }
    applySeedRuns(geo, seeds, runs, D, label);
}

}  // namespace

DomainPartition partitionDomain(const ExactGeodesic& geo, uint32_t seedCount, PartitionOptions::Sampling sampling,
                                uint64_t rngSeed, const std::function<void(double)>& progress,
                                uint32_t maxDiskRounds) {
    auto report = [&](double f) {
        if (progress) progress(f);
    };
    const Mesh& m = geo.mesh();
    const VertexGraph graph(m);
    Random rng(rngSeed);
    DomainPartition out;
    std::vector<uint32_t>& seeds = out.seeds;
    seeds = sampling == PartitionOptions::Sampling::Random ? randomSeeds(m, seedCount, rng)
                                                          : farthestPointSeeds(m, graph, seedCount, rng);
    out.sampledSeeds = uint32_t(seeds.size());
    report(0.1);

    // Exact distance to the nearest seed and which seed it is.
    std::vector<double> D;
    std::vector<uint32_t> label;
    exactVoronoi(geo, graph, seeds, D, label);
    report(0.8);

    std::vector<uint32_t>& faceRegion = out.faceRegion;
    std::vector<RegionTopology> topo;
    std::vector<uint32_t> faulty;
    std::vector<std::vector<uint32_t>> regionFaces;
    auto collectFaces = [&]() {
        regionFaces.assign(seeds.size(), {});
        for (uint32_t f = 0; f < m.faceCount(); ++f) regionFaces[faceRegion[f]].push_back(f);
    };
    for (uint32_t round = 0;; ++round) {
        assignFaces(m, label, faceRegion);
        makeConnected(m, D, faceRegion, seeds);
        topo = regionTopology(m, faceRegion, uint32_t(seeds.size()));
        faulty.clear();
        for (uint32_t r = 0; r < seeds.size(); ++r)
            if (topo[r].faces > 0 && !topo[r].isDisk()) faulty.push_back(r);
        if (faulty.empty() || round == maxDiskRounds) break;
        collectFaces();
        std::vector<uint8_t> isSeed(m.vertexCount(), 0);
        for (uint32_t s : seeds) isSeed[s] = 1;
        std::vector<uint32_t> added;
        for (uint32_t r : faulty) {
            const uint32_t v = splitTarget(m, D, faceRegion, regionFaces[r], r, topo[r], isSeed);
            if (v == kNoRegion) continue;
            isSeed[v] = 1;
            added.push_back(v);
        }
        if (added.empty()) break;
        addSeeds(geo, added, D, label, seeds);
        out.diskSeeds += uint32_t(added.size());
        out.diskRounds = round + 1;
    }

    // Fallback: cut what is still not a disk; the first piece keeps the region.
    if (!faulty.empty()) {
        collectFaces();
        for (uint32_t r : faulty) {
            const auto pieces = cutIntoDisks(m, regionFaces[r]);
            for (size_t i = 1; i < pieces.size(); ++i) {
                const uint32_t nr = uint32_t(seeds.size());
                for (uint32_t f : pieces[i]) faceRegion[f] = nr;
                seeds.push_back(nearestVertex(m, D, pieces[i]));
                ++out.cutRegions;
            }
        }
    }

    report(0.95);
    // Drop regions without faces (a seed whose cell holds no face's majority).
    std::vector<uint32_t> remap(seeds.size(), kNoRegion), used(seeds.size(), 0);
    for (uint32_t r : faceRegion) used[r] = 1;
    std::vector<uint32_t> kept;
    for (uint32_t r = 0; r < seeds.size(); ++r)
        if (used[r]) {
            remap[r] = uint32_t(kept.size());
            kept.push_back(seeds[r]);
        }
    seeds.swap(kept);
    for (uint32_t& r : faceRegion) r = remap[r];
    return out;
}

}  // namespace vorogeo
