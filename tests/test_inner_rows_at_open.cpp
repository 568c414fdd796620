// Hub-label inner rows left to the readers (bake --inner-rows-at-open,
// schema/vorogeo_inner_rows.h, runtime/src/vg_inner_rows.h): vg_open computes the very
// steps the baker stored, in the portable and the AVX2 version, so such a blob answers
// with the same bits; what is not such a blob is refused.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#define ZSTD_STATIC_LINKING_ONLY  // ZSTD_findDecompressedSize
#include <zstd.h>

#include "bake.h"
#include "blob_reader.h"
#include "blob_test_helpers.h"
#include "blob_writer.h"
#include "generators.h"
#include "hub_labels.h"
#include "mesh_io.h"
#include "runtime_graph.h"
#include "test_helpers.h"
#include "vg_field_kernels.h"
#include "vg_graph.h"
#include "vg_inner_rows.h"
#include "vorogeo_container.h"
#include "vorogeo_inner_rows.h"

using namespace vorogeo;

namespace {

std::vector<uint8_t> bakeLabelled(const Mesh& mesh, double delta, bool compact, bool innerRowsAtOpen) {
    BakeOptions o;
    o.n1 = 12;
    o.delta = delta;
    o.hubLabels = true;
    o.compact = compact;
    o.innerRowsAtOpen = innerRowsAtOpen;
    BakeReport report;
    return bakeMesh(mesh, o, report, nullptr);
}

// The unpacked payload of a compressed blob, and its flatbuffer's size.
std::vector<uint8_t> payloadOf(const std::vector<uint8_t>& blob, uint64_t& flatbufferSize) {
    const unsigned char* frames = blob.data() + VG_CONTAINER_HEADER_SIZE;
    const size_t framesSize = blob.size() - VG_CONTAINER_HEADER_SIZE;
    std::vector<uint8_t> payload(size_t(ZSTD_findDecompressedSize(frames, framesSize)));
    REQUIRE(ZSTD_decompress(payload.data(), payload.size(), frames, framesSize) == payload.size());
    flatbufferSize = vg_load_le64(blob.data() + 24);
    return payload;
}

// Recomputes g's inner table in place with one version of the search and checks that it
// gives back what vg_open wrote.
void requireRecomputed(const vg_graph& g, bool avx2) {
    const uint64_t entries = g.hubInnerMatrixBegin[g.firstCount];
    uint16_t* table = const_cast<uint16_t*>(g.hubInner);
    const std::vector<uint16_t> opened(table, table + entries);
    std::memset(table, 0, 2 * entries);
    std::vector<uint64_t> scratch(vg::innerRowsScratchSize() / 8 + 1);
    REQUIRE(vg::computeInnerRows(g, avx2, scratch.data()) == VG_OK);
    REQUIRE(std::memcmp(table, opened.data(), 2 * entries) == 0);
}

}  // namespace

