// Prediction-coded distances (schema/vorogeo_distance_coding.h, baker/distance_coding.h,
// runtime/src/vg_decode.h): the runtime's decoder, AVX2 and portable, gives back exactly
// the quanta the reference encoder was given, on random matrices of every shape and on
// real bakes; a compressed (coded) blob and an uncompressed one answer with the same bits.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "bake.h"
#include "blob_test_helpers.h"
#include "blob_reader.h"
#include "blob_writer.h"
#include "distance_coding.h"
#include "generators.h"
#include "runtime_graph.h"
#include "vg_decode.h"
#include "vg_decode_labels.h"
#include "vg_field_kernels.h"
#include "vg_graph.h"
#include "vorogeo_container.h"
#include "vorogeo_distance_coding.h"
#include "vorogeo_label_coding.h"
#include "vorogeo_topology_coding.h"

#include <zstd.h>

using namespace vorogeo;

namespace {

std::vector<uint8_t> bakeWith(const Mesh& mesh, bool compress, bool compact) {
    BakeOptions o;
    o.compress = compress;
    o.compact = compact;
    BakeReport report;
    return bakeMesh(mesh, o, report, nullptr);
}

// One random patch layout: S slots, the first n of them nodes, on random positions.
struct RandomGraph {
    std::vector<float> positions;
    std::vector<uint32_t> slots, nodeVertex;
    std::vector<vg::Patch> second, first;
    std::vector<uint8_t> secondBytes, firstBytes;
    vg_graph graph{};
};

float randomCoordinate(std::mt19937& rng) {
    switch (rng() % 8) {
        case 0: return 0.0f;
        case 1: return float(rng() % 1000) * 1e-30f;                       // tiny
        case 2: return (rng() & 1 ? 1.0f : -1.0f) * float(rng() % 1000) * 1e30f;  // overflows when squared
        default: return std::uniform_real_distribution<float>(-5.0f, 5.0f)(rng);
    }
}

float randomScale(std::mt19937& rng) {
    switch (rng() % 6) {
        case 0: return 0.0f;  // 0 / 0 and x / 0
        case 1: return 1e-30f;
        default: return std::uniform_real_distribution<float>(1e-4f, 0.01f)(rng);
    }
}

RandomGraph randomGraph(std::mt19937& rng) {
    RandomGraph r;
    const uint32_t V = 40 + rng() % 60;
    for (uint32_t v = 0; v < 3 * V; ++v) r.positions.push_back(randomCoordinate(rng));
    for (uint32_t v = 0; v < V; v += 2) r.nodeVertex.push_back(v);  // every even vertex is a node
    const uint32_t N = uint32_t(r.nodeVertex.size());
    uint64_t secondEntries = 0, firstEntries = 0;
    for (int p = 0; p < 6; ++p) {  // second layer: shapes from 1 slot to 70, any node count
        const uint32_t S = 1 + rng() % 70, n = rng() % (S + 1);
        vg::Patch patch{uint32_t(r.slots.size()), S, n, 0, secondEntries, randomScale(rng), 0};
        for (uint32_t i = 0; i < S; ++i) r.slots.push_back(i < n ? rng() % N : rng() % V);
        secondEntries += vg::secondMatrixEntries(S, n);
        r.second.push_back(patch);
    }
    for (int p = 0; p < 3; ++p) {  // first layer: whole node x node matrices
        const uint32_t S = rng() % 40;
        vg::Patch patch{uint32_t(r.slots.size()), S, S, 0, firstEntries, randomScale(rng), 0};
        for (uint32_t i = 0; i < S; ++i) r.slots.push_back(rng() % N);
        firstEntries += uint64_t(S) * S;
        r.first.push_back(patch);
    }
    // Random bytes: any 12-bit values, and the last patch's entries right at the array's end.
    r.secondBytes.resize((3 * secondEntries + 1) / 2);
    r.firstBytes.resize((3 * firstEntries + 1) / 2);
    for (uint8_t& b : r.secondBytes) b = uint8_t(rng());
    for (uint8_t& b : r.firstBytes) b = uint8_t(rng());
    // After an odd number of entries the last byte's high nibble is no entry's: 0, as the
    // baker writes it and the byte planes' decoder leaves it.
    if (secondEntries % 2 == 1) r.secondBytes.back() &= 0x0F;
    if (firstEntries % 2 == 1) r.firstBytes.back() &= 0x0F;
    r.graph.vertexCount = V;
    r.graph.nodeCount = N;
    r.graph.positions = r.positions.data();
    r.graph.slots = r.slots.data();
    r.graph.nodeVertex = r.nodeVertex.data();
    r.graph.second = r.second.data();
    r.graph.secondCount = uint32_t(r.second.size());
    r.graph.first = r.first.data();
    r.graph.firstCount = uint32_t(r.first.size());
    r.graph.secondDistances = r.secondBytes.data();
    r.graph.secondDistancesEnd = r.secondBytes.data() + r.secondBytes.size();
    r.graph.firstDistances = r.firstBytes.data();
    r.graph.firstDistancesEnd = r.firstBytes.data() + r.firstBytes.size();
    return r;
}

// The reference encoder over a graph's distance arrays (what the baker's codeDistances
// does to a flatbuffer): second and first get the codes of plainSecond and plainFirst.
void encode(const vg_graph& g, const std::vector<uint8_t>& plainSecond, const std::vector<uint8_t>& plainFirst,
            std::vector<uint8_t>& second, std::vector<uint8_t>& first) {
    second = plainSecond;
    first = plainFirst;
    for (uint32_t i = 0; i < g.secondCount; ++i) {
        const vg::Patch& p = g.second[i];
        const vg_coding_slots s{g.positions, g.slots + p.slotBegin, g.nodeVertex, p.nodeCount};
        vg_code_second_matrix(plainSecond.data(), second.data(), p.matrixBegin, p.slotCount, p.nodeCount, p.scale, &s, 0);
    }
    for (uint32_t i = 0; i < g.firstCount; ++i) {
        const vg::Patch& p = g.first[i];
        const vg_coding_slots s{g.positions, g.slots + p.slotBegin, g.nodeVertex, p.slotCount};
        vg_code_first_matrix(plainFirst.data(), first.data(), p.matrixBegin, p.slotCount, p.scale, &s, 0);
    }
    std::vector<unsigned char> scratch(VG_CODING_PLANE_SCRATCH);
    vg_code_planes(second.data(), vg_coding_entries(second.size()), scratch.data(), 0);
    vg_code_planes(first.data(), vg_coding_entries(first.size()), scratch.data(), 0);
}

}  // namespace

