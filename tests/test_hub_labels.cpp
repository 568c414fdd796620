// Hub labels (bake --hub-labels, baker/hub_labels.h, runtime/src/vg_hub_labels.cpp): they
// answer like the search on the same graph, symmetric, deterministic across thread
// counts; reading only the labels the bounds keep, and only the exits the exit lists name
// (baker/hub_exit_lists.h), gives the answers of reading all; and a blob whose label
// tables or exit lists do not add up is refused.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include <tbb/global_control.h>

#include "bake.h"
#include "blob_test_helpers.h"
#include "generators.h"
#include "hub_exit_lists.h"
#include "hub_label_runs.h"
#include "hub_labels.h"
#include "runtime_graph.h"
#include "vg_hub_labels.h"
#include "vg_lower_bound.h"
#include "vorogeo.h"
#include "vorogeo_container.h"
#include "vorogeo_generated.h"

using namespace vorogeo;
using tools::RuntimeGraph;
using tools::RuntimeWorkspace;

namespace {

Mesh labelledMesh() { return bumpyTorus(120, 40); }  // 4,800 vertices

std::vector<uint8_t> bakeLabelled(bool compress, size_t threads = 0, double delta = 0.0) {
    BakeOptions o;
    o.n1 = 10;
    o.delta = delta;
    o.hubLabels = true;
    o.compress = compress;
    BakeReport report;
    if (threads == 0) return bakeMesh(labelledMesh(), o, report, nullptr);
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return bakeMesh(labelledMesh(), o, report, nullptr);
}

const std::vector<uint8_t>& labelledBlob() {
    static const std::vector<uint8_t> blob = bakeLabelled(false);
    return blob;
}

// Labels against the directed search on random pairs of one blob; returns how many pairs
// the labels answered.
size_t compareWithSearch(const std::vector<uint8_t>& blob, size_t pairs) {
    RuntimeGraph g = openOrFail(blob);
    REQUIRE(g.graph()->hubTreeCount > 1);
    RuntimeWorkspace labels(g.graph()), directed(g.graph());
    directed.setSearch(VG_SEARCH_DIRECTED);
    const uint32_t V = vg_vertex_count(g.graph());
    std::mt19937 rng(7);
    std::uniform_int_distribution<uint32_t> pick(0, V - 1);
    size_t answered = 0;
    double worst = 0, sum = 0;
    for (size_t i = 0; i < pairs; ++i) {
        const uint32_t s = pick(rng), t = pick(rng);
        float byLabels = 0;
        const bool labelled = vg::hubDistance(*g.graph(), *labels.get(), s, t, __builtin_inff(), &byLabels);
        answered += labelled;
        const float viaApi = labels.distance(s, t), bySearch = directed.distance(s, t);
        if (labelled) CHECK(viaApi == byLabels);
        else CHECK(viaApi == bySearch);  // the search answers pairs the labels leave
        REQUIRE(std::isfinite(bySearch));
        if (bySearch > 0) {
            const double diff = std::fabs(double(viaApi) - bySearch) / bySearch;
            worst = std::max(worst, diff);
            sum += diff;
        }
        CHECK(labels.distance(t, s) == viaApi);  // symmetric, bit for bit
    }
    // The labels and the search differ only in rounding (16-bit label steps, a larger
    // share of a short pair) and in which border crossings they meet.
    CHECK(sum / double(pairs) < 0.001);
    CHECK(worst < 0.01);
    return answered;
}

// Two label reads (graph a with prune a, graph b with prune b and, with generalB, b's
// general meeting next to t: the same tables, read two ways) of the same random pairs
// through one workspace: how many pairs the labels answer, how many of those meet next to
// a target inside one second-layer patch, and on how many the two answers differ.
struct Agreement {
    size_t answered = 0, targetInside = 0, differ = 0;
};
Agreement compareReads(const vg_graph& a, bool pruneA, const vg_graph& b, bool pruneB, vg_workspace& ws,
                       uint32_t seed, bool generalB = false) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<uint32_t> pick(0, a.vertexCount - 1);
    Agreement out;
    for (int i = 0; i < 3000; ++i) {
        const uint32_t s = pick(rng), t = pick(rng);
        float first = 0, second = 0;
        const bool labelledA = vg::hubDistance(a, ws, s, t, __builtin_inff(), &first, pruneA);
        const bool labelledB = vg::hubDistance(b, ws, s, t, __builtin_inff(), &second, pruneB, generalB);
        REQUIRE(labelledA == labelledB);
        if (!labelledA) continue;
        ++out.answered;
        // The query meets next to the larger vertex id (one order for both directions).
        out.targetInside += vg::vertexNode(a, std::max(s, t)) == vg::kNone;
        out.differ += first != second;
    }
    return out;
}

}  // namespace

TEST_CASE("hub labels answer like the directed search on the same graph", "[hub]") {
    // Most pairs lie in different first-layer patches.
    CHECK(compareWithSearch(labelledBlob(), 400) > 200);
}

TEST_CASE("hub labels on a pruned graph answer like its search", "[hub]") {
    CHECK(compareWithSearch(bakeLabelled(false, 0, 0.002), 200) > 100);
}

