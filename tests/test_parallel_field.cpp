// vg_distance_field_parallel (and its surface-point twin): one one-to-all query whose fill
// several workspaces share, on threads or in turn, against the one-thread query bit for
// bit; and its argument checks.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <thread>
#include <vector>

#include "bake.h"
#include "blob_test_helpers.h"
#include "generators.h"
#include "mesh_io.h"
#include "runtime_graph.h"
#include "vorogeo.h"

using namespace vorogeo;
using tools::RuntimeGraph;
using tools::RuntimeWorkspace;

namespace {

std::vector<uint8_t> bakeTorus(double delta, BakeReport& report) {
    BakeOptions o;
    o.delta = delta;
    return bakeMesh(bumpyTorus(60, 30), o, report, nullptr);  // 1,800 vertices
}

// Schedulers for the tasks: each on a thread of its own, and in turn backwards (any order
// must do). Both count the calls, which must be exactly one per query.
struct Scheduler {
    bool threads = true;
    int calls = 0;
    uint32_t lastCount = 0;
};

void runTasks(void* user, uint32_t count, vg_task task, void* context) {
    Scheduler& s = *static_cast<Scheduler*>(user);
    ++s.calls;
    s.lastCount = count;
    if (!s.threads) {
        for (uint32_t i = count; i-- > 0;) task(context, i);
        return;
    }
    std::vector<std::thread> workers;
    for (uint32_t i = 0; i < count; ++i) workers.emplace_back([=] { task(context, i); });
    for (std::thread& w : workers) w.join();
}

}  // namespace

TEST_CASE("runtime: a one-to-all query on several threads gives the one-thread bits", "[runtime][parallel]") {
    // The plain graph, and a pruned one whose merged-away nodes lie in several patches (the
    // parallel fill leaves them to one pass at the end).
    for (const double delta : {0.0, 0.03}) {
        INFO("delta " << delta);
        BakeReport report;
        RuntimeGraph g = openOrFail(bakeTorus(delta, report));
        if (delta > 0) REQUIRE(report.secondPrune.prunedNodes > 0);
        const vg_graph* graph = g.graph();
        const uint32_t V = g.vertexCount();
        std::vector<RuntimeWorkspace> pool;
        for (int i = 0; i < 4; ++i) pool.emplace_back(graph);
        std::vector<vg_workspace*> workspaces;
        for (const RuntimeWorkspace& w : pool) workspaces.push_back(w.get());
        RuntimeWorkspace reference(graph);
        const std::vector<std::vector<uint32_t>> sourceSets = {{5}, {0, V / 2, V / 2, 1234}};
        for (const std::vector<uint32_t>& sources : sourceSets) {
            std::vector<float> expected(V);
            std::vector<uint32_t> expectedNearest(V);
            REQUIRE(vg_distance_field_nearest(graph, reference.get(), sources.data(), sources.size(), expected.data(),
                                              expectedNearest.data()) == VG_OK);
            for (uint32_t count = 1; count <= 4; ++count) {
                for (const int how : {0, 1, 2}) {  // NULL (in turn), threads, backwards
                    INFO(sources.size() << " sources, " << count << " workspaces, scheduler " << how);
                    Scheduler s;
                    s.threads = how == 1;
                    std::vector<float> got(V, -1.0f);
                    std::vector<uint32_t> nearest(V, 7u);
                    REQUIRE(vg_distance_field_parallel(graph, workspaces.data(), count, sources.data(), sources.size(),
                                                       got.data(), nearest.data(), how == 0 ? nullptr : runTasks,
                                                       &s) == VG_OK);
                    CHECK(std::memcmp(got.data(), expected.data(), V * sizeof(float)) == 0);
                    CHECK(nearest == expectedNearest);
                    if (how != 0) {
                        CHECK(s.calls == 1);
                        CHECK(s.lastCount == count);
                    }
                    // Without `nearest`, the same distances.
                    std::fill(got.begin(), got.end(), -1.0f);
                    REQUIRE(vg_distance_field_parallel(graph, workspaces.data(), count, sources.data(), sources.size(),
                                                       got.data(), nullptr, how == 0 ? nullptr : runTasks,
                                                       &s) == VG_OK);
                    CHECK(std::memcmp(got.data(), expected.data(), V * sizeof(float)) == 0);
                }
            }
        }
    }
}

