// The bake: blob structure and verification, determinism across thread counts, stored
// distances against the exact engine, pruning, container rejection, the bake command.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <tuple>

#include <tbb/global_control.h>

#include "bake.h"
#include "blob_reader.h"
#include "generators.h"
#include "geodesic_exact.h"
#include "geodesic_wavefront.h"
#include "mesh_io.h"
#include "patch_geodesics.h"
#include "test_helpers.h"
#include "vorogeo_baker.h"
#include "vorogeo_container.h"

using namespace vorogeo;

namespace {

std::vector<uint8_t> bakeWith(const Mesh& mesh, BakeOptions o, int threads, BakeReport* reportOut = nullptr) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    BakeReport report;
    std::vector<uint8_t> blob = bakeMesh(mesh, o, report);
    if (reportOut) *reportOut = report;
    return blob;
}

tools::BlobContents unpack(const std::vector<uint8_t>& blob) {
    tools::BlobContents c;
    std::string error;
    INFO(error);
    REQUIRE(tools::unpackBlob(blob, c, error));
    return c;
}

// 12-bit entry k of a packed distance array (see schema/vorogeo.fbs).
uint16_t entry12(const flatbuffers::Vector<uint8_t>& bytes, uint64_t k) {
    const size_t b = size_t(3 * (k / 2));
    return k % 2 == 0 ? uint16_t(bytes[b] | ((bytes[b + 1] & 0x0F) << 8)) : uint16_t((bytes[b + 1] >> 4) | (bytes[b + 2] << 4));
}

// Second-layer matrices (format 4): node x node whole, node x other, then the upper
// triangle of the other slots.
double storedDistance(const fb::PatchRecord& p, const flatbuffers::Vector<uint8_t>& bytes, uint32_t i, uint32_t j) {
    if (i == j) return 0;
    if (i > j) std::swap(i, j);
    const uint64_t S = p.slot_count(), n = p.node_count();
    uint64_t k;
    if (i < n) {
        k = j < n ? p.matrix_begin() + i * n + j : p.matrix_begin() + n * n + i * (S - n) + (j - n);
    } else {
        const uint64_t I = S - n, a = i - n, b = j - n;
        k = p.matrix_begin() + n * S + a * (2 * I - a - 1) / 2 + (b - a - 1);
    }
    const uint16_t q = entry12(bytes, k);
    return q == 4095 ? kInfinity : q * double(p.scale());
}

// First-layer matrices are stored whole, row-major.
double storedFirstDistance(const fb::PatchRecord& p, const flatbuffers::Vector<uint8_t>& bytes, uint32_t i, uint32_t j) {
    const uint16_t q = entry12(bytes, p.matrix_begin() + uint64_t(i) * p.slot_count() + j);
    return q == 4095 ? kInfinity : q * double(p.scale());
}

Mesh smallBumpy() { return bumpyTorus(60, 30); }  // 1,800 vertices, saddles everywhere

}  // namespace

