// The runtime (runtime/, C API) on blobs baked from generated meshes, and on the shared
// meshes against golden distances when ../shared is present.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <thread>
#include <fstream>
#if defined(__linux__)
#include <sys/mman.h>
#include <sys/prctl.h>
#include <unistd.h>
#endif

#include "bake.h"
#include "blob_reader.h"
#include "blob_test_helpers.h"
#include "blob_writer.h"
#include "distance_coding.h"
#include "generators.h"
#include "geodesic_exact.h"
#include "golden.h"
#include "mesh_io.h"
#include "runtime_graph.h"
#include "runtime_stats.h"
#include "test_helpers.h"
#include "vg_point.h"
#include "vg_point_to_point.h"
#include "vorogeo.h"
#include "vorogeo_container.h"
#include "vorogeo_generated.h"

#define ZSTD_STATIC_LINKING_ONLY
#include <zstd.h>
#include <tbb/global_control.h>

using namespace vorogeo;
using tools::RuntimeGraph;
using tools::RuntimeWorkspace;

namespace {

std::vector<uint8_t> bakeBlob(const Mesh& mesh, bool compress = true, uint32_t n2 = 0, double delta = 0.0,
                              BakeReport* reportOut = nullptr) {
    BakeOptions o;
    o.compress = compress;
    o.n2 = n2;
    o.delta = delta;
    BakeReport report;
    std::vector<uint8_t> blob = bakeMesh(mesh, o, report, nullptr);
    if (reportOut) *reportOut = report;
    return blob;
}

// One baked blob per generated mesh, shared by the test cases of one process.
const std::vector<uint8_t>& bumpyBlob() {
    static const std::vector<uint8_t> blob = bakeBlob(bumpyTorus(60, 30));  // 1,800 vertices
    return blob;
}

// Opens a possibly corrupt blob; if accepted, runs every query kind on a few vertices.
// Returns whether it was accepted. Must never crash or read out of bounds.
bool openAndQuery(const std::vector<uint8_t>& blob) {
    tools::AlignedBytes copy, memory, wsMemory;
    copy.resize(blob.size());
    if (!blob.empty()) std::memcpy(copy.data(), blob.data(), blob.size());
    size_t need = 0;
    if (vg_open_size(copy.data(), blob.size(), &need) != VG_OK) return false;
    memory.resize(need);
    const vg_graph* g = nullptr;
    if (vg_open(copy.data(), blob.size(), memory.data(), need, &g) != VG_OK) {
        REQUIRE(g == nullptr);
        return false;
    }
    const size_t wsBytes = vg_workspace_size(g);
    wsMemory.resize(wsBytes);
    vg_workspace* ws = nullptr;
    REQUIRE(vg_workspace_init(g, wsMemory.data(), wsBytes, &ws) == VG_OK);
    const uint32_t V = vg_vertex_count(g);
    float d = 0;
    std::vector<float> field(V);
    const uint32_t picks[3] = {0, V / 2, V - 1};
    for (uint32_t a : picks)
        for (uint32_t b : picks) REQUIRE(vg_distance(g, ws, a, b, &d) == VG_OK);
    REQUIRE(vg_distance_field(g, ws, picks, 3, field.data()) == VG_OK);
    size_t index = 0;
    REQUIRE(vg_nearest(g, ws, picks[0], picks + 1, 2, &index, &d) == VG_OK);
    const uint32_t F = vg_face_count(g);
    if (F > 0) {
        const vg_point pts[2] = {{0, {0.2f, 0.3f, 0.5f}}, {F - 1, {0.6f, 0.3f, 0.1f}}};
        REQUIRE(vg_point_distance(g, ws, &pts[0], &pts[1], &d) == VG_OK);
        REQUIRE(vg_point_distance_field(g, ws, pts, 2, field.data(), nullptr) == VG_OK);
        size_t found = 0;
        REQUIRE(vg_point_k_nearest(g, ws, &pts[0], pts, 2, 1, &index, &d, &found) == VG_OK);
    }
    return true;
}

}  // namespace

TEST_CASE("runtime: opens a baked blob, compressed or in place, and reports its size", "[runtime]") {
    const Mesh mesh = bumpyTorus(60, 30);
    RuntimeGraph g = openOrFail(bumpyBlob());
    CHECK(vg_vertex_count(g.graph()) == mesh.vertexCount());
    CHECK(vg_node_count(g.graph()) > 0);
    CHECK(vg_bbox_diagonal(g.graph()) > 0);
    CHECK(vg_supports_compression() == 1);

    // Uncompressed: the graph points into the caller's blob (zero copy) and needs only the handle.
    const std::vector<uint8_t> raw = bakeBlob(mesh, false);
    tools::AlignedBytes copy;
    copy.resize(raw.size());
    std::memcpy(copy.data(), raw.data(), raw.size());
    size_t need = 0;
    REQUIRE(vg_open_size(copy.data(), raw.size(), &need) == VG_OK);
    CHECK(need < 1024);
    std::vector<unsigned char> memory(need);
    const vg_graph* graph = nullptr;
    REQUIRE(vg_open(copy.data(), raw.size(), memory.data(), need, &graph) == VG_OK);
    RuntimeGraph compressed = openOrFail(bumpyBlob());
    CHECK(RuntimeWorkspace(graph).distance(3, 1500) == RuntimeWorkspace(compressed).distance(3, 1500));

    // Too little memory is an error, not an overrun.
    CHECK(vg_open(copy.data(), raw.size(), memory.data(), need - 1, &graph) == VG_ERR_BUFFER_TOO_SMALL);
    CHECK(graph == nullptr);
}

#if defined(__linux__)
namespace {

// The VmFlags line of /proc/self/smaps for the mapping that holds `address` ("" if none).
std::string vmFlagsAt(const void* address) {
    std::ifstream smaps("/proc/self/smaps");
    const uintptr_t a = reinterpret_cast<uintptr_t>(address);
    std::string line;
    bool inside = false;
    while (std::getline(smaps, line)) {
        unsigned long lo = 0, hi = 0;
        if (std::sscanf(line.c_str(), "%lx-%lx ", &lo, &hi) == 2 && line.find('-') < line.find(' ')) inside = a >= lo && a < hi;
        else if (inside && line.rfind("VmFlags:", 0) == 0) return line;
    }
    return "";
}

bool hasFlag(const std::string& vmFlags, const char* flag) {
    return (vmFlags + " ").find(std::string(" ") + flag + " ") != std::string::npos;
}

}  // namespace

