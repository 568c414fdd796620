// The partition stage: both layers cover the mesh, every patch is a disk with the right
// border and interior vertices, patches are geodesic Voronoi cells, and the result does
// not depend on the number of threads.
#include <catch2/catch.hpp>

#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <set>

#include "generators.h"
#include "geodesic_exact.h"
#include "geodesic_wavefront.h"
#include "mesh_io.h"
#include "mesh_stats.h"
#include "partition.h"
#include "patch_topology.h"
#include "seed_sampling.h"
#include "voronoi_domain.h"
#include "test_helpers.h"

using namespace vorogeo;

namespace {

// The faces of `patch` as a mesh of their own (vertices renumbered, none split).
Mesh extractPatch(const Mesh& mesh, const std::vector<uint32_t>& faces) {
    std::vector<uint32_t> vertices;
    for (uint32_t f : faces)
        for (uint32_t v : mesh.faces[f]) vertices.push_back(v);
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    Mesh sub;
    for (uint32_t v : vertices) sub.positions.push_back(mesh.positions[v]);
    for (uint32_t f : faces) {
        Tri t;
        for (int k = 0; k < 3; ++k)
            t[k] = uint32_t(std::lower_bound(vertices.begin(), vertices.end(), mesh.faces[f][k]) - vertices.begin());
        sub.faces.push_back(t);
    }
    return sub;
}

// Each patch, cut out of the mesh: a manifold (no vertex where two fans touch), one
// component, one boundary loop, Euler characteristic 1.
void checkDisks(const Mesh& mesh, const std::vector<Patch>& patches, const char* layer) {
    for (size_t i = 0; i < patches.size(); ++i) {
        INFO(layer << " patch " << i << " (" << patches[i].faces.size() << " faces)");
        Mesh sub = extractPatch(mesh, patches[i].faces);
        REQUIRE(buildConnectivity(sub).ok);
        const MeshStats s = computeStats(sub);
        CHECK(s.components == 1);
        CHECK(s.boundaryLoops == 1);
        CHECK(s.euler == 1);
    }
}

// Every face in exactly one patch; sorted lists; border/interior as defined.
void checkCover(const Mesh& mesh, const std::vector<Patch>& patches, const std::vector<uint32_t>& faceLabel,
                const char* layer) {
    INFO(layer);
    REQUIRE(faceLabel.size() == mesh.faceCount());
    size_t total = 0;
    for (size_t i = 0; i < patches.size(); ++i) {
        const Patch& p = patches[i];
        REQUIRE(!p.faces.empty());
        CHECK(std::is_sorted(p.faces.begin(), p.faces.end()));
        CHECK(std::is_sorted(p.border.begin(), p.border.end()));
        CHECK(std::is_sorted(p.interior.begin(), p.interior.end()));
        for (uint32_t f : p.faces) REQUIRE(faceLabel[f] == i);
        total += p.faces.size();
    }
    CHECK(total == mesh.faceCount());
    // Expected classification, straight from the definition.
    std::vector<std::set<uint32_t>> border(patches.size()), interior(patches.size());
    std::vector<std::set<uint32_t>> vertexPatches(mesh.vertexCount());
    for (uint32_t f = 0; f < mesh.faceCount(); ++f)
        for (uint32_t v : mesh.faces[f]) vertexPatches[v].insert(faceLabel[f]);
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        const bool isBorder = vertexPatches[v].size() > 1 || mesh.boundaryVertex[v];
        for (uint32_t p : vertexPatches[v]) (isBorder ? border : interior)[p].insert(v);
    }
    for (size_t i = 0; i < patches.size(); ++i) {
        INFO("patch " << i);
        CHECK(std::vector<uint32_t>(border[i].begin(), border[i].end()) == patches[i].border);
        CHECK(std::vector<uint32_t>(interior[i].begin(), interior[i].end()) == patches[i].interior);
    }
}