TEST_CASE("runtime: one-to-all writes every output entry whatever the buffers held", "[runtime][parallel]") {
    // The outputs start uninitialised except at unused vertices: writeNodes writes every
    // node's vertex (unreached ones at +inf) and each patch its interior vertices. Two
    // components, a vertex used by no face and a pruned graph (merged-away nodes) cover
    // what no search reaches.
    Mesh mesh = twoComponents();
    mesh.positions.push_back({7.0, 7.0, 7.0});
    REQUIRE(prepareMesh("two+1", LoadOptions(), mesh).ok);
    const uint32_t lonely = mesh.vertexCount() - 1;
    for (const double delta : {0.0, 0.03}) {
        INFO("delta " << delta);
        BakeOptions o;
        o.delta = delta;
        BakeReport report;
        RuntimeGraph g = openOrFail(bakeMesh(mesh, o, report, nullptr));
        if (delta > 0) REQUIRE(report.secondPrune.prunedNodes > 0);
        const vg_graph* graph = g.graph();
        const uint32_t V = g.vertexCount();
        REQUIRE(V == mesh.vertexCount());
        RuntimeWorkspace a(graph), b(graph);
        vg_workspace* both[2] = {a.get(), b.get()};
        const uint32_t sources[2] = {0, 3};
        std::vector<float> reference;
        std::vector<uint32_t> referenceNearest;
        for (const int how : {0, 1, 2}) {  // one thread, two on threads, sliced
            for (const uint32_t fill : {0x7FC00001u, 0u, 0xDEADBEEFu}) {  // a NaN, zero, garbage
                INFO("query " << how << ", buffers held " << std::hex << fill);
                float fillValue;
                std::memcpy(&fillValue, &fill, sizeof fillValue);
                std::vector<float> out(V, fillValue);
                std::vector<uint32_t> nearest(V, fill);
                if (how == 0) {
                    REQUIRE(vg_distance_field_nearest(graph, a.get(), sources, 2, out.data(), nearest.data()) == VG_OK);
                } else if (how == 1) {
                    Scheduler s;
                    REQUIRE(vg_distance_field_parallel(graph, both, 2, sources, 2, out.data(), nearest.data(), runTasks,
                                                       &s) == VG_OK);
                } else {
                    REQUIRE(vg_distance_field_begin(graph, a.get(), sources, 2, out.data(), nearest.data()) == VG_OK);
                    int done = 0;
                    while (!done) REQUIRE(vg_distance_field_step(graph, a.get(), 5, &done) == VG_OK);
                }
                uint32_t reached = 0, unreached = 0;
                for (uint32_t v = 0; v < V; ++v) {
                    INFO("vertex " << v);
                    const bool finite = std::isfinite(out[v]);
                    REQUIRE((finite || (std::isinf(out[v]) && out[v] > 0)));
                    REQUIRE(nearest[v] == (finite ? nearest[v] : 2u));
                    REQUIRE((!finite || nearest[v] < 2));
                    (finite ? reached : unreached)++;
                }
                CHECK(std::isinf(out[lonely]));
                CHECK(nearest[lonely] == 2);
                CHECK(reached > V / 4);
                CHECK(unreached > V / 4);  // the other component
                if (reference.empty()) {
                    reference = out;
                    referenceNearest = nearest;
                }
                CHECK(std::memcmp(out.data(), reference.data(), V * sizeof(float)) == 0);
                CHECK(nearest == referenceNearest);
            }
        }
    }
}