TEST_CASE("runtime: vg_open and vg_workspace_init ask for huge pages in large buffers only", "[runtime]") {
    if (!std::ifstream("/sys/kernel/mm/transparent_hugepage/enabled") || vmFlagsAt(&bumpyBlob()).empty()) {
        WARN("skipped: no transparent huge pages or no /proc/self/smaps on this system");
        return;
    }
    // 8 MB, 2 MB aligned, fresh from mmap: the graph and the workspace of the test torus fit.
    constexpr size_t kHuge = size_t(2) << 20, kBytes = 4 * kHuge;
    auto fresh = [] {
        void* p = mmap(nullptr, kBytes + kHuge, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        REQUIRE(p != MAP_FAILED);
        return p;
    };
    void* graphMapping = fresh();
    void* wsMapping = fresh();
    auto aligned = [](void* p) { return reinterpret_cast<unsigned char*>((reinterpret_cast<uintptr_t>(p) + kHuge - 1) & ~(kHuge - 1)); };
    unsigned char* graphMemory = aligned(graphMapping);
    unsigned char* wsMemory = aligned(wsMapping);
    CHECK_FALSE(hasFlag(vmFlagsAt(graphMemory), "hg"));

    const std::vector<uint8_t>& blob = bumpyBlob();
    size_t need = 0;
    REQUIRE(vg_open_size(blob.data(), blob.size(), &need) == VG_OK);
    REQUIRE(need <= kBytes);
    const vg_graph* g = nullptr;
    REQUIRE(vg_open(blob.data(), blob.size(), graphMemory, kBytes, &g) == VG_OK);
    CHECK(hasFlag(vmFlagsAt(graphMemory), "hg"));
    CHECK(hasFlag(vmFlagsAt(graphMemory + kBytes - 1), "hg"));
    CHECK_FALSE(hasFlag(vmFlagsAt(graphMemory + kBytes), "hg"));  // the page after the buffer is not ours

    REQUIRE(vg_workspace_size(g) <= kBytes);
    vg_workspace* ws = nullptr;
    REQUIRE(vg_workspace_init(g, wsMemory, kBytes, &ws) == VG_OK);
    CHECK(hasFlag(vmFlagsAt(wsMemory), "hg"));
    float d = 0.0f;
    CHECK(vg_distance(g, ws, 3, 1500, &d) == VG_OK);
    CHECK(d == RuntimeWorkspace(openOrFail(blob).graph()).distance(3, 1500));

    // A buffer holding no whole 2 MB page is left alone.
    void* smallMapping = fresh();
    unsigned char* small = aligned(smallMapping) + 4096;
    REQUIRE(vg_open(blob.data(), blob.size(), small, kHuge - 8192, &g) == (need <= kHuge - 8192 ? VG_OK : VG_ERR_BUFFER_TOO_SMALL));
    CHECK_FALSE(hasFlag(vmFlagsAt(small), "hg"));
    munmap(graphMapping, kBytes + kHuge);
    munmap(wsMapping, kBytes + kHuge);
    munmap(smallMapping, kBytes + kHuge);
}

TEST_CASE("runtime: vg_workspace_init writes every page of its memory, so that no query faults one in", "[runtime]") {
    const RuntimeGraph graph = openOrFail(bumpyBlob());
    const vg_graph* g = graph.graph();
    const size_t bytes = vg_workspace_size(g), page = size_t(sysconf(_SC_PAGESIZE));
    // Fresh pages from mmap, and no huge pages for this process while the workspace is
    // made (a huge page is resident whole once any byte of it is written): pages that
    // nothing wrote are then not resident.
    void* mapping = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    REQUIRE(mapping != MAP_FAILED);
    unsigned char* memory = static_cast<unsigned char*>(mapping);
    const bool hugePagesOff = prctl(PR_SET_THP_DISABLE, 1, 0, 0, 0) == 0;
    vg_workspace* ws = nullptr;
    const vg_status made = vg_workspace_init(g, memory, bytes, &ws);
    if (hugePagesOff) prctl(PR_SET_THP_DISABLE, 0, 0, 0, 0);  // before any REQUIRE can leave
    REQUIRE(made == VG_OK);
    const size_t pages = (bytes + page - 1) / page;
    std::vector<unsigned char> resident(pages);
    REQUIRE(mincore(memory, bytes, resident.data()) == 0);
    size_t missing = 0;
    for (unsigned char r : resident) missing += (r & 1) ? 0 : 1;
    INFO(missing << " of " << pages << " pages never written");
    CHECK(missing == 0);
    float d = 0.0f;
    CHECK(vg_distance(g, ws, 3, 1500, &d) == VG_OK);
    CHECK(d == RuntimeWorkspace(g).distance(3, 1500));
    munmap(mapping, bytes);
}
#endif

TEST_CASE("runtime: vg_open_file maps or decompresses with the caller's allocator", "[runtime]") {
    test::TempDir dir;
    const std::vector<uint8_t> raw = bakeBlob(bumpyTorus(60, 30), false);
    for (const auto* blob : {&bumpyBlob(), &raw}) {
        const std::string path = dir.file("b.vgeo");
        writeFileAtomically(path, *blob);
        struct Counter {
            int live = 0;
        } counter;
        vg_allocator alloc{[](void* user, size_t n) {
                               ++static_cast<Counter*>(user)->live;
                               return std::malloc(n);
                           },
                           [](void* user, void* p) {
                               --static_cast<Counter*>(user)->live;
                               std::free(p);
                           },
                           &counter};
        const vg_graph* g = nullptr;
        REQUIRE(vg_open_file(path.c_str(), &alloc, &g) == VG_OK);
        CHECK(counter.live == 1);  // the handle's memory only; file bytes are mapped
        RuntimeGraph ref = openOrFail(*blob);
        CHECK(RuntimeWorkspace(g).distance(10, 900) == RuntimeWorkspace(ref).distance(10, 900));
        vg_close_file(g);
        CHECK(counter.live == 0);
    }
    const vg_graph* g = nullptr;
    vg_allocator alloc{[](void*, size_t n) { return std::malloc(n); }, [](void*, void* p) { std::free(p); }, nullptr};
    CHECK(vg_open_file(dir.file("missing.vgeo").c_str(), &alloc, &g) == VG_ERR_IO);
    CHECK(vg_open_file(dir.file("missing.vgeo").c_str(), nullptr, &g) == VG_ERR_INVALID_ARGUMENT);
    CHECK(g == nullptr);
}

TEST_CASE("runtime: point-to-point agrees with one-to-all, is symmetric and close to exact", "[runtime]") {
    const Mesh mesh = bumpyTorus(60, 30);
    RuntimeGraph g = openOrFail(bumpyBlob());
    RuntimeWorkspace ws(g);
    const vg_search_mode mode = GENERATE(VG_SEARCH_DIRECTED, VG_SEARCH_BIDIRECTIONAL);
    ws.setSearch(mode);
    ExactGeodesic exact(mesh);
    ExactWorkspace ews;
    std::mt19937 rng(7);
    std::uniform_int_distribution<uint32_t> pick(0, mesh.vertexCount() - 1);
    double sumRel = 0, maxRel = 0, maxP2pField = 0;
    size_t n = 0;
    for (int s = 0; s < 8; ++s) {
        const uint32_t source = pick(rng);
        const std::vector<float> field = ws.field({source});
        std::vector<double> ex;
        ExactQuery q;
        q.sources.push_back(GeodesicSource::atVertex(source));
        ews.run(exact, q, ex);
        CHECK(field[source] == 0.0f);
        for (int t = 0; t < 40; ++t) {
            const uint32_t target = pick(rng);
            const float d = ws.distance(source, target);
            CHECK(d == ws.distance(target, source));  // the same number both ways
            if (source == target) {
                CHECK(d == 0.0f);
                continue;
            }
            // Both answers are the same graph distance, up to where the unfolded border
            // crossing is taken (the field: at the target's patch; point-to-point: where
            // the searches meet) and the 12-bit rounding of the first-layer overlay.
            maxP2pField = std::max(maxP2pField, std::fabs(double(d) - field[target]) / ex[target]);
            const double rel = std::fabs(double(d) - ex[target]) / ex[target];
            sumRel += rel;
            maxRel = std::max(maxRel, rel);
            ++n;
        }
    }
    INFO("search " << mode << ": mean " << sumRel / n << " max " << maxRel << " p2p vs field " << maxP2pField);
    CHECK(maxP2pField <= 0.02);
    CHECK(sumRel / n <= 0.005);
    CHECK(maxRel <= 0.05);
}

TEST_CASE("runtime: a short pair keeps the better answer of the directed searches from both ends", "[runtime]") {
    const Mesh mesh = bumpyTorus(60, 30);
    RuntimeGraph g = openOrFail(bumpyBlob());
    RuntimeWorkspace directed(g), single(g);
    directed.setSearch(VG_SEARCH_DIRECTED);
    const vg_graph& graph = *g.graph();
    const float diagonal = vg_bbox_diagonal(g.graph());
    std::mt19937 rng(23);
    std::uniform_int_distribution<uint32_t> pick(0, mesh.vertexCount() - 1);
    size_t shortPairs = 0, fromSecondLower = 0, fromFirstLower = 0;
    for (int i = 0; i < 100000 && shortPairs < 3000; ++i) {
        const uint32_t s = pick(rng), t = pick(rng);
        const Vec3 a = mesh.positions[s], b = mesh.positions[t];
        const double straight = std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
        if (s == t || straight >= 0.09 * diagonal) continue;
        const vg::Endpoint es = vg::vertexEndpoint(graph, s), et = vg::vertexEndpoint(graph, t);
        const float first = vg::directedSearch(graph, *single.get(), es, et, INFINITY, false);
        const float second = vg::directedSearch(graph, *single.get(), es, et, INFINITY, true);
        // Short for the runtime: its lower bound of the distance is under a tenth of the
        // diagonal, which holds when the answer is under 0.09 of it (the answer is within
        // a percent of the geodesic, the bound below it).
        if (!(first < 0.09f * diagonal)) continue;
        ++shortPairs;
        const float d = directed.distance(s, t);
        CHECK(d == std::min(first, second));
        CHECK(d == directed.distance(t, s));
        // The two searches are one each way, whichever end the caller names first.
        CHECK(first == vg::directedSearch(graph, *single.get(), et, es, INFINITY, false));
        fromSecondLower += second < first;
        fromFirstLower += first < second;
    }
    INFO("short pairs " << shortPairs << ", the search from the second end lower on " << fromSecondLower
                        << ", the first on " << fromFirstLower);
    CHECK(shortPairs >= 100);
    // Each search meets border crossings the other misses: both must be run.
    CHECK(fromSecondLower > 0);
    CHECK(fromFirstLower > 0);
}

TEST_CASE("runtime: one-to-all on a pruned graph (merged-away nodes) stays close to exact", "[runtime]") {
    // The one-to-all search never labels a merged-away node; the fill gives them, like
    // interior vertices, the best of their patch's nodes. (Point-to-point is no reference
    // here: it crosses far first-layer patches through the pruned overlay.)
    const Mesh mesh = bumpyTorus(60, 30);
    BakeReport report;
    const std::vector<uint8_t> blob = bakeBlob(mesh, true, 0, 0.03, &report);
    REQUIRE(report.secondPrune.prunedNodes > 0);
    RuntimeGraph g = openOrFail(blob);
    RuntimeWorkspace ws(g);
    double sumRel = 0, maxRel = 0;
    size_t n = 0;
    for (uint32_t source : {0u, 600u, 1205u}) {
        const std::vector<float> field = ws.field({source});
        const std::vector<double> ex = exactDistancesFrom(mesh, source);
        CHECK(field[source] == 0.0f);
        for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
            if (v == source) continue;
            REQUIRE(field[v] < __builtin_inff());  // one component: every vertex reached
            const double rel = std::fabs(double(field[v]) - ex[v]) / ex[v];
            sumRel += rel;
            maxRel = std::max(maxRel, rel);
            ++n;
        }
    }
    INFO("pruned " << report.secondPrune.prunedNodes << " of " << report.secondPrune.nodes << " nodes; mean "
                   << sumRel / n << " max " << maxRel);
    // Merging nodes with near-equal rows is lossy by design (delta 0 is the default): here
    // 138 of 573 nodes, mean 0.86% and max 32% (against 0.15% and 4.5% at delta 0.02).
    CHECK(sumRel / n <= 0.02);
    CHECK(maxRel <= 0.5);
}

