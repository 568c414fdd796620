// Surface-point queries of the runtime (vg_point_*): agreement with vertex queries at
// vertices, exact answers where the local geometry decides them, accuracy against the
// exact engine run from surface points, k-nearest, and bad points.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <random>

#include "bake.h"
#include "generators.h"
#include "path_check.h"
#include "runtime_graph.h"
#include "runtime_stats.h"
#include "surface_points.h"
#include "vorogeo.h"

using namespace vorogeo;
using tools::RuntimeGraph;
using tools::RuntimeWorkspace;

namespace {

struct Baked {
    Mesh mesh;
    RuntimeGraph graph;
};

// One bake per generated mesh, shared by the test cases of one process.
const Baked& baked(const char* name) {
    static std::map<std::string, std::unique_ptr<Baked>> cache;
    std::unique_ptr<Baked>& slot = cache[name];
    if (!slot) {
        slot = std::make_unique<Baked>();
        const std::string n = name;
        slot->mesh = n == "plane" ? planeGrid(40, 40, 2.0, 0.3, 9) : n == "two" ? twoComponents() : bumpyTorus(60, 30);
        BakeOptions o;
        BakeReport report;
        std::string error;
        REQUIRE(slot->graph.open(bakeMesh(slot->mesh, o, report, nullptr), error));
    }
    return *slot;
}

float pointDistance(const RuntimeGraph& g, const RuntimeWorkspace& ws, const vg_point& a, const vg_point& b) {
    float d = -1;
    REQUIRE(vg_point_distance(g.graph(), ws.get(), &a, &b, &d) == VG_OK);
    return d;
}

}  // namespace

TEST_CASE("points: a point at a vertex answers as the vertex in every query", "[points]") {
    const Baked& b = baked("bumpy");
    RuntimeWorkspace ws(b.graph);
    const vg_graph* g = b.graph.graph();
    std::mt19937 rng(3);
    std::uniform_int_distribution<uint32_t> pick(0, b.mesh.vertexCount() - 1);
    for (int i = 0; i < 40; ++i) {
        const uint32_t s = pick(rng), t = pick(rng);
        vg_point ps, pt;
        REQUIRE(vg_vertex_point(g, s, &ps) == VG_OK);
        REQUIRE(vg_vertex_point(g, t, &pt) == VG_OK);
        CHECK(pointDistance(b.graph, ws, ps, pt) == ws.distance(s, t));
        float within = 0, bound = 0.5f * ws.distance(s, t);
        REQUIRE(vg_point_distance_within(g, ws.get(), &ps, &pt, bound, &within) == VG_OK);
        float vertexWithin = 0;
        REQUIRE(vg_distance_within(g, ws.get(), s, t, bound, &vertexWithin) == VG_OK);
        CHECK(within == vertexWithin);
    }
    const uint32_t sources[3] = {pick(rng), pick(rng), pick(rng)};
    vg_point points[3];
    for (int k = 0; k < 3; ++k) REQUIRE(vg_vertex_point(g, sources[k], &points[k]) == VG_OK);
    const uint32_t V = b.mesh.vertexCount();
    std::vector<float> fromVertices(V), fromPoints(V);
    std::vector<uint32_t> nearVertices(V), nearPoints(V);
    REQUIRE(vg_distance_field_nearest(g, ws.get(), sources, 3, fromVertices.data(), nearVertices.data()) == VG_OK);
    REQUIRE(vg_point_distance_field(g, ws.get(), points, 3, fromPoints.data(), nearPoints.data()) == VG_OK);
    CHECK(fromPoints == fromVertices);
    CHECK(nearPoints == nearVertices);
}

