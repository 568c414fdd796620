#include "landmarks.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "blob_writer.h"
#include "vorogeo.h"
#include "vorogeo_generated.h"

namespace vorogeo {

namespace {

constexpr uint16_t kUnreachable = 65535;
constexpr double kLargestStep = 65534.0;

// Caller memory for the runtime, 16-byte aligned.
struct Block {
    std::unique_ptr<uint64_t[]> words;
    explicit Block(size_t bytes) : words(new uint64_t[bytes / 8 + 2]) {}
    void* data() const { return words.get(); }
};

void check(vg_status st, const char* what) {
    if (st != VG_OK) throw std::runtime_error(std::string("landmarks: ") + what + ": " + vg_status_string(st));
}

}  // namespace

Landmarks computeLandmarks(const std::vector<uint8_t>& flatbuffer, uint32_t count) {
    Landmarks out;
    const std::vector<uint8_t> blob = packContainer(flatbuffer, false, false, 0);
    Block blobCopy(blob.size());  // aligned, so the runtime reads it in place
    std::copy(blob.begin(), blob.end(), static_cast<uint8_t*>(blobCopy.data()));
    size_t need = 0;
    check(vg_open_size(blobCopy.data(), blob.size(), &need), "open size");
    Block memory(need);
    const vg_graph* graph = nullptr;
    check(vg_open(blobCopy.data(), blob.size(), memory.data(), need, &graph), "open");
    const size_t wsBytes = vg_workspace_size(graph);
    Block wsMemory(wsBytes);
    vg_workspace* ws = nullptr;
    check(vg_workspace_init(graph, wsMemory.data(), wsBytes, &ws), "workspace");

    const fb::Graph* g = fb::GetGraph(flatbuffer.data());
    const uint32_t N = g->node_vertex()->size();
    if (N == 0 || count == 0) return out;
    count = std::min(count, N);
    std::vector<float> nearest(N, INFINITY);  // distance to the closest landmark so far
    std::vector<std::vector<float>> values;
    std::vector<float> field(vg_vertex_count(graph));
    // First landmark: the node farthest from node 0, then always the farthest from all.
    uint32_t start = g->node_vertex()->Get(0);
    check(vg_distance_field(graph, ws, &start, 1, field.data()), "field");
    for (uint32_t n = 0; n < N; ++n) nearest[n] = field[g->node_vertex()->Get(n)];
    for (uint32_t k = 0; k < count; ++k) {
        uint32_t pick = 0;
        for (uint32_t n = 1; n < N; ++n)
            if (nearest[n] > nearest[pick]) pick = n;  // +inf (no landmark in its component yet) first
        if (k > 0 && nearest[pick] == 0.0f) break;    // every node is a landmark already
        const uint32_t vertex = g->node_vertex()->Get(pick);
        check(vg_distance_field(graph, ws, &vertex, 1, field.data()), "field");
        std::vector<float> v(N);
        for (uint32_t n = 0; n < N; ++n) {
            v[n] = field[g->node_vertex()->Get(n)];
            nearest[n] = k == 0 ? v[n] : std::min(nearest[n], v[n]);
        }
        // Nodes of other components stay +inf and keep their claim on the next landmark.
        if (k == 0)
            for (uint32_t n = 0; n < N; ++n)
                if (std::isinf(v[n])) nearest[n] = INFINITY;
        out.vertices.push_back(vertex);
        values.push_back(std::move(v));
    }
    const size_t K = out.vertices.size();
    out.nodeValues.assign(size_t(N) * K, kUnreachable);
    for (size_t k = 0; k < K; ++k) {
        float largest = 0;
        for (float d : values[k])
            if (std::isfinite(d)) largest = std::max(largest, d);
        const float scale = largest > 0 ? float(double(largest) / kLargestStep) : 1.0f;
        out.scales.push_back(scale);
        for (uint32_t n = 0; n < N; ++n) {
            const float d = values[k][n];
            if (!std::isfinite(d)) continue;
            out.nodeValues[size_t(n) * K + k] = uint16_t(std::min(kLargestStep, std::floor(double(d) / scale)));
        }
    }
    return out;
}

}  // namespace vorogeo
