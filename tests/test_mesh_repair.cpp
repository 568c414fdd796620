// --repair: what each repair does (counts in the notices) and that the result is a
// valid manifold with the expected topology.
#include <catch2/catch.hpp>

#include <cmath>

#include "generators.h"
#include "mesh_check.h"
#include "mesh_io.h"
#include "mesh_stats.h"

using namespace vorogeo;

namespace {

// Repairs `m` and checks the result is clean; returns the notices joined by " | ".
std::string repair(Mesh& m) {
    const LoadReport r = prepareMesh("repair", LoadOptions{true}, m);
    INFO(r.error);
    REQUIRE(r.ok);
    REQUIRE(checkMesh(m).clean());
    REQUIRE(m.twin.size() == m.halfedgeCount());
    std::string all;
    for (const std::string& n : r.notices) all += n + " | ";
    return all;
}

// Appends `b` to `a`, identifying b's vertex `bv` with a's vertex `av`.
void appendSharing(Mesh& a, const Mesh& b, Vec3 shift, uint32_t av, uint32_t bv) {
    const uint32_t offset = a.vertexCount();
    std::vector<uint32_t> map(b.vertexCount());
    for (uint32_t v = 0, next = offset; v < b.vertexCount(); ++v) {
        if (v == bv) {
            map[v] = av;
            continue;
        }
        map[v] = next++;
        a.positions.push_back(b.positions[v] + shift);
    }
    for (const Tri& t : b.faces) a.faces.push_back({map[t[0]], map[t[1]], map[t[2]]});
}

}  // namespace

TEST_CASE("repair drops degenerate and duplicate faces", "[repair]") {
    Mesh m = icosphere(1);
    const uint32_t faces = m.faceCount();
    m.faces.push_back(m.faces[3]);
    m.faces.push_back({m.faces[5][2], m.faces[5][1], m.faces[5][0]});  // same set, flipped
    m.faces.push_back({1, 1, 2});
    m.faces.push_back({4, 7, 4});
    const std::string notes = repair(m);
    CHECK_THAT(notes, Catch::Contains("dropped 2 degenerate faces") && Catch::Contains("dropped 2 duplicate faces"));
    CHECK(m.faceCount() == faces);
    const MeshStats s = computeStats(m);
    CHECK(s.genus == 0);
    CHECK(s.boundaryLoops == 0);
}

TEST_CASE("repair re-orients flipped faces, keeping each component's majority", "[repair]") {
    Mesh m = torus(1, 0.3, 12, 8);
    for (uint32_t f : {0u, 7u, 30u}) std::swap(m.faces[f][1], m.faces[f][2]);
    const std::vector<Tri> expected = torus(1, 0.3, 12, 8).faces;
    const std::string notes = repair(m);
    CHECK_THAT(notes, Catch::Contains("flipped 3 faces"));
    CHECK(m.faces == expected);
}

TEST_CASE("repair splits a vertex shared by two spheres", "[repair]") {
    Mesh m = icosphere(1);
    const uint32_t v = m.vertexCount();
    // Sphere b touches sphere a at a's vertex 0 with its own vertex 3.
    const Mesh b = icosphere(1);
    appendSharing(m, b, m.positions[0] - b.positions[3], 0, 3);
    Mesh broken = m;
    LoadReport r = prepareMesh("spheres", LoadOptions{}, broken);
    CHECK_THAT(r.error, Catch::Contains("1 non-manifold vertex") && Catch::Contains("first is vertex 0"));

    const std::string notes = repair(m);
    CHECK_THAT(notes, Catch::Contains("split 1 non-manifold vertex") && Catch::Contains("added 1 vertex"));
    const MeshStats s = computeStats(m);
    CHECK(s.vertices == 2 * v);
    CHECK(s.components == 2);
    CHECK(s.genus == 0);
    CHECK(s.euler == 4);
}

TEST_CASE("repair cuts an edge shared by two tetrahedra", "[repair]") {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, -1, 0}, {0, 0, -1}};
    // Tetrahedron 0123 and tetrahedron 0145, both closed, sharing edge 0-1 (four faces on it).
    m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {0, 1, 4}, {0, 5, 1}, {0, 4, 5}, {1, 5, 4}};
    Mesh broken = m;
    CHECK_THAT(prepareMesh("tets", LoadOptions{}, broken).error,
               Catch::Contains("1 non-manifold edge") && Catch::Contains("vertex 0 (edge 0-1)"));
    const std::string notes = repair(m);
    CHECK_THAT(notes, Catch::Contains("cut 1 non-manifold edge") && Catch::Contains("split 2 non-manifold vertices"));
    const MeshStats s = computeStats(m);
    CHECK(s.vertices == 8);
    CHECK(s.components == 2);
    CHECK(s.genus == 0);
    CHECK(s.boundaryLoops == 0);
}

TEST_CASE("repair cuts a fin off an edge", "[repair]") {
    Mesh m = brokenMesh(Defect::NonManifoldEdge);
    const std::string notes = repair(m);
    CHECK_THAT(notes, Catch::Contains("cut 1 non-manifold edge") && Catch::Contains("added 2 vertices"));
    const MeshStats s = computeStats(m);
    CHECK(s.faces == 3);
    CHECK(s.components == 2);
    CHECK(s.boundaryLoops == 2);
}

TEST_CASE("repair makes a Moebius strip orientable by cutting it", "[repair]") {
    // Non-orientable: no flipping can make every edge consistent.
    const uint32_t n = 24;
    Mesh m;
    for (uint32_t i = 0; i < n; ++i) {
        const double u = 2 * M_PI * i / n;
        for (double s : {-0.3, 0.3}) {
            const double r = 1 + s * std::cos(u / 2);
            m.positions.push_back({r * std::cos(u), r * std::sin(u), s * std::sin(u / 2)});
        }
    }
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t a = 2 * i, b = 2 * i + 1;
        // The last band closes with a half twist: bottom meets top.
        const uint32_t c = i + 1 < n ? 2 * i + 3 : 0, d = i + 1 < n ? 2 * i + 2 : 1;
        m.faces.push_back({a, d, c});
        m.faces.push_back({a, c, b});
    }
    Mesh broken = m;
    CHECK_THAT(prepareMesh("moebius", LoadOptions{}, broken).error, Catch::Contains("inconsistent face orientation"));
    const std::string notes = repair(m);
    CHECK_THAT(notes, Catch::Contains("cannot be oriented consistently"));
    const MeshStats s = computeStats(m);
    CHECK(s.components == 1);
    CHECK(s.genus == 0);
    CHECK(s.boundaryLoops == 1);  // cut open: a disk
}

TEST_CASE("repair never welds or moves vertices", "[repair]") {
    // Two triangles with coincident but distinct corner vertices stay separate.
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    m.faces = {{0, 1, 2}, {4, 3, 5}};
    const std::vector<Vec3> before = m.positions;
    const LoadReport r = prepareMesh("apart", LoadOptions{true}, m);
    REQUIRE(r.ok);
    CHECK(r.notices.empty());
    CHECK(m.vertexCount() == 6);
    CHECK(computeStats(m).components == 2);
    for (uint32_t v = 0; v < 6; ++v) CHECK(m.positions[v].x == before[v].x);
}
