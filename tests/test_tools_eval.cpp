// The evaluation tools: rendering, Voronoi partition, and the bench / render / voronoi
// commands through the real binary, on a generated mesh.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include <stb_image.h>

#include "bake.h"
#include "blob_writer.h"
#include "generators.h"
#include "geodesic_exact.h"
#include "mesh_io.h"
#include "render.h"
#include "runtime_graph.h"
#include "test_helpers.h"
#include "voronoi.h"

using namespace vorogeo;
using namespace vorogeo::tools;

namespace {

// A small baked mesh shared by the test cases of one process, on disk for the commands.
struct Fixture {
    test::TempDir dir;
    Mesh mesh = bumpyTorus(40, 20);  // 800 vertices
    std::string meshPath = dir.file("torus.ply"), blobPath = dir.file("torus.vgeo");
    Fixture() {
        std::string error;
        REQUIRE(writeMesh(mesh, meshPath, error));
        BakeOptions o;
        BakeReport report;
        writeFileAtomically(blobPath, bakeMesh(mesh, o, report, nullptr));
        Mesh loaded;
        REQUIRE(loadMesh(meshPath, LoadOptions{}, loaded).ok);
        mesh = loaded;  // the mesh as the commands see it
    }
};
Fixture& fixture() {
    static Fixture f;
    return f;
}

Panel fieldPanel(const std::vector<double>& field) {
    Panel p;
    const double maxFinite = largestFinite(field);
    p.vertexColour = colourField(field, maxFinite);
    p.isoValue = field;
    p.isoSpacing = maxFinite / 10;
    p.caption = "test";
    return p;
}

}  // namespace

TEST_CASE("render: panels have the requested size and follow the field", "[tools][render]") {
    const Mesh& mesh = fixture().mesh;
    const Image a = renderPanels(mesh, {fieldPanel(exactDistancesFrom(mesh, 0))}, 200, 150, View{});
    REQUIRE(a.width == 200);
    REQUIRE(a.height > 150);  // plus the caption strip
    std::set<uint32_t> colours;
    for (const Rgb& c : a.pixels) colours.insert(uint32_t(c.r) << 16 | uint32_t(c.g) << 8 | c.b);
    CHECK(colours.size() > 100);  // shading, colour ramp and isolines, not a flat fill

    // Another source shades other pixels; the same field shades the same ones.
    const Image b = renderPanels(mesh, {fieldPanel(exactDistancesFrom(mesh, 400))}, 200, 150, View{});
    const Image again = renderPanels(mesh, {fieldPanel(exactDistancesFrom(mesh, 0))}, 200, 150, View{});
    size_t differ = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        differ += a.pixels[i].r != b.pixels[i].r || a.pixels[i].g != b.pixels[i].g || a.pixels[i].b != b.pixels[i].b;
    CHECK(differ > a.pixels.size() / 20);
    CHECK(std::equal(a.pixels.begin(), a.pixels.end(), again.pixels.begin(),
                     [](Rgb x, Rgb y) { return x.r == y.r && x.g == y.g && x.b == y.b; }));

    // Two panels side by side; a constant field draws no isolines and one colour ramp value.
    Panel flat = fieldPanel(std::vector<double>(mesh.vertexCount(), 1.0));
    const Image two = renderPanels(mesh, {flat, flat}, 100, 100, View{30, 20});
    CHECK(two.width == 200);
}

TEST_CASE("voronoi: Poisson-disk seeds keep their distance, growing spheres give the nearest seed",
          "[tools][voronoi]") {
    const Mesh& mesh = fixture().mesh;
    double radius = 0;
    const std::vector<uint32_t> seeds = poissonDiskSeeds(mesh, 12, 7, radius);
    REQUIRE(seeds.size() == 12);
    REQUIRE(radius > 0);
    for (size_t i = 0; i < seeds.size(); ++i)
        for (size_t j = i + 1; j < seeds.size(); ++j)
            CHECK(distance(mesh.positions[seeds[i]], mesh.positions[seeds[j]]) >= radius);
    double again = 0;
    CHECK(poissonDiskSeeds(mesh, 12, 7, again) == seeds);

    RuntimeGraph graph;
    std::string error;
    REQUIRE(graph.load(fixture().blobPath, error));
    RuntimeWorkspace ws(graph);
    const VoronoiResult r = growingSpheres(mesh, graph.graph(), ws.get(), seeds, radius);
    CHECK(r.rounds >= 2);
    CHECK(r.boundedQueries > 0);
    // Every label is the argmin over all seeds of the point-to-point distance.
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        float best = INFINITY;
        uint32_t label = uint32_t(seeds.size());
        for (uint32_t k = 0; k < seeds.size(); ++k) {
            const float d = ws.distance(seeds[k], v);
            if (d < best) best = d, label = k;
        }
        REQUIRE(r.distance[v] == best);
        REQUIRE(r.label[v] == label);
    }
}

