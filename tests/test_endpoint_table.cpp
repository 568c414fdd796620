// The endpoint table (vg_endpoint_table_*, runtime/src/vg_endpoint_table.h): a label query
// that reads it takes the same steps per endpoint and gives the same answers, bit for bit,
// as one that works them out from the inner rows; pruned and full reads, on a plain graph
// and on one whose pruning merged nodes away; the portable and AVX2 kernels build the same
// bytes and read them alike. Pairs inside one first-layer patch, which only the table's
// node distances answer (vg_patch_pairs.cpp), are symmetric, bounded as asked, and at
// least as close to the exact distances as the searches they replace. The size query, the
// build and the workspace's use of it refuse what they must.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "bake.h"
#include "blob_test_helpers.h"
#include "generators.h"
#include "geodesic_exact.h"
#include "runtime_graph.h"
#include "vg_endpoint_table.h"
#include "vg_hub_labels.h"
#include "vg_patch_pairs.h"
#include "vorogeo.h"

using namespace vorogeo;
using tools::EndpointTable;
using tools::RuntimeGraph;
using tools::RuntimeWorkspace;

namespace {

std::vector<uint8_t> bakeTorus(bool hubLabels, double delta) {
    BakeOptions o;
    o.n1 = 10;
    o.delta = delta;
    o.hubLabels = hubLabels;
    BakeReport report;
    return bakeMesh(bumpyTorus(120, 40), o, report, nullptr);  // 4,800 vertices
}

}  // namespace

TEST_CASE("endpoint table: the same steps and answers as without it", "[hub][table]") {
    for (const double delta : {0.0, 0.002}) {
        RuntimeGraph g = openOrFail(bakeTorus(true, delta));
        const vg_graph& graph = *g.graph();
        const EndpointTable table(g.graph());
        REQUIRE(table.get() != nullptr);
        RuntimeWorkspace plain(g.graph()), fast(g.graph());
        fast.useTable(table);

        // Every vertex's steps to its patch's first-layer nodes, entry by entry, and its
        // landmark distances.
        std::vector<uint16_t> mine(65536), theirs(65536);
        std::vector<float> ownLandmarks(64), tableLandmarks(64);
        size_t endpoints = 0, entries = 0, landmarked = 0;
        for (uint32_t x = 0; x < graph.vertexCount; ++x) {
            const uint32_t n = vg::hubEndpointSteps(graph, *plain.get(), x, mine.data());
            REQUIRE(vg::hubEndpointSteps(graph, *fast.get(), x, theirs.data()) == n);
            endpoints += n > 0;
            for (uint32_t k = 0; k < n; ++k) entries += mine[k] != 65535;
            CHECK(std::equal(mine.begin(), mine.begin() + n, theirs.begin()));
            const float slack = vg::hubEndpointLandmarks(graph, *plain.get(), x, ownLandmarks.data());
            CHECK(vg::hubEndpointLandmarks(graph, *fast.get(), x, tableLandmarks.data()) == slack);
            if (slack < 0) continue;
            ++landmarked;
            CHECK(std::equal(ownLandmarks.begin(), ownLandmarks.begin() + graph.landmarkCount, tableLandmarks.begin()));
        }
        CHECK(graph.landmarkCount > 0);
        CHECK(landmarked > graph.vertexCount / 2);
        CHECK(endpoints > graph.vertexCount / 2);
        CHECK(entries > endpoints * 10);  // real distances, not "no path"

        // Random pairs: the label answers, pruned and full, and through the API.
        std::mt19937 rng(5);
        std::uniform_int_distribution<uint32_t> pick(0, graph.vertexCount - 1);
        size_t answered = 0, differ = 0;
        for (int i = 0; i < 3000; ++i) {
            const uint32_t s = pick(rng), t = pick(rng);
            for (const bool prune : {true, false}) {
                float a = 0, b = 0;
                const bool labelled = vg::hubDistance(graph, *plain.get(), s, t, __builtin_inff(), &a, prune);
                REQUIRE(vg::hubDistance(graph, *fast.get(), s, t, __builtin_inff(), &b, prune) == labelled);
                answered += labelled && prune;
                differ += labelled && a != b;
            }
            // Pairs inside one first-layer patch are the table's own (the next test).
            float inPatch = 0;
            if (!vg::patchPairDistance(graph, *fast.get(), s, t, __builtin_inff(), &inPatch))
                differ += plain.distance(s, t) != fast.distance(s, t);
            else
                differ += fast.distance(s, t) != inPatch;
        }
        CHECK(answered > 1500);
        CHECK(differ == 0);
    }
}

