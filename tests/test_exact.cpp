// The exact engine against closed-form distances, and its guarantees on awkward meshes.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "generators.h"
#include "geodesic_exact.h"
#include "geodesic_wavefront.h"

using namespace vorogeo;

namespace {

std::vector<double> field(const Mesh& mesh, uint32_t source) { return exactDistancesFrom(mesh, source); }

double maxRelativeError(const std::vector<double>& got, const std::vector<double>& want) {
    double worst = 0;
    for (size_t i = 0; i < got.size(); ++i)
        if (want[i] > 0) worst = std::max(worst, std::fabs(got[i] - want[i]) / want[i]);
        else worst = std::max(worst, std::fabs(got[i]));
    return worst;
}

}  // namespace

TEST_CASE("flat grids give Euclidean distances", "[exact]") {
    for (double jitter : {0.0, 0.6}) {
        const Mesh m = planeGrid(24, 17, 2.0, jitter, 7);
        for (uint32_t s : {0u, 200u, m.vertexCount() - 1}) {
            auto d = field(m, s);
            std::vector<double> want(m.vertexCount());
            for (uint32_t v = 0; v < m.vertexCount(); ++v) want[v] = distance(m.positions[s], m.positions[v]);
            INFO("jitter " << jitter << " source " << s);
            CHECK(maxRelativeError(d, want) < 1e-12);
        }
    }
}

TEST_CASE("an open cylinder gives unrolled distances", "[exact]") {
    const uint32_t segments = 24, rings = 10;
    const double radius = 1.0, height = 3.0;
    const Mesh m = openCylinder(radius, height, segments, rings);
    const double chord = 2 * radius * std::sin(M_PI / segments), perimeter = segments * chord;
    for (uint32_t s : {0u, 5u * segments + 7u}) {
        auto d = field(m, s);
        std::vector<double> want(m.vertexCount());
        for (uint32_t v = 0; v < m.vertexCount(); ++v) {
            double du = std::fabs(double(int(v % segments) - int(s % segments))) * chord;
            du = std::min(du, perimeter - du);
            const double dz = double(int(v / segments) - int(s / segments)) * height / rings;
            want[v] = std::sqrt(du * du + dz * dz);
        }
        CHECK(maxRelativeError(d, want) < 1e-12);
    }
}

TEST_CASE("a cone gives distances in its unrolled sector", "[exact]") {
    const uint32_t segments = 16, rings = 8;
    const double radius = 1.0, height = 2.0;
    const Mesh m = cone(radius, height, segments, rings);
    const double slant = std::sqrt(radius * radius + height * height);
    const double sector = 2 * std::asin(radius * std::sin(M_PI / segments) / slant);  // apex angle per segment
    const double total = sector * segments;
    auto polar = [&](uint32_t v, double& rho, double& phi) {
        if (v == m.vertexCount() - 1) {  // the apex
            rho = 0;
            phi = 0;
            return;
        }
        rho = slant * (1.0 - double(v / segments) / rings);
        phi = sector * double(v % segments);
    };
    for (uint32_t s : {0u, 3u * segments + 5u}) {
        auto d = field(m, s);
        double rs, ps;
        polar(s, rs, ps);
        std::vector<double> want(m.vertexCount());
        for (uint32_t v = 0; v < m.vertexCount(); ++v) {
            double rv, pv;
            polar(v, rv, pv);
            double dphi = std::fabs(pv - ps);
            dphi = std::min(dphi, total - dphi);
            want[v] = std::sqrt(std::max(0.0, rs * rs + rv * rv - 2 * rs * rv * std::cos(dphi)));
        }
        CHECK(maxRelativeError(d, want) < 1e-10);
    }
}