TEST_CASE("hub labels: the pruned reads answer like reading every label", "[hub]") {
    // The query reads only the first-layer nodes and hub blocks whose lower bounds stay
    // within an upper bound of the answer, widened by the longest node edge next to t (an
    // unfolded crossing there undercuts a node path by less than that). So it answers
    // exactly as reading every label does, bit for bit.
    for (const double delta : {0.0, 0.002}) {
        const std::vector<uint8_t> blob = delta == 0.0 ? labelledBlob() : bakeLabelled(false, 0, delta);
        RuntimeGraph g = openOrFail(blob);
        REQUIRE(g.graph()->hubBlockBounds != nullptr);
        REQUIRE(g.graph()->hubExitLists != nullptr);  // the pruned reads take the exit lists too
        RuntimeWorkspace ws(g.graph());
        const Agreement prunedAndFull = compareReads(*g.graph(), true, *g.graph(), false, *ws.get(), 11);
        CHECK(prunedAndFull.answered > 1500);
        CHECK(prunedAndFull.differ == 0);
    }
}

TEST_CASE("hub labels: the upper bound meets the hubs at the blocks that can lower it", "[hub]") {
    // The upper bound's hub-to-hub part reads a block only while its lower bound is below
    // the best sum so far: the same bound as meeting at every block, and so the same
    // answers, on the plain and on a pruned graph. Without block bounds every block is read.
    for (const double delta : {0.0, 0.002}) {
        const std::vector<uint8_t> blob = delta == 0.0 ? labelledBlob() : bakeLabelled(false, 0, delta);
        RuntimeGraph g = openOrFail(blob);
        const vg_graph& graph = *g.graph();
        REQUIRE(graph.hubBlockBounds != nullptr);
        vg_graph unbounded = graph;
        unbounded.hubBlockBounds = nullptr;
        RuntimeWorkspace ws(g.graph());
        std::mt19937 rng(29);
        std::uniform_int_distribution<uint32_t> pick(0, graph.vertexCount - 1);
        size_t answered = 0, bounded = 0, differ = 0, below = 0;
        for (int i = 0; i < 3000; ++i) {
            const uint32_t s = pick(rng), t = pick(rng);
            float some = 0, every = 0, plain = 0, upperSome = 0, upperEvery = 0, upperPlain = 0;
            const bool a = vg::hubDistance(graph, *ws.get(), s, t, __builtin_inff(), &some, true, false, false, &upperSome);
            const bool b = vg::hubDistance(graph, *ws.get(), s, t, __builtin_inff(), &every, true, false, true, &upperEvery);
            const bool c = vg::hubDistance(unbounded, *ws.get(), s, t, __builtin_inff(), &plain, true, false, false, &upperPlain);
            REQUIRE(a == b);
            REQUIRE(a == c);
            if (!a) continue;
            ++answered;
            bounded += upperSome != __builtin_inff();
            differ += upperSome != upperEvery || upperSome != upperPlain || some != every || some != plain;
            below += upperSome < some;
        }
        CHECK(answered > 1500);
        CHECK(bounded > answered * 9 / 10);
        CHECK(differ == 0);
        CHECK(below == 0);  // an upper bound
    }
}

TEST_CASE("hub labels: the meeting inside t's patch answers like the general meeting", "[hub]") {
    // A target inside one second-layer patch (no node) meets s's distances from slot-local
    // arrays and the patch's edge list; any other target through the search labels and the
    // node edge lists. Both must give the same numbers, pruned and full, also on a graph
    // whose pruning merged nodes away.
    for (const double delta : {0.0, 0.002}) {
        const std::vector<uint8_t> blob = delta == 0.0 ? labelledBlob() : bakeLabelled(false, 0, delta);
        RuntimeGraph g = openOrFail(blob);
        const vg_graph& graph = *g.graph();
        RuntimeWorkspace ws(g.graph());
        for (const bool prune : {true, false}) {
            const Agreement localAndGeneral = compareReads(graph, prune, graph, prune, *ws.get(), 23, true);
            CHECK(localAndGeneral.targetInside > 1000);
            CHECK(localAndGeneral.differ == 0);
        }
    }
}

TEST_CASE("hub labels: the exit lists name a few exits per block and answer as every exit does", "[hub]") {
    // Per second-layer patch and block, only the exits that are the best way from some node
    // of the patch to some hub of the block (baker/hub_exit_lists.h). Reading those alone
    // gives the same answers as reading every exit's rows, bit for bit, with the bounds on.
    RuntimeGraph g = openOrFail(labelledBlob());
    const vg_graph& graph = *g.graph();
    REQUIRE(graph.hubExitLists != nullptr);
    vg_graph everyExit = graph;  // the same tables without the lists
    everyExit.hubExitLists = nullptr;
    RuntimeWorkspace ws(g.graph());

    // The lists are a small part of the exits the block's rows cover.
    uint64_t listed = 0, covered = 0;
    for (uint32_t q = 0; q < graph.secondCount; ++q) {
        const uint32_t p = graph.second[q].parent;
        std::vector<uint32_t> exitHubs;  // p's exits in hub order (the lists' indices)
        for (uint32_t k = 0; k < graph.first[p].slotCount; ++k) {
            const uint32_t hub = graph.nodeHub[graph.slots[graph.first[p].slotBegin + k]];
            if (hub != vg::kNone) exitHubs.push_back(hub);
        }
        std::sort(exitHubs.begin(), exitHubs.end());
        std::vector<uint32_t> path;  // root first, as the lists are
        for (uint32_t t = graph.hubFirstLeaf[p]; t != vg::kNone; t = graph.hubTree[t].parent) path.push_back(t);
        std::reverse(path.begin(), path.end());
        uint32_t list = graph.hubExitPatchBegin[q];
        for (const uint32_t t : path) {
            const uint32_t lo = graph.hubTree[t].hubBegin,
                           hi = vg::hubSubtreeEnd(graph.hubTree, graph.hubTreeCount, graph.hubCount, t);
            const uint64_t inRange = uint64_t(std::count_if(exitHubs.begin(), exitHubs.end(),
                                                            [&](uint32_t h) { return h >= lo && h < hi; }));
            for (uint32_t b = 0; b < (graph.hubTree[t].hubCount + vg::kHubBlock - 1) / vg::kHubBlock; ++b, ++list) {
                for (uint32_t m = graph.hubExitListBegin[list]; m < graph.hubExitListBegin[list + 1]; ++m)
                    CHECK((exitHubs[graph.hubExitLists[m]] >= lo && exitHubs[graph.hubExitLists[m]] < hi));
                listed += graph.hubExitListBegin[list + 1] - graph.hubExitListBegin[list];
                covered += inRange;
            }
        }
        CHECK(list == graph.hubExitPatchBegin[q + 1]);
    }
    CHECK(listed > 0);
    CHECK(double(listed) < 0.5 * double(covered));

    const Agreement listsAndEveryExit = compareReads(graph, true, everyExit, true, *ws.get(), 13);
    CHECK(listsAndEveryExit.answered > 1500);
    CHECK(listsAndEveryExit.differ == 0);
}