TEST_CASE("distance coding: a row's predictions are vg_predicted_quantum's, in both versions", "[runtime][coding]") {
    const bool avx2 = vg::cpuHasAvx2();
    if (!avx2) WARN("this CPU has no AVX2: only the portable version is checked");
    std::mt19937 rng(7);
    std::vector<uint8_t> scratch(vg::decodeScratchSize());
    for (int round = 0; round < 300; ++round) {
        const uint32_t S = 1 + rng() % 90;
        std::vector<float> x(S + 16, 0.0f), y(S + 16, 0.0f), z(S + 16, 0.0f);
        for (uint32_t i = 0; i < S; ++i) x[i] = randomCoordinate(rng), y[i] = randomCoordinate(rng), z[i] = randomCoordinate(rng);
        const float scale = randomScale(rng);
        const uint32_t i = rng() % S, j0 = rng() % (S + 1);
        for (int version = 0; version < (avx2 ? 2 : 1); ++version) {
            std::vector<uint16_t> out(S + 16, 0xFFFF);
            vg::predictRow(version == 1, x.data(), y.data(), z.data(), i, j0, S, scale, out.data());
            for (uint32_t j = j0; j < S; ++j) {
                const float a[3] = {x[i], y[i], z[i]}, b[3] = {x[j], y[j], z[j]};
                const uint32_t expected = vg_predicted_quantum(a, b, scale);
                REQUIRE(expected <= VG_CODING_MAX_QUANTUM);
                REQUIRE(out[j] == expected);
            }
        }
    }
}

TEST_CASE("distance coding: decode(encode(q)) = q for any bytes and patch shapes, in both versions",
          "[runtime][coding]") {
    const bool avx2 = vg::cpuHasAvx2();
    std::mt19937 rng(11);
    std::vector<uint8_t> scratch(vg::decodeScratchSize() + 16);
    void* aligned = scratch.data() + (16 - reinterpret_cast<uintptr_t>(scratch.data()) % 16) % 16;
    for (int round = 0; round < 200; ++round) {
        RandomGraph r = randomGraph(rng);
        std::vector<uint8_t> second, first;
        encode(r.graph, r.secondBytes, r.firstBytes, second, first);
        for (int version = 0; version < (avx2 ? 2 : 1); ++version) {
            std::vector<uint8_t> s2 = second, s1 = first;
            vg_graph g = r.graph;
            g.secondDistances = s2.data();
            g.secondDistancesEnd = s2.data() + s2.size();
            g.firstDistances = s1.data();
            g.firstDistancesEnd = s1.data() + s1.size();
            vg::decodeDistances(g, version == 1, aligned);
            REQUIRE(s2 == r.secondBytes);
            REQUIRE(s1 == r.firstBytes);
        }
    }
}