TEST_CASE("runtime: a one-to-all query from surface points on several threads gives the one-thread bits",
          "[runtime][parallel]") {
    BakeReport report;
    RuntimeGraph g = openOrFail(bakeTorus(0.0, report));
    const vg_graph* graph = g.graph();
    const uint32_t V = g.vertexCount(), F = vg_face_count(graph);
    RuntimeWorkspace reference(graph), a(graph), b(graph);
    vg_workspace* const two[2] = {a.get(), b.get()};
    const std::vector<vg_point> points = {{3, {0.2f, 0.3f, 0.5f}}, {F / 2, {1.0f, 0.0f, 0.0f}}, {F - 1, {0.1f, 0.1f, 0.8f}}};
    std::vector<float> expected(V), got(V);
    std::vector<uint32_t> expectedNearest(V), nearest(V);
    REQUIRE(vg_point_distance_field(graph, reference.get(), points.data(), points.size(), expected.data(),
                                    expectedNearest.data()) == VG_OK);
    for (const bool threads : {false, true}) {
        Scheduler s;
        s.threads = threads;
        REQUIRE(vg_point_distance_field_parallel(graph, two, 2, points.data(), points.size(), got.data(),
                                                 nearest.data(), runTasks, &s) == VG_OK);
        CHECK(std::memcmp(got.data(), expected.data(), V * sizeof(float)) == 0);
        CHECK(nearest == expectedNearest);
        CHECK(s.calls == 1);
    }
    const vg_point bad[1] = {{F, {0.2f, 0.3f, 0.5f}}};
    CHECK(vg_point_distance_field_parallel(graph, two, 2, bad, 1, got.data(), nullptr, nullptr, nullptr) ==
          VG_ERR_INVALID_POINT);
    CHECK(vg_point_distance_field_parallel(graph, two, 2, nullptr, 1, got.data(), nullptr, nullptr, nullptr) ==
          VG_ERR_INVALID_ARGUMENT);
}

TEST_CASE("runtime: vg_distance_field_parallel names bad workspaces and arguments", "[runtime][parallel]") {
    BakeReport report;
    RuntimeGraph g = openOrFail(bakeTorus(0.0, report));
    RuntimeGraph other = openOrFail(bakeTorus(0.0, report));
    const vg_graph* graph = g.graph();
    const uint32_t V = g.vertexCount();
    RuntimeWorkspace a(graph), b(graph), foreign(other.graph());
    std::vector<float> out(V);
    const uint32_t source = 3, bad = V;
    vg_workspace* const two[2] = {a.get(), b.get()};
    vg_workspace* const repeated[2] = {a.get(), a.get()};
    vg_workspace* const withNull[2] = {a.get(), nullptr};
    vg_workspace* const mixed[2] = {a.get(), foreign.get()};
    auto run = [&](vg_workspace* const* ws, uint32_t n, const uint32_t* s, float* o) {
        return vg_distance_field_parallel(graph, ws, n, s, 1, o, nullptr, nullptr, nullptr);
    };
    CHECK(run(nullptr, 2, &source, out.data()) == VG_ERR_INVALID_ARGUMENT);
    CHECK(run(two, 0, &source, out.data()) == VG_ERR_INVALID_ARGUMENT);
    CHECK(run(repeated, 2, &source, out.data()) == VG_ERR_INVALID_ARGUMENT);
    CHECK(run(withNull, 2, &source, out.data()) == VG_ERR_INVALID_ARGUMENT);
    CHECK(run(mixed, 2, &source, out.data()) == VG_ERR_WRONG_WORKSPACE);
    CHECK(run(two, 2, &bad, out.data()) == VG_ERR_INVALID_VERTEX);
    CHECK(run(two, 2, &source, nullptr) == VG_ERR_INVALID_ARGUMENT);
    CHECK(vg_distance_field_parallel(nullptr, two, 2, &source, 1, out.data(), nullptr, nullptr, nullptr) ==
          VG_ERR_INVALID_ARGUMENT);

    // A sliced query on a helper workspace ends: the call took the workspace.
    std::vector<float> sliced(V);
    int done = 0;
    REQUIRE(vg_distance_field_begin(graph, b.get(), &source, 1, sliced.data(), nullptr) == VG_OK);
    REQUIRE(vg_distance_field_step(graph, b.get(), 1, &done) == VG_OK);
    REQUIRE(run(two, 2, &source, out.data()) == VG_OK);
    CHECK(vg_distance_field_step(graph, b.get(), 1, &done) == VG_ERR_NO_SLICED_QUERY);
    CHECK(out[source] == 0.0f);
}