TEST_CASE("inner rows at open: the blob leaves them out and opens to the stored steps, in both versions, with the same answers",
          "[runtime][hub][coding]") {
    const Mesh mesh = bumpyTorus(60, 30);
    // The default bake, and one whose pruning merges first-layer nodes away (such a slot
    // starts its search at its own rows).
    for (const double delta : {-1.0, 0.03}) {
        const std::vector<uint8_t> stored = bakeLabelled(mesh, delta, true, false);
        const std::vector<uint8_t> atOpen = bakeLabelled(mesh, delta, true, true);
        INFO("delta " << delta << ": stored " << stored.size() << " bytes, at open " << atOpen.size());
        CHECK(atOpen.size() < stored.size());
        if (delta < 0) CHECK(atOpen.size() * 10 < stored.size() * 9);  // (pruning shrinks the rows)
        CHECK(vg_load_le32(atOpen.data() + 12) == (VG_FLAG_ZSTD | VG_FLAG_CODED_DISTANCES | VG_FLAG_INNER_ROWS_AT_OPEN));

        tools::RuntimeGraph want = openOrFail(stored), got = openOrFail(atOpen);
        const vg_graph& w = *want.graph();
        const vg_graph& g = *got.graph();
        REQUIRE(g.hubTreeCount > 1);
        REQUIRE(g.firstCount == w.firstCount);
        const uint64_t entries = w.hubInnerMatrixBegin[w.firstCount];
        REQUIRE(g.hubInnerMatrixBegin[g.firstCount] == entries);
        uint64_t unreachable = 0, mergedSlots = 0;
        for (uint64_t e = 0; e < entries; ++e) unreachable += w.hubInner[e] == VG_LABEL_NO_PATH;
        for (uint32_t p = 0; p < w.firstCount; ++p)
            for (uint32_t k = 0; k < w.first[p].slotCount; ++k)
                mergedSlots += vg::nodeActive(w, w.slots[w.first[p].slotBegin + k]) ? 0 : 1;
        INFO(entries << " inner entries, " << unreachable << " without a path, " << mergedSlots
                     << " first-layer slots merged away");
        if (delta > 0) CHECK(mergedSlots > 0);
        CHECK(unreachable < entries / 2);
        REQUIRE(std::memcmp(g.hubInner, w.hubInner, 2 * entries) == 0);
        REQUIRE(std::memcmp(g.hubColumns, w.hubColumns, 2 * w.hubColumnBegin[w.hubTreeCount]) == 0);
        requireRecomputed(g, false);
        if (vg::cpuHasAvx2()) requireRecomputed(g, true);
        tools::RuntimeWorkspace wa(want), wb(got);
        requireSamePointToPoint(want, wa, got, wb, 300, 7);

        // The tools' reader keeps the zeros and says so.
        tools::BlobContents c;
        std::string error;
        REQUIRE(tools::unpackBlob(atOpen, c, error));
        CHECK(c.innerRowsAtOpen);
        REQUIRE(c.hubInner.size() == entries);
        for (uint16_t v : c.hubInner) REQUIRE(v == 0);
    }
}

TEST_CASE("inner rows at open: a table that is not zeros, or the flag on a blob that is not coded or has no labels, is refused",
          "[runtime][hub][coding]") {
    const Mesh mesh = bumpyTorus(40, 20);
    tools::BlobContents c;
    std::string error;

    // One entry of the left-out table set.
    const std::vector<uint8_t> atOpen = bakeLabelled(mesh, -1.0, true, true);
    uint64_t flatbufferSize = 0;
    std::vector<uint8_t> payload = payloadOf(atOpen, flatbufferSize);
    const fb::Graph* fg = fb::GetGraph(payload.data());
    vg_label_tables at;
    REQUIRE(vg_label_tables_at(flatbufferSize, fg->hub_columns_count(), fg->hub_inner_count(), &at));
    REQUIRE(fg->hub_inner_count() > 10);
    payload[at.inner_offset + 2 * (fg->hub_inner_count() / 2)] = 1;
    const uint32_t flags = VG_FLAG_ZSTD | VG_FLAG_CODED_DISTANCES | VG_FLAG_INNER_ROWS_AT_OPEN;
    const std::vector<uint8_t> nonZero = sealContainer(payload, flags, 1, flatbufferSize);
    CHECK(openStatus(nonZero) == VG_ERR_CORRUPT_CONTENT);
    CHECK_FALSE(tools::unpackBlob(nonZero, c, error));
    CHECK(error.find("not zeros") != std::string::npos);

    // The flag on a labelled blob whose tables are not coded.
    std::vector<uint8_t> plain = bakeLabelled(mesh, -1.0, false, false);
    vg_store_le32(plain.data() + 12, VG_FLAG_ZSTD | VG_FLAG_INNER_ROWS_AT_OPEN);
    size_t need = 0;
    CHECK(vg_open_size(plain.data(), plain.size(), &need) == VG_ERR_CORRUPT_STRUCTURE);
    CHECK_FALSE(tools::unpackBlob(plain, c, error));
    CHECK(error.find("not coded") != std::string::npos);

    // The flag on a coded blob without labels.
    BakeOptions o;
    o.compact = true;
    BakeReport report;
    std::vector<uint8_t> unlabelled = bakeMesh(mesh, o, report, nullptr);
    vg_store_le32(unlabelled.data() + 12, flags);
    CHECK(vg_open_size(unlabelled.data(), unlabelled.size(), &need) == VG_ERR_CORRUPT_STRUCTURE);
    CHECK_FALSE(tools::unpackBlob(unlabelled, c, error));
    CHECK(error.find("without hub labels") != std::string::npos);
}