TEST_CASE("distance coding: byte planes give back any packed codes, over several chunks", "[runtime][coding]") {
    std::mt19937 rng(5);
    std::vector<unsigned char> scratch(VG_CODING_PLANE_SCRATCH);
    const uint64_t C = VG_CODING_PLANE_ENTRIES;
    for (const uint64_t entries : {uint64_t(0), uint64_t(1), uint64_t(2), uint64_t(7), C - 1, C, C + 1, 2 * C + 3}) {
        for (const uint64_t spare : {uint64_t(0), uint64_t(1)}) {  // a byte after the last entry, untouched
            if (spare && entries % 2 == 1) continue;  // that byte would hold one more entry
            const uint64_t bytes = (3 * entries + 1) / 2 + spare;
            std::vector<unsigned char> plain(bytes);
            for (unsigned char& b : plain) b = uint8_t(rng());
            // Codes near 0 either way, as in a blob, and some anywhere.
            for (uint64_t k = 0; k < entries; ++k)
                vg_coding_set(plain.data(), k, rng() % 4 == 0 ? rng() % 4096 : (4096 + rng() % 21 - 10) % 4096);
            if (entries % 2 == 1) plain[(3 * entries + 1) / 2 - 1] &= 0x0F;  // the nibble of no entry: 0
            INFO(entries << " entries, " << bytes << " bytes");
            REQUIRE(vg_coding_entries(bytes) == entries);
            std::vector<unsigned char> coded = plain;
            vg_code_planes(coded.data(), entries, scratch.data(), 0);
            if (entries >= 7) CHECK(coded != plain);
            if (spare) CHECK(coded.back() == plain.back());
            if (entries >= C) {  // the first chunk's high plane: mostly zeros, as zstd likes it
                uint64_t zeros = 0;
                for (uint64_t j = C; j < C + C / 2; ++j) zeros += coded[j] == 0;
                CHECK(zeros > C / 2 * 2 / 5);  // both nibbles 0: ~57% of the bytes here
            }
            vg_code_planes(coded.data(), entries, scratch.data(), 1);
            REQUIRE(coded == plain);
        }
    }
    // zigzag on its own: 0 -> 0, +1 -> 2, -1 (4095) -> 1, and both ends.
    CHECK(vg_coding_zigzag(0) == 0);
    CHECK(vg_coding_zigzag(1) == 2);
    CHECK(vg_coding_zigzag(4095) == 1);
    CHECK(vg_coding_zigzag(2047) == 4094);
    CHECK(vg_coding_zigzag(2048) == 4095);
    for (uint32_t c = 0; c < 4096; ++c) REQUIRE(vg_coding_unzigzag(vg_coding_zigzag(c)) == c);
}