TEST_CASE("bake: blob passes the container checks and the flatbuffers verifier, indices in range", "[bake]") {
    const Mesh mesh = smallBumpy();
    BakeReport report;
    const std::vector<uint8_t> blob = bakeWith(mesh, BakeOptions(), 2, &report);
    CHECK(report.blobBytes == blob.size());
    const tools::BlobContents c = unpack(blob);
    CHECK(c.compressed);
    const fb::Graph* g = c.graph();
    REQUIRE(g->vertex_count() == mesh.vertexCount());
    REQUIRE(g->positions()->size() == 3 * size_t(mesh.vertexCount()));
    const uint32_t N = g->node_vertex()->size();
    REQUIRE(N > 0);
    REQUIRE(g->node_second_begin()->size() == N + 1);
    REQUIRE(g->node_first_begin()->size() == N + 1);
    CHECK(g->node_second_begin()->Get(N) == g->node_second()->size());
    CHECK(g->node_first_begin()->Get(N) == g->node_first()->size());
    const auto* sp = g->second_patches();
    const auto* fp = g->first_patches();
    CHECK(sp->size() == report.secondPatches);
    CHECK(fp->size() == report.firstPatches);
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        const uint32_t p = g->vertex_patch()->Get(v);
        REQUIRE(p < sp->size());
        const auto* rec = sp->Get(p);
        const uint32_t slot = g->vertex_slot()->Get(v);
        REQUIRE(slot < rec->slot_count());
        const uint32_t id = g->slots()->Get(rec->slot_begin() + slot);
        // A slot holds a node id for the first node_count slots, else the vertex id.
        CHECK((slot < rec->node_count() ? g->node_vertex()->Get(id) : id) == v);
    }
    for (uint32_t n = 0; n < N; ++n) {
        for (uint32_t k = g->node_second_begin()->Get(n); k < g->node_second_begin()->Get(n + 1); ++k) {
            const auto* m = g->node_second()->Get(k);
            REQUIRE(m->patch() < sp->size());
            REQUIRE(m->slot() < sp->Get(m->patch())->node_count());
            CHECK(g->slots()->Get(sp->Get(m->patch())->slot_begin() + m->slot()) == n);
        }
        for (uint32_t k = g->node_first_begin()->Get(n); k < g->node_first_begin()->Get(n + 1); ++k) {
            const auto* m = g->node_first()->Get(k);
            REQUIRE(m->patch() < fp->size());
            CHECK(g->slots()->Get(fp->Get(m->patch())->slot_begin() + m->slot()) == n);
        }
    }
    uint64_t secondEntries = 0;
    for (const auto* rec : *sp) {
        CHECK(rec->parent() < fp->size());
        CHECK(rec->matrix_begin() == secondEntries);
        const uint64_t S = rec->slot_count(), n = rec->node_count(), I = S - n;
        for (uint32_t a = 0; a < n; ++a)  // a node's own entry in its row is "no path"
            CHECK(entry12(*g->second_distances(), rec->matrix_begin() + a * n + a) == 4095);
        secondEntries += n * S + (I > 0 ? I * (I - 1) / 2 : 0);
    }
    CHECK(g->second_distances()->size() == (secondEntries * 3 + 1) / 2);

    // Patch edges: exactly the node edges with both ends among a patch's nodes, both ways,
    // in order of their first slot (the runtime refuses any other), with the float length of
    // the stored positions.
    const auto* edges = g->second_edges();
    REQUIRE(edges != nullptr);
    uint64_t expectedEdges = 0;
    for (uint32_t p = 0; p < sp->size(); ++p) {
        const auto* rec = sp->Get(p);
        const uint32_t begin = rec->edge_begin(), end = p + 1 < sp->size() ? sp->Get(p + 1)->edge_begin() : edges->size();
        REQUIRE(begin <= end);
        CHECK(begin == expectedEdges);
        std::map<uint32_t, uint32_t> slotOfNode;
        for (uint32_t i = 0; i < rec->node_count(); ++i) slotOfNode[g->slots()->Get(rec->slot_begin() + i)] = i;
        std::set<std::pair<uint32_t, uint32_t>> expected, found;
        for (const auto& [node, slot] : slotOfNode)
            for (uint32_t e = g->node_edge_begin()->Get(node); e < g->node_edge_begin()->Get(node + 1); ++e) {
                const auto it = slotOfNode.find(g->node_edge()->Get(e));
                if (it != slotOfNode.end()) expected.emplace(slot, it->second);
            }
        uint32_t lastFrom = 0;
        for (uint32_t e = begin; e < end; ++e) {
            const auto* E = edges->Get(e);
            REQUIRE(E->from() < rec->node_count());
            REQUIRE(E->to() < rec->node_count());
            CHECK(E->from() >= lastFrom);
            lastFrom = E->from();
            found.emplace(E->from(), E->to());
            const uint32_t a = g->node_vertex()->Get(g->slots()->Get(rec->slot_begin() + E->from()));
            const uint32_t b = g->node_vertex()->Get(g->slots()->Get(rec->slot_begin() + E->to()));
            float d[3];
            for (int k = 0; k < 3; ++k) d[k] = g->positions()->Get(3 * a + k) - g->positions()->Get(3 * b + k);
            CHECK(E->length() == std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
        }
        CHECK(found == expected);
        CHECK(found.size() == end - begin);
        expectedEdges += expected.size();
    }
    CHECK(edges->size() == expectedEdges);
}

