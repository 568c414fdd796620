// Concurrency and determinism: many threads running mixed queries on one shared graph for
// a bounded time, checked bit for bit against one thread; repeated runs, fresh and reused
// workspaces, compressed and in-place handles; bakes with several thread counts.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <random>
#include <thread>

#include <tbb/global_control.h>

#include "bake.h"
#include "generators.h"
#include "runtime_graph.h"
#include "vorogeo.h"

using namespace vorogeo;
using tools::RuntimeGraph;
using tools::RuntimeWorkspace;

namespace {

std::vector<uint8_t> bake(const Mesh& mesh, bool compress, int threads, uint64_t seed = 1) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    BakeOptions o;
    o.compress = compress;
    o.seed = seed;
    BakeReport report;
    return bakeMesh(mesh, o, report);
}

// Two components (a torus and a grid), so that some answers are +infinity.
Mesh stressMesh() {
    Mesh mesh = bumpyTorus(48, 24);
    const Mesh grid = planeGrid(12, 12, 1.0, 0.2, 3);
    const uint32_t offset = mesh.vertexCount();
    mesh.positions.insert(mesh.positions.end(), grid.positions.begin(), grid.positions.end());
    for (Tri t : grid.faces) mesh.faces.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    REQUIRE(buildConnectivity(mesh).ok);
    return mesh;
}

// One query of any kind and its answer as raw words (floats by bits, indices as they are).
struct Query {
    enum Kind { Distance, Within, Nearest, Field, FieldNearest } kind;
    std::vector<uint32_t> vertices;  // source first, then targets or further sources
    float bound = 0;
};

// No Catch2 assertions in here: it runs on worker threads (Catch2 is not thread-safe).
// A failed call gives an empty answer, which never equals a reference answer.
std::vector<uint32_t> run(const vg_graph* g, vg_workspace* ws, const Query& q) {
    auto bits = [](float f) {
        uint32_t u;
        std::memcpy(&u, &f, 4);
        return u;
    };
    const uint32_t V = vg_vertex_count(g);
    std::vector<uint32_t> out;
    float d = 0;
    switch (q.kind) {
        case Query::Distance:
            if (vg_distance(g, ws, q.vertices[0], q.vertices[1], &d) != VG_OK) return {};
            out.push_back(bits(d));
            break;
        case Query::Within:
            if (vg_distance_within(g, ws, q.vertices[0], q.vertices[1], q.bound, &d) != VG_OK) return {};
            out.push_back(bits(d));
            break;
        case Query::Nearest: {
            size_t index = 0;
            if (vg_nearest(g, ws, q.vertices[0], q.vertices.data() + 1, q.vertices.size() - 1, &index, &d) != VG_OK)
                return {};
            out = {uint32_t(index), bits(d)};
            break;
        }
        case Query::Field:
        case Query::FieldNearest: {
            std::vector<float> field(V);
            std::vector<uint32_t> labels(V, 0xFFFFFFFFu);
            if (vg_distance_field_nearest(g, ws, q.vertices.data(), q.vertices.size(), field.data(),
                                          q.kind == Query::FieldNearest ? labels.data() : nullptr) != VG_OK)
                return {};
            for (float f : field) out.push_back(bits(f));
            out.insert(out.end(), labels.begin(), labels.end());
            break;
        }
    }
    return out;
}

std::vector<Query> mixedQueries(uint32_t V, size_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<uint32_t> pick(0, V - 1);
    std::vector<Query> queries;
    for (size_t i = 0; i < count; ++i) {
        Query q;
        q.kind = Query::Kind(i % 5);
        const size_t n = q.kind == Query::Nearest ? 9 : q.kind >= Query::Field ? 1 + i % 4 : 2;
        for (size_t k = 0; k < n; ++k) q.vertices.push_back(pick(rng));
        q.bound = std::uniform_real_distribution<float>(0.0f, 4.0f)(rng);
        queries.push_back(q);
    }
    return queries;
}