TEST_CASE("hub labels: the exit lists are the same with and without AVX2 and as stored", "[hub]") {
    const std::vector<uint8_t>& blob = labelledBlob();  // uncompressed: the flatbuffer follows the header
    const std::vector<uint8_t> flatbuffer(blob.begin() + VG_CONTAINER_HEADER_SIZE, blob.end());
    HubLabels labels = computeHubLabels(flatbuffer);
    REQUIRE(!labels.exitLists.empty());
    HubLabels portable = labels;
    computeHubExitLists(flatbuffer, portable, false);
    CHECK(portable.exitPatchBegin == labels.exitPatchBegin);
    CHECK(portable.exitListBegin == labels.exitListBegin);
    CHECK(portable.exitLists == labels.exitLists);
    const fb::Graph* g = fb::GetGraph(flatbuffer.data());
    REQUIRE(g->hub_exit_lists() != nullptr);
    CHECK(std::vector<uint16_t>(g->hub_exit_lists()->begin(), g->hub_exit_lists()->end()) == labels.exitLists);
}

namespace {

// A label entry as a distance: hub `row` (of tree node x's subtree) to hub h of x.
double labelEntry(const HubLabels& l, uint32_t x, uint32_t hubEnd, uint32_t row, uint32_t h) {
    const uint32_t local = h - l.tree[x].hubBegin, subtree = hubEnd - l.tree[x].hubBegin;
    const uint16_t steps = l.columns[l.columnBegin[x] + uint64_t(local / kHubBlock) * kHubBlock * subtree +
                                     uint64_t(row - l.tree[x].hubBegin) * kHubBlock + local % kHubBlock];
    return steps == kHubUnreachable ? HUGE_VAL : double(steps) * l.labelScale;
}

// Per tree node the end of its subtree's hubs (tree nodes in preorder).
std::vector<uint32_t> subtreeHubEnds(const HubLabels& l) {
    const uint32_t T = uint32_t(l.tree.size());
    std::vector<uint32_t> end(T);
    for (uint32_t t = 0; t < T; ++t) end[t] = t + 1;
    for (uint32_t t = T; t-- > 1;) end[l.tree[t].parent] = std::max(end[l.tree[t].parent], end[t]);
    std::vector<uint32_t> hubEnd(T);
    for (uint32_t t = 0; t < T; ++t) hubEnd[t] = end[t] < T ? l.tree[end[t]].hubBegin : l.hubCount;
    return hubEnd;
}

// The labels' distance between hubs a and b: the best sum over the hubs of every tree node
// from their tree nodes' common ancestor up to the root (as the runtime's hubToHub).
double twoHop(const HubLabels& l, const std::vector<uint32_t>& hubEnd, const std::vector<uint32_t>& hubTree,
              uint32_t a, uint32_t b) {
    std::vector<bool> aboveA(l.tree.size(), false);
    for (uint32_t x = hubTree[a]; x != UINT32_MAX; x = l.tree[x].parent) aboveA[x] = true;
    uint32_t x = hubTree[b];
    while (!aboveA[x]) x = l.tree[x].parent;
    double best = HUGE_VAL;
    for (; x != UINT32_MAX; x = l.tree[x].parent)
        for (uint32_t h = l.tree[x].hubBegin; h < l.tree[x].hubBegin + l.tree[x].hubCount; ++h)
            best = std::min(best, labelEntry(l, x, hubEnd[x], a, h) + labelEntry(l, x, hubEnd[x], b, h));
    return best;
}

}  // namespace