TEST_CASE("bake: the same blob bytes for 1 and 2 threads", "[bake]") {
    const Mesh mesh = smallBumpy();
    BakeOptions o;
    o.delta = 0.002;  // pruning on too
    const std::vector<uint8_t> one = bakeWith(mesh, o, 1);
    const std::vector<uint8_t> two = bakeWith(mesh, o, 2);
    CHECK(one.size() == two.size());
    CHECK(one == two);
    o.seed = 7;  // and the seed matters
    CHECK(bakeWith(mesh, o, 2) != two);
}

TEST_CASE("bake library: vorogeo::bake reports progress, can be cancelled, gives bakeMesh's bytes", "[bake]") {
    const Mesh mesh = smallBumpy();
    std::vector<std::string> stages;
    const BakeResult r = bake(mesh, BakeOptions(), [&](const char* stage, double fraction) {
        CHECK(fraction >= 0.0);
        CHECK(fraction <= 1.0);
        if (stages.empty() || stages.back() != stage) stages.push_back(stage);
    });
    CHECK(stages.size() >= 4);
    CHECK(r.report.blobBytes == r.blob.size());
    BakeReport report;
    CHECK(bakeMesh(mesh, BakeOptions(), report) == r.blob);

    // Cancelled at the third progress step: BakeCancelled, whatever stage that is.
    std::atomic<bool> cancel{false};
    int calls = 0;
    CHECK_THROWS_AS(bake(mesh, BakeOptions(), [&](const char*, double) { cancel = ++calls >= 3; }, &cancel),
                    BakeCancelled);
    CHECK(calls == 3);
    cancel = true;
    CHECK_THROWS_AS(bake(mesh, BakeOptions(), BakeProgress(), &cancel), BakeCancelled);
    CHECK(automaticLevel(false, 100 << 20) == 9);
    CHECK(automaticLevel(true, 1 << 20) == 19);
    CHECK(automaticLevel(true, 32 << 20) == 19);
    CHECK(automaticLevel(true, (32 << 20) + 1) == 17);
    CHECK(automaticLevel(true, 100 << 20) == 17);
    CHECK(automaticLevel(true, uint64_t(1) << 30) == 17);
    CHECK(automaticLevel(true, (uint64_t(1) << 30) + 1) == 11);
    CHECK(automaticLevel(true, uint64_t(3) << 30) == 11);
    BakeOptions bad;
    bad.compressionLevel = 99;
    CHECK_THROWS_AS(bake(mesh, bad), std::invalid_argument);
}

TEST_CASE("bake: --no-compress stores the same flatbuffer, uncompressed", "[bake]") {
    const Mesh mesh = smallBumpy();
    BakeOptions o;
    const tools::BlobContents z = unpack(bakeWith(mesh, o, 2));
    o.compress = false;
    const std::vector<uint8_t> raw = bakeWith(mesh, o, 2);
    const tools::BlobContents r = unpack(raw);
    CHECK_FALSE(r.compressed);
    CHECK(z.flatbuffer == r.flatbuffer);
    CHECK(raw.size() == VG_CONTAINER_HEADER_SIZE + r.flatbuffer.size());
}

TEST_CASE("bake: second-layer entries equal exact runs on the patch plus its margin ring", "[bake]") {
    const Mesh mesh = smallBumpy();
    const tools::BlobContents c = unpack(bakeWith(mesh, BakeOptions(), 2));
    const fb::Graph* g = c.graph();
    Partition partition = partitionMesh(mesh, PartitionOptions());  // the same partition the bake made
    REQUIRE(partition.second.size() == g->second_patches()->size());
    ExactWorkspace ws;
    std::vector<double> dist;
    size_t checked = 0;
    for (uint32_t p = 0; p < partition.second.size(); p += 7) {
        const auto* rec = g->second_patches()->Get(p);
        const ExactGeodesic geo(mesh, growFaces(mesh, partition.second[p].faces, 1));
        auto vertexOf = [&](uint32_t slot) {
            const uint32_t id = g->slots()->Get(rec->slot_begin() + slot);
            return slot < rec->node_count() ? g->node_vertex()->Get(id) : id;
        };
        for (uint32_t i = 0; i < rec->slot_count(); i += 5) {
            ExactQuery q;
            q.sources.push_back(GeodesicSource::atVertex(uint32_t(geo.localVertex(vertexOf(i)))));
            ws.run(geo, q, dist);
            for (uint32_t j = 0; j < rec->slot_count(); ++j) {
                const double exact = dist[geo.localVertex(vertexOf(j))];
                const double stored = storedDistance(*rec, *g->second_distances(), i, j);
                REQUIRE(std::fabs(stored - exact) <= 0.5 * rec->scale() + 1e-12);
                ++checked;
            }
        }
    }
    CHECK(checked > 1000);
}