TEST_CASE("endpoint table: pairs inside one first-layer patch meet through its node distances", "[hub][table]") {
    const Mesh mesh = bumpyTorus(120, 40);
    BakeOptions o;
    o.n1 = 10;
    o.hubLabels = true;
    BakeReport report;
    RuntimeGraph g = openOrFail(bakeMesh(mesh, o, report, nullptr));
    const vg_graph& graph = *g.graph();
    const EndpointTable table(g.graph());
    RuntimeWorkspace plain(g.graph()), fast(g.graph());
    fast.useTable(table);
    float unused = 0;

    std::mt19937 rng(11);
    std::uniform_int_distribution<uint32_t> pick(0, graph.vertexCount - 1);
    size_t pairs = 0, hubEnds = 0, asymmetric = 0, unbounded = 0, misbounded = 0, closer = 0, farther = 0;
    size_t leaving = 0, prunedDiffer = 0, leavingBelow = 0;
    double tableError = 0, searchError = 0, worst = 0, searchWorst = 0;
    for (int k = 0; k < 6; ++k) {
        const uint32_t s = pick(rng);
        const std::vector<double> exact = exactDistancesFrom(mesh, s);
        for (uint32_t t = 0; t < graph.vertexCount; ++t) {
            float a = 0;
            if (!vg::patchPairDistance(graph, *fast.get(), s, t, __builtin_inff(), &a)) continue;
            CHECK_FALSE(vg::patchPairDistance(graph, *plain.get(), s, t, __builtin_inff(), &unused));  // no table
            ++pairs;
            for (const uint32_t x : {s, t}) {
                const uint32_t node = vg::vertexNode(graph, x);
                hubEnds += node != vg::kNone && graph.nodeHub[node] != vg::kNone;
            }
            asymmetric += fast.distance(t, s) != a || fast.distance(s, t) != a;
            // Bounded as asked: +inf just below the answer, the answer at it.
            float below = 0, at = 0;
            REQUIRE(vg_distance_within(g.graph(), fast.get(), s, t, std::nextafter(a, 0.0f), &below) == VG_OK);
            REQUIRE(vg_distance_within(g.graph(), fast.get(), s, t, a, &at) == VG_OK);
            misbounded += below != __builtin_inff();
            unbounded += at != a;
            // The labels' leaving paths, pruned by the answer inside, give the same minimum
            // as the full reads.
            float full = 0, pruned = 0;
            if (vg::hubLeavingDistance(graph, *fast.get(), s, t, __builtin_inff(), &full)) {
                ++leaving;
                for (const float beaten : {a, 1.05f * a}) {
                    REQUIRE(vg::hubLeavingDistance(graph, *fast.get(), s, t, beaten, &pruned));
                    prunedDiffer += std::min(beaten, pruned) != std::min(beaten, full);
                }
                leavingBelow += full < a;
            }
            const float b = plain.distance(s, t);
            closer += std::fabs(a - exact[t]) < std::fabs(b - exact[t]);
            farther += std::fabs(a - exact[t]) > std::fabs(b - exact[t]);
            tableError += std::fabs(a - exact[t]) / exact[t];
            searchError += std::fabs(b - exact[t]) / exact[t];
            worst = std::max(worst, std::fabs(a - exact[t]) / exact[t]);
            searchWorst = std::max(searchWorst, std::fabs(b - exact[t]) / exact[t]);
        }
    }
    INFO("pairs " << pairs << ", with a hub end " << hubEnds << ", closer " << closer << ", farther " << farther
                  << "; mean error table " << tableError / pairs << ", searches " << searchError / pairs << ", worst "
                  << worst << " (searches " << searchWorst << ")");
    CHECK(pairs > 1000);
    CHECK(hubEnds > 20);
    CHECK(asymmetric == 0);
    CHECK(leaving > pairs / 2);
    CHECK(prunedDiffer == 0);
    CHECK(leavingBelow == 0);  // the answer has them
    CHECK(misbounded == 0);
    CHECK(unbounded == 0);
    // At least as close to the exact distances as the two searches, on the whole.
    CHECK(tableError <= 1.02 * searchError);
    CHECK(closer > farther);
    CHECK(worst <= 1.02 * searchWorst);
    // Pairs in two first-layer patches, and a hub with a vertex of a patch it is not on,
    // are the labels'.
    size_t refused = 0, labelled = 0;
    for (int i = 0; i < 500; ++i) {
        const uint32_t s = pick(rng), t = pick(rng);
        if (!vg::hubDistance(graph, *fast.get(), s, t, __builtin_inff(), &unused)) continue;
        ++labelled;
        refused += !vg::patchPairDistance(graph, *fast.get(), s, t, __builtin_inff(), &unused);
    }
    CHECK(labelled > 300);
    CHECK(refused == labelled);
}