namespace {

// Block runs on random matrices over shared nodes (columns without a node, a node at two
// slots of one patch, "no path" entries unless closed, patches outside the searched leaf
// range, fewer sources than lanes, a reused scratch) against a Dijkstra per source:
// entries 1..maxQuantum, patch p's step per quantum scaleOf(p, rng). Closed: the runs
// search the closed matrices (closePatchMatrix, AVX2 and portable alike); with exact sums
// they skip rows, reading fewer than on the open ones, for the same distances; with steps
// whose sums round they skip none and give the same distances up to that rounding.
enum class Closed { no, exactSums, roundedSums };
template <class ScaleOf>
void checkBlockRunsAgainstDijkstra(uint32_t maxQuantum, const ScaleOf& scaleOf, Closed closed = Closed::no) {
    const bool close = closed != Closed::no;
    std::mt19937 rng(3);
    LabelOverlay o;
    o.noPath = 4095;
    const uint32_t nodes = 160, patches = 14;
    std::vector<std::vector<std::pair<uint32_t, uint32_t>>> rowsOf(nodes);
    o.quantaBegin.push_back(0);
    o.slotBegin.push_back(0);
    for (uint32_t p = 0; p < patches; ++p) {
        const uint32_t S = 5 + rng() % 36;
        std::vector<uint32_t> pick(nodes);
        for (uint32_t n = 0; n < nodes; ++n) pick[n] = n;
        std::shuffle(pick.begin(), pick.end(), rng);
        for (uint32_t j = 0; j < S; ++j) {
            const bool none = rng() % 20 == 0, again = j == S - 1 && p % 4 == 1;
            const uint32_t n = again ? pick[0] : pick[j];
            o.slotNode.push_back(none ? UINT32_MAX : n);
            if (!none) rowsOf[n].push_back({p, j});
        }
        for (uint32_t i = 0; i < S; ++i)
            for (uint32_t j = 0; j < S; ++j)
                o.quanta.push_back(
                    uint16_t(i == j ? 0 : !close && rng() % 10 == 0 ? o.noPath : 1 + rng() % maxQuantum));
        o.quantaBegin.push_back(o.quanta.size());
        o.slotBegin.push_back(uint32_t(o.slotNode.size()));
        o.scale.push_back(scaleOf(p, rng));
        o.patchLeaf.push_back(rng() % 4);
    }
    o.memberBegin.push_back(0);
    for (uint32_t n = 0; n < nodes; ++n) {
        o.members.insert(o.members.end(), rowsOf[n].begin(), rowsOf[n].end());
        o.memberBegin.push_back(uint32_t(o.members.size()));
    }
    auto dijkstra = [&](uint32_t source, uint32_t leafBegin, uint32_t leafEnd) {
        std::vector<double> d(nodes, HUGE_VAL);
        std::vector<bool> done(nodes, false);
        d[source] = 0;
        for (;;) {
            uint32_t u = UINT32_MAX;
            for (uint32_t n = 0; n < nodes; ++n)
                if (!done[n] && std::isfinite(d[n]) && (u == UINT32_MAX || d[n] < d[u])) u = n;
            if (u == UINT32_MAX) return d;
            done[u] = true;
            for (uint32_t m = o.memberBegin[u]; m < o.memberBegin[u + 1]; ++m) {
                const uint32_t p = o.members[m].first, slot = o.members[m].second;
                if (o.patchLeaf[p] < leafBegin || o.patchLeaf[p] >= leafEnd) continue;
                const uint32_t S = o.slotBegin[p + 1] - o.slotBegin[p];
                for (uint32_t j = 0; j < S; ++j) {
                    const uint16_t q = o.quanta[o.quantaBegin[p] + uint64_t(slot) * S + j];
                    const uint32_t to = o.slotNode[o.slotBegin[p] + j];
                    if (q == o.noPath || to == UINT32_MAX) continue;
                    d[to] = std::min(d[to], d[u] + double(q) * o.scale[p]);
                }
            }
        }
    };
    LabelOverlay searched = o;
    if (close) {
        LabelOverlay portableClosed = o;
        searched.closed.assign(patches, 0);
        portableClosed.closed.assign(patches, 0);
        for (uint32_t p = 0; p < patches; ++p) {
            closePatchMatrix(searched, p, true);
            closePatchMatrix(portableClosed, p, false);
        }
        CHECK(searched.quanta == portableClosed.quanta);
        CHECK(searched.quanta != o.quanta);  // random entries break the triangle inequality
        CHECK(std::count(searched.closed.begin(), searched.closed.end(), uint8_t(1)) == patches);
    }
    BlockRuns avx2, portable, open;
    for (const auto& leaves : {std::pair<uint32_t, uint32_t>{0, 4}, std::pair<uint32_t, uint32_t>{1, 3}}) {
        uint32_t sources[BlockRuns::kLanes];
        for (uint32_t i = 0; i < 11; ++i) sources[i] = (i * 37 + leaves.first * 5) % nodes;
        avx2.run(searched, sources, 11, leaves.first, leaves.second, true);
        portable.run(searched, sources, 11, leaves.first, leaves.second, false);
        open.run(o, sources, 11, leaves.first, leaves.second, true);
        CHECK(!open.skippedRows());
        CHECK(avx2.skippedRows() == (closed == Closed::exactSums));
        CHECK(portable.skippedRows() == avx2.skippedRows());
        if (closed == Closed::exactSums) CHECK(avx2.rowsRead() < open.rowsRead() * 9 / 10);
        size_t differ = 0, reached = 0, unreachedLanes = 0;
        for (uint32_t i = 0; i < 11; ++i) {
            const std::vector<double> reference = dijkstra(sources[i], leaves.first, leaves.second);
            for (uint32_t n = 0; n < nodes; ++n) {
                // Rounded sums: a closed entry's one product against a chain's sum of two.
                const double slack = closed == Closed::roundedSums ? 1e-12 * reference[n] : 0.0;
                for (const BlockRuns* runs : {&avx2, &portable}) {
                    const double d = runs->distances(n)[i];
                    differ += d != reference[n] && !(std::fabs(d - reference[n]) <= slack);
                }
                reached += std::isfinite(reference[n]) && reference[n] > 0;
            }
        }
        for (uint32_t n = 0; n < nodes; ++n)
            for (uint32_t i = 11; i < BlockRuns::kLanes; ++i) unreachedLanes += !std::isfinite(avx2.distances(n)[i]);
        CHECK(differ == 0);
        CHECK(reached > 11 * nodes / 4);
        CHECK(unreachedLanes == nodes * (BlockRuns::kLanes - 11));
    }
}

}  // namespace

