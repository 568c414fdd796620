// Loop subdivision (baker/subdivide) and `vorogeo subdivide`: counts, topology kept,
// the smoothing rules on known shapes, isolated vertices, the command's errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include "generators.h"
#include "mesh_io.h"
#include "mesh_stats.h"
#include "subdivide.h"
#include "test_helpers.h"

using namespace vorogeo;

TEST_CASE("Loop subdivision adds one vertex per edge and quadruples the faces", "[subdivide]") {
    const Mesh torus = vorogeo::torus(1.0, 0.3, 24, 12);
    const MeshStats before = computeStats(torus);
    for (unsigned rounds : {1u, 2u}) {
        Mesh fine;
        std::string error;
        REQUIRE(loopSubdivide(torus, rounds, fine, error));
        const MeshStats after = computeStats(fine);
        uint64_t v = before.vertices, e = before.edges, f = before.faces;
        for (unsigned r = 0; r < rounds; ++r) {
            v += e;
            e = 2 * e + 3 * f;
            f *= 4;
        }
        CHECK(after.vertices == v);
        CHECK(after.edges == e);
        CHECK(after.faces == f);
        CHECK(after.genus == 1);
        CHECK(after.components == 1);
        CHECK(after.boundaryLoops == 0);
        CHECK(fine.twin.size() == 3 * fine.faces.size());  // connectivity built
    }
}

TEST_CASE("Loop subdivision of a flat grid stays flat and keeps its straight borders", "[subdivide]") {
    // The interior rule averages neighbours and the boundary rule (1-6-1, 1-1 at edge
    // midpoints) averages along the border: a plane stays a plane, a straight border a line.
    const Mesh grid = planeGrid(6, 5, 1.0);
    Mesh fine;
    std::string error;
    REQUIRE(loopSubdivide(grid, 1, fine, error));
    const MeshStats s = computeStats(fine);
    CHECK(s.boundaryLoops == 1);
    CHECK(s.genus == 0);
    const MeshStats g = computeStats(grid);
    for (uint32_t v = 0; v < fine.vertexCount(); ++v) {
        const Vec3 p = fine.positions[v];
        CHECK(std::fabs(p.z) < 1e-12);
        CHECK(p.x >= g.bboxMin.x - 1e-12);
        CHECK(p.x <= g.bboxMax.x + 1e-12);
        CHECK(p.y >= g.bboxMin.y - 1e-12);
        CHECK(p.y <= g.bboxMax.y + 1e-12);
    }
    // A boundary vertex in the middle of a straight border keeps its place.
    for (uint32_t v = 0; v < grid.vertexCount(); ++v) {
        const Vec3 p = grid.positions[v];
        const bool onBottom = std::fabs(p.y - g.bboxMin.y) < 1e-12;
        const bool corner = std::fabs(p.x - g.bboxMin.x) < 1e-12 || std::fabs(p.x - g.bboxMax.x) < 1e-12;
        if (!onBottom || corner) continue;
        CHECK(std::fabs((fine.positions[v].x) - (p.x)) < 1e-12);
        CHECK(std::fabs((fine.positions[v].y) - (p.y)) < 1e-12);
    }
}

TEST_CASE("Loop subdivision shrinks a sphere slightly and keeps isolated vertices in place", "[subdivide]") {
    Mesh sphere = icosphere(1, 1.0);
    sphere.positions.push_back(Vec3{5.0, 6.0, 7.0});  // isolated
    REQUIRE(buildConnectivity(sphere).ok);
    Mesh fine;
    std::string error;
    REQUIRE(loopSubdivide(sphere, 1, fine, error));
    const uint32_t isolated = sphere.vertexCount() - 1;
    CHECK(fine.positions[isolated].x == 5.0);
    CHECK(fine.positions[isolated].y == 6.0);
    CHECK(fine.positions[isolated].z == 7.0);
    CHECK(computeStats(fine).isolatedVertices == 1);
    // Loop's limit surface lies inside the control mesh's vertices: every radius < 1, none tiny.
    for (uint32_t v = 0; v < fine.vertexCount(); ++v) {
        if (v == isolated) continue;
        const double r = length(fine.positions[v]);
        CHECK(r < 1.0 + 1e-12);
        CHECK(r > 0.8);
    }
}

TEST_CASE("vorogeo subdivide writes the finer mesh and names its errors", "[subdivide][cli]") {
    test::TempDir dir;
    const std::string in = dir.file("grid.ply"), out = dir.file("grid-x16.ply");
    std::string error;
    REQUIRE(writeMesh(planeGrid(8, 8, 1.0), in, error));  // 81 vertices, 128 faces
    const test::ToolResult r = test::runTool("subdivide " + test::quote(in) + " -o " + test::quote(out) + " --rounds 2");
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(r.out.find("2048 faces") != std::string::npos);
    Mesh fine;
    REQUIRE(loadMesh(out, {}, fine).ok);
    CHECK(fine.faceCount() == 2048);
    CHECK(fine.vertexCount() == 1089);  // (8 * 4 + 1)^2

    const std::string missingOut = dir.file("never.ply");
    const test::ToolResult missing = test::runTool("subdivide " + test::quote(dir.file("absent.ply")) + " -o " + test::quote(missingOut));
    CHECK(missing.status == 1);
    CHECK(missing.err.find("absent.ply") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(missingOut));
    CHECK(test::runTool("subdivide " + test::quote(in) + " -o " + test::quote(missingOut) + " --rounds 0").status == 2);
    CHECK(test::runTool("subdivide " + test::quote(in)).status == 2);
    const test::ToolResult badExt = test::runTool("subdivide " + test::quote(in) + " -o " + test::quote(dir.file("x.xyz")));
    CHECK(badExt.status == 1);
    CHECK(badExt.err.find("unknown extension") != std::string::npos);
    // Nothing but the two meshes is left in the directory (no temporary files).
    int files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir.path())) files += entry.is_regular_file();
    CHECK(files == 2);
}
