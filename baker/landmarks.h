// Landmarks for the runtime's A* (the "ALT" lower bounds of route planning): a few graph
// nodes spread over the surface, and every node's distance to each. For any vertices v, t
// and landmark L, |d(L, v) - d(L, t)| <= d(v, t), a lower bound much tighter than the
// straight line wherever the surface folds away from it.
#pragma once

#include <cstdint>
#include <vector>

namespace vorogeo {

struct Landmarks {
    std::vector<uint32_t> vertices;    // mesh vertex of each landmark
    std::vector<float> scales;         // per landmark: distance per 16-bit step
    std::vector<uint16_t> nodeValues;  // node-major: K values per node; 65535 = unreachable
};

// Chooses `count` landmarks by farthest-point sampling in the graph's own metric (the
// runtime's one-to-all query on `flatbuffer`, a graph buffer without landmarks), each
// next landmark farthest from those taken (a component without one comes first), and
// stores the node distances rounded down. Deterministic; single-threaded.
Landmarks computeLandmarks(const std::vector<uint8_t>& flatbuffer, uint32_t count);

}  // namespace vorogeo
