// The wavefront engine (geodesic_wavefront.h) against the MMP engine, which the golden
// tests tie to CGAL, and against CGAL's fields directly where ../shared is present: both
// are exact, so they must agree to rounding on every vertex of every kind of mesh.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "generators.h"
#include "geodesic_exact.h"
#include "geodesic_wavefront.h"
#include "mesh_io.h"
#include "test_helpers.h"

using namespace vorogeo;

namespace {

std::vector<double> mmpField(const ExactGeodesic& geo, const std::vector<uint32_t>& sources) {
    ExactWorkspace ws;
    ExactQuery q;
    for (uint32_t s : sources) q.sources.push_back(GeodesicSource::atVertex(s));
    std::vector<double> d;
    ws.run(geo, q, d);
    return d;
}

// Largest relative difference; an infinity must be matched by an infinity.
double disagreement(const std::vector<double>& got, const std::vector<double>& want) {
    REQUIRE(got.size() == want.size());
    double worst = 0;
    for (size_t v = 0; v < got.size(); ++v) {
        REQUIRE_FALSE(std::isnan(got[v]));
        REQUIRE(std::isinf(got[v]) == std::isinf(want[v]));
        if (std::isinf(want[v])) continue;
        worst = std::max(worst, std::fabs(got[v] - want[v]) / std::max(want[v], 1e-300));
    }
    return worst;
}

void checkAgainstMmp(const std::string& name, const Mesh& mesh) {
    INFO(name);
    ExactGeodesic geo(mesh);
    WavefrontWorkspace ws;  // reused across runs, as a worker would
    const uint32_t n = mesh.vertexCount();
    for (uint32_t s : {0u, n / 3, n / 2 + 1, n - 1}) {
        INFO("source " << s);
        std::vector<double> d;
        ExactStats stats;
        ws.run(geo, {s}, d, &stats);
        CHECK(d[s] == 0.0);
        CHECK(disagreement(d, mmpField(geo, {s})) < 1e-10);
        CHECK(stats.windowsPropagated == stats.windowsCreated);  // every window crosses or dies
    }
    std::vector<double> d;
    ws.run(geo, {1, n - 2}, d);
    CHECK(disagreement(d, mmpField(geo, {1, n - 2})) < 1e-10);
}

}  // namespace

TEST_CASE("wavefront: flat, developable and cone meshes give their closed forms", "[exact][wavefront]") {
    const Mesh grid = planeGrid(24, 17, 2.0, 0.6, 7);
    ExactGeodesic geo(grid);
    for (uint32_t s : {0u, 200u, grid.vertexCount() - 1}) {
        const std::vector<double> d = wavefrontDistancesFrom(geo, s);
        for (uint32_t v = 0; v < grid.vertexCount(); ++v)
            REQUIRE(d[v] == Approx(distance(grid.positions[s], grid.positions[v])).epsilon(1e-12).margin(1e-14));
    }
    checkAgainstMmp("cylinder", openCylinder(1.0, 3.0, 24, 10));
    checkAgainstMmp("cone", cone(1.0, 2.0, 16, 8));
}

TEST_CASE("wavefront: agrees with MMP on saddles, needles, noise, holes and components", "[exact][wavefront]") {
    checkAgainstMmp("needles", needleMesh());
    checkAgainstMmp("noisy sphere", noisy(icosphere(3), 0.02, 5));
    checkAgainstMmp("holes", gridWithHoles(16, 5));
    checkAgainstMmp("bumpy torus", bumpyTorus(60, 30));
    checkAgainstMmp("noisy torus", noisy(torus(1.0, 0.4, 48, 24), 0.01, 3));
    checkAgainstMmp("two components", twoComponents());
}

TEST_CASE("wavefront: a patch domain, pinched vertex included, matches MMP", "[exact][wavefront]") {
    const Mesh m = bumpyTorus(60, 30);
    std::vector<uint32_t> faces;
    for (uint32_t f = 0; f < m.faceCount(); ++f)
        if ((f / 7) % 3 != 1) faces.push_back(f);  // a domain full of holes and pinches
    ExactGeodesic patch(m, faces);
    WavefrontWorkspace ws;
    for (uint32_t s : {0u, patch.vertexCount() / 2}) {
        std::vector<double> d;
        ws.run(patch, {s}, d);
        CHECK(disagreement(d, mmpField(patch, {s})) < 1e-10);
    }
}

