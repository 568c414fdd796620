// The one-to-all query's kernels (runtime/src/vg_field_kernels.h): the AVX2 versions give
// the same bits as the portable ones and as a plain reference, on random packed rows of
// every length and parity, up to the end of the packed array; and whole fields are the
// same bits with either.
#include <catch2/catch.hpp>

#include <cstring>
#include <random>
#include <vector>

#include "bake.h"
#include "generators.h"
#include "runtime_graph.h"
#include "vg_field_kernels.h"
#include "vg_graph.h"

using namespace vorogeo;

namespace {

// 12-bit entries packed two per three bytes, as the baker writes them.
std::vector<uint8_t> pack(const std::vector<uint16_t>& q) {
    std::vector<uint8_t> bytes((q.size() * 3 + 1) / 2, 0);
    for (size_t k = 0; k < q.size(); ++k) {
        const size_t b = 3 * (k / 2);
        if (k % 2 == 0) {
            bytes[b] = uint8_t(q[k]);
            bytes[b + 1] = uint8_t((bytes[b + 1] & 0xF0) | (q[k] >> 8));
        } else {
            bytes[b + 1] = uint8_t((bytes[b + 1] & 0x0F) | ((q[k] & 0xF) << 4));
            bytes[b + 2] = uint8_t(q[k] >> 4);
        }
    }
    return bytes;
}

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

struct Rows {
    std::vector<uint16_t> quanta;
    std::vector<uint8_t> bytes;
    vg_graph graph{};
};

Rows randomRows(std::mt19937& rng, size_t entries) {
    Rows r;
    std::uniform_int_distribution<int> q(0, 4094);
    for (size_t k = 0; k < entries; ++k) r.quanta.push_back(rng() % 11 == 0 ? 4095 : uint16_t(q(rng)));
    r.bytes = pack(r.quanta);
    r.graph.secondDistances = r.bytes.data();
    r.graph.secondDistancesEnd = r.bytes.data() + r.bytes.size();
    return r;
}

}  // namespace

TEST_CASE("field kernels: lowering from rows and decoding match a plain loop, bit for bit, in every version",
          "[runtime][kernels]") {
    const bool avx2 = vg::cpuHasAvx2(), avx512 = vg::cpuHasAvx512();
    if (!avx2) WARN("this CPU has no AVX2: only the portable kernels are checked");
    else if (!avx512) WARN("this CPU has no AVX-512: its row kernel is not checked");
    const int versions = avx512 ? 3 : avx2 ? 2 : 1;  // portable, AVX2, AVX-512
    std::mt19937 rng(11);
    Rows r = randomRows(rng, 2001);  // odd: the last entry ends mid-byte
    const float scale = 0.00123f;
    for (int trial = 0; trial < 400; ++trial) {
        const uint32_t count = 1 + rng() % 6, n = rng() % 75;
        std::vector<uint64_t> rows(count);
        std::vector<float> bases(count);
        std::vector<uint32_t> tags(count);
        for (uint32_t i = 0; i < count; ++i) {
            // Some rows end exactly at the last entry, so the vector loads stop short of it.
            rows[i] = trial % 5 == 0 ? r.quanta.size() - n : rng() % (r.quanta.size() - n + 1);
            bases[i] = float(rng() % 1000) * 0.01f;
            tags[i] = uint32_t(rng() % 100);
        }
        const uint32_t stride = vg::entriesStride(n);
        std::vector<float> start(n + vg::kRowSlack);
        for (float& b : start) b = rng() % 4 == 0 ? __builtin_inff() : float(rng() % 2000) * 0.005f;
        // Reference: the definition.
        std::vector<float> refBest(start.begin(), start.begin() + n);
        std::vector<uint32_t> refFrom(n, 7777);
        for (uint32_t i = 0; i < count; ++i)
            for (uint32_t j = 0; j < n; ++j) {
                const uint16_t q = r.quanta[rows[i] + j];
                const float v = bases[i] + float(int32_t(q)) * scale;
                if (q != 4095 && v < refBest[j]) {
                    refBest[j] = v;
                    refFrom[j] = tags[i];
                }
            }
        for (int version = 0; version < versions; ++version) {
            std::vector<float> best = start;
            std::vector<uint32_t> from(n + vg::kRowSlack, 7777);
            std::vector<float> entries(uint64_t(count) * stride + vg::kRowSlack);
            r.graph.avx512 = version == 2;
            // Half of the calls also ask for a range of lines a share per row (the next
            // patch's block): the same answers, and every line asked for by the last row.
            vg::PrefetchDrip drip;
            drip.set(r.bytes.data() + trial % 64, r.bytes.data() + r.bytes.size() - trial % 7);
            const bool dripping = trial % 2 == 1;
            vg::lowerFromRows(version >= 1, r.graph, scale, rows.data(), bases.data(), tags.data(), count, n, best.data(),
                              from.data(), entries.data(), stride, dripping ? &drip : nullptr);
            if (dripping) REQUIRE(drip.lines() == 0);
            for (uint32_t j = 0; j < n; ++j) {
                INFO("trial " << trial << " version " << version << " slot " << j);
                REQUIRE(sameBits(best[j], refBest[j]));
                REQUIRE(from[j] == refFrom[j]);
                for (uint32_t i = 0; i < count; ++i) {
                    const uint16_t q = r.quanta[rows[i] + j];
                    REQUIRE(sameBits(entries[i * stride + j], q == 4095 ? __builtin_inff() : float(int32_t(q)) * scale));
                }
            }
            std::vector<float> decoded(n + vg::kRowSlack, -1.0f);
            vg::decodeRow(version >= 1, r.graph, scale, rows[0], n, decoded.data());
            // Nothing past the row's stride, where the next row's entries lie.
            for (size_t j = vg::entriesStride(n); j < decoded.size(); ++j) REQUIRE(decoded[j] == -1.0f);
            for (uint32_t j = 0; j < n; ++j) REQUIRE(sameBits(decoded[j], entries[j]));
        }
    }
}