// Longest edge of the faces around each vertex (the edges opposite it included).
std::vector<double> longestEdge(const Mesh& mesh) {
    std::vector<double> len(mesh.vertexCount(), 0.0);
    for (uint32_t f = 0; f < mesh.faceCount(); ++f) {
        double l = 0;
        for (int k = 0; k < 3; ++k) l = std::max(l, mesh.edgeLength(int32_t(3 * f + k)));
        for (uint32_t v : mesh.faces[f]) len[v] = std::max(len[v], l);
    }
    return len;
}

// Voronoi property over a domain, in edge lengths (the longest edge around each vertex):
// `best` is the worst over vertices of how much farther the nearest of the seeds of the
// patches holding the vertex is than its nearest seed (the vertex is in a patch of its
// nearest seed, within that excess); `any` the worst over every patch holding the vertex.
// Distances come from exact runs from every seed over the domain.
struct Slack {
    double best = 0, any = 0;
};
Slack voronoiSlack(const Mesh& mesh, const ExactGeodesic& geo, const std::vector<const Patch*>& patches) {
    std::vector<uint32_t> seeds;
    for (const Patch* p : patches) seeds.push_back(uint32_t(geo.localVertex(p->seedVertex)));
    const auto dist = exactDistancesBatch(geo, seeds);
    const std::vector<double> edge = longestEdge(mesh);
    std::vector<double> nearest(geo.vertexCount(), kInfinity), nearestOwn(geo.vertexCount(), kInfinity);
    for (const auto& d : dist)
        for (size_t v = 0; v < d.size(); ++v) nearest[v] = std::min(nearest[v], d[v]);
    Slack s;
    for (size_t i = 0; i < patches.size(); ++i)
        for (const auto* list : {&patches[i]->border, &patches[i]->interior})
            for (uint32_t v : *list) {
                const uint32_t lv = uint32_t(geo.localVertex(v));
                nearestOwn[lv] = std::min(nearestOwn[lv], dist[i][lv]);
                s.any = std::max(s.any, (dist[i][lv] - nearest[lv]) / edge[v]);
            }
    for (uint32_t lv = 0; lv < geo.vertexCount(); ++lv)
        s.best = std::max(s.best, (nearestOwn[lv] - nearest[lv]) / edge[geo.globalVertex(lv)]);
    return s;
}

// All checks on both layers; returns the partition.
Partition checkedPartition(const Mesh& mesh, const PartitionOptions& options) {
    const Partition part = partitionMesh(mesh, options);
    checkCover(mesh, part.first, part.faceFirst, "first layer");
    checkCover(mesh, part.second, part.faceSecond, "second layer");
    checkDisks(mesh, part.first, "first layer");
    checkDisks(mesh, part.second, "second layer");
    for (const Patch& p : part.first) CHECK(p.parent == UINT32_MAX);
    for (size_t i = 0; i < part.second.size(); ++i) {
        const Patch& p = part.second[i];
        REQUIRE(p.parent < part.first.size());
        for (uint32_t f : p.faces) REQUIRE(part.faceFirst[f] == p.parent);
        if (i > 0) CHECK(part.second[i - 1].parent <= p.parent);
    }
    // Second-layer borders include the first-layer borders.
    for (const Patch& p : part.second) {
        const auto& outer = part.first[p.parent].border;
        for (uint32_t v : p.interior) CHECK(!std::binary_search(outer.begin(), outer.end(), v));
    }
    // Voronoi property, first layer over the mesh, second inside each first-layer patch:
    // every vertex lies in a patch of its nearest seed within one edge length, and in no
    // patch whose seed is more than two edge lengths farther than that (a face follows
    // the majority of its vertices, so a border vertex can be one edge off its cell).
    Slack first, second;
    {
        const ExactGeodesic geo(mesh);
        std::vector<const Patch*> all;
        for (const Patch& p : part.first) all.push_back(&p);
        first = voronoiSlack(mesh, geo, all);
    }
    for (size_t i = 0; i < part.first.size(); ++i) {
        const ExactGeodesic geo(mesh, part.first[i].faces);
        std::vector<const Patch*> inside;
        for (const Patch& p : part.second)
            if (p.parent == i) inside.push_back(&p);
        const Slack s = voronoiSlack(mesh, geo, inside);
        second.best = std::max(second.best, s.best);
        second.any = std::max(second.any, s.any);
    }
    INFO("excess over the nearest seed in edge lengths: first layer " << first.best << " (any patch " << first.any
         << "), second layer " << second.best << " (any patch " << second.any << ")");
    // Random seeds can fall a vertex or two apart and make sliver cells, whose faces the
    // majority vote cuts off and hands to a neighbour: a looser bound there.
    const bool random = options.sampling == PartitionOptions::Sampling::Random;
    const double bestLimit = random ? 2.0 : 1.0, anyLimit = random ? 2.5 : 2.0;
    CHECK(first.best <= bestLimit);
    CHECK(second.best <= bestLimit);
    CHECK(first.any <= anyLimit);
    CHECK(second.any <= anyLimit);
    return part;
}