TEST_CASE("hub labels: block runs give a Dijkstra per source's distances, AVX2 and portable", "[hub]") {
    SECTION("steps of a graph's size") {
        checkBlockRunsAgainstDijkstra(4000, [](uint32_t, std::mt19937& rng) { return 0.001 * (1 + rng() % 7); });
    }
    SECTION("many equal paths: the float screen's ties decided in double") {
        // Small integer steps of one scale: most nodes are reached by several shortest
        // paths of equal length, and many sums tie with a node's distance.
        checkBlockRunsAgainstDijkstra(3, [](uint32_t, std::mt19937&) { return 0.25; });
    }
    SECTION("paths shorter than others by less than a float's precision") {
        // Steps apart by 2^-30 of themselves: a column's sum is often below a node's
        // distance by less than a float can tell, and must still lower it.
        checkBlockRunsAgainstDijkstra(3, [](uint32_t p, std::mt19937&) { return 0.25 * (1 + (p % 5) * 0x1p-30); });
    }
    SECTION("closed matrices, rows skipped") {
        const auto floatSteps = [](uint32_t, std::mt19937& rng) { return double(float(0.001 * (1 + rng() % 7))); };
        checkBlockRunsAgainstDijkstra(4000, floatSteps, Closed::exactSums);
        checkBlockRunsAgainstDijkstra(3, [](uint32_t, std::mt19937&) { return 0.25; }, Closed::exactSums);
    }
    SECTION("closed matrices whose sums could round: no row skipped") {
        // Steps of 53 significant bits: a run's sums are not exact, so it searches again
        // without skipping, and gives the Dijkstra's distances up to their rounding.
        checkBlockRunsAgainstDijkstra(4000, [](uint32_t, std::mt19937& rng) { return 0.001 * (1 + rng() % 7); },
                                      Closed::roundedSums);
    }
    SECTION("patches of zero steps beside others") {
        checkBlockRunsAgainstDijkstra(50, [](uint32_t p, std::mt19937&) { return p % 3 == 0 ? 0.0 : 1e-3; });
    }
    SECTION("steps too large or too small for the float screen: the double test alone") {
        checkBlockRunsAgainstDijkstra(4000, [](uint32_t, std::mt19937& rng) { return 1e24 * (1 + rng() % 7); });
        // Distances past the floats' range (3.4e38): the bounds kept are +inf.
        checkBlockRunsAgainstDijkstra(4000, [](uint32_t, std::mt19937& rng) { return 1e36 * (1 + rng() % 7); });
        checkBlockRunsAgainstDijkstra(4000, [](uint32_t, std::mt19937& rng) { return 1e-33 * (1 + rng() % 7); });
    }
}

TEST_CASE("hub labels: a search per block of hubs gives the Dijkstra per hub's labels", "[hub]") {
    // The bake's label-correcting search over vectors of 16 lanes (hub_label_runs.h) ends at
    // the distances of separate Dijkstra runs over the same subtree, so at the same steps.
    // Also on a pruned graph, whose merged-away first-layer nodes start inner rows through
    // their own rows.
    for (double delta : {0.0, 0.05}) {
        const std::vector<uint8_t> blob = bakeLabelled(false, 0, delta);  // the flatbuffer follows the header
        const std::vector<uint8_t> flatbuffer(blob.begin() + VG_CONTAINER_HEADER_SIZE, blob.end());
        const fb::Graph* g = fb::GetGraph(flatbuffer.data());
        size_t mergedAway = 0;  // first-layer slots whose node is merged away
        for (uint32_t p = 0; p < g->first_patches()->size(); ++p) {
            const fb::PatchRecord& r = *g->first_patches()->Get(p);
            for (uint32_t j = 0; j < r.slot_count(); ++j)
                mergedAway += (g->node_flags()->Get(g->slots()->Get(r.slot_begin() + j)) & 1u) != 0;
        }
        CHECK((delta > 0) == (mergedAway > 0));
        const HubLabels blocks = computeHubLabels(flatbuffer);
        const HubLabels perHub = computeHubLabels(flatbuffer, HubProgress(), HubPlanCheck(), HubLabelRuns::perHub);
        REQUIRE(blocks.columns.size() == perHub.columns.size());
        CHECK(blocks.labelScale == perHub.labelScale);
        size_t differ = 0, unreachable = 0;
        for (size_t k = 0; k < blocks.columns.size(); ++k) {
            differ += blocks.columns[k] != perHub.columns[k];
            unreachable += perHub.columns[k] == kHubUnreachable;
        }
        CHECK(differ == 0);
        CHECK(unreachable < blocks.columns.size() / 2);
        CHECK(blocks.inner == perHub.inner);
        CHECK(blocks.exitLists == perHub.exitLists);
    }
}