TEST_CASE("distance coding: a compact blob is coded, smaller, and opens to the same quanta and answers",
          "[runtime][coding]") {
    const Mesh mesh = bumpyTorus(60, 30);
    const std::vector<uint8_t> coded = bakeWith(mesh, true, true), plain = bakeWith(mesh, false, false);
    const std::vector<uint8_t> zstd = bakeWith(mesh, true, false);
    REQUIRE(vg_load_le32(coded.data() + 12) == (VG_FLAG_ZSTD | VG_FLAG_CODED_DISTANCES));
    REQUIRE(vg_load_le32(zstd.data() + 12) == VG_FLAG_ZSTD);
    REQUIRE(vg_load_le32(plain.data() + 12) == 0u);
    CHECK(coded.size() * 4 < zstd.size() * 3);  // igea: 2.0x; this small torus: 1.4x

    // The tools' reference decoder gives back the plain flatbuffer byte for byte.
    tools::BlobContents a, b;
    std::string error;
    REQUIRE(tools::unpackBlob(coded, a, error));
    REQUIRE(tools::unpackBlob(plain, b, error));
    CHECK(a.coded);
    CHECK_FALSE(b.coded);
    REQUIRE(a.flatbuffer == b.flatbuffer);

    // So does the runtime's, in both versions; and a coded blob stored uncompressed opens too
    // (copied, then decoded).
    std::vector<uint8_t> codedPlain = plain;
    {
        std::vector<uint8_t> flatbuffer(plain.begin() + VG_CONTAINER_HEADER_SIZE, plain.end());
        codeDistances(flatbuffer);
        // The patch edges keep their ends and store no length (format 11).
        const auto* stored = fb::GetGraph(flatbuffer.data())->second_edges();
        REQUIRE(stored != nullptr);
        REQUIRE(stored->size() > 100);
        for (const fb::PatchEdge* E : *stored) REQUIRE(E->length() == 0.0f);
        codedPlain = sealContainer(flatbuffer, VG_FLAG_CODED_DISTANCES, 0);
    }
    tools::RuntimeGraph reference;
    REQUIRE(reference.open(plain, error));
    const vg_graph& want = *reference.graph();
    const size_t secondBytes = size_t(want.secondDistancesEnd - want.secondDistances);
    const size_t firstBytes = size_t(want.firstDistancesEnd - want.firstDistances);
    for (const std::vector<uint8_t>* blob : std::vector<const std::vector<uint8_t>*>{&coded, &codedPlain}) {
        tools::RuntimeGraph g;
        REQUIRE(g.open(*blob, error));
        const vg_graph& got = *g.graph();
        REQUIRE(size_t(got.secondDistancesEnd - got.secondDistances) == secondBytes);
        REQUIRE(std::memcmp(got.secondDistances, want.secondDistances, secondBytes) == 0);
        REQUIRE(std::memcmp(got.firstDistances, want.firstDistances, firstBytes) == 0);
        // the topology, delta-coded (vorogeo_topology_coding.h)
        REQUIRE(got.faceCount == want.faceCount);
        REQUIRE(std::memcmp(got.faceVertices, want.faceVertices, 12 * size_t(want.faceCount)) == 0);
        REQUIRE(std::memcmp(got.faceTwin, want.faceTwin, 12 * size_t(want.faceCount)) == 0);
        REQUIRE(std::memcmp(got.vertexHalfedge, want.vertexHalfedge, 4 * size_t(want.vertexCount)) == 0);
        // the patch edges' lengths, computed at open: the baker's bits
        REQUIRE(got.secondEdgeCount == want.secondEdgeCount);
        REQUIRE(std::memcmp(got.secondEdges, want.secondEdges, sizeof(vg::PatchEdge) * want.secondEdgeCount) == 0);
        // the positions and the index sequences (vg_code_positions, vg_code_sequence)
        const uint32_t N = want.nodeCount;
        REQUIRE(got.nodeCount == N);
        REQUIRE(std::memcmp(got.positions, want.positions, 12 * size_t(want.vertexCount)) == 0);
        REQUIRE(std::memcmp(got.nodeVertex, want.nodeVertex, 4 * size_t(N)) == 0);
        REQUIRE(std::memcmp(got.nodeSecondBegin, want.nodeSecondBegin, 4 * size_t(N + 1)) == 0);
        REQUIRE(std::memcmp(got.nodeFirstBegin, want.nodeFirstBegin, 4 * size_t(N + 1)) == 0);
        REQUIRE(std::memcmp(got.nodeEdgeBegin, want.nodeEdgeBegin, 4 * size_t(N + 1)) == 0);
        REQUIRE(std::memcmp(got.nodeEdge, want.nodeEdge, 4 * size_t(want.nodeEdgeBegin[N])) == 0);
        const vg::Patch& last = want.first[want.firstCount - 1];
        REQUIRE(std::memcmp(got.slots, want.slots, 4 * size_t(last.slotBegin + last.slotCount)) == 0);
    }
    {  // the portable decoder on the real arrays, re-coded by the reference encoder
        const vg_graph& g = want;
        const std::vector<uint8_t> plain2(g.secondDistances, g.secondDistances + secondBytes);
        const std::vector<uint8_t> plain1(g.firstDistances, g.firstDistances + firstBytes);
        std::vector<uint8_t> s2, s1;
        encode(g, plain2, plain1, s2, s1);
        vg_graph copy = g;
        copy.secondDistances = s2.data();
        copy.secondDistancesEnd = s2.data() + s2.size();
        copy.firstDistances = s1.data();
        copy.firstDistancesEnd = s1.data() + s1.size();
        std::vector<uint8_t> scratch(vg::decodeScratchSize() + 16);
        vg::decodeDistances(copy, false, scratch.data() + (16 - reinterpret_cast<uintptr_t>(scratch.data()) % 16) % 16);
        REQUIRE(s2 == plain2);
        REQUIRE(s1 == plain1);
    }

    // Same answers, bit for bit: point-to-point and a field.
    tools::RuntimeGraph opened;
    REQUIRE(opened.open(coded, error));
    tools::RuntimeWorkspace wa(reference), wb(opened);
    requireSamePointToPoint(reference, wa, opened, wb, 200, 3);
    const uint32_t V = vg_vertex_count(reference.graph());
    std::vector<float> fa(V), fb(V);
    const uint32_t source = V / 2;
    REQUIRE(vg_distance_field(reference.graph(), wa.get(), &source, 1, fa.data()) == VG_OK);
    REQUIRE(vg_distance_field(opened.graph(), wb.get(), &source, 1, fb.data()) == VG_OK);
    REQUIRE(std::memcmp(fa.data(), fb.data(), V * sizeof(float)) == 0);
}