TEST_CASE("inner rows at open: a slot whose node no inner row holds is refused", "[runtime][hub][coding]") {
    const std::vector<uint8_t> atOpen = bakeLabelled(bumpyTorus(40, 20), -1.0, true, true);
    // The decoded graph (the tools' reader) says which inner row is a slot node of patch 0;
    // hub_inner_node is stored as it is, so the same entry of the payload is moved off it.
    tools::BlobContents c;
    std::string error;
    REQUIRE(tools::unpackBlob(atOpen, c, error));
    const fb::Graph* g = c.graph();
    const auto* innerNode = g->hub_inner_node();
    const uint32_t rowEnd = g->hub_inner_begin()->Get(1);
    const fb::PatchRecord* first = g->first_patches()->Get(0);
    uint32_t moved = UINT32_MAX;
    for (uint32_t i = 0; i + 1 < rowEnd && moved == UINT32_MAX; ++i) {
        if (innerNode->Get(i) + 1 >= innerNode->Get(i + 1)) continue;  // no room: the list stays increasing
        for (uint32_t k = 0; k < first->slot_count(); ++k)
            if (g->slots()->Get(first->slot_begin() + k) == innerNode->Get(i)) moved = i;
    }
    REQUIRE(moved != UINT32_MAX);
    uint64_t flatbufferSize = 0;
    std::vector<uint8_t> payload = payloadOf(atOpen, flatbufferSize);
    const auto* stored = fb::GetGraph(payload.data())->hub_inner_node();
    REQUIRE(stored->Get(moved) == innerNode->Get(moved));
    const uint32_t flags = VG_FLAG_ZSTD | VG_FLAG_CODED_DISTANCES | VG_FLAG_INNER_ROWS_AT_OPEN;
    CHECK(openStatus(sealContainer(payload, flags, 1, flatbufferSize)) == VG_OK);  // resealed as it was
    uint8_t* entry = payload.data() + (reinterpret_cast<const uint8_t*>(stored->data() + moved) - payload.data());
    vg_store_le32(entry, innerNode->Get(moved) + 1);
    CHECK(openStatus(sealContainer(payload, flags, 1, flatbufferSize)) == VG_ERR_CORRUPT_CONTENT);
}

TEST_CASE("inner rows at open: vorogeo bake writes such a blob and vorogeo info says so", "[bake][hub][cli]") {
    test::TempDir dir;
    std::string error;
    const std::string meshPath = dir.file("torus.ply"), out = dir.file("torus.vgeo");
    REQUIRE(writeMesh(bumpyTorus(40, 20), meshPath, error));
    const test::ToolResult r = test::runTool("bake " + test::quote(meshPath) + " -o " + test::quote(out) +
                                             " --n1 8 --compact --hub-labels --inner-rows-at-open");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK(r.out.find("inner rows left to vg_open") != std::string::npos);
    const test::ToolResult info = test::runTool("info " + test::quote(out));
    CHECK(info.status == 0);
    CHECK(info.out.find("inner entries (computed at open)") != std::string::npos);
    const test::ToolResult json = test::runTool("info " + test::quote(out) + " --json");
    CHECK(json.out.find("\"inner_rows_at_open\":true") != std::string::npos);
}

