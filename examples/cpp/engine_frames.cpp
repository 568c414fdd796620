// Engine-style use of the runtime: one immutable graph shared by every thread, one
// workspace per worker, and a frame loop in which agents ask distances to their goals.
//   engine_frames BLOB.vgeo [WORKERS] [FRAMES]
#include <chrono>
#include <cstddef>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <thread>
#include <vector>

#include "vorogeo.h"

namespace {

// Memory the runtime is given: the engine's own allocations (here, 16-byte aligned heap).
struct Buffer {
    std::unique_ptr<std::max_align_t[]> words;
    explicit Buffer(size_t bytes) : words(new std::max_align_t[bytes / sizeof(std::max_align_t) + 1]) {}
    void* data() const { return words.get(); }
};

struct Agent {
    uint32_t at, goal;
};

// Where agent `a` stands in frame `f`, and where it wants to go (deterministic).
Agent agentInFrame(uint32_t a, uint32_t f, uint32_t vertices) {
    return Agent{(a * 7919u + f * 104729u) % vertices, (a * 15485863u + 17u) % vertices};
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: engine_frames BLOB.vgeo [WORKERS] [FRAMES]\n");
        return 2;
    }
    const unsigned workers = argc > 2 ? unsigned(std::atoi(argv[2])) : 4;
    const unsigned frames = argc > 3 ? unsigned(std::atoi(argv[3])) : 30;
    const unsigned agentsPerWorker = 16;
    std::ifstream in(argv[1], std::ios::binary);
    const std::vector<char> file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (file.empty() || workers == 0) {
        std::fprintf(stderr, "engine_frames: cannot read %s (or no workers)\n", argv[1]);
        return 1;
    }
    Buffer blob(file.size());
    std::copy(file.begin(), file.end(), static_cast<char*>(blob.data()));

    size_t need = 0;
    vg_status st = vg_open_size(blob.data(), file.size(), &need);
    Buffer graphMemory(need);
    const vg_graph* graph = nullptr;
    if (st == VG_OK) st = vg_open(blob.data(), file.size(), graphMemory.data(), need, &graph);
    if (st != VG_OK) {
        std::fprintf(stderr, "engine_frames: %s\n", vg_status_string(st));
        return 1;
    }
    const uint32_t vertices = vg_vertex_count(graph);

    // One workspace per worker, made once at start-up: queries never allocate.
    const size_t wsBytes = vg_workspace_size(graph);
    std::vector<Buffer> wsMemory;
    std::vector<vg_workspace*> ws(workers + 1);
    for (unsigned w = 0; w <= workers; ++w) {
        wsMemory.emplace_back(wsBytes);
        if (vg_workspace_init(graph, wsMemory.back().data(), wsBytes, &ws[w]) != VG_OK) return 1;
    }
    float d = 0;
    vg_distance(graph, ws[workers], 0, vertices / 2, &d);
    std::printf("distance 0 -> %u = %.5f\n", vertices / 2, d);

    // Frame loop: every worker moves its agents and asks each one's distance to its goal.
    std::vector<std::vector<float>> answers(workers);
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::thread> threads;
    for (unsigned w = 0; w < workers; ++w)
        threads.emplace_back([&, w] {
            for (uint32_t f = 0; f < frames; ++f)
                for (uint32_t k = 0; k < agentsPerWorker; ++k) {
                    const Agent a = agentInFrame(w * agentsPerWorker + k, f, vertices);
                    float dist = 0;
                    vg_distance(graph, ws[w], a.at, a.goal, &dist);
                    answers[w].push_back(dist);
                }
        });
    for (std::thread& t : threads) t.join();
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

    // The same questions asked again on one thread give the same bits.
    size_t mismatches = 0, count = 0;
    for (unsigned w = 0; w < workers; ++w)
        for (uint32_t f = 0, i = 0; f < frames; ++f)
            for (uint32_t k = 0; k < agentsPerWorker; ++k, ++i) {
                const Agent a = agentInFrame(w * agentsPerWorker + k, f, vertices);
                float dist = 0;
                vg_distance(graph, ws[workers], a.at, a.goal, &dist);
                mismatches += std::memcmp(&dist, &answers[w][i], sizeof dist) != 0;
                ++count;
            }
    std::printf("%u workers x %u frames x %u agents: %zu queries in %.1f ms (%.1f us each, wall)\n", workers, frames,
                agentsPerWorker, count, ms, 1e3 * ms / double(count));
    std::printf("answers identical to one thread: %s\n", mismatches == 0 ? "yes" : "NO");
    return mismatches == 0 ? 0 : 1;
}