TEST_CASE("runtime: the triangle inequality holds up to rounding on random triples", "[runtime]") {
    RuntimeGraph g = openOrFail(bumpyBlob());
    RuntimeWorkspace ws(g);
    ws.setSearch(GENERATE(VG_SEARCH_DIRECTED, VG_SEARCH_BIDIRECTIONAL));
    const tools::MetricReport m = tools::checkMetric(ws, g.vertexCount(), 400, 3);
    CHECK(m.symmetryViolations == 0);
    CHECK(m.triples == 400);
    // Unfolded crossings can undercut a path through a node by a hair; never more than
    // a thousandth of the bounding-box diagonal.
    CHECK(m.maxTriangleExcess <= 1e-3 * vg_bbox_diagonal(g.graph()));
}

TEST_CASE("runtime: bounded queries, nearest of a set and multi-source fields agree", "[runtime]") {
    RuntimeGraph g = openOrFail(bumpyBlob());
    RuntimeWorkspace ws(g);
    const vg_graph* graph = g.graph();
    const uint32_t V = g.vertexCount();
    std::mt19937 rng(11);
    std::uniform_int_distribution<uint32_t> pick(0, V - 1);
    for (vg_search_mode mode : {VG_SEARCH_DIRECTED, VG_SEARCH_BIDIRECTIONAL}) {
        ws.setSearch(mode);
        for (int i = 0; i < 50; ++i) {
            const uint32_t s = pick(rng), t = pick(rng);
            const float d = ws.distance(s, t);
            float within = -1;
            REQUIRE(vg_distance_within(graph, ws.get(), s, t, d, &within) == VG_OK);
            CHECK(within == d);
            REQUIRE(vg_distance_within(graph, ws.get(), s, t, d * 0.99f, &within) == VG_OK);
            CHECK((d == 0 || std::isinf(within)));
        }
    }
    ws.setSearch(VG_SEARCH_DIRECTED);
    // Nearest of 12 targets = the smallest point-to-point distance, first index on ties.
    for (int i = 0; i < 20; ++i) {
        const uint32_t s = pick(rng);
        std::vector<uint32_t> targets;
        for (int k = 0; k < 12; ++k) targets.push_back(pick(rng));
        targets.push_back(targets[3]);  // a duplicate never wins over its first listing
        size_t index = 99;
        float d = -1;
        REQUIRE(vg_nearest(graph, ws.get(), s, targets.data(), targets.size(), &index, &d) == VG_OK);
        float best = INFINITY;
        for (uint32_t t : targets) best = std::min(best, ws.distance(s, t));
        REQUIRE(index < 12);
        // Nearest offers stored entries from settled nodes; point-to-point may also
        // unfold a border crossing, which shortens a path by at most 5%.
        CHECK(d >= best * 0.9999f);
        CHECK(d <= best * 1.05f + 1e-6f);
    }
    size_t index = 0;
    float d = 0;
    REQUIRE(vg_nearest(graph, ws.get(), 5, nullptr, 0, &index, &d) == VG_OK);
    CHECK(index == 0);
    CHECK(std::isinf(d));
    // A multi-source field is the pointwise minimum of the single-source fields (nodes
    // exactly; other vertices up to which source's border crossing is unfolded).
    const std::vector<uint32_t> sources = {17, 900, 1400};
    const std::vector<float> multi = ws.field(sources);
    std::vector<float> minimum(V, INFINITY);
    for (uint32_t s : sources) {
        const std::vector<float> one = ws.field({s});
        for (uint32_t v = 0; v < V; ++v) minimum[v] = std::min(minimum[v], one[v]);
    }
    for (uint32_t v = 0; v < V; ++v) REQUIRE(std::fabs(multi[v] - minimum[v]) <= 0.02f * minimum[v]);

    // The nearest-source labels name a source whose own field gives that distance (the
    // Voronoi cell), and the distances are those of vg_distance_field.
    std::vector<float> labelled(V);
    std::vector<uint32_t> nearest(V, 77);
    REQUIRE(vg_distance_field_nearest(graph, ws.get(), sources.data(), sources.size(), labelled.data(),
                                      nearest.data()) == VG_OK);
    std::vector<std::vector<float>> single;
    for (uint32_t s : sources) single.push_back(ws.field({s}));
    size_t agree = 0;
    for (uint32_t v = 0; v < V; ++v) {
        REQUIRE(labelled[v] == multi[v]);
        REQUIRE(nearest[v] < sources.size());
        CHECK(single[nearest[v]][v] <= labelled[v] * 1.02f + 1e-6f);
        agree += single[nearest[v]][v] == minimum[v];
    }
    CHECK(agree >= V * 95 / 100);  // off only where two sources tie within the unfolding
    for (size_t i = 0; i < sources.size(); ++i) CHECK(nearest[sources[i]] == i);
    // A source listed twice is named by its first listing; no source: none reachable.
    const uint32_t twice[3] = {900, 17, 900};
    REQUIRE(vg_distance_field_nearest(graph, ws.get(), twice, 3, labelled.data(), nearest.data()) == VG_OK);
    CHECK(nearest[900] == 0);
    CHECK(nearest[17] == 1);
    REQUIRE(vg_distance_field_nearest(graph, ws.get(), twice, 0, labelled.data(), nearest.data()) == VG_OK);
    CHECK(nearest[5] == 0);
    CHECK(std::isinf(labelled[5]));
}