PartitionOptions withSeeds(uint32_t n1, uint32_t n2 = 0) {
    PartitionOptions o;
    o.firstLayerSeeds = n1;
    o.secondLayerSeeds = n2;
    return o;
}

}  // namespace

TEST_CASE("a bumpy torus partitions into disks of both layers", "[partition]") {
    const Mesh m = bumpyTorus(120, 60);
    const Partition part = checkedPartition(m, withSeeds(6));
    CHECK(part.first.size() >= 6);
    CHECK(part.second.size() > part.first.size());
}

TEST_CASE("a grid with holes puts every hole on patch borders", "[partition]") {
    const Mesh m = gridWithHoles(30, 4);
    const Partition part = checkedPartition(m, withSeeds(2, 6));
    // Hole-adjacent vertices are border vertices in both layers.
    const std::vector<uint8_t> hole = holeAdjacentVertices(m);
    for (const auto* layer : {&part.first, &part.second})
        for (const Patch& p : *layer)
            for (uint32_t v : p.interior) CHECK(!hole[v]);
}

TEST_CASE("two components each get patches", "[partition]") {
    const Mesh m = twoComponents();
    std::vector<uint32_t> faceComp;
    vertexComponents(m, &faceComp);
    for (auto sampling : {PartitionOptions::Sampling::FarthestPoint, PartitionOptions::Sampling::Random}) {
        PartitionOptions o = withSeeds(1, 3);  // fewer seeds than components: raised to 2
        o.sampling = sampling;
        const Partition part = checkedPartition(m, o);
        std::set<uint32_t> seen;
        for (const Patch& p : part.first) {
            seen.insert(faceComp[p.faces.front()]);
            for (uint32_t f : p.faces) CHECK(faceComp[f] == faceComp[p.faces.front()]);
        }
        CHECK(seen.size() == 2);
        CHECK(part.stats.firstSeeds == 2);
    }
}

TEST_CASE("an open cylinder's boundary loops are borders", "[partition]") {
    const Mesh m = openCylinder(1.0, 3.0, 48, 30);
    const Partition part = checkedPartition(m, withSeeds(1));  // one seed: an annulus, split
    CHECK(part.first.size() >= 2);
    CHECK(part.stats.firstDiskSeeds >= 1);
}

TEST_CASE("an icosphere with one seed is split into disks", "[partition]") {
    const Mesh m = icosphere(3);
    const Partition part = checkedPartition(m, withSeeds(1));
    CHECK(part.first.size() >= 2);
    const Partition part2 = checkedPartition(m, PartitionOptions());  // automatic sizes
    CHECK(part2.first.size() >= 2);
}

TEST_CASE("random sampling also gives disks and Voronoi cells", "[partition]") {
    PartitionOptions o = withSeeds(5);
    o.sampling = PartitionOptions::Sampling::Random;
    o.seed = 7;
    checkedPartition(bumpyTorus(96, 48), o);
}