TEST_CASE("bake: first-layer entries are the shortest second-layer node paths inside the first-layer patch", "[bake]") {
    const Mesh mesh = smallBumpy();
    BakeOptions o;
    o.n1 = 3;
    const tools::BlobContents c = unpack(bakeWith(mesh, o, 2));
    const fb::Graph* g = c.graph();
    const auto* sp = g->second_patches();
    const uint32_t N = g->node_vertex()->size();
    size_t checked = 0;
    for (uint32_t f = 0; f < g->first_patches()->size(); ++f) {
        const auto* rec = g->first_patches()->Get(f);
        // Dijkstra over the node x node blocks of the second-layer patches inside f (dense, small).
        double tolerance = 0.5 * rec->scale();
        for (const auto* s : *sp)
            if (s->parent() == f) tolerance += 0.5 * s->scale() * 8;  // a few hops of 12-bit rounding
        for (uint32_t i = 0; i < rec->slot_count(); ++i) {
            std::vector<double> dist(N, kInfinity);
            std::vector<uint8_t> done(N, 0);
            dist[g->slots()->Get(rec->slot_begin() + i)] = 0;
            for (;;) {
                uint32_t u = UINT32_MAX;
                for (uint32_t n = 0; n < N; ++n)
                    if (!done[n] && std::isfinite(dist[n]) && (u == UINT32_MAX || dist[n] < dist[u])) u = n;
                if (u == UINT32_MAX) break;
                done[u] = 1;
                for (uint32_t k = g->node_second_begin()->Get(u); k < g->node_second_begin()->Get(u + 1); ++k) {
                    const auto* m = g->node_second()->Get(k);
                    const auto* s = sp->Get(m->patch());
                    if (s->parent() != f) continue;
                    for (uint32_t j = 0; j < s->node_count(); ++j) {
                        const uint32_t w = g->slots()->Get(s->slot_begin() + j);
                        dist[w] = std::min(dist[w], dist[u] + storedDistance(*s, *g->second_distances(), m->slot(), j));
                    }
                }
            }
            for (uint32_t j = 0; j < rec->slot_count(); ++j) {
                const uint32_t node = g->slots()->Get(rec->slot_begin() + j);
                const double stored = storedFirstDistance(*rec, *g->first_distances(), i, j);
                REQUIRE(std::fabs(stored - dist[node]) <= tolerance);
                // Never below the straight line between the two vertices.
                const double straight = distance(mesh.positions[g->node_vertex()->Get(node)],
                                                 mesh.positions[g->node_vertex()->Get(g->slots()->Get(rec->slot_begin() + i))]);
                REQUIRE(stored >= straight - 0.5 * rec->scale() - 1e-9);
                ++checked;
            }
        }
    }
    CHECK(checked > 1000);
}