TEST_CASE("runtime: vertices of different components are at +infinity in every query", "[runtime]") {
    const Mesh mesh = twoComponents();
    RuntimeGraph g = openOrFail(bakeBlob(mesh));
    RuntimeWorkspace ws(g);
    const vg_graph* graph = g.graph();
    // Label the components by one field: finite = same component as vertex 0.
    const std::vector<float> field = ws.field({0});
    uint32_t other = UINT32_MAX, same = UINT32_MAX;
    for (uint32_t v = 1; v < mesh.vertexCount(); ++v) {
        if (std::isinf(field[v]) && other == UINT32_MAX) other = v;
        if (std::isfinite(field[v]) && same == UINT32_MAX) same = v;
    }
    REQUIRE(other != UINT32_MAX);
    REQUIRE(same != UINT32_MAX);
    float d = 0;
    for (vg_search_mode mode : {VG_SEARCH_DIRECTED, VG_SEARCH_BIDIRECTIONAL}) {
        ws.setSearch(mode);
        CHECK(std::isinf(ws.distance(0, other)));
        CHECK(std::isinf(ws.distance(other, 0)));
        CHECK(std::isfinite(ws.distance(0, same)));
        CHECK(ws.distance(0, same) > 0);
        REQUIRE(vg_distance_within(graph, ws.get(), 0, other, 1e30f, &d) == VG_OK);
        CHECK(std::isinf(d));
    }
    size_t index = 0;
    const uint32_t targets[1] = {other};
    REQUIRE(vg_nearest(graph, ws.get(), 0, targets, 1, &index, &d) == VG_OK);
    CHECK(index == 1);
    CHECK(std::isinf(d));
    const uint32_t both[2] = {other, same};
    REQUIRE(vg_nearest(graph, ws.get(), 0, both, 2, &index, &d) == VG_OK);
    CHECK(index == 1);
    CHECK(std::isfinite(d));
}