TEST_CASE("inner rows at open: the baker names a first-layer patch past a reader's search", "[bake][hub]") {
    // The format's limits take a mesh of hundreds of thousands of vertices to pass; the check
    // is the same with smaller ones. Each limit at the largest count a patch of this bake
    // has passes, one less fails and names the patch and the count.
    const std::vector<uint8_t> stored = bakeLabelled(bumpyTorus(60, 30), -1.0, false, false);
    tools::BlobContents c;
    std::string error;
    REQUIRE(tools::unpackBlob(stored, c, error));
    const fb::Graph* g = c.graph();
    uint64_t rows = 0, children = 0, childNodes = 0;
    for (uint32_t f = 0; f < g->first_patches()->size(); ++f) {
        rows = std::max<uint64_t>(rows, g->hub_inner_begin()->Get(f + 1) - g->hub_inner_begin()->Get(f));
        uint64_t n = 0, slots = 0;
        for (uint32_t q = 0; q < g->second_patches()->size(); ++q)
            if (g->second_patches()->Get(q)->parent() == f) ++n, slots += g->second_patches()->Get(q)->node_count();
        children = std::max(children, n);
        childNodes = std::max(childNodes, slots);
    }
    INFO(rows << " rows, " << children << " second-layer patches, " << childNodes << " node slots at most");
    REQUIRE(rows > 10);
    REQUIRE(children > 1);
    CHECK(innerRowsAtOpenExcess(c.flatbuffer) == "");  // the format's limits
    CHECK(innerRowsAtOpenExcess(c.flatbuffer, {rows, children, childNodes}) == "");
    CHECK_THAT(innerRowsAtOpenExcess(c.flatbuffer, {rows - 1, children, childNodes}),
               Catch::Contains("first-layer patch") && Catch::Contains(std::to_string(rows) + " inner rows") &&
                   Catch::Contains("--n1"));
    CHECK_THAT(innerRowsAtOpenExcess(c.flatbuffer, {rows, children - 1, childNodes}),
               Catch::Contains(std::to_string(children) + " second-layer patches"));
    CHECK_THAT(innerRowsAtOpenExcess(c.flatbuffer, {rows, children, childNodes - 1}),
               Catch::Contains(std::to_string(childNodes) + " node slots"));
}

TEST_CASE("inner rows at open: the bake needs --compact and --hub-labels", "[bake][hub]") {
    BakeOptions o;
    o.hubLabels = true;
    o.innerRowsAtOpen = true;
    BakeReport report;
    REQUIRE_THROWS_WITH(bakeMesh(planeGrid(6, 6, 1.0), o, report, nullptr),
                        Catch::Contains("--inner-rows-at-open") && Catch::Contains("--compact"));
    o.compact = true;
    o.hubLabels = false;
    REQUIRE_THROWS_WITH(bakeMesh(planeGrid(6, 6, 1.0), o, report, nullptr), Catch::Contains("--hub-labels"));
}

TEST_CASE("inner rows at open: steps round to nearest, stop at 65534, and say no path for +inf and NaN", "[coding]") {
    const float scale = 0.25f;
    CHECK(vg_label_steps(0.0, scale) == 0);
    CHECK(vg_label_steps(0.124, scale) == 0);
    CHECK(vg_label_steps(0.125, scale) == 1);  // half a step rounds up
    CHECK(vg_label_steps(2.6, scale) == 10);
    CHECK(vg_label_steps(65533.9 * 0.25, scale) == 65534);
    CHECK(vg_label_steps(1e30, scale) == 65534);
    CHECK(vg_label_steps(std::numeric_limits<double>::infinity(), scale) == VG_LABEL_NO_PATH);
    CHECK(vg_label_steps(std::nan(""), scale) == VG_LABEL_NO_PATH);
}