TEST_CASE("paths bend around the reflex corner of an L-shaped patch", "[exact]") {
    // 20x20 grid on [0,1]^2; the patch drops the cells of the upper-right quadrant.
    const uint32_t n = 20;
    const Mesh m = planeGrid(n, n, 1.0);
    std::vector<uint32_t> faces;
    for (uint32_t f = 0; f < m.faceCount(); ++f) {
        Vec3 c = (m.positions[m.faces[f][0]] + m.positions[m.faces[f][1]] + m.positions[m.faces[f][2]]) * (1.0 / 3);
        if (!(c.x > 0.5 && c.y > 0.5)) faces.push_back(f);
    }
    ExactGeodesic patch(m, faces);
    auto vertexAt = [&](double x, double y) {
        for (uint32_t v = 0; v < m.vertexCount(); ++v)
            if (std::fabs(m.positions[v].x - x) < 1e-9 && std::fabs(m.positions[v].y - y) < 1e-9) return v;
        FAIL("no vertex at " << x << "," << y);
        return 0u;
    };
    const uint32_t a = vertexAt(1.0, 0.25), b = vertexAt(0.25, 1.0);
    const Vec3 corner{0.5, 0.5, 0};
    ExactWorkspace ws;
    ExactQuery q;
    q.sources.push_back(GeodesicSource::atVertex(uint32_t(patch.localVertex(a))));
    std::vector<double> d;
    ws.run(patch, q, d);
    const double want = distance(m.positions[a], corner) + distance(corner, m.positions[b]);
    CHECK(d[patch.localVertex(b)] == Approx(want).epsilon(1e-12));
    CHECK(patch.localVertex(vertexAt(1.0, 1.0)) == -1);  // outside the patch
    CHECK(patch.vertexCount() < m.vertexCount());
}

TEST_CASE("surface-point sources on a plane give Euclidean distances", "[exact]") {
    const Mesh m = planeGrid(12, 12, 1.0, 0.4, 3);
    ExactGeodesic geo(m);
    ExactWorkspace ws;
    std::vector<double> d;
    SurfacePoint inside{37, {0.2, 0.3, 0.5}};
    SurfacePoint onEdge{52, {0.5, 0.5, 0.0}};
    for (const SurfacePoint& p : {inside, onEdge}) {
        Vec3 pos{0, 0, 0};
        for (int k = 0; k < 3; ++k) pos = pos + m.positions[m.faces[p.face][k]] * p.bary[k];
        ExactQuery q;
        q.sources.push_back(GeodesicSource::atPoint(p));
        ws.run(geo, q, d);
        for (uint32_t v = 0; v < m.vertexCount(); ++v) CHECK(d[v] == Approx(distance(pos, m.positions[v])).epsilon(1e-12));
    }
}

namespace {

SurfacePoint randomPoint(const Mesh& m, std::mt19937_64& rng) {
    std::uniform_int_distribution<uint32_t> face(0, m.faceCount() - 1);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double a = unit(rng), b = unit(rng);
    if (a + b > 1) {
        a = 1 - a;
        b = 1 - b;
    }
    return SurfacePoint{face(rng), {a, b, 1 - a - b}};
}

}  // namespace

TEST_CASE("distances at surface points: Euclidean on a plane, unrolled on a cylinder", "[exact]") {
    std::mt19937_64 rng(11);
    SECTION("plane, point and vertex sources, points inside faces, on edges and at corners") {
        const Mesh m = planeGrid(16, 13, 1.0, 0.5, 5);
        ExactGeodesic geo(m);
        ExactWorkspace ws;
        std::vector<double> d;
        for (int run = 0; run < 6; ++run) {
            ExactQuery q;
            const SurfacePoint src = run == 5 ? SurfacePoint{9, {0.0, 0.5, 0.5}} : randomPoint(m, rng);
            q.sources.push_back(run == 4 ? GeodesicSource::atVertex(40) : GeodesicSource::atPoint(src));
            const Vec3 s = run == 4 ? m.positions[40] : positionOf(m, src);
            ws.run(geo, q, d);
            for (int i = 0; i < 200; ++i) {
                SurfacePoint t = randomPoint(m, rng);
                if (i % 10 == 1) t.bary[0] = 0, t.bary[1] = 0.3, t.bary[2] = 0.7;  // on an edge
                if (i % 10 == 2) t.bary[0] = 1, t.bary[1] = 0, t.bary[2] = 0;      // at a corner
                const double want = distance(s, positionOf(m, t));
                INFO("run " << run << " target face " << t.face);
                CHECK(ws.distanceAt(t, d) == Approx(want).epsilon(1e-12).margin(1e-12));
            }
        }
    }
    SECTION("cylinder") {
        const uint32_t segments = 24, rings = 10;
        const double radius = 1.0, height = 3.0;
        const Mesh m = openCylinder(radius, height, segments, rings);
        const double chord = 2 * radius * std::sin(M_PI / segments), perimeter = segments * chord;
        // Unrolled coordinates of a point: arc position along the polygon, height.
        auto unrolled = [&](const SurfacePoint& p, double& u, double& z) {
            u = 0;
            z = 0;
            const uint32_t* c = &m.faces[p.face][0];
            double base = c[0] % segments;
            for (int k = 0; k < 3; ++k) {
                double col = c[k] % segments;
                if (col - base > segments / 2.0) col -= segments;
                if (base - col > segments / 2.0) col += segments;
                u += p.bary[k] * col * chord;
                z += p.bary[k] * double(c[k] / segments) * height / rings;
            }
        };
        ExactGeodesic geo(m);
        ExactWorkspace ws;
        std::vector<double> d;
        for (int run = 0; run < 4; ++run) {
            const SurfacePoint src = randomPoint(m, rng);
            ExactQuery q;
            q.sources.push_back(GeodesicSource::atPoint(src));
            ws.run(geo, q, d);
            double su, sz;
            unrolled(src, su, sz);
            for (int i = 0; i < 200; ++i) {
                const SurfacePoint t = randomPoint(m, rng);
                double tu, tz;
                unrolled(t, tu, tz);
                double du = std::fmod(std::fabs(tu - su), perimeter);
                du = std::min(du, perimeter - du);
                CHECK(ws.distanceAt(t, d) == Approx(std::hypot(du, tz - sz)).epsilon(1e-9));
            }
        }
    }
}