TEST_CASE("runtime: arguments are checked and named by status codes", "[runtime]") {
    RuntimeGraph g = openOrFail(bumpyBlob());
    RuntimeWorkspace ws(g);
    const vg_graph* graph = g.graph();
    const uint32_t V = g.vertexCount();
    float d = 0;
    CHECK(vg_distance(graph, ws.get(), 0, V, &d) == VG_ERR_INVALID_VERTEX);
    CHECK(vg_distance(graph, ws.get(), V, 0, &d) == VG_ERR_INVALID_VERTEX);
    CHECK(vg_distance(nullptr, ws.get(), 0, 1, &d) == VG_ERR_INVALID_ARGUMENT);
    CHECK(vg_distance(graph, nullptr, 0, 1, &d) == VG_ERR_INVALID_ARGUMENT);
    CHECK(vg_distance(graph, ws.get(), 0, 1, nullptr) == VG_ERR_INVALID_ARGUMENT);
    CHECK(vg_distance_within(graph, ws.get(), 0, 1, NAN, &d) == VG_ERR_INVALID_ARGUMENT);
    CHECK(vg_workspace_set_search(nullptr, VG_SEARCH_DIRECTED) == VG_ERR_INVALID_ARGUMENT);
    CHECK(vg_workspace_set_search(ws.get(), vg_search_mode(3)) == VG_ERR_INVALID_ARGUMENT);
    CHECK(vg_workspace_set_search(ws.get(), vg_search_mode(-1)) == VG_ERR_INVALID_ARGUMENT);
    CHECK(vg_workspace_set_search(ws.get(), VG_SEARCH_BIDIRECTIONAL) == VG_OK);
    CHECK(vg_workspace_set_search(ws.get(), VG_SEARCH_DIRECTED) == VG_OK);
    const uint32_t bad[2] = {0, V + 5};
    std::vector<float> field(V);
    CHECK(vg_distance_field(graph, ws.get(), bad, 2, field.data()) == VG_ERR_INVALID_VERTEX);
    size_t index = 0;
    CHECK(vg_nearest(graph, ws.get(), 0, bad, 2, &index, &d) == VG_ERR_INVALID_VERTEX);
    // A workspace made for another graph is refused.
    RuntimeGraph other = openOrFail(bakeBlob(planeGrid(12, 12, 1.0)));
    RuntimeWorkspace otherWs(other);
    CHECK(vg_distance(graph, otherWs.get(), 0, 1, &d) == VG_ERR_WRONG_WORKSPACE);
    // Workspace memory too small.
    std::vector<unsigned char> small(16);
    vg_workspace* w = nullptr;
    CHECK(vg_workspace_init(graph, small.data(), small.size(), &w) == VG_ERR_BUFFER_TOO_SMALL);
    CHECK(w == nullptr);
    for (int s = 0; s <= 17; ++s) CHECK(std::string(vg_status_string(vg_status(s))) != "unknown status");
    CHECK(std::string(vg_status_string(vg_status(99))) == "unknown status");
}

TEST_CASE("runtime: many threads on one graph give the same bits as one thread", "[runtime]") {
    RuntimeGraph g = openOrFail(bumpyBlob());
    const uint32_t V = g.vertexCount();
    std::vector<std::pair<uint32_t, uint32_t>> pairs;
    std::mt19937 rng(5);
    std::uniform_int_distribution<uint32_t> pick(0, V - 1);
    for (int i = 0; i < 400; ++i) pairs.emplace_back(pick(rng), pick(rng));
    auto answer = [&](std::vector<float>& out) {
        RuntimeWorkspace ws(g);
        for (const auto& p : pairs) out.push_back(ws.distance(p.first, p.second));
        ws.setSearch(VG_SEARCH_BIDIRECTIONAL);
        for (const auto& p : pairs) out.push_back(ws.distance(p.first, p.second));
        const std::vector<float> f = ws.field({pairs[0].first, pairs[1].first});
        out.insert(out.end(), f.begin(), f.end());
    };
    std::vector<float> reference;
    answer(reference);
    std::vector<std::vector<float>> results(4);
    std::vector<std::thread> threads;
    for (auto& r : results) threads.emplace_back([&answer, &r] { answer(r); });
    for (auto& t : threads) t.join();
    for (const auto& r : results) {
        REQUIRE(r.size() == reference.size());
        CHECK(std::memcmp(r.data(), reference.data(), r.size() * sizeof(float)) == 0);
    }
}

TEST_CASE("runtime: every truncation and every flipped byte of a blob is rejected", "[runtime]") {
    const std::vector<uint8_t> blob = bakeBlob(planeGrid(10, 10, 1.0), true, 4);
    REQUIRE(openAndQuery(blob));
    for (size_t n = 0; n < blob.size(); ++n) {
        const std::vector<uint8_t> cut(blob.begin(), blob.begin() + n);
        REQUIRE_FALSE(openAndQuery(cut));
    }
    for (size_t i = 0; i < blob.size(); ++i) {
        std::vector<uint8_t> flipped = blob;
        flipped[i] ^= 0x5A;
        REQUIRE_FALSE(openAndQuery(flipped));
    }
    std::vector<uint8_t> longer = blob;
    longer.push_back(0);
    CHECK_FALSE(openAndQuery(longer));
}