TEST_CASE("vorogeo bench, render and voronoi run on a baked mesh", "[tools][cli]") {
    const Fixture& f = fixture();
    const std::string mesh = test::quote(f.meshPath), blob = test::quote(f.blobPath);

    test::ToolResult r = test::runTool("bench " + mesh + " " + blob + " --pairs 50 --sources 2 --json");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    for (const char* key : {"sssd_p50_us", "sssd_p99_us", "bidirectional_sssd_p50_us", "bidirectional_sssd_p99_us",
                            "msad_p50_ms", "exact_ssad_p50_ms", "exact_sssd_p50_ms", "dijkstra_sssd_p50_us",
                            "dijkstra_ssad_p50_ms", "field_mean_rel_error", "open_ms", "fixed_work_p50_us",
                            "fixed_work_p99_us"})
        CHECK_THAT(r.out, Catch::Contains(std::string("\"") + key + "\":"));
    r = test::runTool("bench " + mesh + " " + blob + " --pairs 50 --sources 2 --json --runtime-only");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.out, Catch::Contains("\"sssd_p50_us\":") && Catch::Contains("\"msad_p50_ms\":") &&
                          Catch::Contains("\"bidirectional_sssd_p50_us\":") && Catch::Contains("\"open_ms\":") &&
                          Catch::Contains("\"fixed_work_p99_us\":") && Catch::Contains("\"host_multiply_add_ns\":") &&
                          Catch::Contains("\"host_load_ns\":"));
    CHECK_THAT(r.out, !Catch::Contains("exact_ssad_p50_ms"));
    CHECK_THAT(r.out, Catch::Contains("\"turn_pairs\":500,"));     // the default turn
    CHECK_THAT(r.out, Catch::Contains("\"warmup_pairs\":500,"));   // and untimed pairs
    r = test::runTool("bench " + mesh + " " + blob + " --pairs 50 --sources 1 --json --runtime-only --turn 7");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.out, Catch::Contains("\"turn_pairs\":7,") && Catch::Contains("\"pairs\":50,"));
    r = test::runTool("bench " + mesh + " " + blob + " --pairs 50 --sources 1 --json --runtime-only --warmup 0");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.out, Catch::Contains("\"warmup_pairs\":0,"));
    r = test::runTool("bench " + mesh + " " + blob + " --pairs 50 --runtime-only --turn 0");
    CHECK(r.status == 2);
    CHECK_THAT(r.err, Catch::Contains("--turn"));
    r = test::runTool("bench " + mesh + " " + blob + " --pairs 50 --runtime-only --warmup -1");
    CHECK(r.status == 2);
    CHECK_THAT(r.err, Catch::Contains("--warmup"));

    // vorogeo eval with either point-to-point search; the search is named in the report.
    for (const char* search : {"directed", "bidirectional"}) {
        r = test::runTool("eval " + mesh + " " + blob + " --pairs 100 --triples 50 --json --search " + search);
        INFO(r.out << r.err);
        REQUIRE(r.status == 0);
        CHECK_THAT(r.out, Catch::Contains(std::string("\"search\":\"") + search + "\""));
        CHECK_THAT(r.out, Catch::Contains("\"mean_rel_error\":"));
    }
    r = test::runTool("eval " + mesh + " " + blob + " --pairs 10 --search sideways");
    CHECK(r.status == 2);
    CHECK_THAT(r.err, Catch::Contains("--search"));

    const std::string png = f.dir.file("field.png"), ply = f.dir.file("field.ply");
    r = test::runTool("render " + mesh + " --blob " + blob + " --source 3 --exact --size 120x90 --out " +
                      test::quote(png) + " --ply " + test::quote(ply));
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    int w = 0, h = 0, channels = 0;
    unsigned char* pixels = stbi_load(png.c_str(), &w, &h, &channels, 3);
    REQUIRE(pixels != nullptr);
    CHECK(w == 360);  // runtime, exact and error panels
    CHECK(h > 90);
    std::set<int> reds;
    for (int i = 0; i < w * h; ++i) reds.insert(pixels[3 * i]);
    stbi_image_free(pixels);
    CHECK(reds.size() > 20);
    Mesh coloured;
    CHECK(loadMesh(ply, LoadOptions{}, coloured).ok);
    CHECK(coloured.vertexCount() == f.mesh.vertexCount());

    const std::string csv = f.dir.file("labels.csv");
    r = test::runTool("voronoi " + mesh + " " + blob + " --seeds 6 --out " + test::quote(csv));
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.out, Catch::Contains("growing spheres") && Catch::Contains("multi-source labels"));
    std::ifstream in(csv);
    std::string line;
    size_t lines = 0;
    std::getline(in, line);
    CHECK(line == "vertex,seed,seed_vertex,distance");
    while (std::getline(in, line)) ++lines;
    CHECK(lines == f.mesh.vertexCount());

    // Bad input names the problem.
    r = test::runTool("render " + mesh + " --source 999999 --out " + test::quote(png));
    CHECK(r.status == 1);
    CHECK_THAT(r.err, Catch::Contains("out of range"));
    CHECK(test::runTool("voronoi " + mesh + " " + blob + " --out x.csv").status == 2);
    CHECK(test::runTool("bench " + mesh).status == 2);
}

