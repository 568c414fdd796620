// `vorogeo info` and `vorogeo demo` through the real binary: output, exit statuses.
#include <catch2/catch.hpp>

#include <filesystem>

#include "generators.h"
#include "mesh_io.h"
#include "test_helpers.h"

using namespace vorogeo;

TEST_CASE("vorogeo info --json prints one object with every key", "[cli]") {
    test::TempDir dir;
    const std::string path = dir.file("holes.obj");
    std::string error;
    REQUIRE(writeMesh(gridWithHoles(8, 4), path, error));
    const test::ToolResult r = test::runTool("info --json " + test::quote(path));
    REQUIRE(r.status == 0);
    CHECK(r.err.empty());
    CHECK(r.out.front() == '{');
    CHECK(r.out.find('\n') == r.out.size() - 1);
    for (const char* key : {"vertices", "faces", "edges", "boundary_edges", "boundary_loops", "components", "genus",
                            "euler", "bbox_min", "bbox_max", "bbox_diag", "edge_len_min", "edge_len_mean",
                            "edge_len_max", "saddle_ratio", "near_flat_saddle_ratio", "area", "isolated_vertices", "load_seconds"})
        CHECK_THAT(r.out, Catch::Contains(std::string("\"") + key + "\":"));
    CHECK_THAT(r.out, Catch::Contains("\"vertices\":81,") && Catch::Contains("\"boundary_loops\":5,") &&
                          Catch::Contains("\"euler\":-3,") && Catch::Contains("\"bbox_min\":[0,0,0]"));
}

TEST_CASE("vorogeo info prints readable statistics and notices", "[cli]") {
    test::TempDir dir;
    const std::string path = dir.write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
    const test::ToolResult r = test::runTool("info " + test::quote(path));
    REQUIRE(r.status == 0);
    CHECK_THAT(r.out, Catch::Contains("valid mesh") && Catch::Contains("note: triangulated 1 polygon") &&
                          Catch::Contains("boundary loops    1"));
}

TEST_CASE("vorogeo info usage errors exit 2", "[cli]") {
    CHECK(test::runTool("info").status == 2);
    CHECK(test::runTool("info a.obj b.obj").status == 2);
    const test::ToolResult r = test::runTool("info --bogus a.obj");
    CHECK(r.status == 2);
    CHECK_THAT(r.err, Catch::Contains("unknown option --bogus"));
    CHECK(test::runTool("info --help").status == 0);
}

TEST_CASE("vorogeo demo runs every step and writes the mesh and the blob", "[cli][demo]") {
    test::TempDir dir;
    const test::ToolResult r = test::runTool("demo --out " + test::quote(dir.file("out")));
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.out, Catch::Contains("28800 vertices") && Catch::Contains("genus") && Catch::Contains("[6/6]"));
    CHECK_THAT(r.out, Catch::Contains("point-to-point from vertex 0") && Catch::Contains("one-to-all"));
    CHECK(std::filesystem::exists(dir.file("out/bumpy-torus.ply")));
    CHECK(std::filesystem::exists(dir.file("out/bumpy-torus.vgeo")));
    Mesh m;
    CHECK(loadMesh(dir.file("out/bumpy-torus.ply"), LoadOptions{}, m).ok);
    CHECK(test::runTool("demo extra").status == 2);
}