TEST_CASE("runtime: a payload in several zstd frames opens as in one, frames of another size are refused", "[runtime]") {
    // The baker cuts a compressed payload into frames of VG_CONTAINER_FRAME_BYTES; here
    // frames of 4 KB, so that a small labelled blob has hundreds of them.
    const Mesh mesh = bumpyTorus(60, 30);
    BakeOptions o;
    o.compress = false;
    o.hubLabels = true;
    BakeReport report;
    const std::vector<uint8_t> plain = bakeMesh(mesh, o, report, nullptr);
    const std::vector<uint8_t> payload(plain.begin() + VG_CONTAINER_HEADER_SIZE, plain.end());
    const uint64_t flatbufferSize = vg_load_le64(plain.data() + 24);
    const std::vector<uint8_t> one = sealContainer(payload, VG_FLAG_ZSTD, 3, flatbufferSize, uint64_t(1) << 40);
    const std::vector<uint8_t> many = sealContainer(payload, VG_FLAG_ZSTD, 3, flatbufferSize, 4096);
    REQUIRE(payload.size() > 100 * 4096);
    CHECK(ZSTD_findDecompressedSize(one.data() + VG_CONTAINER_HEADER_SIZE, one.size() - VG_CONTAINER_HEADER_SIZE) ==
          payload.size());
    CHECK(ZSTD_getFrameContentSize(many.data() + VG_CONTAINER_HEADER_SIZE, many.size() - VG_CONTAINER_HEADER_SIZE) == 4096);
    size_t needOne = 0, needMany = 0;
    REQUIRE(vg_open_size(one.data(), one.size(), &needOne) == VG_OK);
    REQUIRE(vg_open_size(many.data(), many.size(), &needMany) == VG_OK);
    CHECK(needOne == needMany);
    RuntimeGraph a = openOrFail(plain), b = openOrFail(many);
    RuntimeWorkspace wa(a.graph()), wb(b.graph());
    for (uint32_t s : {0u, 17u, 900u})
        for (uint32_t t : {5u, 1200u, 1799u}) CHECK(wa.distance(s, t) == wb.distance(s, t));

    // The same bytes for any number of threads.
    {
        tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
        CHECK(sealContainer(payload, VG_FLAG_ZSTD, 3, flatbufferSize, 4096) == many);
    }

    // A header that claims another unpacked size than the frames hold together, frames
    // missing at the end, a frame that does not state its size: refused before any memory
    // is sized by them.
    auto sizeStatus = [](const std::vector<uint8_t>& blob) {
        size_t need = 0;
        return vg_open_size(blob.data(), blob.size(), &need);
    };
    std::vector<uint8_t> claims = many;
    vg_store_le64(claims.data() + 32, vg_load_le64(many.data() + 32) + 64);  // 64 table bytes more
    CHECK(sizeStatus(claims) == VG_ERR_DECOMPRESSION);
    size_t at = VG_CONTAINER_HEADER_SIZE, frames = 0, lastStart = at;
    while (at < many.size()) {
        lastStart = at;
        at += ZSTD_findFrameCompressedSize(many.data() + at, many.size() - at);
        ++frames;
    }
    REQUIRE(at == many.size());
    CHECK(frames == (payload.size() + 4095) / 4096);
    std::vector<uint8_t> shorter(many.begin(), many.begin() + long(lastStart));
    vg_store_le64(shorter.data() + 16, shorter.size() - VG_CONTAINER_HEADER_SIZE);
    resealChecksum(shorter);
    CHECK(sizeStatus(shorter) == VG_ERR_DECOMPRESSION);
    std::vector<uint8_t> unsized(many.begin(), many.begin() + long(lastStart));
    {
        const size_t tail = payload.size() - (frames - 1) * 4096;
        std::vector<uint8_t> frame(ZSTD_compressBound(tail));
        ZSTD_CCtx* context = ZSTD_createCCtx();
        ZSTD_CCtx_setParameter(context, ZSTD_c_contentSizeFlag, 0);
        const size_t n = ZSTD_compress2(context, frame.data(), frame.size(), payload.data() + (frames - 1) * 4096, tail);
        ZSTD_freeCCtx(context);
        REQUIRE_FALSE(ZSTD_isError(n));
        unsized.insert(unsized.end(), frame.begin(), frame.begin() + long(n));
    }
    vg_store_le64(unsized.data() + 16, unsized.size() - VG_CONTAINER_HEADER_SIZE);
    resealChecksum(unsized);
    CHECK(sizeStatus(unsized) == VG_ERR_DECOMPRESSION);
}

TEST_CASE("runtime: corrupt flatbuffers with a valid checksum are refused or answered safely", "[runtime]") {
    // The checksum catches accidents; this reaches the verifier and the index checks, the
    // way a crafted blob would. Every byte of an uncompressed flatbuffer is changed in
    // turn (then the checksum is made to match again).
    const std::vector<uint8_t> blob = bakeBlob(planeGrid(10, 10, 1.0), false, 4);
    REQUIRE(openAndQuery(blob));
    size_t accepted = 0, rejected = 0;
    for (size_t i = VG_CONTAINER_HEADER_SIZE; i < blob.size(); ++i) {
        for (uint8_t mask : {uint8_t(0x01), uint8_t(0x80), uint8_t(0xFF)}) {
            std::vector<uint8_t> bad = blob;
            bad[i] ^= mask;
            resealChecksum(bad);
            (openAndQuery(bad) ? accepted : rejected)++;
        }
    }
    INFO("accepted " << accepted << " rejected " << rejected);
    CHECK(rejected > 0);
    CHECK(accepted > 0);  // distances and positions may change without breaking any index
}