TEST_CASE("the partition does not depend on the number of threads", "[partition]") {
    const Mesh m = bumpyTorus(120, 60);
    for (auto sampling : {PartitionOptions::Sampling::FarthestPoint, PartitionOptions::Sampling::Random}) {
        PartitionOptions o = withSeeds(6);
        o.sampling = sampling;
        o.seed = 42;
        Partition a, b;
        {
            tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
            a = partitionMesh(m, o);
        }
        {
            tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
            b = partitionMesh(m, o);
        }
        CHECK(a.faceFirst == b.faceFirst);
        CHECK(a.faceSecond == b.faceSecond);
        REQUIRE(a.second.size() == b.second.size());
        for (size_t i = 0; i < a.second.size(); ++i) {
            CHECK(a.second[i].seedVertex == b.second[i].seedVertex);
            CHECK(a.second[i].border == b.second[i].border);
        }
        // Another seed gives another partition.
        o.seed = 43;
        CHECK(partitionMesh(m, o).faceFirst != a.faceFirst);
    }
}

TEST_CASE("disk rounds do not depend on the number of threads either", "[partition]") {
    const Mesh m = gridWithHoles(30, 4);
    Partition a, b;
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        a = partitionMesh(m, withSeeds(1, 8));
    }
    {
        tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
        b = partitionMesh(m, withSeeds(1, 8));
    }
    CHECK(a.stats.firstDiskSeeds > 0);
    CHECK(a.stats.firstDiskSeeds == b.stats.firstDiskSeeds);
    CHECK(a.faceFirst == b.faceFirst);
    CHECK(a.faceSecond == b.faceSecond);
}

TEST_CASE("automatic sizes follow the documented rules", "[partition]") {
    const Mesh m = bumpyTorus(120, 60);  // 7,200 vertices: n1 = round(7200 / 3000) = 2
    const Partition part = partitionMesh(m, PartitionOptions());
    CHECK(part.stats.firstSeeds == 2);
    for (size_t i = 0; i < part.first.size(); ++i) {
        const size_t vp = part.first[i].border.size() + part.first[i].interior.size();
        size_t sampled = 0;
        for (const Patch& p : part.second) sampled += p.parent == i;
        // n2 = round(Vp / 100) sampled; disk seeds may add, empty cells may drop a few.
        CHECK(double(sampled) >= 0.8 * std::round(vp / 100.0));
    }
    const PatchSizeStats s = patchSizeStats(part.second);
    CHECK(s.meanVertices > 60);
    CHECK(s.meanVertices < 200);
}

TEST_CASE("bad parameters are rejected", "[partition]") {
    const Mesh m = icosphere(1);  // 42 vertices
    CHECK_THROWS_AS(partitionMesh(m, withSeeds(43)), std::invalid_argument);
    CHECK_THROWS_AS(partitionMesh(m, withSeeds(2, 43)), std::invalid_argument);
    PartitionOptions bad;
    bad.sampling = static_cast<PartitionOptions::Sampling>(7);
    CHECK_THROWS_AS(partitionMesh(m, bad), std::invalid_argument);
    Mesh raw;  // no connectivity
    raw.positions = m.positions;
    raw.faces = m.faces;
    CHECK_THROWS_AS(partitionMesh(raw, PartitionOptions()), std::invalid_argument);
    Mesh empty;
    CHECK_THROWS_AS(partitionMesh(empty, PartitionOptions()), std::invalid_argument);
    // Every vertex a seed is allowed.
    CHECK_NOTHROW(partitionMesh(m, withSeeds(42, 42)));
}

TEST_CASE("progress is reported per stage up to completion", "[partition]") {
    std::vector<std::pair<std::string, double>> calls;
    partitionMesh(icosphere(2), withSeeds(3), [&](const char* stage, double f) { calls.push_back({stage, f}); });
    REQUIRE(!calls.empty());
    for (const auto& c : calls) {
        CHECK(c.second >= 0.0);
        CHECK(c.second <= 1.0);
    }
    CHECK(calls.front() == std::make_pair(std::string("first layer"), 0.0));
    CHECK(calls.back() == std::make_pair(std::string("second layer"), 1.0));
}