TEST_CASE("points: exact where the local geometry decides, symmetric everywhere", "[points]") {
    const Baked& b = baked("plane");
    RuntimeWorkspace ws(b.graph);
    // On a plane the geodesic is the straight segment: between points of one face, of faces
    // around one vertex (the fan paths) and, through the patch rows, farther apart.
    const std::vector<SurfacePoint> pts = tools::randomSurfacePoints(b.mesh, 400, 5);
    double worstNear = 0, worstFar = 0, sumFar = 0;
    size_t far = 0;
    for (size_t i = 0; i + 1 < pts.size(); i += 2) {
        const SurfacePoint& a = pts[i];
        // A neighbour of a: the same face, or a face around one of its corners.
        SurfacePoint near = pts[i + 1];
        const uint32_t corner = b.mesh.faces[a.face][i % 3];
        std::vector<uint32_t> around;
        for (uint32_t f = 0; f < b.mesh.faceCount(); ++f)
            for (int k = 0; k < 3; ++k)
                if (b.mesh.faces[f][k] == corner) around.push_back(f);
        near.face = around[(i / 2) % around.size()];
        for (const SurfacePoint& t : {near, pts[i + 1]}) {
            const vg_point pa = tools::toRuntimePoint(a), pt = tools::toRuntimePoint(t);
            const float d = pointDistance(b.graph, ws, pa, pt);
            CHECK(d == pointDistance(b.graph, ws, pt, pa));
            const double want = distance(positionOf(b.mesh, a), positionOf(b.mesh, t));
            const double err = std::fabs(d - want) / std::max(want, 1e-9);
            if (&t == &near) worstNear = std::max(worstNear, err);
            else {
                worstFar = std::max(worstFar, err);
                sumFar += err;
                ++far;
            }
        }
    }
    // Random pairs bend at a graph node where their segment crosses a patch border next
    // to a third patch (as vertex pairs do): a few percent at worst, for short pairs.
    INFO("worst relative error: neighbours " << worstNear << ", random pairs " << worstFar << " (mean "
                                             << sumFar / far << ")");
    CHECK(worstNear < 1e-4);
    CHECK(sumFar / far < 0.002);
    CHECK(worstFar < 0.04);
}

TEST_CASE("points: accuracy against the exact engine run from surface points", "[points]") {
    const Baked& b = baked("bumpy");
    RuntimeWorkspace ws(b.graph);
    const std::vector<tools::PointPair> pairs = tools::exactPointPairs(b.mesh, 1000, 50, 17);
    std::vector<tools::DistancePair> asPairs;
    std::vector<double> values;
    for (const tools::PointPair& p : pairs) {
        values.push_back(pointDistance(b.graph, ws, tools::toRuntimePoint(p.source), tools::toRuntimePoint(p.target)));
        asPairs.push_back({p.source.face, p.target.face, p.distance});
    }
    const tools::AccuracyReport r = tools::errorStatistics(asPairs, values);
    INFO("mean " << r.meanRel << " p99 " << r.p99Rel << " max " << r.maxRel);
    CHECK(r.pairs == pairs.size());
    CHECK(r.meanRel < 0.005);
    CHECK(r.maxRel < 0.06);
    // The field from a point agrees with point-to-point at the vertices (both are the same
    // graph distance up to where the border crossings are unfolded).
    const vg_point src = tools::toRuntimePoint(pairs[0].source);
    std::vector<float> field(b.mesh.vertexCount());
    REQUIRE(vg_point_distance_field(b.graph.graph(), ws.get(), &src, 1, field.data(), nullptr) == VG_OK);
    double worst = 0;
    for (uint32_t v = 0; v < b.mesh.vertexCount(); v += 7) {
        vg_point pv;
        REQUIRE(vg_vertex_point(b.graph.graph(), v, &pv) == VG_OK);
        const float d = pointDistance(b.graph, ws, src, pv);
        worst = std::max(worst, std::fabs(double(d) - field[v]) / std::max(double(d), 1e-9));
    }
    CHECK(worst < 0.03);
}