TEST_CASE("runtime: a coded blob whose decoded arrays share bytes with others is refused", "[runtime][coding]") {
    // The flatbuffers verifier lets two vectors overlap; a coded blob's topology and
    // distances are decoded where they lie, so an overlap would rewrite arrays already
    // checked. Here face_twin is pointed at face_vertices' bytes.
    const std::vector<uint8_t> blob = bakeBlob(planeGrid(10, 10, 1.0), false, 4);
    std::vector<uint8_t> flatbuffer(blob.begin() + VG_CONTAINER_HEADER_SIZE, blob.end());
    codeDistances(flatbuffer);
    CHECK(openStatus(sealContainer(flatbuffer, VG_FLAG_CODED_DISTANCES, 0)) == VG_OK);
    const fb::Graph* g = fb::GetGraph(flatbuffer.data());
    const uint8_t* field = reinterpret_cast<const flatbuffers::Table*>(g)->GetAddressOf(fb::Graph::VT_FACE_TWIN);
    REQUIRE(field != nullptr);
    const uint8_t* target = reinterpret_cast<const uint8_t*>(g->face_vertices());
    REQUIRE(target > field);
    const uint32_t offset = uint32_t(target - field);
    std::memcpy(flatbuffer.data() + (field - flatbuffer.data()), &offset, 4);
    REQUIRE(fb::GetGraph(flatbuffer.data())->face_twin() == fb::GetGraph(flatbuffer.data())->face_vertices());
    const std::vector<uint8_t> crafted = sealContainer(flatbuffer, VG_FLAG_CODED_DISTANCES, 0);
    CHECK(openStatus(crafted) == VG_ERR_CORRUPT_STRUCTURE);
    tools::BlobContents contents;  // the tools' reader relies on the runtime's check before it decodes
    std::string error;
    CHECK_FALSE(tools::unpackBlob(crafted, contents, error));
    CHECK(error.find("the runtime refuses the blob") != std::string::npos);
}

TEST_CASE("runtime: a coded sequence laid over another's length decodes within the buffer and is refused",
          "[runtime][coding]") {
    // node_vertex, the first coded sequence decoded, is pointed at a one-entry vector whose
    // only entry is the length field of a later coded sequence (its data shares no byte with
    // any array, so the overlap checks let it through). Decoding node_vertex rewrites that
    // length; an odd length decodes to a huge one, which the later sequence's decoding must
    // not follow past the buffer (CI's fuzzer found this in session 61's try).
    const uint16_t later[] = {fb::Graph::VT_SLOTS, fb::Graph::VT_NODE_EDGE, fb::Graph::VT_NODE_SECOND_BEGIN,
                              fb::Graph::VT_NODE_FIRST_BEGIN, fb::Graph::VT_NODE_EDGE_BEGIN};
    // Returns whether the case could be laid out over `field`'s length.
    auto layOver = [](std::vector<uint8_t> flatbuffer, uint16_t field) {
        const auto* table = reinterpret_cast<const flatbuffers::Table*>(fb::GetGraph(flatbuffer.data()));
        const auto* victim = table->GetPointer<const flatbuffers::Vector<uint32_t>*>(field);
        if (victim == nullptr || victim->size() % 2 == 0) return false;  // an even length decodes smaller
        const uint8_t* length = reinterpret_cast<const uint8_t*>(victim);
        const uint8_t* slot = table->GetAddressOf(fb::Graph::VT_NODE_VERTEX);
        REQUIRE(slot != nullptr);
        REQUIRE(length - 4 > slot);
        const uint32_t one = 1, offset = uint32_t(length - 4 - slot);
        std::memcpy(flatbuffer.data() + (length - 4 - flatbuffer.data()), &one, 4);  // the new vector's length
        std::memcpy(flatbuffer.data() + (slot - flatbuffer.data()), &offset, 4);
        flatbuffers::Verifier verifier(flatbuffer.data(), flatbuffer.size());
        if (!fb::VerifyGraphBuffer(verifier)) return false;  // the word before was structure
        const fb::Graph* g = fb::GetGraph(flatbuffer.data());
        REQUIRE(g->node_vertex()->size() == 1);
        REQUIRE(reinterpret_cast<const uint8_t*>(g->node_vertex()->data()) == length);
        const std::vector<uint8_t> crafted = sealContainer(flatbuffer, VG_FLAG_CODED_DISTANCES, 0);
        CHECK(openStatus(crafted) == VG_ERR_CORRUPT_STRUCTURE);
        tools::BlobContents contents;  // the tools' reader, which decodes in place too: refused (for any reason)
        std::string error;
        CHECK_FALSE(tools::unpackBlob(crafted, contents, error));
        CHECK_FALSE(error.empty());
        return true;
    };
    int built = 0;
    for (int side = 9; side <= 14 && built == 0; ++side) {  // until some later length is odd
        const std::vector<uint8_t> blob = bakeBlob(planeGrid(side, side, 1.0), false, 4);
        std::vector<uint8_t> coded(blob.begin() + VG_CONTAINER_HEADER_SIZE, blob.end());
        codeDistances(coded);
        REQUIRE(openStatus(sealContainer(coded, VG_FLAG_CODED_DISTANCES, 0)) == VG_OK);
        for (uint16_t field : later) built += layOver(coded, field);
    }
    CHECK(built > 0);
}

TEST_CASE("runtime: accuracy against the golden pairs of the shared meshes", "[runtime][shared]") {
    const std::string dir = test::sharedMeshDir();
    if (dir.empty()) {
        WARN("skipped: ../shared/meshes is absent, golden accuracy not checked");
        return;
    }
    // spot: a coarse mesh (2,930 vertices, long edges) is the hardest case for the graph.
    struct Case {
        const char* mesh;
        double maxMean, maxMax;
    };
    for (const Case& c : {Case{"spot", 0.002, 0.05}, Case{"fandisk", 0.002, 0.05}}) {
        Mesh mesh;
        LoadOptions lo;
        loadMesh(dir + "/" + c.mesh + ".ply", lo, mesh);
        RuntimeGraph g = openOrFail(bakeBlob(mesh));
        RuntimeWorkspace ws(g);
        std::vector<tools::DistancePair> pairs;
        std::string error;
        REQUIRE(tools::readPairs(dir + "/../golden/" + c.mesh + ".pairs.csv", pairs, error));
        for (vg_search_mode mode : {VG_SEARCH_DIRECTED, VG_SEARCH_BIDIRECTIONAL}) {
            ws.setSearch(mode);
            const tools::AccuracyReport r = tools::measureAccuracy(ws, pairs);
            INFO(c.mesh << ", search " << mode << ": mean " << r.meanRel << " max " << r.maxRel);
            CHECK(r.pairs > 9000);
            CHECK(r.infiniteMismatches == 0);
            CHECK(r.meanRel <= c.maxMean);
            CHECK(r.maxRel <= c.maxMax);
        }
    }
}