TEST_CASE("hub labels: runs inside each subtree give the whole overlay's hub-to-hub distances", "[hub]") {
    // Each label run searches only its hub's subtree (hub_labels.h): its entries may be
    // longer than the whole overlay's, but the best sum over the common tree path, which is
    // all a query takes, is the same distance up to the rounding of two label steps.
    const std::vector<uint8_t>& blob = labelledBlob();  // uncompressed: the flatbuffer follows the header
    const std::vector<uint8_t> flatbuffer(blob.begin() + VG_CONTAINER_HEADER_SIZE, blob.end());
    const HubLabels subtree = computeHubLabels(flatbuffer);
    const HubLabels whole = computeHubLabels(flatbuffer, HubProgress(), HubPlanCheck(), HubLabelRuns::perHubWholeOverlay);
    REQUIRE(subtree.tree.size() > 3);
    REQUIRE(subtree.columnBegin == whole.columnBegin);  // the same tree, hubs and layout
    REQUIRE(subtree.nodeHub == whole.nodeHub);
    const std::vector<uint32_t> hubEnd = subtreeHubEnds(subtree);
    std::vector<uint32_t> hubTree(subtree.hubCount);
    for (uint32_t x = 0; x < subtree.tree.size(); ++x)
        for (uint32_t h = subtree.tree[x].hubBegin; h < subtree.tree[x].hubBegin + subtree.tree[x].hubCount; ++h)
            hubTree[h] = x;
    const double rounding = subtree.labelScale + whole.labelScale;

    // Entry by entry: never shorter (a subtree has no shortcut), some of them longer.
    size_t shorter = 0, longer = 0;
    for (uint32_t x = 0; x < subtree.tree.size(); ++x)
        for (uint32_t row = subtree.tree[x].hubBegin; row < hubEnd[x]; ++row)
            for (uint32_t h = subtree.tree[x].hubBegin; h < subtree.tree[x].hubBegin + subtree.tree[x].hubCount; ++h) {
                const double inside = labelEntry(subtree, x, hubEnd[x], row, h);
                const double anywhere = labelEntry(whole, x, hubEnd[x], row, h);
                shorter += inside < anywhere - rounding;
                longer += inside > anywhere + rounding;
            }
    CHECK(shorter == 0);
    CHECK(longer > 0);

    // Hub to hub through the labels: the same distances.
    std::mt19937 rng(5);
    std::uniform_int_distribution<uint32_t> pick(0, subtree.hubCount - 1);
    size_t differ = 0;
    for (int i = 0; i < 4000; ++i) {
        const uint32_t a = pick(rng), b = pick(rng);
        const double inside = twoHop(subtree, hubEnd, hubTree, a, b), anywhere = twoHop(whole, hubEnd, hubTree, a, b);
        REQUIRE(std::isfinite(anywhere));
        differ += !(std::fabs(inside - anywhere) <= rounding * 1.001);
    }
    CHECK(differ == 0);
}

TEST_CASE("hub labels: the portable and AVX2 block bounds are the same numbers", "[hub]") {
    // The query drops the blocks whose lower bounds leave no room under its upper bound;
    // the AVX2 kernel takes the landmarks eight at a time (12 here: a whole group and a
    // masked one) and must give every bound bit for bit as the portable loop does.
    RuntimeGraph g = openOrFail(labelledBlob());
    REQUIRE(g.graph()->hubBlockBounds != nullptr);
    REQUIRE(g.graph()->landmarkCount % 8 != 0);
    if (!g.graph()->avx2) WARN("this CPU has no AVX2: the portable kernel is compared with itself");
    vg_graph portable = *g.graph();
    portable.avx2 = false;
    RuntimeWorkspace ws(g.graph());
    const uint32_t blocks = ws.get()->hubBlockBegin[g.graph()->hubTreeCount];
    const uint32_t V = vg_vertex_count(g.graph());
    std::mt19937 rng(17);
    std::uniform_int_distribution<uint32_t> pick(0, V - 1);
    size_t compared = 0, positive = 0;
    for (int i = 0; i < 200; ++i) {
        const uint32_t x = pick(rng);
        for (uint32_t b = 0; b < blocks; ++b) {
            const float fast = vg::hubBlockBound(*g.graph(), *ws.get(), x, b);
            const float plain = vg::hubBlockBound(portable, *ws.get(), x, b);
            REQUIRE(fast == plain);
            compared += fast >= 0.0f;
            positive += fast > 0.0f;
        }
    }
    CHECK(compared > 1000);
    CHECK(positive > compared / 4);
}

TEST_CASE("hub labels: a block's sphere bound is at most its whole bound", "[hub]") {
    // The query tests a block's sphere first (a workspace copy, four floats per block) and
    // reads its landmark ranges only when that leaves room, so the sphere alone must never
    // bound higher than sphere and landmarks together.
    for (const double delta : {0.0, 0.002}) {
        const std::vector<uint8_t> blob = delta == 0.0 ? labelledBlob() : bakeLabelled(false, 0, delta);
        RuntimeGraph g = openOrFail(blob);
        REQUIRE(g.graph()->hubBlockBounds != nullptr);
        RuntimeWorkspace ws(g.graph());
        const uint32_t blocks = ws.get()->hubBlockBegin[g.graph()->hubTreeCount];
        std::mt19937 rng(19);
        std::uniform_int_distribution<uint32_t> pick(0, vg_vertex_count(g.graph()) - 1);
        size_t compared = 0, positive = 0, tighter = 0, above = 0;
        for (int i = 0; i < 200; ++i) {
            const uint32_t x = pick(rng);
            for (uint32_t b = 0; b < blocks; ++b) {
                const float whole = vg::hubBlockBound(*g.graph(), *ws.get(), x, b);
                const float sphere = vg::hubBlockBound(*g.graph(), *ws.get(), x, b, true);
                REQUIRE((whole < 0.0f) == (sphere < 0.0f));
                if (whole < 0.0f) continue;
                ++compared;
                positive += sphere > 0.0f;
                tighter += whole > sphere;
                above += sphere > whole;
            }
        }
        CHECK(compared > 1000);
        CHECK(positive > compared / 4);  // the spheres alone already bound many blocks
        CHECK(tighter > 0);              // and the landmarks tighten some
        CHECK(above == 0);
    }
}