TEST_CASE("region topology tells disks from other surfaces", "[partition]") {
    const Mesh torus = vorogeo::torus(2.0, 0.7, 24, 12);
    const Mesh sphere = icosphere(1);
    const Mesh grid = gridWithHoles(8, 1);
    for (const Mesh* m : {&torus, &sphere, &grid}) {
        std::vector<uint32_t> one(m->faceCount(), 0);
        const RegionTopology t = regionTopology(*m, one, 1)[0];
        CHECK(!t.isDisk());
        CHECK(t.components == 1);
        // The greedy cut makes disks of any face set.
        std::vector<uint32_t> all(m->faceCount());
        for (uint32_t f = 0; f < m->faceCount(); ++f) all[f] = f;
        const auto pieces = cutIntoDisks(*m, all);
        CHECK(pieces.size() >= 2);
        std::vector<uint32_t> label(m->faceCount(), kNoRegion);
        for (uint32_t i = 0; i < pieces.size(); ++i)
            for (uint32_t f : pieces[i]) label[f] = i;
        for (uint32_t l : label) REQUIRE(l != kNoRegion);
        for (const RegionTopology& r : regionTopology(*m, label, uint32_t(pieces.size()))) CHECK(r.isDisk());
    }
    CHECK(regionTopology(torus, std::vector<uint32_t>(torus.faceCount(), 0), 1)[0].euler() == 0);
    CHECK(regionTopology(sphere, std::vector<uint32_t>(sphere.faceCount(), 0), 1)[0].euler() == 2);
    CHECK(regionTopology(grid, std::vector<uint32_t>(grid.faceCount(), 0), 1)[0].boundaryLoops == 2);
    // Two triangles of a grid touching only at a corner: one pinched vertex.
    const Mesh g = planeGrid(2, 2);
    std::vector<uint32_t> label(g.faceCount(), 1);
    uint32_t centre = 4, picked = 0;
    for (uint32_t f = 0; f < g.faceCount() && picked < 2; ++f) {
        const auto& t = g.faces[f];
        if (std::find(t.begin(), t.end(), centre) == t.end()) continue;
        bool touches = false;  // skip faces sharing an edge with one already picked
        for (uint32_t h = 0; h < 3; ++h) {
            const int32_t tw = g.twin[3 * f + h];
            if (tw >= 0 && label[tw / 3] == 0) touches = true;
        }
        if (!touches) label[f] = 0, ++picked;
    }
    const RegionTopology t = regionTopology(g, label, 2)[0];
    CHECK(t.faces == 2);
    CHECK(t.components == 2);
    CHECK(t.pinchedVertices == 1);
    CHECK(t.firstPinchedVertex == centre);
}

TEST_CASE("the fallback cut makes disks when no disk rounds are allowed", "[partition]") {
    const Mesh m = torus(2.0, 0.7, 32, 16);
    const ExactGeodesic geo(m);
    const DomainPartition d = partitionDomain(geo, 1, PartitionOptions::Sampling::FarthestPoint, 1, {}, 0);
    CHECK(d.diskSeeds == 0);
    CHECK(d.cutRegions >= 1);
    REQUIRE(d.faceRegion.size() == m.faceCount());
    for (const RegionTopology& t : regionTopology(m, d.faceRegion, uint32_t(d.seeds.size()))) CHECK(t.isDisk());
    // With rounds, seeds do it instead.
    const DomainPartition e = partitionDomain(geo, 1, PartitionOptions::Sampling::FarthestPoint, 1);
    CHECK(e.diskSeeds >= 1);
    CHECK(e.cutRegions == 0);
}