TEST_CASE("points: k nearest are the k smallest distances, in order, across target chunks", "[points]") {
    const Baked& b = baked("bumpy");
    RuntimeWorkspace ws(b.graph);
    const vg_graph* g = b.graph.graph();
    std::vector<vg_point> targets;
    for (const SurfacePoint& p : tools::randomSurfacePoints(b.mesh, 3000, 23)) targets.push_back(tools::toRuntimePoint(p));
    targets[10] = targets[20];  // a duplicate: ties go to the lower index
    const vg_point source = tools::toRuntimePoint(tools::randomSurfacePoints(b.mesh, 1, 29)[0]);
    const size_t k = 16;
    std::vector<size_t> index(k);
    std::vector<float> dist(k);
    size_t found = 0;
    REQUIRE(vg_point_k_nearest(g, ws.get(), &source, targets.data(), targets.size(), k, index.data(), dist.data(),
                               &found) == VG_OK);
    REQUIRE(found == k);
    // Reference: every target's point-to-point distance.
    std::vector<std::pair<float, size_t>> all;
    for (size_t i = 0; i < targets.size(); ++i) all.push_back({pointDistance(b.graph, ws, source, targets[i]), i});
    std::sort(all.begin(), all.end());
    // The same distances as point-to-point up to the unfolded border crossings that only
    // point-to-point adds (shorter by less than kUnfoldSlack, 15%), so the same set up to such ties.
    for (size_t j = 0; j < k; ++j) {
        INFO("rank " << j);
        if (j > 0) CHECK(dist[j] >= dist[j - 1]);
        CHECK(std::count(index.begin(), index.end(), index[j]) == 1);
        const float p2p = pointDistance(b.graph, ws, source, targets[index[j]]);
        CHECK(p2p <= dist[j] * 1.0001f);
        CHECK(p2p >= dist[j] / 1.15f);  // kUnfoldSlack bounds what a crossing saves
        CHECK(dist[j] <= all[j].first * 1.15f);
    }
    for (size_t j = k; j < all.size(); ++j)
        if (std::find(index.begin(), index.end(), all[j].second) == index.end()) CHECK(all[j].first >= dist[k - 1] / 1.15f);
    // The nearest is the first of the k.
    size_t nearest = 0;
    float nd = 0;
    REQUIRE(vg_point_nearest(g, ws.get(), &source, targets.data(), targets.size(), &nearest, &nd) == VG_OK);
    CHECK(nearest == index[0]);
    CHECK(nd == dist[0]);
    // Fewer reachable targets than k: the rest is target_count / +inf.
    std::vector<size_t> index2(5);
    std::vector<float> dist2(5);
    REQUIRE(vg_point_k_nearest(g, ws.get(), &source, targets.data(), 3, 5, index2.data(), dist2.data(), &found) == VG_OK);
    CHECK(found == 3);
    CHECK(index2[3] == 3);
    CHECK(std::isinf(dist2[4]));
}

