// Procedural meshes have the topology they promise, and the statistics see it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "generators.h"
#include "mesh_check.h"
#include "mesh_stats.h"

using namespace vorogeo;

namespace {

void checkTopology(const Mesh& m, uint64_t components, int64_t euler, int64_t genus, uint64_t loops) {
    REQUIRE(checkMesh(m).clean());
    const MeshStats s = computeStats(m);
    CHECK(s.vertices == m.vertexCount());
    CHECK(s.faces == m.faceCount());
    CHECK(s.components == components);
    CHECK(s.euler == euler);
    CHECK(s.genus == genus);
    CHECK(s.boundaryLoops == loops);
    CHECK(int64_t(s.vertices) - int64_t(s.edges) + int64_t(s.faces) == euler);
}

double maxAngleDegrees(const Mesh& m) {
    double worst = 0;
    for (uint32_t f = 0; f < m.faceCount(); ++f)
        for (int k = 0; k < 3; ++k) worst = std::max(worst, cornerAngle(m, f, k));
    return worst * 180 / M_PI;
}

}  // namespace

TEST_CASE("plane grid: a flat disk", "[generators]") {
    const Mesh m = planeGrid(4, 3, 2.0);
    CHECK(m.vertexCount() == 20);
    CHECK(m.faceCount() == 24);
    checkTopology(m, 1, 1, 0, 1);
    const MeshStats s = computeStats(m);
    CHECK(s.area == Approx(4.0));
    CHECK(s.saddleRatio == 0);
    CHECK(s.boundaryEdges == 14);
    CHECK(s.bboxDiag == Approx(std::sqrt(8.0)));

    const Mesh j = planeGrid(10, 10, 1.0, 0.6, 3);
    checkTopology(j, 1, 1, 0, 1);
    CHECK(computeStats(j).area == Approx(1.0));
    CHECK(computeStats(j).saddleRatio == 0);  // still flat
    CHECK(j.positions[12].x != m.positions[12].x);
    CHECK(planeGrid(10, 10, 1.0, 0.6, 3).positions[12].x == j.positions[12].x);  // deterministic
}

TEST_CASE("cylinder, cone, sphere and torus", "[generators]") {
    const Mesh cyl = openCylinder(1.0, 2.0, 16, 4);
    checkTopology(cyl, 1, 0, 0, 2);
    CHECK(computeStats(cyl).saddleRatio == 0);  // developable: every angle sum is 2*pi

    const Mesh c = cone(1.0, 1.5, 24, 5);
    checkTopology(c, 1, 1, 0, 1);
    const std::vector<double> sums = vertexAngleSums(c);
    CHECK(sums.back() < 2 * M_PI - 0.5);  // the apex (last vertex) is a cone point

    const Mesh s = icosphere(2, 2.0);
    CHECK(s.vertexCount() == 162);
    checkTopology(s, 1, 2, 0, 0);
    CHECK(computeStats(s).area == Approx(4 * M_PI * 4).epsilon(0.05));
    CHECK(computeStats(s).saddleRatio == 0);  // convex

    const Mesh t = torus(1.0, 0.25, 32, 16);
    checkTopology(t, 1, 0, 1, 0);
    const double ratio = computeStats(t).saddleRatio;  // the inner half curves negatively
    CHECK(ratio > 0.3);
    CHECK(ratio < 0.7);
    CHECK(computeStats(t).nearFlatSaddleRatio == 0);  // 32 x 16 segments: every saddle bends clearly
}

TEST_CASE("near-flat saddles: a gently curved saddle surface", "[generators]") {
    // z = k (x^2 - y^2) on a grid: every interior vertex is a saddle, with an angle excess
    // that grows with k; a gentle surface has only near-flat ones, a steep one few (its
    // flattest corners).
    auto saddleSurface = [](double k) {
        Mesh m = planeGrid(12, 12, 1.0);
        for (Vec3& p : m.positions) p.z = k * ((p.x - 0.5) * (p.x - 0.5) - (p.y - 0.5) * (p.y - 0.5));
        return m;
    };
    const MeshStats gentle = computeStats(saddleSurface(0.01));
    CHECK(gentle.saddleVertices == gentle.interiorVertices);
    CHECK(gentle.nearFlatSaddleVertices == gentle.saddleVertices);
    CHECK(gentle.nearFlatSaddleRatio == Approx(1.0));
    const MeshStats steep = computeStats(saddleSurface(3.0));
    CHECK(steep.saddleVertices == steep.interiorVertices);
    CHECK(steep.nearFlatSaddleVertices * 10 < steep.saddleVertices);
}

