// What the runtime tests share about blobs: opening one (a failed open fails the test)
// and resealing a blob whose payload a test edited on purpose.
#pragma once

#include <catch2/catch.hpp>

#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "runtime_graph.h"
#include "vorogeo_container.h"

inline vorogeo::tools::RuntimeGraph openOrFail(const std::vector<uint8_t>& blob) {
    vorogeo::tools::RuntimeGraph g;
    std::string error;
    REQUIRE(g.open(blob, error));
    return g;
}

// Recomputes the container checksum after the payload was edited on purpose.
inline void resealChecksum(std::vector<uint8_t>& blob) {
    vg_store_le64(blob.data() + 40, vg_checksum64(blob.data() + VG_CONTAINER_HEADER_SIZE,
                                                  blob.size() - VG_CONTAINER_HEADER_SIZE));
}

// vg_open's status for a blob whose header passes vg_open_size (checked), opened from an
// aligned copy into memory of the size asked for; the graph is dropped.
inline vg_status openStatus(const std::vector<uint8_t>& blob) {
    vorogeo::tools::AlignedBytes copy, memory;
    copy.resize(blob.size());
    if (!blob.empty()) std::memcpy(copy.data(), blob.data(), blob.size());
    size_t need = 0;
    REQUIRE(vg_open_size(copy.data(), blob.size(), &need) == VG_OK);
    memory.resize(need);
    const vg_graph* graph = nullptr;
    return vg_open(copy.data(), blob.size(), memory.data(), need, &graph);
}

// Random pairs (from `seed`) answered by two opened blobs: the same bits.
inline void requireSamePointToPoint(const vorogeo::tools::RuntimeGraph& a, vorogeo::tools::RuntimeWorkspace& wa,
                                    const vorogeo::tools::RuntimeGraph& b, vorogeo::tools::RuntimeWorkspace& wb,
                                    int pairs, uint32_t seed) {
    const uint32_t V = vg_vertex_count(a.graph());
    std::mt19937 rng(seed);
    for (int i = 0; i < pairs; ++i) {
        const uint32_t s = rng() % V, t = rng() % V;
        float da = 0, db = 0;
        REQUIRE(vg_distance(a.graph(), wa.get(), s, t, &da) == VG_OK);
        REQUIRE(vg_distance(b.graph(), wb.get(), s, t, &db) == VG_OK);
        REQUIRE(std::memcmp(&da, &db, sizeof da) == 0);
    }
}