TEST_CASE("isolated vertices belong to no patch", "[partition]") {
    Mesh m = icosphere(2);
    m.positions.push_back({5.0, 5.0, 5.0});
    REQUIRE(prepareMesh("isolated", LoadOptions(), m).ok);
    const Partition part = checkedPartition(m, withSeeds(3));
    const uint32_t lonely = m.vertexCount() - 1;
    for (const auto* layer : {&part.first, &part.second})
        for (const Patch& p : *layer) {
            CHECK(!std::binary_search(p.border.begin(), p.border.end(), lonely));
            CHECK(!std::binary_search(p.interior.begin(), p.interior.end(), lonely));
            CHECK(p.seedVertex != lonely);
        }
    CHECK_THROWS_AS(partitionMesh(m, withSeeds(m.vertexCount())), std::invalid_argument);  // one is unused
}

TEST_CASE("seed sampling covers components and keeps off the boundary", "[partition]") {
    const Mesh two = twoComponents();
    const VertexGraph graph(two);
    const std::vector<uint32_t> comp = vertexComponents(two);
    for (int method = 0; method < 2; ++method) {
        Random rng(3);
        const auto seeds = method == 0 ? farthestPointSeeds(two, graph, 2, rng) : randomSeeds(two, 2, rng);
        REQUIRE(seeds.size() == 2);
        CHECK(comp[seeds[0]] != comp[seeds[1]]);
        Random rng2(3);
        CHECK_THROWS_AS(method == 0 ? farthestPointSeeds(two, graph, 1, rng2) : randomSeeds(two, 1, rng2),
                        std::invalid_argument);
    }
    // On a square the first farthest-point seed is its centre, away from the border.
    const Mesh grid = planeGrid(20, 20);
    Random rng(1);
    const auto seeds = farthestPointSeeds(grid, VertexGraph(grid), 5, rng);
    CHECK(distance(grid.positions[seeds[0]], {0.5, 0.5, 0.0}) < 1e-9);
    for (uint32_t s : seeds) CHECK(!grid.boundaryVertex[s]);
    std::set<uint32_t> distinct(seeds.begin(), seeds.end());
    CHECK(distinct.size() == seeds.size());
}

// Hidden: patch-size uniformity of farthest-point against random sampling, and timing,
// on a generated mesh and (when the shared meshes are there) spot and igea.
TEST_CASE("measure: sampling uniformity and partition time", "[.measure]") {
    std::vector<std::pair<std::string, Mesh>> meshes;
    meshes.push_back({"bumpyTorus", bumpyTorus()});
    const std::string dir = test::sharedMeshDir();
    if (dir.empty()) {
        WARN("shared meshes not found; measuring the generated mesh only");
    } else {
        for (const char* name : {"spot", "igea"}) {
            Mesh m;
            const LoadReport r = loadMesh(dir + "/" + name + ".ply", LoadOptions(), m);
            REQUIRE(r.ok);
            meshes.push_back({name, std::move(m)});
        }
    }
    for (const auto& [name, mesh] : meshes)
        for (auto sampling : {PartitionOptions::Sampling::FarthestPoint, PartitionOptions::Sampling::Random}) {
            PartitionOptions o;
            o.sampling = sampling;
            const auto start = std::chrono::steady_clock::now();
            const Partition part = partitionMesh(mesh, o);
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            const PatchSizeStats a = patchSizeStats(part.first), b = patchSizeStats(part.second);
            std::printf("%-10s %-6s V %6u  %.2f s (first %.2f, second %.2f)\n", name.c_str(),
                        sampling == PartitionOptions::Sampling::Random ? "random" : "fps", mesh.vertexCount(), seconds,
                        part.stats.firstLayerSeconds, part.stats.secondLayerSeconds);
            std::printf("    first  %4zu patches  min %5zu max %5zu mean %7.1f sd %6.1f  (disk seeds %u, cut %u)\n",
                        a.patches, a.minVertices, a.maxVertices, a.meanVertices, a.stddevVertices,
                        part.stats.firstDiskSeeds, part.stats.firstCutPatches);
            std::printf("    second %4zu patches  min %5zu max %5zu mean %7.1f sd %6.1f  (disk seeds %u, cut %u)\n",
                        b.patches, b.minVertices, b.maxVertices, b.meanVertices, b.stddevVertices,
                        part.stats.secondDiskSeeds, part.stats.secondCutPatches);
        }
}