TEST_CASE("bumpy torus: the demo mesh", "[generators]") {
    const Mesh m = bumpyTorus();
    CHECK(m.vertexCount() >= 20000);
    CHECK(m.vertexCount() <= 50000);
    checkTopology(m, 1, 0, 1, 0);
}

TEST_CASE("grid with holes: one boundary loop per hole", "[generators]") {
    const Mesh m = gridWithHoles(12, 9);
    checkTopology(m, 1, 1 - 9, 0, 10);
    const BoundaryLoops loops = boundaryLoops(m);
    REQUIRE(loops.loops.size() == 10);
    size_t fours = 0;
    for (const auto& loop : loops.loops) fours += loop.size() == 4;
    CHECK(fours == 9);  // each hole is one missing cell
    for (const auto& loop : loops.loops)
        for (size_t i = 0; i < loop.size(); ++i)  // consecutive half-edges chain head to tail
            CHECK(m.head(loop[i]) == m.tail(loop[(i + 1) % loop.size()]));
    const std::vector<uint8_t> rim = holeAdjacentVertices(m);
    CHECK(std::count(rim.begin(), rim.end(), 1) == 4 * 12 + 9 * 4);
    CHECK_THROWS_AS(gridWithHoles(4, 2), std::invalid_argument);
}

TEST_CASE("two components: a sphere and a torus", "[generators]") {
    const Mesh m = twoComponents();
    checkTopology(m, 2, 2, 1, 0);
    std::vector<uint32_t> faceComp;
    const std::vector<uint32_t> comp = vertexComponents(m, &faceComp);
    CHECK(comp.front() == 0);
    CHECK(comp.back() == 1);
    CHECK(faceComp.back() == 1);
    const MeshStats s = computeStats(m);
    REQUIRE(s.componentList.size() == 2);
    CHECK(s.componentList[0].genus == 0);
    CHECK(s.componentList[1].genus == 1);
}

TEST_CASE("needle mesh: thin obtuse triangles", "[generators]") {
    const Mesh m = needleMesh(40, 6, 0.02);
    checkTopology(m, 1, 1, 0, 1);
    CHECK(maxAngleDegrees(m) > 170);
}

TEST_CASE("noisy meshes are deterministic per seed", "[generators]") {
    const Mesh base = icosphere(2);
    const Mesh a = noisy(base, 0.01, 42), b = noisy(base, 0.01, 42), c = noisy(base, 0.01, 43);
    checkTopology(a, 1, 2, 0, 0);
    CHECK(a.positions[10].x == b.positions[10].x);
    CHECK(a.positions[10].x != c.positions[10].x);
    for (uint32_t v = 0; v < base.vertexCount(); ++v) CHECK(distance(a.positions[v], base.positions[v]) <= 0.01 * std::sqrt(3.0));
    // The raw generator output is fixed, so results are portable across standard libraries.
    Random rng(5489);
    const double first = rng.uniform();
    CHECK(first == 0.7868209548678019);  // (14514284786278117030 >> 11) * 2^-53
}

TEST_CASE("vertex components mark isolated vertices", "[stats]") {
    Mesh m = planeGrid(2, 2);
    m.positions.push_back({9, 9, 9});
    Mesh copy;
    copy.positions = m.positions;
    copy.faces = m.faces;
    REQUIRE(prepareMesh("grid+1", LoadOptions{}, copy).ok);
    const std::vector<uint32_t> comp = vertexComponents(copy);
    CHECK(comp.back() == kNoComponent);
    CHECK(computeStats(copy).isolatedVertices == 1);
    Mesh bare;
    bare.positions = m.positions;
    bare.faces = m.faces;
    CHECK_THROWS_AS(computeStats(bare), std::invalid_argument);
}