TEST_CASE("field kernels: a prefetch drip counts and asks for each line of its range once", "[runtime][kernels]") {
    alignas(64) static uint8_t buffer[64 * 10];
    vg::PrefetchDrip drip;
    drip.clear();
    REQUIRE(drip.lines() == 0);
    drip.issue(3);  // nothing to ask for: no change
    REQUIRE(drip.lines() == 0);
    // [5, 64 * 3 + 1): lines 0 .. 3, the first and last partly.
    drip.set(buffer + 5, buffer + 64 * 3 + 1);
    REQUIRE(drip.lines() == 4);
    drip.issue(3);
    REQUIRE(drip.lines() == 1);
    drip.issue(5);  // only what is left
    REQUIRE(drip.lines() == 0);
    drip.set(buffer + 64, buffer + 64 * 2);  // exactly one line
    REQUIRE(drip.lines() == 1);
    drip.set(buffer + 64, buffer + 64);  // empty
    REQUIRE(drip.lines() == 0);
}

TEST_CASE("field kernels: crossings match crossing() of vg_graph.h, bit for bit, in both versions",
          "[runtime][kernels]") {
    const bool avx2 = vg::cpuHasAvx2();
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.1f, 2.0f);
    for (int trial = 0; trial < 300; ++trial) {
        const uint32_t interior = 1 + rng() % 40, edgeCount = rng() % 12, memberCount = rng() % (interior + 1);
        const uint32_t stride = vg::entriesStride(interior);
        std::vector<float> rows(uint64_t(edgeCount + 1) * stride + vg::kRowSlack);
        for (float& v : rows) v = rng() % 9 == 0 ? __builtin_inff() : u(rng);
        const float* c = rows.data() + uint64_t(edgeCount) * stride;  // the best node's own row
        const float a = u(rng);
        std::vector<vg::CrossingEdge> edges;
        for (uint32_t k = 0; k < edgeCount; ++k) {
            const float b = u(rng), l = 0.05f + u(rng) * 0.5f;
            vg::UnfoldedPoint s;
            if (!vg::unfoldPoint(a, b, l, s)) continue;
            edges.push_back(vg::CrossingEdge{k * stride, b, l, l * l, 0.5f / l, s});
        }
        std::vector<uint32_t> members(interior);
        for (uint32_t j = 0; j < interior; ++j) members[j] = j;
        std::shuffle(members.begin(), members.end(), rng);
        members.resize(memberCount);
        std::vector<float> start(interior);
        for (float& v : start) v = a + u(rng);
        std::vector<float> ref = start;
        for (uint32_t j : members)
            for (const vg::CrossingEdge& E : edges) {
                const float e = rows[E.row + j];
                if (e == __builtin_inff() || c[j] == __builtin_inff()) continue;
                ref[j] = std::min(ref[j], vg::crossing(a, E.b, c[j], e, E.length));
            }
        for (int version = 0; version < (avx2 ? 2 : 1); ++version) {
            std::vector<float> best = start;
            vg::lowerByCrossings(version == 1, rows.data(), a, c, edges.data(), uint32_t(edges.size()), members.data(),
                                 memberCount, best.data());
            for (uint32_t j = 0; j < interior; ++j) {
                INFO("trial " << trial << " version " << version << " slot " << j);
                REQUIRE(sameBits(best[j], ref[j]));
            }
        }
    }
}

