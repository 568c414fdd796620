// The search's landmark bounds (runtime/src/vg_lower_bound.h): the four-lane loops give the
// bits of a plain loop for every landmark count, with unreachable landmarks, infinite
// distances and no landmarks at all.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "vg_lower_bound.h"

namespace {

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The loops as they read without vectors.
void plainLower(const uint16_t* q, const float* scale, uint32_t K, float offset, float* out) {
    for (uint32_t k = 0; k < K; ++k) {
        if (q[k] == vg::kLandmarkUnreachable) continue;
        const float d = float(q[k]) * scale[k] + offset;
        if (d < out[k]) out[k] = d;
    }
}

float plainBound(const float* scale, uint32_t K, const float* record, const float* x, float straight, float slack) {
    float best = straight;
    for (uint32_t k = 0; k < K; ++k) {
        const float d = std::fabs(record[3 + k] - x[k]) - (2.0f * scale[k] + slack);
        if (d > best && d != INFINITY) best = d;
    }
    return best;
}

}  // namespace

TEST_CASE("lower bounds: the landmark loops match a plain loop, bit for bit, for every landmark count", "[runtime]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    auto distance = [&] {  // a landmark distance, now and then none (+inf)
        return rng() % 9 == 0 ? INFINITY : 2.0f * unit(rng);
    };
    size_t lowered = 0, bounded = 0;
    for (uint32_t K = 0; K <= 19; ++K) {
        std::vector<float> scale(K), record(3 + K), x(K);
        for (int trial = 0; trial < 400; ++trial) {
            for (float& s : scale) s = 1e-4f * (0.5f + unit(rng));
            // Offered steps: some unreachable; the running minimum: some +inf, some low.
            std::vector<uint16_t> q(K);
            std::vector<float> out(K), plain(K);
            for (uint32_t k = 0; k < K; ++k) {
                q[k] = rng() % 7 == 0 ? vg::kLandmarkUnreachable : uint16_t(rng() % 65535);
                out[k] = plain[k] = rng() % 3 == 0 ? INFINITY : 4.0f * unit(rng);
            }
            const float offset = rng() % 5 == 0 ? 0.0f : unit(rng);
            vg::lowerLandmarkDistances(q.data(), scale.data(), K, offset, out.data());
            plainLower(q.data(), scale.data(), K, offset, plain.data());
            for (uint32_t k = 0; k < K; ++k) {
                CHECK(sameBits(out[k], plain[k]));
                lowered += !sameBits(out[k], INFINITY);
            }

            vg_graph g{};
            g.landmarkCount = K;
            g.landmarkScale = scale.data();
            for (float& r : record) r = distance();
            for (float& v : x) v = distance();
            const float straight = unit(rng), slack = rng() % 2 ? 0.0f : 1e-3f * unit(rng);
            const float bound = vg::withLandmarks(g, record.data(), x.data(), straight, slack);
            CHECK(sameBits(bound, plainBound(scale.data(), K, record.data(), x.data(), straight, slack)));
            bounded += bound > straight;
        }
    }
    // Both loops did real work: offers that lowered, landmark bounds above the straight line.
    CHECK(lowered > 10000);
    CHECK(bounded > 1000);
}