TEST_CASE("points: other components are at +infinity, bad points get VG_ERR_INVALID_POINT", "[points]") {
    const Baked& b = baked("two");
    RuntimeWorkspace ws(b.graph);
    const vg_graph* g = b.graph.graph();
    // A face of each component: follow the field from face 0's first vertex.
    const std::vector<float> field = ws.field({b.mesh.faces[0][0]});
    uint32_t other = UINT32_MAX;
    for (uint32_t f = 0; f < b.mesh.faceCount() && other == UINT32_MAX; ++f)
        if (std::isinf(field[b.mesh.faces[f][0]])) other = f;
    REQUIRE(other != UINT32_MAX);
    const vg_point a{0, {0.2f, 0.3f, 0.5f}}, c{other, {0.3f, 0.3f, 0.4f}};
    CHECK(std::isinf(pointDistance(b.graph, ws, a, c)));
    size_t index = 7;
    float d = 0;
    REQUIRE(vg_point_nearest(g, ws.get(), &a, &c, 1, &index, &d) == VG_OK);
    CHECK(index == 1);
    CHECK(std::isinf(d));

    const uint32_t F = vg_face_count(g);
    CHECK(F == b.mesh.faceCount());
    const float nan = std::nanf("");
    const vg_point bad[] = {{F, {1.0f / 3, 1.0f / 3, 1.0f / 3}}, {0, {nan, 0.5f, 0.5f}}, {0, {-0.1f, 0.6f, 0.5f}},
                            {0, {0.5f, 0.5f, 0.5f}}, {0, {INFINITY, 0.0f, 0.0f}}};
    for (const vg_point& p : bad) {
        CHECK(vg_point_distance(g, ws.get(), &p, &a, &d) == VG_ERR_INVALID_POINT);
        CHECK(vg_point_distance_within(g, ws.get(), &a, &p, 1.0f, &d) == VG_ERR_INVALID_POINT);
        std::vector<float> out(b.mesh.vertexCount());
        CHECK(vg_point_distance_field(g, ws.get(), &p, 1, out.data(), nullptr) == VG_ERR_INVALID_POINT);
        CHECK(vg_point_nearest(g, ws.get(), &a, &p, 1, &index, &d) == VG_ERR_INVALID_POINT);
        size_t found = 0;
        CHECK(vg_point_k_nearest(g, ws.get(), &p, &a, 1, 1, &index, &d, &found) == VG_ERR_INVALID_POINT);
        float xyz[3];
        CHECK(vg_point_position(g, &p, xyz) == VG_ERR_INVALID_POINT);
    }
    // Within the tolerance: accepted and renormalised.
    const vg_point slightly{0, {0.5f + 5e-5f, 0.5f, -5e-5f}};
    CHECK(vg_point_distance(g, ws.get(), &slightly, &a, &d) == VG_OK);
    uint32_t corners[3];
    CHECK(vg_face_vertices(g, F, corners) == VG_ERR_INVALID_POINT);
    REQUIRE(vg_face_vertices(g, 0, corners) == VG_OK);
    CHECK(corners[0] == b.mesh.faces[0][0]);
    vg_point at;
    CHECK(vg_vertex_point(g, b.mesh.vertexCount(), &at) == VG_ERR_INVALID_VERTEX);
    CHECK(vg_point_distance(g, ws.get(), nullptr, &a, &d) == VG_ERR_INVALID_ARGUMENT);
}

namespace {

// vg_path into a vector (size query, then the call); the distance it returns.
float pathBetween(const RuntimeGraph& g, const RuntimeWorkspace& ws, const vg_point& a, const vg_point& b,
                  std::vector<vg_path_point>& out) {
    size_t count = 0;
    float d = -1;
    REQUIRE(vg_path(g.graph(), ws.get(), &a, &b, nullptr, 0, &count, &d) == VG_OK);
    out.assign(count, vg_path_point{});
    size_t written = 0;
    float again = -1;
    REQUIRE(vg_path(g.graph(), ws.get(), &a, &b, out.data(), out.size(), &written, &again) == VG_OK);
    REQUIRE(written == count);
    REQUIRE(again == d);
    return d;
}

// Relative differences of path length and vg_point_distance over random point pairs,
// with every path checked to lie on the surface, to join its two points and to come with
// its own length as the distance.
std::vector<double> pathLengthDifferences(const Baked& b, size_t pairs, uint64_t seed) {
    RuntimeWorkspace ws(b.graph);
    const tools::PathChecker checker(b.mesh);
    const std::vector<SurfacePoint> pts = tools::randomSurfacePoints(b.mesh, 2 * pairs, seed);
    std::vector<double> diffs;
    std::vector<vg_path_point> path;
    for (size_t i = 0; i < pairs; ++i) {
        const vg_point s = tools::toRuntimePoint(pts[2 * i]), t = tools::toRuntimePoint(pts[2 * i + 1]);
        const float d = pathBetween(b.graph, ws, s, t, path);
        const float searched = pointDistance(b.graph, ws, s, t);
        const tools::PathCheck c = checker.check(path);
        CHECK(d == Approx(c.length).epsilon(1e-6));
        INFO("pair " << i << ": " << c.problem);
        CHECK(c.ok);
        REQUIRE(path.size() >= 2);
        float ps[3], pt[3];
        REQUIRE(vg_point_position(b.graph.graph(), &s, ps) == VG_OK);
        REQUIRE(vg_point_position(b.graph.graph(), &t, pt) == VG_OK);
        for (int k = 0; k < 3; ++k) {
            CHECK(path.front().position[k] == Approx(ps[k]).margin(1e-6));
            CHECK(path.back().position[k] == Approx(pt[k]).margin(1e-6));
        }
        diffs.push_back(std::fabs(c.length - searched) / searched);
    }
    std::sort(diffs.begin(), diffs.end());
    return diffs;
}

}  // namespace