TEST_CASE("endpoint table: size, build and use refuse what they must", "[hub][table]") {
    RuntimeGraph labelled = openOrFail(bakeTorus(true, 0.0));
    RuntimeGraph bare = openOrFail(bakeTorus(false, 0.0));
    RuntimeGraph other = openOrFail(bakeTorus(true, 0.002));
    const vg_graph* g = labelled.graph();

    // No labels: nothing to build, and a status that says so.
    CHECK(vg_endpoint_table_size(nullptr) == 0);
    CHECK(vg_endpoint_table_size(bare.graph()) == 0);
    std::vector<unsigned char> memory(vg_endpoint_table_size(g) + 1);
    const vg_endpoint_table* table = nullptr;
    CHECK(vg_endpoint_table_build(bare.graph(), memory.data(), memory.size(), &table) == VG_ERR_NO_HUB_LABELS);
    CHECK(table == nullptr);
    CHECK(std::string(vg_status_string(VG_ERR_NO_HUB_LABELS)).find("hub labels") != std::string::npos);

    // Bad arguments and too little memory.
    const size_t need = vg_endpoint_table_size(g);
    REQUIRE(need > 0);
    CHECK(vg_endpoint_table_build(g, memory.data(), need, nullptr) == VG_ERR_INVALID_ARGUMENT);
    CHECK(vg_endpoint_table_build(nullptr, memory.data(), need, &table) == VG_ERR_INVALID_ARGUMENT);
    CHECK(vg_endpoint_table_build(g, nullptr, need, &table) == VG_ERR_INVALID_ARGUMENT);
    CHECK(vg_endpoint_table_build(g, memory.data(), need - 1, &table) == VG_ERR_BUFFER_TOO_SMALL);
    CHECK(table == nullptr);

    // Any alignment: one byte past an aligned start.
    REQUIRE(vg_endpoint_table_build(g, memory.data() + 1, need, &table) == VG_OK);
    REQUIRE(table != nullptr);

    // A workspace takes only its own graph's table; NULL detaches it.
    RuntimeWorkspace ws(g), otherWs(other.graph());
    CHECK(vg_workspace_use_endpoint_table(nullptr, table) == VG_ERR_INVALID_ARGUMENT);
    CHECK(vg_workspace_use_endpoint_table(otherWs.get(), table) == VG_ERR_WRONG_WORKSPACE);
    const float before = ws.distance(0, labelled.vertexCount() - 1);
    CHECK(vg_workspace_use_endpoint_table(ws.get(), table) == VG_OK);
    CHECK(ws.distance(0, labelled.vertexCount() - 1) == before);
    CHECK(vg_workspace_use_endpoint_table(ws.get(), nullptr) == VG_OK);
    CHECK(ws.distance(0, labelled.vertexCount() - 1) == before);
}