TEST_CASE("distance coding: a coded blob with a flipped payload bit or an unknown flag is refused",
          "[runtime][coding]") {
    const std::vector<uint8_t> coded = bakeWith(planeGrid(12, 12, 1.0, 0.05, 3), true, true);
    std::string error;
    tools::RuntimeGraph g;
    std::vector<uint8_t> flipped = coded;
    flipped[VG_CONTAINER_HEADER_SIZE + flipped.size() / 3] ^= 0x10;
    CHECK_FALSE(g.open(flipped, error));
    CHECK(error.find("checksum") != std::string::npos);
    std::vector<uint8_t> unknown = coded;
    vg_store_le32(unknown.data() + 12, VG_FLAG_ZSTD | VG_FLAG_CODED_DISTANCES | 8u);
    CHECK_FALSE(g.open(unknown, error));
    tools::BlobContents c;
    CHECK_FALSE(tools::unpackBlob(unknown, c, error));
    CHECK(error.find("unknown flags") != std::string::npos);
}

TEST_CASE("distance coding: a coded blob that stores a patch edge length is refused", "[runtime][coding]") {
    const std::vector<uint8_t> plain = bakeWith(planeGrid(12, 12, 1.0, 0.05, 3), false, false);
    std::vector<uint8_t> flatbuffer(plain.begin() + VG_CONTAINER_HEADER_SIZE, plain.end());
    codeDistances(flatbuffer);
    std::string error;
    tools::RuntimeGraph g;
    tools::BlobContents c;
    REQUIRE(g.open(sealContainer(flatbuffer, VG_FLAG_CODED_DISTANCES, 0), error));
    const auto* edges = fb::GetGraph(flatbuffer.data())->second_edges();
    REQUIRE(edges->size() > 10);
    // The length of the middle edge, set to a plausible length (1.0f) and to a NaN.
    uint8_t* length = flatbuffer.data() + (edges->Data() - flatbuffer.data()) + VG_PATCH_EDGE_BYTES * (edges->size() / 2) + VG_PATCH_EDGE_LENGTH_AT;
    for (const uint32_t bits : {0x3F800000u, 0x7FC00000u}) {
        std::memcpy(length, &bits, 4);
        const std::vector<uint8_t> blob = sealContainer(flatbuffer, VG_FLAG_CODED_DISTANCES, 0);
        CHECK_FALSE(g.open(blob, error));
        size_t need = 0;
        REQUIRE(vg_open_size(blob.data(), blob.size(), &need) == VG_OK);
        std::vector<uint64_t> memory(need / 8 + 1);
        const vg_graph* graph = nullptr;
        CHECK(vg_open(blob.data(), blob.size(), memory.data(), need, &graph) == VG_ERR_CORRUPT_CONTENT);
        CHECK(graph == nullptr);
        CHECK_FALSE(tools::unpackBlob(blob, c, error));
        CHECK(error.find("patch edge length") != std::string::npos);
    }
}

