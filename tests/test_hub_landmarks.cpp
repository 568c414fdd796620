// The hubs' landmark distances in the labels' metric (baker/hub_landmarks.h, vorogeo.fbs
// hub_landmarks): what makes the label query's landmark bounds sound without a shrink. A
// hub's values undercut no first-layer matrix entry (the edges of the labels' metric), stay
// below and near the landmark table they start from, and the blocks' ranges and a query
// endpoint's values are taken from them.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "bake.h"
#include "blob_test_helpers.h"
#include "generators.h"
#include "vg_hub_labels.h"
#include "vg_lower_bound.h"
#include "vorogeo.h"

using namespace vorogeo;
using tools::RuntimeGraph;
using tools::RuntimeWorkspace;

namespace {

// A labelled torus (4,800 vertices); delta > 0 prunes the graph, which may merge
// first-layer nodes away.
std::vector<uint8_t> labelledTorus(double delta) {
    BakeOptions o;
    o.n1 = 10;
    o.delta = delta;
    o.hubLabels = true;
    BakeReport report;
    return bakeMesh(bumpyTorus(120, 40), o, report, nullptr);
}

float stepsDistance(const vg_graph& g, uint32_t k, uint16_t steps) {
    return steps == vg::kLandmarkUnreachable ? INFINITY : float(steps) * g.landmarkScale[k];
}

}  // namespace

TEST_CASE("hub landmarks: no first-layer entry is undercut, and the values lie just below the table", "[hub]") {
    for (const double delta : {0.0, 0.002}) {  // also a pruned graph, whose overlay has nodes without hubs
        const std::vector<uint8_t> blob = labelledTorus(delta);
        RuntimeGraph g = openOrFail(blob);
        const vg_graph& graph = *g.graph();
        REQUIRE(graph.hubTreeCount > 1);
        REQUIRE(graph.landmarkCount > 1);
        REQUIRE(graph.hubLandmarks != nullptr);
        const uint32_t K = graph.landmarkCount;
        const uint16_t* hubSteps = graph.hubLandmarks;
        size_t edges = 0, asymmetric = 0, undercut = 0;
        for (uint32_t p = 0; p < graph.firstCount; ++p) {
            const vg::Patch& patch = graph.first[p];
            for (uint32_t i = 0; i < patch.slotCount; ++i)
                for (uint32_t j = 0; j < patch.slotCount; ++j) {
                    if (i == j) continue;
                    const uint32_t q = vg::quantum(graph.firstDistances, patch.matrixBegin + uint64_t(i) * patch.slotCount + j);
                    // The query's argument takes the entries both ways alike (the baker packs
                    // one value per pair).
                    asymmetric += q != vg::quantum(graph.firstDistances, patch.matrixBegin + uint64_t(j) * patch.slotCount + i);
                    const uint32_t a = graph.nodeHub[graph.slots[patch.slotBegin + i]];
                    const uint32_t b = graph.nodeHub[graph.slots[patch.slotBegin + j]];
                    if (q == vg::kNoPathQuantum || a == vg::kNone || b == vg::kNone) continue;
                    const float w = float(q) * patch.scale;
                    for (uint32_t k = 0; k < K; ++k) {
                        const float la = stepsDistance(graph, k, hubSteps[uint64_t(a) * K + k]);
                        const float lb = stepsDistance(graph, k, hubSteps[uint64_t(b) * K + k]);
                        // Rounded down to steps: b's value may sit a step above a's path's.
                        undercut += lb > la + w + graph.landmarkScale[k] * 1.001f;
                        ++edges;
                    }
                }
        }
        CHECK(edges > 10000);
        CHECK(asymmetric == 0);
        CHECK(undercut == 0);

        // Below the table (they start from it and only drop), and near it: both are landmark
        // distances, over the second layer and over the first-layer matrices.
        size_t values = 0, above = 0, far = 0, lowered = 0;
        for (uint32_t n = 0; n < graph.nodeCount; ++n) {
            const uint32_t h = graph.nodeHub[n];
            if (h == vg::kNone) continue;
            for (uint32_t k = 0; k < K; ++k) {
                const uint16_t table = graph.nodeLandmarks[uint64_t(n) * K + k], mine = hubSteps[uint64_t(h) * K + k];
                REQUIRE(table != vg::kLandmarkUnreachable);
                REQUIRE(mine != vg::kLandmarkUnreachable);
                ++values;
                above += mine > table;
                lowered += mine < table;
                far += float(mine) < 0.97f * float(table) - 2.0f;
            }
        }
        CHECK(values > 1000);
        CHECK(above == 0);
        CHECK(far == 0);
        CHECK(lowered > values / 10);  // the table does undercut entries: this is no copy of it
    }
}