TEST_CASE("wavefront: a patch domain in Morton order maps every vertex and face and gives the same distances",
          "[exact][wavefront]") {
    const Mesh m = bumpyTorus(60, 30);
    std::vector<uint32_t> faces;
    for (uint32_t f = 0; f < m.faceCount(); ++f)
        if ((f / 7) % 3 != 1) faces.push_back(f);  // holes and pinches, as above
    const ExactGeodesic input(m, faces), spatial(m, faces, true);
    REQUIRE(spatial.vertexCount() == input.vertexCount());  // the same pinched copies
    bool reordered = false;
    for (uint32_t v = 0; v < spatial.vertexCount(); ++v) {
        const uint32_t global = spatial.globalVertex(v);
        REQUIRE(global < m.vertexCount());
        const int64_t back = spatial.localVertex(global);
        REQUIRE(back >= 0);
        // A pinched vertex's copies map back to its first domain vertex, at the same point.
        CHECK(spatial.globalVertex(uint32_t(back)) == global);
        if (v > 0 && global < spatial.globalVertex(v - 1)) reordered = true;
    }
    CHECK(reordered);  // the flag took effect: not the input's ascending order
    std::vector<uint8_t> inDomain(m.faceCount(), 0);
    for (uint32_t f : faces) inDomain[f] = 1;
    std::vector<uint8_t> hit(spatial.mesh().faceCount(), 0);
    for (uint32_t f = 0; f < m.faceCount(); ++f) {
        const int64_t local = spatial.localFace(f);
        REQUIRE((local >= 0) == (inDomain[f] != 0));
        if (local < 0) continue;
        REQUIRE(local < int64_t(spatial.mesh().faceCount()));
        CHECK(hit[size_t(local)]++ == 0);
        for (int k = 0; k < 3; ++k)  // the same corners, in the same turn
            CHECK(spatial.globalVertex(spatial.mesh().faces[size_t(local)][k]) == m.faces[f][k]);
    }
    WavefrontWorkspace ws;
    for (uint32_t source : {m.faces[faces[0]][0], m.faces[faces[faces.size() / 2]][1], m.faces[faces.back()][2]}) {
        INFO("source " << source);
        std::vector<double> a, b;
        ws.run(input, {uint32_t(input.localVertex(source))}, a);
        ws.run(spatial, {uint32_t(spatial.localVertex(source))}, b);
        double worst = 0;
        for (uint32_t v = 0; v < input.vertexCount(); ++v) {
            const double want = a[v], got = b[size_t(spatial.localVertex(input.globalVertex(v)))];
            REQUIRE(std::isinf(want) == std::isinf(got));
            if (!std::isinf(want)) worst = std::max(worst, std::fabs(got - want) / std::max(want, 1e-300));
        }
        CHECK(worst < 1e-12);
    }
}

TEST_CASE("wavefront: out-of-range sources are rejected", "[exact][wavefront]") {
    const Mesh m = planeGrid(4, 4);
    ExactGeodesic geo(m);
    WavefrontWorkspace ws;
    std::vector<double> d;
    CHECK_THROWS_AS(ws.run(geo, {m.vertexCount()}, d), std::invalid_argument);
}