TEST_CASE("runtime: a blob whose patch edges are not in order of their first slot is refused", "[runtime]") {
    // The one-to-all fill finds a node slot's edges by where they start (slotFirstEdge).
    std::vector<uint8_t> blob = bakeWith(planeGrid(12, 12, 1.0, 0.05, 3), false, false);
    const fb::Graph* g = fb::GetGraph(blob.data() + VG_CONTAINER_HEADER_SIZE);
    const auto* edges = g->second_edges();
    const auto* patches = g->second_patches();
    REQUIRE(openStatus(blob) == VG_OK);
    // Two edges of one patch: a pair with the same first slot, and the first pair whose
    // first slots differ.
    uint32_t same = UINT32_MAX, differ = UINT32_MAX;
    const uint32_t end = patches->size() > 1 ? patches->Get(1)->edge_begin() : edges->size();
    for (uint32_t e = patches->Get(0)->edge_begin(); e + 1 < end; ++e) {
        uint32_t& first = edges->Get(e)->from() == edges->Get(e + 1)->from() ? same : differ;
        if (first == UINT32_MAX) first = e;
    }
    REQUIRE(same != UINT32_MAX);
    REQUIRE(differ != UINT32_MAX);
    const size_t at = size_t(reinterpret_cast<const uint8_t*>(edges->Data()) - blob.data());
    auto swapped = [&](uint32_t e) {
        std::vector<uint8_t> b = blob;
        uint8_t* x = b.data() + at + VG_PATCH_EDGE_BYTES * e;
        std::swap_ranges(x, x + VG_PATCH_EDGE_BYTES, x + VG_PATCH_EDGE_BYTES);
        resealChecksum(b);
        return b;
    };
    CHECK(openStatus(swapped(same)) == VG_OK);  // still in order
    CHECK(openStatus(swapped(differ)) == VG_ERR_CORRUPT_CONTENT);
}

TEST_CASE("runtime: a blob that lists a vertex in two interior slots is refused", "[runtime]") {
    // One-to-all writes each interior vertex once, from its home patch, without comparing
    // (vg_field.cpp): vg_open must refuse a second interior slot for it. The blob stays
    // consistent otherwise: vertex w, next to v in a patch's interior slots, gives its
    // slot and its face corners to v and becomes a vertex used by no face.
    std::vector<uint8_t> blob = bakeWith(planeGrid(12, 12, 1.0, 0.05, 3), false, false);
    REQUIRE(openStatus(blob) == VG_OK);
    const fb::Graph* g = fb::GetGraph(blob.data() + VG_CONTAINER_HEADER_SIZE);
    const auto* patches = g->second_patches();
    const auto* slots = g->slots();
    uint32_t at = UINT32_MAX;  // the slot of w, after v's
    for (uint32_t i = 0; i < patches->size() && at == UINT32_MAX; ++i) {
        const auto* p = patches->Get(i);
        if (p->slot_count() >= p->node_count() + 2) at = p->slot_begin() + p->node_count() + 1;
    }
    REQUIRE(at != UINT32_MAX);
    const uint32_t v = slots->Get(at - 1), w = slots->Get(at);
    auto offset = [&](const void* x) { return size_t(static_cast<const uint8_t*>(x) - blob.data()); };
    auto put32 = [&](std::vector<uint8_t>& b, size_t o, uint32_t x) { std::memcpy(b.data() + o, &x, 4); };
    std::vector<uint8_t> bad = blob;
    put32(bad, offset(slots->Data()) + 4 * size_t(at), v);
    const auto* corners = g->face_vertices();
    for (uint32_t h = 0; h < corners->size(); ++h)
        if (corners->Get(h) == w) put32(bad, offset(corners->Data()) + 4 * size_t(h), v);
    put32(bad, offset(g->vertex_patch()->Data()) + 4 * size_t(w), UINT32_MAX);
    put32(bad, offset(g->vertex_halfedge()->Data()) + 4 * size_t(w), UINT32_MAX);
    resealChecksum(bad);
    CHECK(openStatus(bad) == VG_ERR_CORRUPT_CONTENT);
}

TEST_CASE("distance coding: --compact needs compression", "[runtime][coding]") {
    BakeOptions o;
    o.compress = false;
    o.compact = true;
    BakeReport report;
    REQUIRE_THROWS_WITH(bakeMesh(planeGrid(6, 6, 1.0), o, report, nullptr),
                        Catch::Contains("--compact") && Catch::Contains("--no-compress"));
}