TEST_CASE("hub landmarks: an endpoint takes a hub's own values, else the best through its patch's nodes", "[hub]") {
    const std::vector<uint8_t> blob = labelledTorus(0.0);
    RuntimeGraph g = openOrFail(blob);
    const vg_graph& graph = *g.graph();
    RuntimeWorkspace ws(g.graph());
    const uint32_t K = graph.landmarkCount;
    size_t hubs = 0, throughSlots = 0, compared = 0, inside = 0, far = 0;
    for (uint32_t x = 0; x < graph.vertexCount; x += 5) {
        float mine[vg::kMaxLandmarks], fromRows[vg::kMaxLandmarks];
        const float slack = vg::hubEndpointLandmarks(graph, *ws.get(), x, mine);
        if (slack < 0.0f) continue;
        CHECK(slack > 0.0f);
        const uint32_t node = vg::vertexNode(graph, x);
        const uint32_t hub = node == vg::kNone ? vg::kNone : graph.nodeHub[node];
        if (hub != vg::kNone) {
            ++hubs;
            for (uint32_t k = 0; k < K; ++k)
                CHECK(mine[k] == stepsDistance(graph, k, graph.hubLandmarks[uint64_t(hub) * K + k]));
            continue;
        }
        // Through the patch's nodes: a landmark distance like the searches' (from the row
        // nodes and the table) up to the two metrics' difference, for a landmark outside
        // the patch. One inside it may be nearer than any of the patch's nodes: a bound
        // still (a path to a hub leaves by them), but no distance to it.
        ++throughSlots;
        vg::landmarkDistances(graph, x, fromRows);
        const uint32_t first = graph.second[graph.vertexPatch[x]].parent;
        for (uint32_t k = 0; k < K; ++k) {
            REQUIRE(std::isfinite(fromRows[k]));
            REQUIRE(std::isfinite(mine[k]));
            bool landmarkInside = false;
            vg::forEachPatchOf(graph, graph.landmarkVertex[k], [&](uint32_t patch, uint32_t) {
                landmarkInside |= graph.second[patch].parent == first;
            });
            if (landmarkInside) {
                ++inside;
                continue;
            }
            ++compared;
            far += std::fabs(mine[k] - fromRows[k]) > 0.03f * fromRows[k] + slack + 2.0f * graph.landmarkScale[k];
        }
    }
    CHECK(hubs > 50);
    CHECK(throughSlots > 300);
    CHECK(compared > 3000);
    CHECK(inside > 0);
    CHECK(far == 0);
}

TEST_CASE("hub landmarks: a block's ranges are its hubs' least and largest values, in the workspace too", "[hub]") {
    const std::vector<uint8_t> blob = labelledTorus(0.0);
    RuntimeGraph g = openOrFail(blob);
    const vg_graph& graph = *g.graph();
    REQUIRE(graph.hubBlockBounds != nullptr);
    RuntimeWorkspace ws(g.graph());
    const uint32_t K = graph.landmarkCount, stride = vg::blockRangeStride(K);
    uint32_t block = 0;
    size_t ranges = 0, wrong = 0, wrongSteps = 0;
    for (uint32_t t = 0; t < graph.hubTreeCount; ++t) {
        const vg::HubTreeNode& node = graph.hubTree[t];
        for (uint32_t first = node.hubBegin; first < node.hubBegin + node.hubCount; first += vg::kHubBlock, ++block) {
            const uint32_t end = std::min(first + vg::kHubBlock, node.hubBegin + node.hubCount);
            const float* record = graph.hubBlockBounds + uint64_t(block) * (4 + 2 * K);
            const uint16_t* steps = ws.get()->hubBlockRanges + uint64_t(block) * stride;
            for (uint32_t k = 0; k < K; ++k) {
                uint16_t lo = 65535, hi = 0;
                for (uint32_t h = first; h < end; ++h) {
                    lo = std::min(lo, graph.hubLandmarks[uint64_t(h) * K + k]);
                    hi = std::max(hi, graph.hubLandmarks[uint64_t(h) * K + k]);
                }
                wrong += record[4 + 2 * k] != stepsDistance(graph, k, lo) || record[5 + 2 * k] != stepsDistance(graph, k, hi);
                wrongSteps += steps[k] != lo || steps[K + k] != hi;  // the workspace's copy, exactly
                ++ranges;
            }
        }
    }
    CHECK(block == ws.get()->hubBlockBegin[graph.hubTreeCount]);
    CHECK(ranges > 100);
    CHECK(wrong == 0);
    CHECK(wrongSteps == 0);
}