TEST_CASE("wavefront: a run to targets gives their distances bit for bit, and does less", "[exact][wavefront]") {
    for (const auto& [name, mesh] : {std::pair<const char*, Mesh>{"bumpy torus", bumpyTorus(60, 30)},
                                     {"noisy sphere", noisy(icosphere(4), 0.02, 5)},
                                     {"holes", gridWithHoles(24, 5)}}) {
        INFO(name);
        ExactGeodesic geo(mesh);
        WavefrontWorkspace ws;  // reused: a targeted run leaves nothing behind for a full one
        const uint32_t n = mesh.vertexCount();
        for (uint32_t s : {0u, n / 3}) {
            INFO("source " << s);
            std::vector<double> full;
            ExactStats fullStats;
            ws.run(geo, {s}, full, &fullStats);
            // A cluster of targets half way out, each bounded by its edge path (never shorter),
            // as the baker bounds a run by the composed overlay.
            double farthest = 0;
            for (double x : full)
                if (x < kInfinity) farthest = std::max(farthest, x);
            uint32_t centre = s;
            for (uint32_t v = 0; v < n; ++v)
                if (std::fabs(full[v] - 0.5 * farthest) < std::fabs(full[centre] - 0.5 * farthest)) centre = v;
            std::vector<double> edges, nearCentre;
            edgeDijkstra(geo.mesh(), s, edges);
            edgeDijkstra(geo.mesh(), centre, nearCentre);
            std::vector<WavefrontWorkspace::Target> targets;
            for (uint32_t v = 0; v < n; ++v)
                if (nearCentre[v] < 0.15 * farthest) targets.push_back({v, edges[v] * (1.0 + 1e-6)});
            REQUIRE(targets.size() >= 3);
            std::vector<double> got;
            ExactStats stats;
            ws.runToTargets(geo, s, targets, got, &stats);
            for (const auto& t : targets) REQUIRE(got[t.vertex] == full[t.vertex]);
            CHECK(stats.windowsPropagated < fullStats.windowsPropagated / 2);  // 13-27% here
            // A bound below a target's distance gives +inf there, as a bounded run does.
            std::vector<WavefrontWorkspace::Target> tight(targets);
            tight[0].bound = full[tight[0].vertex] * 0.5;
            ws.runToTargets(geo, s, tight, got);
            CHECK(got[tight[0].vertex] == kInfinity);
            for (size_t k = 1; k < tight.size(); ++k) CHECK(got[tight[k].vertex] == full[tight[k].vertex]);
            ws.run(geo, {s}, got);
            CHECK(got == full);
        }
    }
}

TEST_CASE("wavefront: a run to targets rejects bad sources, targets and bounds", "[exact][wavefront]") {
    const Mesh m = planeGrid(4, 4);
    ExactGeodesic geo(m);
    WavefrontWorkspace ws;
    std::vector<double> d;
    const uint32_t n = m.vertexCount();
    CHECK_THROWS_AS(ws.runToTargets(geo, n, {{0, 1.0}}, d), std::invalid_argument);
    CHECK_THROWS_AS(ws.runToTargets(geo, 0, {{n, 1.0}}, d), std::invalid_argument);
    CHECK_THROWS_AS(ws.runToTargets(geo, 0, {{1, -1.0}}, d), std::invalid_argument);
    CHECK_THROWS_AS(ws.runToTargets(geo, 0, {{1, std::nan("")}}, d), std::invalid_argument);
    ws.runToTargets(geo, 0, {{n - 1, 100.0}}, d);  // still usable after a refusal
    CHECK(d[n - 1] == Approx(distance(m.positions[0], m.positions[n - 1])));
}

TEST_CASE("wavefront: CGAL's golden fields of the smaller shared meshes", "[exact][wavefront][golden]") {
    const std::string dir = test::sharedMeshDir();
    if (dir.empty()) {
        WARN("skipped: ../shared/meshes is absent, no golden fields to compare with");
        return;
    }
    const std::filesystem::path golden = std::filesystem::path(dir).parent_path() / "golden";
    size_t fields = 0;
    for (const char* name : {"spot", "fandisk", "rocker-arm"}) {
        Mesh mesh;
        REQUIRE(loadMesh(dir + "/" + name + ".ply", LoadOptions{}, mesh).ok);
        ExactGeodesic geo(mesh);
        for (const auto& entry : std::filesystem::directory_iterator(golden)) {
            const std::string file = entry.path().filename().string(), prefix = std::string(name) + ".field.";
            if (file.rfind(prefix, 0) != 0) continue;
            std::vector<double> want(mesh.vertexCount());
            std::ifstream in(entry.path());
            for (double& x : want) REQUIRE(in >> x);
            INFO(file);
            CHECK(disagreement(wavefrontDistancesFrom(geo, uint32_t(std::stoul(file.substr(prefix.size())))), want) <
                  1e-6);
            ++fields;
        }
    }
    CHECK(fields == 6);
}