TEST_CASE("runtime: error statistics on answers known in advance", "[runtime][eval]") {
    std::vector<tools::DistancePair> pairs;
    std::vector<double> values;
    for (uint32_t i = 0; i < 100; ++i) {
        pairs.push_back({i, i + 1, 1.0});
        values.push_back(1.0004 + 0.001 * i);  // relative errors 0.0004, 0.0014, ..., 0.0994
    }
    pairs.push_back({7, 8, INFINITY});
    values.push_back(INFINITY);  // agreeing infinities are not pairs
    pairs.push_back({8, 9, 2.0});
    values.push_back(INFINITY);  // a reachability mismatch
    const tools::AccuracyReport r = tools::errorStatistics(pairs, values);
    CHECK(r.pairs == 100);
    CHECK(r.infiniteMismatches == 1);
    CHECK(std::fabs(r.meanRel - 0.0499) < 1e-9);
    CHECK(std::fabs(r.maxRel - 0.0994) < 1e-9);
    CHECK(std::fabs(r.p99Rel - 0.0984) < 1e-9);   // nearest rank 99 of 100
    CHECK(std::fabs(r.medianRel - 0.0494) < 1e-9);
    CHECK(r.overOnePercent == 90);
    REQUIRE(r.worst.size() == 5);
    CHECK(r.worst[0].source == 99);
}

TEST_CASE("runtime: a time-sliced one-to-all query equals the one-shot query bit for bit", "[runtime][sliced]") {
    RuntimeGraph g = openOrFail(bumpyBlob());
    const vg_graph* graph = g.graph();
    const uint32_t V = g.vertexCount();
    const std::vector<uint32_t> sources = {5, V / 3, 2 * V / 3, 5};  // a source listed twice
    RuntimeWorkspace oneShot(g), sliced(g), other(g);
    std::vector<float> expected(V), got(V);
    std::vector<uint32_t> expectedLabels(V), labels(V);
    REQUIRE(vg_distance_field_nearest(graph, oneShot.get(), sources.data(), sources.size(), expected.data(),
                                      expectedLabels.data()) == VG_OK);
    size_t previousSteps = 0;
    for (uint32_t budget : {1u, 3u, 50u, 1000u, 0xFFFFFFFFu}) {
        INFO("max_steps " << budget);
        std::fill(got.begin(), got.end(), -1.0f);
        REQUIRE(vg_distance_field_begin(graph, sliced.get(), sources.data(), sources.size(), got.data(),
                                        labels.data()) == VG_OK);
        int done = 0;
        size_t steps = 0;
        while (!done) {
            REQUIRE(vg_distance_field_step(graph, sliced.get(), budget, &done) == VG_OK);
            ++steps;
            REQUIRE(steps < 1000000);
        }
        CHECK(std::memcmp(got.data(), expected.data(), V * sizeof(float)) == 0);
        CHECK(labels == expectedLabels);
        if (previousSteps) CHECK(steps <= previousSteps);  // larger slices, fewer calls
        if (budget == 1) CHECK(steps > g.vertexCount() / 100);
        if (budget == 0xFFFFFFFFu) CHECK(steps == 1);
        previousSteps = steps;
        REQUIRE(vg_distance_field_step(graph, sliced.get(), 1, &done) == VG_OK);  // finished stays finished
        CHECK(done == 1);
    }

    // Two sliced queries on two workspaces, interleaved, do not disturb each other.
    std::vector<float> second(V);
    const uint32_t single = V / 2;
    std::vector<float> singleExpected = RuntimeWorkspace(g).field({single});
    REQUIRE(vg_distance_field_begin(graph, sliced.get(), sources.data(), sources.size(), got.data(), nullptr) == VG_OK);
    REQUIRE(vg_distance_field_begin(graph, other.get(), &single, 1, second.data(), nullptr) == VG_OK);
    int doneA = 0, doneB = 0;
    while (!doneA || !doneB) {
        REQUIRE(vg_distance_field_step(graph, sliced.get(), 7, &doneA) == VG_OK);
        REQUIRE(vg_distance_field_step(graph, other.get(), 11, &doneB) == VG_OK);
    }
    CHECK(std::memcmp(got.data(), expected.data(), V * sizeof(float)) == 0);
    CHECK(std::memcmp(second.data(), singleExpected.data(), V * sizeof(float)) == 0);

    // Another query on the workspace abandons the sliced one; bad calls are named.
    int done = 0;
    REQUIRE(vg_distance_field_begin(graph, sliced.get(), sources.data(), sources.size(), got.data(), nullptr) == VG_OK);
    REQUIRE(vg_distance_field_step(graph, sliced.get(), 2, &done) == VG_OK);
    float d = 0;
    REQUIRE(vg_distance(graph, sliced.get(), 0, 1, &d) == VG_OK);
    CHECK(vg_distance_field_step(graph, sliced.get(), 2, &done) == VG_ERR_NO_SLICED_QUERY);
    CHECK(done == 0);
    RuntimeWorkspace fresh(g);
    CHECK(vg_distance_field_step(graph, fresh.get(), 2, &done) == VG_ERR_NO_SLICED_QUERY);
    CHECK(vg_distance_field_step(graph, fresh.get(), 2, nullptr) == VG_ERR_INVALID_ARGUMENT);
    CHECK(vg_distance_field_step(nullptr, fresh.get(), 2, &done) == VG_ERR_INVALID_ARGUMENT);
    const uint32_t bad = V;
    CHECK(vg_distance_field_begin(graph, fresh.get(), &bad, 1, got.data(), nullptr) == VG_ERR_INVALID_VERTEX);
    CHECK(vg_distance_field_begin(graph, fresh.get(), nullptr, 1, got.data(), nullptr) == VG_ERR_INVALID_ARGUMENT);
    CHECK(vg_distance_field_begin(graph, fresh.get(), &single, 1, nullptr, nullptr) == VG_ERR_INVALID_ARGUMENT);
}