TEST_CASE("field kernels: the search's slot scan and changed slots match a plain loop in both versions",
          "[runtime][kernels]") {
    const int versions = vg::cpuHasAvx512() ? 2 : 1;  // portable, AVX-512
    if (versions == 1) WARN("this CPU has no AVX-512: only the portable version runs");
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(0.0f, 4.0f);
    const float inf = __builtin_inff();
    for (int trial = 0; trial < 400; ++trial) {
        const uint32_t n = rng() % 70;
        std::vector<float> dist(n), sent(n);
        for (uint32_t j = 0; j < n; ++j) {
            const uint32_t kind = rng() % 6;  // unlabelled, merged away, equal, lower, higher
            dist[j] = kind == 0 ? inf : kind == 1 ? -inf : u(rng);
            sent[j] = kind == 0 ? inf : kind == 1 ? -inf : kind == 2 ? dist[j] : kind == 3 ? dist[j] + 0.5f : inf;
        }
        // The plain loop the kernels stand for.
        std::vector<float> refSent = sent;
        std::vector<uint32_t> refSources;
        for (uint32_t j = 0; j < n; ++j)
            if (dist[j] < refSent[j]) refSent[j] = dist[j], refSources.push_back(j);
        std::vector<uint32_t> from(n + vg::kRowSlack, 0u);
        for (uint32_t j = 0; j < n; ++j) from[j] = rng() % 3 == 0 ? 5u : vg::kNone;
        std::vector<uint32_t> refChanged;
        for (uint32_t j = 0; j < n; ++j)
            if (from[j] != vg::kNone) refChanged.push_back(j);
        for (int version = 0; version < versions; ++version) {
            INFO("trial " << trial << " n " << n << " version " << version);
            std::vector<float> s = sent, best(n + vg::kRowSlack, 7.0f), labels(n + vg::kRowSlack);
            std::vector<uint32_t> marks(n + vg::kRowSlack, 3u), sources(n + vg::kRowSlack);
            const uint32_t count = vg::scanSources(version == 1, dist.data(), s.data(), best.data(), marks.data(), n,
                                                   sources.data(), labels.data());
            REQUIRE(count == refSources.size());
            for (uint32_t k = 0; k < count; ++k) {
                REQUIRE(sources[k] == refSources[k]);
                REQUIRE(sameBits(labels[k], dist[sources[k]]));
            }
            for (uint32_t j = 0; j < n; ++j) {
                REQUIRE(sameBits(s[j], refSent[j]));
                REQUIRE(sameBits(best[j], dist[j]));
                REQUIRE(marks[j] == vg::kNone);
            }
            std::vector<uint32_t> changed(n + vg::kRowSlack);
            const uint32_t changedCount = vg::changedSlots(version == 1, from.data(), n, changed.data());
            REQUIRE(changedCount == refChanged.size());
            for (uint32_t k = 0; k < changedCount; ++k) REQUIRE(changed[k] == refChanged[k]);
        }
    }
}

TEST_CASE("field kernels: one-to-all fields are the same bits with the AVX2, AVX-512 and portable kernels",
          "[runtime][kernels]") {
    if (!vg::cpuHasAvx2()) {
        WARN("this CPU has no AVX2: nothing to compare");
        return;
    }
    BakeOptions o;
    BakeReport report;
    const std::vector<uint8_t> blob = bakeMesh(bumpyTorus(60, 30), o, report, nullptr);
    tools::RuntimeGraph g;
    std::string error;
    REQUIRE(g.open(blob, error));
    vg_graph& graph = const_cast<vg_graph&>(*g.graph());
    tools::RuntimeWorkspace ws(g);
    const uint32_t V = vg_vertex_count(&graph);
    const std::vector<std::vector<uint32_t>> queries = {{0}, {V / 3}, {5, V / 2, V - 1}};
    for (const auto& sources : queries) {
        const int versions = vg::cpuHasAvx512() ? 3 : 2;  // portable, AVX2, AVX-512
        std::vector<float> dist[3];
        std::vector<uint32_t> nearest[3];
        for (int version = 0; version < versions; ++version) {
            graph.avx2 = version >= 1;
            graph.avx512 = version == 2;
            dist[version].resize(V);
            nearest[version].resize(V);
            REQUIRE(vg_distance_field_nearest(&graph, ws.get(), sources.data(), sources.size(), dist[version].data(),
                                              nearest[version].data()) == VG_OK);
        }
        for (int version = 1; version < versions; ++version) {
            INFO("version " << version);
            REQUIRE(std::memcmp(dist[0].data(), dist[version].data(), V * sizeof(float)) == 0);
            REQUIRE(nearest[0] == nearest[version]);
        }
    }
    graph.avx2 = true;
    graph.avx512 = vg::cpuHasAvx512();
}