TEST_CASE("wavefront: vorogeo exact answers with either engine, the same field", "[exact][wavefront][cli]") {
    test::TempDir dir;
    const Mesh mesh = bumpyTorus(40, 20);
    const std::string path = dir.file("torus.ply");
    std::string error;
    REQUIRE(writeMesh(mesh, path, error));
    const std::string wave = dir.file("wave.csv"), mmp = dir.file("mmp.csv");
    test::ToolResult r = test::runTool("exact " + test::quote(path) + " --source 5 --out " + test::quote(wave));
    REQUIRE(r.status == 0);
    CHECK_THAT(r.err, Catch::Contains("(wavefront)"));
    r = test::runTool("exact " + test::quote(path) + " --source 5 --engine mmp --out " + test::quote(mmp));
    REQUIRE(r.status == 0);
    CHECK_THAT(r.err, Catch::Contains("(mmp)"));
    std::ifstream a(wave), b(mmp);
    size_t values = 0;
    for (double x, y; a >> x && b >> y; ++values) REQUIRE(x == Approx(y).epsilon(1e-12).margin(1e-15));
    CHECK(values == mesh.vertexCount());
    // A single target needs MMP's early stop; a misspelt engine is named.
    r = test::runTool("exact " + test::quote(path) + " --source 5 --target 9 --engine wavefront");
    CHECK(r.status == 2);
    CHECK_THAT(r.err, Catch::Contains("--engine mmp"));
    r = test::runTool("exact " + test::quote(path) + " --source 5 --target 9");
    CHECK(r.status == 0);
    CHECK_THAT(r.err, Catch::Contains("(mmp)"));
    const std::string bounded = dir.file("bounded.csv");
    r = test::runTool("exact " + test::quote(path) + " --source 5 --max-distance 0.5 --out " + test::quote(bounded));
    REQUIRE(r.status == 0);
    CHECK_THAT(r.err, Catch::Contains("(wavefront)"));
    r = test::runTool("exact " + test::quote(path) + " --source 5 --engine vtp");
    CHECK(r.status == 2);
    CHECK_THAT(r.err, Catch::Contains("'vtp'"));

    // --pairs checks a pairs file with either engine and names it.
    Mesh loaded;
    REQUIRE(loadMesh(path, LoadOptions{}, loaded).ok);
    const std::vector<double> from5 = wavefrontDistancesFrom(ExactGeodesic(loaded), 5);
    std::string csv = "source,target,distance\n";
    for (uint32_t t : {0u, 17u, 400u, 799u}) {
        char line[96];
        std::snprintf(line, sizeof line, "5,%u,%.17g\n", t, from5[t]);
        csv += line;
    }
    const std::string pairs = dir.write("pairs.csv", csv);
    for (const char* engine : {"wavefront", "mmp"}) {
        r = test::runTool("exact " + test::quote(path) + " --pairs " + test::quote(pairs) + " --json --engine " + engine);
        CHECK(r.status == 0);
        CHECK_THAT(r.out, Catch::Contains(std::string("\"engine\":\"") + engine + "\""));
        CHECK_THAT(r.out, Catch::Contains("\"failures\":0"));
    }
}

TEST_CASE("wavefront: a distance bound drops the work beyond it, not the distances within", "[exact][wavefront]") {
    for (const Mesh& m : {bumpyTorus(60, 30), gridWithHoles(16, 5), noisy(icosphere(3), 0.02, 5)}) {
        ExactGeodesic geo(m);
        WavefrontWorkspace ws;
        std::vector<double> all, bounded;
        ExactStats fullStats, boundedStats;
        ws.run(geo, {11}, all, &fullStats);
        double far = 0;
        for (double d : all)
            if (std::isfinite(d)) far = std::max(far, d);
        const double bound = 0.4 * far;
        ws.run(geo, {11}, bounded, &boundedStats, bound);
        for (uint32_t v = 0; v < m.vertexCount(); ++v) {
            if (all[v] <= bound) REQUIRE(bounded[v] == all[v]);
            else REQUIRE(std::isinf(bounded[v]));
        }
        CHECK(boundedStats.windowsPropagated < fullStats.windowsPropagated);
        CHECK_THROWS_AS(ws.run(geo, {11}, bounded, nullptr, -1.0), std::invalid_argument);
    }
}