double stressSeconds() {
    const char* env = std::getenv("VOROGEO_STRESS_SECONDS");
    const double s = env ? std::atof(env) : 3.0;
    return s > 0 ? s : 3.0;
}

}  // namespace

TEST_CASE("stress: threads running mixed queries on one graph for a while match one thread", "[stress][runtime]") {
    const Mesh mesh = stressMesh();
    RuntimeGraph graph;
    std::string error;
    REQUIRE(graph.open(bake(mesh, true, 2), error));
    const vg_graph* g = graph.graph();
    const std::vector<Query> queries = mixedQueries(vg_vertex_count(g), 200, 11);

    std::vector<std::vector<uint32_t>> expected;
    {
        RuntimeWorkspace ws(graph);
        for (const Query& q : queries) expected.push_back(run(g, ws.get(), q));
    }
    for (const auto& e : expected) REQUIRE_FALSE(e.empty());
    // Some answers cross the components: +infinity, and nearest's "none reachable".
    const float inf = INFINITY;
    uint32_t infBits;
    std::memcpy(&infBits, &inf, 4);
    size_t infinite = 0;
    for (size_t i = 0; i < queries.size(); ++i)
        if (queries[i].kind == Query::Distance && expected[i][0] == infBits) ++infinite;
    CHECK(infinite > 0);

    const unsigned threads = std::max(4u, 2 * std::thread::hardware_concurrency());
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(stressSeconds());
    std::atomic<uint64_t> done{0}, mismatches{0};
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t) {
        pool.emplace_back([&, t] {
            RuntimeWorkspace ws(graph);  // one workspace per thread, reused for every query
            std::mt19937 rng(100 + t);
            std::uniform_int_distribution<size_t> pick(0, queries.size() - 1);
            while (std::chrono::steady_clock::now() < deadline) {
                const size_t i = pick(rng);
                if (run(g, ws.get(), queries[i]) != expected[i]) ++mismatches;
                ++done;
            }
        });
    }
    for (auto& t : pool) t.join();
    INFO(threads << " threads, " << done.load() << " queries");
    CHECK(done.load() >= threads);
    CHECK(mismatches.load() == 0);
}

TEST_CASE("determinism: answers do not depend on the workspace's history or the handle", "[stress][runtime]") {
    const Mesh mesh = stressMesh();
    RuntimeGraph compressed, inPlace;
    std::string error;
    REQUIRE(compressed.open(bake(mesh, true, 1), error));
    REQUIRE(inPlace.open(bake(mesh, false, 1), error));
    const std::vector<Query> queries = mixedQueries(compressed.vertexCount(), 60, 21);

    RuntimeWorkspace reused(compressed);
    for (const Query& q : queries) run(compressed.graph(), reused.get(), q);  // dirty it
    for (size_t i = 0; i < queries.size(); ++i) {
        RuntimeWorkspace fresh(compressed), other(inPlace);
        const std::vector<uint32_t> a = run(compressed.graph(), fresh.get(), queries[i]);
        REQUIRE_FALSE(a.empty());
        CHECK(run(compressed.graph(), reused.get(), queries[i]) == a);
        CHECK(run(inPlace.graph(), other.get(), queries[i]) == a);
        CHECK(run(compressed.graph(), fresh.get(), queries[i]) == a);  // and once more
    }
}

TEST_CASE("determinism: bakes with 1, 2, 3 and 4 threads, and repeated, give the same bytes", "[stress][bake]") {
    const Mesh mesh = stressMesh();
    const std::vector<uint8_t> reference = bake(mesh, true, 1);
    for (int threads : {2, 3, 4, 4}) {
        INFO(threads << " threads");
        CHECK(bake(mesh, true, threads) == reference);
    }
    CHECK(bake(mesh, true, 2, 9) != reference);  // the seed is an input
}