TEST_CASE("robust on needles, noise, holes, saddles and several components", "[exact]") {
    std::vector<std::pair<const char*, Mesh>> meshes;
    meshes.emplace_back("needles", needleMesh());
    meshes.emplace_back("noisy sphere", noisy(icosphere(3), 0.02, 5));
    meshes.emplace_back("holes", gridWithHoles(16, 5));
    meshes.emplace_back("bumpy torus", bumpyTorus(60, 30));
    meshes.emplace_back("two components", twoComponents());
    for (auto& [name, m] : meshes) {
        INFO(name);
        ExactGeodesic geo(m);
        ExactWorkspace ws;
        std::vector<std::vector<double>> fields;
        const uint32_t sources[3] = {0, m.vertexCount() / 3, m.vertexCount() - 1};
        for (uint32_t s : sources) {
            ExactQuery q;
            q.sources.push_back(GeodesicSource::atVertex(s));
            std::vector<double> d;
            ws.run(geo, q, d);
            std::vector<double> dijkstra;
            edgeDijkstra(m, s, dijkstra);
            for (uint32_t v = 0; v < m.vertexCount(); ++v) {
                REQUIRE_FALSE(std::isnan(d[v]));
                // Never shorter than the straight line, never longer than the edge path;
                // unreachable exactly when Dijkstra cannot reach it either.
                REQUIRE(std::isinf(d[v]) == std::isinf(dijkstra[v]));
                if (std::isinf(d[v])) continue;
                REQUIRE(d[v] >= distance(m.positions[s], m.positions[v]) * (1 - 1e-12));
                REQUIRE(d[v] <= dijkstra[v] * (1 + 1e-12));
            }
            fields.push_back(d);
        }
        for (int i = 0; i < 3; ++i)  // symmetry
            for (int j = 0; j < 3; ++j)
                if (std::isfinite(fields[i][sources[j]]))
                    CHECK(fields[i][sources[j]] == Approx(fields[j][sources[i]]).epsilon(1e-9));
    }
}

TEST_CASE("vertices in another component are at infinity", "[exact]") {
    const Mesh m = twoComponents();
    auto d = field(m, 0);
    size_t inf = 0, finite = 0;
    for (double x : d) (std::isinf(x) ? inf : finite)++;
    CHECK(inf > 0);
    CHECK(finite > 0);
}