// Hub-label tables (schema/vorogeo_label_coding.h).
TEST_CASE("label coding: decode(encode(x)) = x for any steps, shapes and sites, in the reference and the runtime",
          "[runtime][coding]") {
    std::mt19937 rng(11);
    std::vector<float> positions;
    for (int v = 0; v < 3 * 50; ++v) positions.push_back(randomCoordinate(rng));
    std::vector<uint32_t> nodeVertex, nodes;
    for (uint32_t n = 0; n < 25; ++n) nodeVertex.push_back(rng() % 50);
    for (int i = 0; i < 200; ++i) nodes.push_back(rng() % 25);
    std::vector<int32_t> detours(2 * 200);
    std::vector<unsigned char> planes(2 * VG_LABEL_CHUNK);
    std::vector<uint8_t> scratchBytes(vg::labelDecodeScratchSize() + 16);
    void* scratch = scratchBytes.data() + (16 - reinterpret_cast<uintptr_t>(scratchBytes.data()) % 16) % 16;
    for (int trial = 0; trial < 300; ++trial) {
        const uint32_t rows = rng() % 40, cols = 1 + rng() % 60;
        std::vector<uint16_t> plain(uint64_t(rows) * cols + 7);
        const uint32_t markerOdds = trial % 3 == 0 ? 5 : (trial % 3 == 1 ? 500 : 1u << 30);  // rows with and without
        for (uint16_t& x : plain) {
            if (rng() % markerOdds != 0) {
                x = uint16_t(rng() % 8 ? 30000 + rng() % 200 : rng() % 65535);  // mostly smooth, some jumps
                continue;
            }
            switch (rng() % 5) {
                case 0: x = uint16_t(VG_LABEL_NO_PATH); break;
                case 1: x = uint16_t(rng() % 3 ? 65534 : 0); break;
                default: x = uint16_t(rng() % 65535);
            }
        }
        const float scale = trial % 7 == 0 ? 0.0f : randomScale(rng);
        const vg_label_sites sites{positions.data(), nodeVertex.data(), nodes.data() + rng() % 100,
                                   nodes.data() + rng() % 100, 1.0f / scale};
        const vg_label_sites* s = trial % 2 ? &sites : nullptr;
        std::vector<uint16_t> coded = plain;
        vg_code_label_table(plain.data(), coded.data(), 7, rows, cols, s, detours.data(), 0);
        for (uint64_t i = 0; i < 7; ++i) REQUIRE(coded[i] == plain[i]);  // outside the table: untouched
        std::vector<uint16_t> split = coded;
        vg_label_planes(reinterpret_cast<unsigned char*>(split.data()), split.size(), planes.data(), 1);
        if (split.size() > 1 && coded != plain) CHECK(split != coded);
        vg_label_planes(reinterpret_cast<unsigned char*>(split.data()), split.size(), planes.data(), 0);
        REQUIRE(split == coded);
        std::vector<uint16_t> fast = coded;  // the runtime's decoder
        vg_code_label_table(coded.data(), coded.data(), 7, rows, cols, s, detours.data(), 1);
        REQUIRE(coded == plain);
        vg::decodeLabelTable(fast.data() + 7, rows, cols, s, scratch);
        REQUIRE(fast == plain);
    }
    // Any codes decode to valid steps (65535 only where the code is 65535).
    std::vector<uint16_t> codes(64 * 16);
    for (uint16_t& x : codes) x = uint16_t(rng());
    const std::vector<uint16_t> before = codes;
    vg_code_label_table(codes.data(), codes.data(), 0, 64, 16, nullptr, detours.data(), 1);
    for (size_t i = 0; i < codes.size(); ++i) CHECK((codes[i] == VG_LABEL_NO_PATH) == (before[i] == VG_LABEL_NO_PATH));
    // Smooth tables code to small residuals: a plane of steps codes to zeros past the first
    // row and column.
    std::vector<uint16_t> ramp(20 * 16), rampCoded(20 * 16);
    for (uint32_t r = 0; r < 20; ++r)
        for (uint32_t c = 0; c < 16; ++c) ramp[r * 16 + c] = uint16_t(1000 + 37 * r + 11 * c);
    vg_code_label_table(ramp.data(), rampCoded.data(), 0, 20, 16, nullptr, detours.data(), 0);
    for (uint32_t r = 1; r < 20; ++r)
        for (uint32_t c = 1; c < 16; ++c) CHECK(rampCoded[r * 16 + c] == 0);
}