TEST_CASE("bake: pruning merges nodes only when delta allows, and reports it", "[bake]") {
    const Mesh mesh = planeGrid(60, 60, 1.0);
    BakeReport none, some;
    BakeOptions o;
    o.n1 = 4;
    const tools::BlobContents c0 = unpack(bakeWith(mesh, o, 2, &none));
    o.delta = 0.01;
    const tools::BlobContents c1 = unpack(bakeWith(mesh, o, 2, &some));
    CHECK(none.firstPrune.prunedNodes == 0);
    CHECK(none.secondPrune.prunedNodes == 0);
    CHECK(some.firstPrune.nodes == none.firstPrune.nodes);
    CHECK(some.firstPrune.prunedNodes > 0);
    CHECK(some.firstPrune.prunedEdges > 0);
    CHECK(some.firstPrune.prunedNodes < some.firstPrune.nodes);
    // Flags in the blob match the second-layer count; first-layer rows shrink.
    const fb::Graph* g1 = c1.graph();
    uint64_t flagged = 0;
    for (uint8_t f : *g1->node_flags()) flagged += f & 1;
    CHECK(flagged == some.secondPrune.prunedNodes);
    auto firstRows = [](const fb::Graph* g) {
        uint64_t rows = 0;
        for (const auto* rec : *g->first_patches()) rows += rec->slot_count();
        return rows;
    };
    CHECK(firstRows(g1) == g1->node_first()->size());
    CHECK(firstRows(g1) < firstRows(c0.graph()));
}

TEST_CASE("bake: the container rejects other versions, bad magic, truncation and corruption", "[bake]") {
    const std::vector<uint8_t> blob = bakeWith(planeGrid(20, 20, 1.0), BakeOptions(), 2);
    tools::BlobContents c;
    std::string error;
    REQUIRE(tools::unpackBlob(blob, c, error));

    std::vector<uint8_t> v1 = blob;  // the version before whole first-layer rows and landmarks
    vg_store_le32(v1.data() + 8, 1);
    CHECK_FALSE(tools::unpackBlob(v1, c, error));
    CHECK(error.find("format version 1 is not supported") != std::string::npos);

    std::vector<uint8_t> magic = blob;
    magic[0] = 'X';
    CHECK_FALSE(tools::unpackBlob(magic, c, error));
    CHECK(error.find("magic") != std::string::npos);

    for (size_t cut : {size_t(0), size_t(39), size_t(40), blob.size() / 2, blob.size() - 1}) {
        std::vector<uint8_t> shortBlob(blob.begin(), blob.begin() + long(cut));
        CHECK_FALSE(tools::unpackBlob(shortBlob, c, error));
    }
    for (size_t at : {size_t(40), blob.size() / 3, blob.size() - 1}) {
        std::vector<uint8_t> flipped = blob;
        flipped[at] ^= 0x10;
        CHECK_FALSE(tools::unpackBlob(flipped, c, error));
        CHECK(error.find("checksum") != std::string::npos);
    }
}

TEST_CASE("bake command: writes the blob, the report and a summary", "[bake][cli]") {
    test::TempDir dir;
    std::string error;
    const std::string meshPath = dir.file("torus.ply");
    REQUIRE(writeMesh(smallBumpy(), meshPath, error));
    const std::string out = dir.file("torus.vgeo"), report = dir.file("report.json");
    const test::ToolResult r = test::runTool("bake " + test::quote(meshPath) + " -o " + test::quote(out) +
                                             " --threads 2 --report " + test::quote(report));
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(r.out.find("bytes per vertex") != std::string::npos);
    CHECK(r.err.find("bake: second-layer geodesics") != std::string::npos);  // plain progress lines off a terminal
    tools::BlobContents c;
    REQUIRE(tools::readBlobFile(out, c, error));
    // `vorogeo info` describes the blob; a truncated copy is rejected with the reason.
    // --level changes the compressed bytes only.
    const std::string fast = dir.file("fast.vgeo");
    REQUIRE(test::runTool("bake " + test::quote(meshPath) + " -o " + test::quote(fast) + " --level 1 --quiet").status == 0);
    tools::BlobContents f;
    REQUIRE(tools::readBlobFile(fast, f, error));
    CHECK(f.flatbuffer == c.flatbuffer);
    CHECK(std::filesystem::file_size(fast) != std::filesystem::file_size(out));
    const test::ToolResult info = test::runTool("info " + test::quote(out) + " --json");
    CHECK(info.status == 0);
    CHECK(info.out.find("\"vertices\":1800") != std::string::npos);
    {
        std::ifstream whole(out, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(whole)), std::istreambuf_iterator<char>());
        dir.write("cut.vgeo", bytes.substr(0, bytes.size() / 2));
    }
    const test::ToolResult cut = test::runTool("info " + test::quote(dir.file("cut.vgeo")));
    CHECK(cut.status == 1);
    CHECK(cut.err.find("truncated") != std::string::npos);
    std::ifstream in(report);
    const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const char* key : {"\"wall_s\"", "\"peak_rss_mb\"", "\"blob_bytes\"", "\"bytes_per_vertex\"", "\"vertices\": 1800",
                            "\"threads\": 2", "\"stages_s\"", "\"partition\"", "\"second-layer geodesics\"", "\"pruning\""})
        CHECK(json.find(key) != std::string::npos);
}