TEST_CASE("hub labels: a workspace's landmark ranges in steps hold the blob's ranges", "[hub]") {
    // The query reads each block's landmark ranges from the workspace, in landmark steps (one
    // cache line): every range as the query rebuilds it (steps times the scale, in float)
    // must hold the blob's, so that a bound from it is never higher; and be at most a step
    // wider at each end, or the bounds would lose their use.
    const RuntimeGraph g = openOrFail(labelledBlob());
    const vg_graph& graph = *g.graph();
    REQUIRE(graph.hubBlockBounds != nullptr);
    REQUIRE(graph.landmarkCount > 0);
    RuntimeWorkspace ws(g.graph());
    const uint32_t blocks = ws.get()->hubBlockBegin[graph.hubTreeCount], L = graph.landmarkCount;
    const uint32_t stride = vg::blockRangeStride(L);
    CHECK(stride * sizeof(uint16_t) % 64 == 0);
    CHECK(reinterpret_cast<uintptr_t>(ws.get()->hubBlockRanges) % 64 == 0);  // a block: whole cache lines
    size_t ranges = 0, bounded = 0, wide = 0, outside = 0;
    for (uint32_t b = 0; b < blocks; ++b) {
        const float* record = graph.hubBlockBounds + uint64_t(b) * (4 + 2 * L);
        const uint16_t* steps = ws.get()->hubBlockRanges + uint64_t(b) * stride;
        for (uint32_t k = 0; k < L; ++k) {
            const float scale = graph.landmarkScale[k], lo = record[4 + 2 * k], hi = record[5 + 2 * k];
            const float low = float(steps[k]) * scale;
            const float high = steps[L + k] == vg::kNoRangeEnd ? INFINITY : float(steps[L + k]) * scale;
            ++ranges;
            outside += (std::isfinite(lo) && low > lo) || high < hi;
            if (!std::isfinite(hi)) {
                CHECK(steps[L + k] == vg::kNoRangeEnd);
                continue;
            }
            ++bounded;
            // A high end past the largest step (the baker widens its ranges by a millionth)
            // can only be kept open.
            const bool top = steps[L + k] == vg::kNoRangeEnd && hi > 65533.0f * scale;
            wide += (lo > 0.0f && lo - low > 1.5f * scale) || (!top && high - hi > 1.5f * scale);
        }
    }
    CHECK(ranges > 100);
    CHECK(bounded > ranges / 2);
    CHECK(outside == 0);
    CHECK(wide == 0);
}

TEST_CASE("hub labels: the portable and AVX2 label kernels give the same answers", "[hub]") {
    RuntimeGraph g = openOrFail(labelledBlob());
    if (!g.graph()->avx2) WARN("this CPU has no AVX2: only the portable kernels run");
    vg_graph portable = *g.graph();  // the same tables, the portable kernels
    portable.avx2 = false;
    RuntimeWorkspace ws(g.graph());
    const uint32_t V = vg_vertex_count(g.graph());
    std::mt19937 rng(5);
    std::uniform_int_distribution<uint32_t> pick(0, V - 1);
    size_t answered = 0;
    for (int i = 0; i < 400; ++i) {
        const uint32_t s = pick(rng), t = pick(rng);
        for (const bool prune : {true, false}) {
            float fast = -1, plain = -2;
            const bool a = vg::hubDistance(*g.graph(), *ws.get(), s, t, __builtin_inff(), &fast, prune);
            const bool b = vg::hubDistance(portable, *ws.get(), s, t, __builtin_inff(), &plain, prune);
            REQUIRE(a == b);
            if (!a) continue;
            ++answered;
            CHECK(fast == plain);
        }
    }
    CHECK(answered > 200);
}

TEST_CASE("hub labels: a bounded query and the modes", "[hub]") {
    RuntimeGraph g = openOrFail(labelledBlob());
    RuntimeWorkspace ws(g.graph());
    const uint32_t V = vg_vertex_count(g.graph());
    float d = 0, within = 0;
    uint32_t s = 0, t = V - 1;
    REQUIRE(vg_distance(g.graph(), ws.get(), s, t, &d) == VG_OK);
    REQUIRE(std::isfinite(d));
    REQUIRE(vg_distance_within(g.graph(), ws.get(), s, t, 0.5f * d, &within) == VG_OK);
    CHECK(std::isinf(within));
    REQUIRE(vg_distance_within(g.graph(), ws.get(), s, t, d, &within) == VG_OK);
    CHECK(within == d);
    CHECK(vg_workspace_set_search(ws.get(), VG_SEARCH_HUB_LABELS) == VG_OK);
}

TEST_CASE("hub labels: the same bytes for any thread count", "[hub]") {
    CHECK(bakeLabelled(true, 1) == bakeLabelled(true, 2));
}