TEST_CASE("paths: on the surface, joining the points, as long as vg_point_distance", "[points][paths]") {
    // Both estimate the geodesic; they part most on coarse meshes (1,800 and 1,600
    // vertices, a few dozen per patch), where the search's distance is least exact.
    for (const char* name : {"bumpy", "plane"}) {
        const std::vector<double> diffs = pathLengthDifferences(baked(name), 300, 41);
        const double median = diffs[diffs.size() / 2], p90 = diffs[diffs.size() * 9 / 10];
        INFO(name << ": length vs vg_point_distance median " << median << ", p90 " << p90 << ", max " << diffs.back());
        CHECK(median < 2e-3);  // measured 0.13% (bumpy), 0.03% (plane)
        CHECK(p90 < 1e-2);
        CHECK(diffs.back() < 0.05);
    }
}

TEST_CASE("paths: pulled taut, within a hair of the exact geodesic", "[points][paths]") {
    const Baked& b = baked("bumpy");
    RuntimeWorkspace ws(b.graph);
    const std::vector<tools::PointPair> pairs = tools::exactPointPairs(b.mesh, 400, 20, 59);
    std::vector<vg_path_point> path;
    double sum = 0, worst = 0, shortest = 1;
    for (const tools::PointPair& p : pairs) {
        const vg_point s = tools::toRuntimePoint(p.source), t = tools::toRuntimePoint(p.target);
        const float d = pathBetween(b.graph, ws, s, t, path);
        const double excess = (tools::polylineLength(path) - p.distance) / p.distance;
        sum += excess;
        worst = std::max(worst, excess);
        shortest = std::min(shortest, excess);
        // A path on the surface is never shorter than the geodesic (float rounding aside),
        // and the distance it reports is its length.
        CHECK(excess > -1e-5);
        CHECK(d == Approx(tools::polylineLength(path)).epsilon(1e-6));
    }
    const double mean = sum / double(pairs.size());
    INFO("path length over the exact distance: mean " << mean << ", max " << worst << ", min " << shortest);
    CHECK(mean < 5e-4);
    CHECK(worst < 0.02);
}

TEST_CASE("paths: on a plane, the straight segment", "[points][paths]") {
    const Baked& b = baked("plane");
    RuntimeWorkspace ws(b.graph);
    const std::vector<SurfacePoint> pts = tools::randomSurfacePoints(b.mesh, 200, 43);
    std::vector<vg_path_point> path;
    double worst = 0;
    for (size_t i = 0; i + 1 < pts.size(); i += 2) {
        pathBetween(b.graph, ws, tools::toRuntimePoint(pts[i]), tools::toRuntimePoint(pts[i + 1]), path);
        const double straight = distance(positionOf(b.mesh, pts[i]), positionOf(b.mesh, pts[i + 1]));
        worst = std::max(worst, (tools::polylineLength(path) - straight) / straight);
    }
    // Pulled taut, the path is the segment up to what the last pass left over (the passes
    // stop when a bend is less than 0.05 rad short or a pass gains under 0.02%).
    INFO("worst excess over the straight segment " << worst);
    CHECK(worst < 1e-3);
}

TEST_CASE("paths: the reverse path is the same polyline backwards", "[points][paths]") {
    const Baked& b = baked("bumpy");
    RuntimeWorkspace ws(b.graph);
    const std::vector<SurfacePoint> pts = tools::randomSurfacePoints(b.mesh, 40, 47);
    std::vector<vg_path_point> forward, backward;
    for (size_t i = 0; i + 1 < pts.size(); i += 2) {
        const vg_point s = tools::toRuntimePoint(pts[i]), t = tools::toRuntimePoint(pts[i + 1]);
        CHECK(pathBetween(b.graph, ws, s, t, forward) == pathBetween(b.graph, ws, t, s, backward));
        REQUIRE(forward.size() == backward.size());
        for (size_t k = 0; k < forward.size(); ++k)
            for (int c = 0; c < 3; ++c) CHECK(forward[k].position[c] == backward[forward.size() - 1 - k].position[c]);
    }
}