TEST_CASE("label coding: a compact blob's hub labels are coded, smaller, and open to the same steps and answers",
          "[runtime][coding][hub]") {
    const Mesh mesh = bumpyTorus(60, 30);
    auto bake = [&](bool compact) {
        BakeOptions o;
        o.n1 = 12;
        o.hubLabels = true;
        o.compress = true;
        o.compact = compact;
        BakeReport report;
        return bakeMesh(mesh, o, report, nullptr);
    };
    const std::vector<uint8_t> coded = bake(true), zstd = bake(false);
    std::string error;
    tools::BlobContents a, b;
    REQUIRE(tools::unpackBlob(coded, a, error));
    REQUIRE(tools::unpackBlob(zstd, b, error));
    REQUIRE(a.graph()->hub_tree()->size() > 1);
    REQUIRE(a.flatbuffer == b.flatbuffer);  // the tools' decoder
    REQUIRE(a.hubColumns == b.hubColumns);
    REQUIRE(a.hubInner == b.hubInner);

    // What the coding does to the label tables alone: zstd of the plain and the coded arrays.
    auto zstdSize = [](const uint16_t* v, size_t n) {
        std::vector<uint8_t> out(ZSTD_compressBound(n * 2));
        return ZSTD_compress(out.data(), out.size(), v, n * 2, 9);
    };
    vg_label_tables at;
    REQUIRE(vg_label_tables_at(b.flatbuffer.size(), b.hubColumns.size(), b.hubInner.size(), &at));
    std::vector<uint8_t> recoded = b.flatbuffer;
    recoded.resize(at.payload_size, 0);
    std::memcpy(recoded.data() + at.columns_offset, b.hubColumns.data(), 2 * b.hubColumns.size());
    std::memcpy(recoded.data() + at.inner_offset, b.hubInner.data(), 2 * b.hubInner.size());
    codeDistances(recoded, b.flatbuffer.size());
    const uint16_t* codedColumns = reinterpret_cast<const uint16_t*>(recoded.data() + at.columns_offset);
    const uint16_t* codedInner = reinterpret_cast<const uint16_t*>(recoded.data() + at.inner_offset);
    const size_t plainBytes = zstdSize(b.hubColumns.data(), b.hubColumns.size()) + zstdSize(b.hubInner.data(), b.hubInner.size());
    const size_t codedBytes = zstdSize(codedColumns, b.hubColumns.size()) + zstdSize(codedInner, b.hubInner.size());
    INFO("label tables, zstd: plain " << plainBytes << " bytes, coded " << codedBytes);
    CHECK(codedBytes * 4 < plainBytes * 3);  // this torus: 1.5x; igea: 3.4x

    tools::RuntimeGraph want, got;
    REQUIRE(want.open(zstd, error));
    REQUIRE(got.open(coded, error));
    const vg_graph& w = *want.graph();
    const vg_graph& g = *got.graph();
    REQUIRE(g.hubTreeCount == w.hubTreeCount);
    REQUIRE(std::memcmp(g.hubColumns, w.hubColumns, w.hubColumnBegin[w.hubTreeCount] * 2) == 0);
    REQUIRE(std::memcmp(g.hubInner, w.hubInner, w.hubInnerMatrixBegin[w.firstCount] * 2) == 0);
    tools::RuntimeWorkspace wa(want), wb(got);
    requireSamePointToPoint(want, wa, got, wb, 300, 5);
}

TEST_CASE("topology coding: decode(encode(x)) = x for any indices, and any codes decode", "[runtime][coding]") {
    std::mt19937 rng(17);
    for (int trial = 0; trial < 50; ++trial) {
        const size_t H = rng() % 300, V = rng() % 100;
        std::vector<uint32_t> fv(H), tw(H), vh(V);
        for (uint32_t& x : fv) x = rng() % 4 == 0 ? uint32_t(rng()) : rng() % 1000;
        for (uint32_t& x : tw) x = rng() % 5 == 0 ? VG_TOPOLOGY_NONE : uint32_t(rng()) >> (rng() % 2 ? 1 : 20);
        for (uint32_t& x : vh) x = rng() % 5 == 0 ? VG_TOPOLOGY_NONE : uint32_t(rng()) >> (rng() % 2 ? 1 : 20);
        std::vector<uint32_t> a = fv, b = tw, c = vh;
        vg_code_topology(a.data(), b.data(), H, c.data(), V, 0);
        if (H > 2) CHECK(a != fv);
        vg_code_topology(a.data(), b.data(), H, c.data(), V, 1);
        REQUIRE(a == fv);
        REQUIRE(b == tw);
        REQUIRE(c == vh);
    }
    // A mesh stored with locality codes to small numbers: a strip of faces.
    std::vector<uint32_t> strip, twins(30, VG_TOPOLOGY_NONE), none;
    for (uint32_t f = 0; f < 10; ++f) strip.insert(strip.end(), {f, f + 1, f + 2});
    vg_code_topology(strip.data(), twins.data(), strip.size(), none.data(), 0, 0);
    for (size_t h = 1; h < strip.size(); ++h) CHECK(strip[h] <= 4);
}