TEST_CASE("bake command: bad parameters and outputs give clear errors and leave no file", "[bake][cli]") {
    test::TempDir dir;
    std::string error;
    const std::string meshPath = dir.file("grid.obj");
    REQUIRE(writeMesh(planeGrid(10, 10, 1.0), meshPath, error));  // 121 vertices
    const std::string out = dir.file("out.vgeo");
    struct Case {
        std::string args, message;
        int status;
    };
    const Case cases[] = {
        {"--n1 0", "--n1 must be at least 1", 2},
        {"--n1 500", "--n1 500 is larger than the 121 vertices", 2},
        {"--n2 -3", "--n2 must be at least 1", 2},
        {"--delta -0.1", "--delta must be in [0, 1)", 2},
        {"--delta abc", "--delta", 2},
        {"--threads 0x", "--threads", 2},
        {"--frobnicate", "--frobnicate", 2},
        {"--level 0", "--level must be in [1, 22]", 2},
        {"--level 23", "--level must be in [1, 22]", 2},
        {"--level 5 --no-compress", "--level sets the zstd level", 2},
        {"--inner-rows-at-open", "--inner-rows-at-open needs --compact and --hub-labels", 2},
        {"--inner-rows-at-open --compact", "--inner-rows-at-open needs --compact and --hub-labels", 2},
    };
    for (const Case& c : cases) {
        const test::ToolResult r = test::runTool("bake " + test::quote(meshPath) + " -o " + test::quote(out) + " " + c.args);
        INFO(c.args << " -> " << r.err);
        CHECK(r.status == c.status);
        CHECK(r.err.find(c.message) != std::string::npos);
        CHECK_FALSE(std::filesystem::exists(out));
    }
    // Unwritable output: a missing directory.
    const test::ToolResult r1 = test::runTool("bake " + test::quote(meshPath) + " -o " + test::quote(dir.file("no/such/dir/x.vgeo")));
    CHECK(r1.status == 1);
    CHECK(r1.err.find("cannot write") != std::string::npos);
    // A mesh the loader refuses: its error, and no output.
    const std::string broken = dir.write("broken.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
    const test::ToolResult r2 = test::runTool("bake " + test::quote(broken) + " -o " + test::quote(out));
    CHECK(r2.status == 1);
    CHECK(r2.err.find("out of range") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(out));
    // No temporary files left behind in the output directory.
    for (const auto& e : std::filesystem::directory_iterator(dir.file("")))
        CHECK(e.path().filename().string().find(".tmp-") == std::string::npos);
}

TEST_CASE("bake: every shared mesh bakes with defaults", "[bake][shared]") {
    const std::string dir = test::sharedMeshDir();
    if (dir.empty()) {
        WARN("skipped: ../shared/meshes is absent");
        return;
    }
    for (const char* name : {"spot", "fandisk", "rocker-arm", "stanford-bunny", "armadillo-50k", "nefertiti-50k", "igea"}) {
        Mesh mesh;
        const LoadReport load = loadMesh(dir + "/" + name + ".ply", LoadOptions(), mesh);
        INFO(name << ": " << load.error);
        REQUIRE(load.ok);
        BakeReport report;
        const tools::BlobContents c = unpack(bakeWith(mesh, BakeOptions(), 2, &report));
        CHECK(c.graph()->vertex_count() == mesh.vertexCount());
        CHECK(report.secondPatches > report.firstPatches);
    }
}

TEST_CASE("bake: second-layer entries equal unbounded exact runs, for any thread count", "[bake]") {
    // The second layer's rows run bounded by the rows run before them (patch_geodesics.cpp):
    // every entry, interior pairs included, must still be the exact distance on the patch
    // plus its margin ring, in either direction, on saddles, holes, needles and meshes of
    // two components.
    for (const auto& [name, mesh, n1, n2] :
         {std::tuple<const char*, Mesh, uint32_t, uint32_t>{"bumpy torus", smallBumpy(), 4, 10},
          {"grid with holes", gridWithHoles(30, 4), 3, 6},
          {"needles", needleMesh(60, 8), 2, 5},
          {"two components", twoComponents(), 2, 4}}) {
        INFO(name);
        PartitionOptions po;
        po.firstLayerSeeds = n1;
        po.secondLayerSeeds = n2;
        const Partition partition = partitionMesh(mesh, po);
        const PatchGeodesics g = computePatchGeodesics(mesh, partition, PatchGeodesicsOptions());
        REQUIRE(g.second.size() == partition.second.size());
        WavefrontWorkspace ws;
        std::vector<double> dist;
        size_t checked = 0;
        for (uint32_t p = 0; p < partition.second.size(); ++p) {
            const PatchMatrix& m = g.second[p];
            REQUIRE(m.rows == m.vertices.size());
            const ExactGeodesic geo(mesh, growFaces(mesh, partition.second[p].faces, PatchGeodesicsOptions().marginRings));
            for (uint32_t i = 0; i < m.rows; ++i) {
                ws.run(geo, {uint32_t(geo.localVertex(m.vertices[i]))}, dist);
                for (uint32_t j = 0; j < m.rows; ++j) {
                    const double exact = dist[geo.localVertex(m.vertices[j])];
                    if (exact == kInfinity) REQUIRE(m.at(i, j) == kInfinity);
                    else REQUIRE(std::fabs(m.at(i, j) - exact) <= 1e-9 * (1.0 + exact));
                    ++checked;
                }
            }
        }
        CHECK(checked > 1000);
        BakeOptions b;
        b.n1 = n1;
        b.n2 = n2;
        CHECK(bakeWith(mesh, b, 1) == bakeWith(mesh, b, 2));
    }
}

TEST_CASE("bake: --exact-first-layer entries equal unbounded exact runs, for any thread count", "[bake]") {
    // The exact first layer runs to its remaining pairs, each bounded by the composed
    // overlay, in an order that leaves them close to its source (patch_geodesics.cpp):
    // every entry must still be the exact distance on the first-layer patch plus its
    // margin ring.
    const Mesh mesh = smallBumpy();
    PartitionOptions po;
    po.firstLayerSeeds = 4;
    const Partition partition = partitionMesh(mesh, po);
    PatchGeodesicsOptions o;
    o.firstLayer = PatchGeodesicsOptions::FirstLayer::Exact;
    const PatchGeodesics g = computePatchGeodesics(mesh, partition, o);
    REQUIRE(g.first.size() == partition.first.size());
    REQUIRE(partition.first.size() >= 2);
    WavefrontWorkspace ws;
    std::vector<double> dist;
    size_t checked = 0;
    for (uint32_t p = 0; p < partition.first.size(); ++p) {
        const PatchMatrix& m = g.first[p];
        const ExactGeodesic geo(mesh, growFaces(mesh, partition.first[p].faces, o.marginRings));
        for (uint32_t i = 0; i < m.rows; ++i) {
            ws.run(geo, {uint32_t(geo.localVertex(m.vertices[i]))}, dist);
            for (uint32_t j = 0; j < m.rows; ++j) {
                const double exact = dist[geo.localVertex(m.vertices[j])];
                REQUIRE(std::fabs(m.at(i, j) - exact) <= 1e-9 * (1.0 + exact));
                ++checked;
            }
        }
    }
    CHECK(checked > 1000);
    BakeOptions b;
    b.exactFirstLayer = true;
    b.hubLabels = true;
    b.n1 = 4;
    CHECK(bakeWith(mesh, b, 1) == bakeWith(mesh, b, 2));
}