TEST_CASE("hub labels: tables that do not add up are refused", "[hub]") {
    const std::vector<uint8_t>& blob = labelledBlob();
    const fb::Graph* g = fb::GetGraph(blob.data() + VG_CONTAINER_HEADER_SIZE);
    REQUIRE(g->hub_tree() != nullptr);
    auto offsetOf = [&](const void* p) { return size_t(static_cast<const uint8_t*>(p) - blob.data()); };
    auto refused = [&](size_t offset, uint32_t value) {
        std::vector<uint8_t> bad(blob);
        std::memcpy(bad.data() + offset, &value, 4);
        resealChecksum(bad);
        return openStatus(bad) == VG_ERR_CORRUPT_CONTENT;
    };
    uint32_t H = 0;
    for (const auto* t : *g->hub_tree()) H += t->hub_count();
    CHECK(refused(offsetOf(g->node_hub()->data()), H));                      // a hub out of range
    CHECK(refused(offsetOf(g->hub_tree()->Get(1)), 7));                      // a parent after its child
    CHECK(refused(offsetOf(g->hub_tree()->Get(1)) + 12, 0xFFFFu));           // a wrong path position
    CHECK(refused(offsetOf(g->hub_first_leaf()->data()), uint32_t(g->hub_tree()->size())));
    CHECK(refused(offsetOf(g->hub_column_begin()->data()) + 8, 0xFFFFFFFFu));  // a column matrix past the end
    CHECK(refused(offsetOf(g->hub_column_begin()->data()) + 8, uint32_t(g->hub_column_begin()->Get(1) + 16)));  // one row too many
    CHECK(refused(offsetOf(g->hub_inner_node()->data()), 0xFFFFFFF0u));       // a node out of range
    CHECK(refused(offsetOf(g->hub_inner_begin()->data()) + 4, 0xFFFFFFF0u));
    CHECK(refused(offsetOf(g->hub_inner_matrix_begin()->data()) + 8, 3));    // a matrix of the wrong size
    REQUIRE(g->hub_block_bounds() != nullptr);
    const size_t bounds = offsetOf(g->hub_block_bounds()->data());
    CHECK(refused(bounds - 4, g->hub_block_bounds()->size() - 1));           // a block short
    CHECK(refused(bounds + 12, 0xBF800000u));                                // a radius of -1
    CHECK(refused(bounds + 4, 0x7FC00000u));                                 // a NaN centre
    if (g->landmark_scale() && g->landmark_scale()->size() > 0)
        CHECK(refused(bounds + 16, 0x7F800000u));                            // a range from +inf (above its end)
    REQUIRE(g->hub_landmarks() != nullptr);
    const size_t hubLandmarks = offsetOf(g->hub_landmarks()->data());
    CHECK(refused(hubLandmarks - 4, g->hub_landmarks()->size() - 1));         // a hub's landmark short
    REQUIRE(g->hub_exit_lists() != nullptr);
    const size_t lists = offsetOf(g->hub_exit_lists()->data());
    CHECK(refused(lists, 0xFFFFu));                                          // an exit past the patch's exits
    uint32_t pair = 0;  // the first list with two entries: make them equal
    while (pair + 1 < g->hub_exit_list_begin()->size() && g->hub_exit_list_begin()->Get(pair + 1) - g->hub_exit_list_begin()->Get(pair) < 2) ++pair;
    REQUIRE(pair + 1 < g->hub_exit_list_begin()->size());
    const uint32_t at = g->hub_exit_list_begin()->Get(pair), second = g->hub_exit_lists()->Get(at + 1);
    CHECK(refused(lists + 2 * size_t(at), second | (second << 16)));        // not increasing
    CHECK(refused(offsetOf(g->hub_exit_patch_begin()->data()) + 4, g->hub_exit_patch_begin()->Get(1) + 1));  // a list too many
    CHECK(refused(offsetOf(g->hub_exit_list_begin()->data()) + 4, 0xFFFFFFF0u));  // a list past the end
    // The tables after the flatbuffer (format 9): their counts must fill exactly the bytes
    // the header gives them.
    const uint64_t columns = g->hub_columns_count();
    REQUIRE(columns > 0);
    CHECK(refused(offsetOf(reinterpret_cast<const flatbuffers::Table*>(g)->GetAddressOf(fb::Graph::VT_HUB_COLUMNS_COUNT)), uint32_t(columns + 32)));
    CHECK(refused(offsetOf(reinterpret_cast<const flatbuffers::Table*>(g)->GetAddressOf(fb::Graph::VT_HUB_COLUMNS_COUNT)), uint32_t(columns - 16)));
    CHECK(refused(offsetOf(reinterpret_cast<const flatbuffers::Table*>(g)->GetAddressOf(fb::Graph::VT_HUB_INNER_COUNT)), uint32_t(g->hub_inner_count() + 32)));
    {  // a header that gives the tables 64 bytes more (and a payload that has them)
        std::vector<uint8_t> longer(blob);
        longer.resize(longer.size() + 64, 0);
        vg_store_le64(longer.data() + 16, vg_load_le64(longer.data() + 16) + 64);
        vg_store_le64(longer.data() + 32, vg_load_le64(longer.data() + 32) + 64);
        resealChecksum(longer);
        CHECK(openStatus(longer) == VG_ERR_CORRUPT_CONTENT);
    }
    CHECK(refused(lists - 4, g->hub_exit_lists()->size() - 1));             // an entry short
}