TEST_CASE("vorogeo path prints, checks and draws a path, --random gives its statistics", "[tools][cli][paths]") {
    const Fixture& f = fixture();
    const std::string mesh = test::quote(f.meshPath), blob = test::quote(f.blobPath);
    const std::string png = f.dir.file("path.png");
    test::ToolResult r = test::runTool("path " + mesh + " " + blob + " --from 3,0.2,0.3 --to 700,0.1,0.1 --size 100x80 --png " +
                                       test::quote(png));
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.out, Catch::Contains("path length") && Catch::Contains("on the surface: yes"));
    int w = 0, h = 0, channels = 0;
    unsigned char* pixels = stbi_load(png.c_str(), &w, &h, &channels, 3);
    REQUIRE(pixels != nullptr);
    CHECK(w == 100);
    size_t white = 0;  // the path is drawn in white over the coloured field
    for (int i = 0; i < w * h; ++i) white += pixels[3 * i] == 255 && pixels[3 * i + 1] == 255 && pixels[3 * i + 2] == 255;
    stbi_image_free(pixels);
    CHECK(white > 10);

    r = test::runTool("path " + mesh + " " + blob + " --random 50 --json");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    for (const char* key : {"mean_length_rel_diff", "max_length_rel_diff", "path_p50_us", "distance_p50_us",
                            "distance_p90_us", "extraction_p50_us", "extraction_p90_us", "off_surface\":0",
                            "vs_point_distance_mean", "vs_point_distance_max"})
        CHECK_THAT(r.out, Catch::Contains(key));
    CHECK_THAT(r.out, !Catch::Contains("path_vs_exact_mean"));
    r = test::runTool("path " + mesh + " " + blob + " --random 20 --exact --json");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    for (const char* key : {"path_vs_exact_mean", "path_vs_exact_max", "path_vs_exact_min", "point_distance_vs_exact_mean",
                            "point_distance_vs_exact_max"})
        CHECK_THAT(r.out, Catch::Contains(key));

    // Bad input names the problem.
    r = test::runTool("path " + mesh + " " + blob + " --from 999999,0.2,0.3 --to 1,0.1,0.1");
    CHECK(r.status == 2);
    CHECK_THAT(r.err, Catch::Contains("out of range"));
    r = test::runTool("path " + mesh + " " + blob + " --from 3,0.2 --to 1,0.1,0.1");
    CHECK(r.status == 2);
    CHECK_THAT(r.err, Catch::Contains("F,U,V"));
    CHECK(test::runTool("path " + mesh + " " + blob).status == 2);
}