TEST_CASE("paths: size query, small buffers, one point, other components, bad input", "[points][paths]") {
    const Baked& b = baked("bumpy");
    RuntimeWorkspace ws(b.graph);
    const vg_graph* g = b.graph.graph();
    const std::vector<SurfacePoint> pts = tools::randomSurfacePoints(b.mesh, 2, 53);
    const vg_point s = tools::toRuntimePoint(pts[0]), t = tools::toRuntimePoint(pts[1]);
    std::vector<vg_path_point> full;
    const float d = pathBetween(b.graph, ws, s, t, full);
    REQUIRE(full.size() > 2);
    // Too small: the needed count, whatever the capacity.
    std::vector<vg_path_point> small(full.size() - 1);
    size_t count = 0;
    float got = 0;
    CHECK(vg_path(g, ws.get(), &s, &t, small.data(), small.size(), &count, &got) == VG_ERR_BUFFER_TOO_SMALL);
    CHECK(count == full.size());
    CHECK(got == d);
    std::vector<vg_path_point> roomy(full.size() + 10);
    CHECK(vg_path(g, ws.get(), &s, &t, roomy.data(), roomy.size(), &count, &got) == VG_OK);
    CHECK(count == full.size());
    for (size_t k = 0; k < full.size(); ++k) CHECK(roomy[k].position[0] == full[k].position[0]);
    // The same point: one point, distance 0.
    CHECK(vg_path(g, ws.get(), &s, &s, roomy.data(), roomy.size(), &count, &got) == VG_OK);
    CHECK(count == 1);
    CHECK(got == 0.0f);
    // Bad input.
    vg_point bad = s;
    bad.face = vg_face_count(g);
    CHECK(vg_path(g, ws.get(), &bad, &t, roomy.data(), roomy.size(), &count, &got) == VG_ERR_INVALID_POINT);
    bad = s;
    bad.bary[0] = NAN;
    CHECK(vg_path(g, ws.get(), &s, &bad, roomy.data(), roomy.size(), &count, &got) == VG_ERR_INVALID_POINT);
    CHECK(vg_path(g, ws.get(), &s, &t, nullptr, 5, &count, &got) == VG_ERR_INVALID_ARGUMENT);
    CHECK(vg_path(g, ws.get(), &s, &t, roomy.data(), roomy.size(), nullptr, &got) == VG_ERR_INVALID_ARGUMENT);
    CHECK(vg_path(g, ws.get(), &s, &t, roomy.data(), roomy.size(), &count, nullptr) == VG_ERR_INVALID_ARGUMENT);
    CHECK(vg_path(g, ws.get(), nullptr, &t, roomy.data(), roomy.size(), &count, &got) == VG_ERR_INVALID_ARGUMENT);
    // Other components: no path.
    const Baked& two = baked("two");
    RuntimeWorkspace ws2(two.graph);
    uint32_t fa[3], fb[3];
    const uint32_t F = vg_face_count(two.graph.graph());
    REQUIRE(vg_face_vertices(two.graph.graph(), 0, fa) == VG_OK);
    REQUIRE(vg_face_vertices(two.graph.graph(), F - 1, fb) == VG_OK);
    const vg_point p0{0, {0.3f, 0.3f, 0.4f}}, p1{F - 1, {0.3f, 0.3f, 0.4f}};
    float pd = 0;
    REQUIRE(vg_point_distance(two.graph.graph(), ws2.get(), &p0, &p1, &pd) == VG_OK);
    REQUIRE(pd == INFINITY);  // the first and last faces lie on different components
    CHECK(vg_path(two.graph.graph(), ws2.get(), &p0, &p1, roomy.data(), roomy.size(), &count, &got) == VG_OK);
    CHECK(count == 0);
    CHECK(got == INFINITY);
}