TEST_CASE("max distance and targets stop early without changing what they return", "[exact]") {
    const Mesh m = bumpyTorus(60, 30);
    ExactGeodesic geo(m);
    ExactWorkspace ws;
    ExactQuery full;
    full.sources.push_back(GeodesicSource::atVertex(11));
    std::vector<double> all, bounded, targeted;
    ExactStats fullStats, boundedStats, targetStats;
    ws.run(geo, full, all, &fullStats);

    ExactQuery b = full;
    b.maxDistance = 0.8;
    ws.run(geo, b, bounded, &boundedStats);
    for (uint32_t v = 0; v < m.vertexCount(); ++v) {
        if (all[v] <= 0.8) REQUIRE(bounded[v] == all[v]);
        else REQUIRE(std::isinf(bounded[v]));
    }
    CHECK(boundedStats.windowsPropagated < fullStats.windowsPropagated);

    ExactQuery t = full;
    t.targets = {12, 40, 75};
    ws.run(geo, t, targeted, &targetStats);
    for (uint32_t v : t.targets) CHECK(targeted[v] == all[v]);
    CHECK(targetStats.windowsPropagated < fullStats.windowsPropagated);
}

TEST_CASE("the parallel batch equals one run at a time", "[exact]") {
    const Mesh m = noisy(torus(1.0, 0.4, 40, 20), 0.01, 9);
    ExactGeodesic geo(m);
    std::vector<uint32_t> sources = {0, 7, 100, 333, 512, 799};
    auto batch = exactDistancesBatch(geo, sources);
    REQUIRE(batch.size() == sources.size());
    for (size_t i = 0; i < sources.size(); ++i) {
        CHECK(batch[i] == wavefrontDistancesFrom(geo, sources[i]));  // the batch's engine, bit for bit
        CHECK(maxRelativeError(batch[i], field(m, sources[i])) < 1e-12);  // and MMP, to rounding
    }
}

TEST_CASE("bad sources and targets are rejected", "[exact]") {
    const Mesh m = planeGrid(4, 4);
    ExactGeodesic geo(m);
    ExactWorkspace ws;
    std::vector<double> d;
    ExactQuery q;
    q.sources.push_back(GeodesicSource::atVertex(m.vertexCount()));
    CHECK_THROWS_AS(ws.run(geo, q, d), std::invalid_argument);
    q.sources = {GeodesicSource::atPoint({m.faceCount(), {1, 0, 0}})};
    CHECK_THROWS_AS(ws.run(geo, q, d), std::invalid_argument);
    q.sources = {GeodesicSource::atPoint({0, {0.5, 0.7, 0.1}})};
    CHECK_THROWS_AS(ws.run(geo, q, d), std::invalid_argument);
    q.sources = {GeodesicSource::atPoint({0, {NAN, 0.5, 0.5}})};
    CHECK_THROWS_AS(ws.run(geo, q, d), std::invalid_argument);
    q.sources = {GeodesicSource::atVertex(0)};
    q.targets = {m.vertexCount() + 3};
    CHECK_THROWS_AS(ws.run(geo, q, d), std::invalid_argument);
}

TEST_CASE("a patch pinched at a vertex is crossed through that vertex", "[exact]") {
    // Two 2x2-cell blocks of a 4x4 grid on [0,1]^2 that touch only at the centre.
    const Mesh m = planeGrid(4, 4, 1.0);
    std::vector<uint32_t> faces;
    for (uint32_t f = 0; f < m.faceCount(); ++f) {
        Vec3 c = (m.positions[m.faces[f][0]] + m.positions[m.faces[f][1]] + m.positions[m.faces[f][2]]) * (1.0 / 3);
        if ((c.x < 0.5 && c.y < 0.5) || (c.x > 0.5 && c.y > 0.5)) faces.push_back(f);
    }
    ExactGeodesic patch(m, faces);
    auto local = [&](double x, double y) {
        for (uint32_t v = 0; v < m.vertexCount(); ++v)
            if (std::fabs(m.positions[v].x - x) < 1e-9 && std::fabs(m.positions[v].y - y) < 1e-9)
                return patch.localVertex(v);
        return int64_t(-1);
    };
    ExactWorkspace ws;
    ExactQuery q;
    q.sources.push_back(GeodesicSource::atVertex(uint32_t(local(0.0, 0.5))));
    std::vector<double> d;
    ws.run(patch, q, d);
    CHECK(d[local(0.5, 1.0)] == Approx(1.0).epsilon(1e-12));   // through the pinch at (0.5, 0.5)
    CHECK(d[local(1.0, 1.0)] == Approx(0.5 + std::sqrt(0.5)).epsilon(1e-12));
    CHECK(patch.vertexCount() == 9 + 9);  // 17 points, the centre once per block
}