TEST_CASE("endpoint table: the portable and AVX2 kernels build and read it alike", "[hub][table]") {
    RuntimeGraph g = openOrFail(bakeTorus(true, 0.0));
    if (!g.graph()->avx2) WARN("this CPU has no AVX2: only the portable kernels run");
    vg_graph portable = *g.graph();  // the same tables, the portable kernels
    portable.avx2 = false;
    const EndpointTable fast(g.graph());
    std::vector<unsigned char> memory(vg_endpoint_table_size(&portable));
    const vg_endpoint_table* plain = nullptr;
    REQUIRE(vg_endpoint_table_build(&portable, memory.data(), memory.size(), &plain) == VG_OK);
    const vg_endpoint_table& a = *fast.get();
    const uint32_t P = portable.secondCount;
    REQUIRE(a.vertexRowBegin[P] == plain->vertexRowBegin[P]);
    REQUIRE(a.patchColumnBegin[P] == plain->patchColumnBegin[P]);
    REQUIRE(a.vertexEntryBegin[P] == plain->vertexEntryBegin[P]);
    CHECK(std::equal(a.vertexRows, a.vertexRows + a.vertexRowBegin[P], plain->vertexRows));
    CHECK(std::equal(a.patchColumns, a.patchColumns + a.patchColumnBegin[P], plain->patchColumns));
    CHECK(std::equal(a.vertexEntries, a.vertexEntries + a.vertexEntryBegin[P], plain->vertexEntries));
    const uint64_t landmarks = uint64_t(portable.vertexCount) * portable.landmarkCount;
    CHECK(std::equal(a.vertexLandmarks, a.vertexLandmarks + landmarks, plain->vertexLandmarks));
    const uint32_t F = portable.firstCount;
    REQUIRE(a.nodeDistanceBegin[F] == plain->nodeDistanceBegin[F]);
    CHECK(std::equal(a.nodeDistances, a.nodeDistances + a.nodeDistanceBegin[F], plain->nodeDistances));
    CHECK(std::equal(a.nodeDistanceScale, a.nodeDistanceScale + F, plain->nodeDistanceScale));

    RuntimeWorkspace ws(g.graph());
    ws.useTable(fast);
    std::mt19937 rng(9);
    std::uniform_int_distribution<uint32_t> pick(0, portable.vertexCount - 1);
    size_t answered = 0, inPatch = 0, differ = 0;
    for (int i = 0; i < 3000; ++i) {
        const uint32_t s = pick(rng), t = pick(rng);
        float x = 0, y = 0;
        const bool labelled = vg::hubDistance(*g.graph(), *ws.get(), s, t, __builtin_inff(), &x);
        REQUIRE(vg::hubDistance(portable, *ws.get(), s, t, __builtin_inff(), &y) == labelled);
        answered += labelled;
        differ += labelled && x != y;
        const bool paired = vg::patchPairDistance(*g.graph(), *ws.get(), s, t, __builtin_inff(), &x);
        REQUIRE(vg::patchPairDistance(portable, *ws.get(), s, t, __builtin_inff(), &y) == paired);
        inPatch += paired;
        differ += paired && x != y;
    }
    CHECK(answered > 1500);
    CHECK(inPatch > 100);
    CHECK(differ == 0);
}

TEST_CASE("endpoint table: threads sharing one table answer as one thread with it", "[hub][table]") {
    // The table is read-only once built: workspaces on several threads read it at once.
    RuntimeGraph g = openOrFail(bakeTorus(true, 0.0));
    const EndpointTable table(g.graph());
    const uint32_t V = vg_vertex_count(g.graph());
    std::mt19937 rng(3);
    std::uniform_int_distribution<uint32_t> pick(0, V - 1);
    std::vector<std::pair<uint32_t, uint32_t>> pairs(600);
    for (auto& p : pairs) p = {pick(rng), pick(rng)};
    std::vector<float> expected;
    {
        RuntimeWorkspace ws(g.graph());
        ws.useTable(table);
        for (const auto& p : pairs) expected.push_back(ws.distance(p.first, p.second));
    }
    const unsigned threads = 4;
    std::vector<size_t> mismatches(threads, 0);
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t)
        pool.emplace_back([&, t] {  // no Catch2 assertions on worker threads
            RuntimeWorkspace ws(g.graph());
            ws.useTable(table);
            for (size_t i = 0; i < pairs.size(); ++i) {
                const size_t k = (i + 150 * t) % pairs.size();
                mismatches[t] += ws.distance(pairs[k].first, pairs[k].second) != expected[k];
            }
        });
    for (auto& t : pool) t.join();
    for (unsigned t = 0; t < threads; ++t) CHECK(mismatches[t] == 0);
}
