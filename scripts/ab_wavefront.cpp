// Two builds of the wavefront engine in one process (scripts/ab-wavefront.sh): on the same
// patches of a mesh, whole runs from the same sources and runs to the same targets, the two
// taking turns (which goes first alternates), with the medians, the median of the per-turn
// time ratios A/B (above 1: B is faster) and how many results differ in any bit.
//
// usage: ab_wavefront A.so B.so MESH [--sizes V,V,...] [--domains N] [--sources N] [--seed S]
#include <dlfcn.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace {

struct Engine {
    void* (*open)(const char*, char*, size_t);
    uint32_t (*meshVertices)(void*);
    uint32_t (*domain)(void*, uint32_t, uint32_t);
    void (*run)(void*, uint32_t, double*);
    void (*runToTargets)(void*, uint32_t, const uint32_t*, const double*, uint32_t, double*);
    void* shim;
};

template <typename F>
void bind(void* lib, const char* name, F& f) {
    f = reinterpret_cast<F>(dlsym(lib, name));
    if (f == nullptr) {
        std::fprintf(stderr, "ab_wavefront: %s lacks %s\n", name, dlerror());
        std::exit(1);
    }
}

Engine load(const char* path, const char* mesh) {
    // DEEPBIND: each library's C++ symbols resolve inside it, never in the other one.
    void* lib = dlopen(path, RTLD_NOW | RTLD_LOCAL | RTLD_DEEPBIND);
    if (lib == nullptr) {
        std::fprintf(stderr, "ab_wavefront: %s\n", dlerror());
        std::exit(1);
    }
    Engine e{};
    bind(lib, "abw_open", e.open);
    bind(lib, "abw_mesh_vertices", e.meshVertices);
    bind(lib, "abw_domain", e.domain);
    bind(lib, "abw_run", e.run);
    bind(lib, "abw_run_to_targets", e.runToTargets);
    char error[512] = "";
    e.shim = e.open(mesh, error, sizeof error);
    if (e.shim == nullptr) {
        std::fprintf(stderr, "ab_wavefront: %s\n", error);
        std::exit(1);
    }
    return e;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

using Clock = std::chrono::steady_clock;

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: ab_wavefront A.so B.so MESH [--sizes V,V,...] [--domains N] [--sources N] [--seed S]\n");
        return 2;
    }
    std::vector<uint32_t> sizes{200, 3000};
    uint32_t domains = 12, sourceCount = 20, seed = 1;
    for (int i = 4; i + 1 < argc; i += 2) {
        const std::string flag = argv[i];
        if (flag == "--sizes") {
            sizes.clear();
            for (char* p = argv[i + 1]; *p;) {
                sizes.push_back(uint32_t(std::strtoul(p, &p, 10)));
                if (*p == ',') ++p;
            }
        } else if (flag == "--domains") domains = uint32_t(std::atoi(argv[i + 1]));
        else if (flag == "--sources") sourceCount = uint32_t(std::atoi(argv[i + 1]));
        else if (flag == "--seed") seed = uint32_t(std::atoi(argv[i + 1]));
        else {
            std::fprintf(stderr, "ab_wavefront: unknown option %s\n", flag.c_str());
            return 2;
        }
    }
    Engine engines[2] = {load(argv[1], argv[3]), load(argv[2], argv[3])};
    const uint32_t meshVertices = engines[0].meshVertices(engines[0].shim);
    std::mt19937 rng(seed);
    constexpr uint32_t kTargets = 50;

    std::printf("| patch size | runs | whole runs: A, B (ms per turn) | ratio A/B | to %u targets: A, B | ratio A/B | results with other bits |\n", kTargets);
    std::printf("|---:|---:|---|---:|---|---:|---:|\n");
    for (uint32_t want : sizes) {
        std::vector<double> whole[2], targeted[2], wholeRatio, targetRatio;
        uint64_t differing = 0, runs = 0;
        for (uint32_t d = 0; d < domains; ++d) {
            const uint32_t center = rng() % meshVertices;
            const uint32_t n = engines[0].domain(engines[0].shim, center, want);
            if (engines[1].domain(engines[1].shim, center, want) != n) {
                std::fprintf(stderr, "ab_wavefront: the two builds cut different patches\n");
                return 1;
            }
            std::vector<uint32_t> sources(sourceCount), targets(kTargets);
            for (uint32_t& s : sources) s = rng() % n;
            for (uint32_t& t : targets) t = rng() % n;
            std::vector<double> out[2], bounds(size_t(sourceCount) * kTargets);
            out[0].resize(n);
            out[1].resize(n);
            // Each source's bounds from a whole run, with the slack the exact first layer gives them.
            for (uint32_t i = 0; i < sourceCount; ++i) {
                engines[0].run(engines[0].shim, sources[i], out[0].data());
                for (uint32_t k = 0; k < kTargets; ++k) bounds[i * kTargets + k] = out[0][targets[k]] * (1 + 1e-6);
            }
            double took[2][2];
            for (int turn = 0; turn < 2; ++turn) {
                const int e = (turn + int(d)) % 2;
                Engine& E = engines[e];
                auto t0 = Clock::now();
                for (uint32_t s : sources) E.run(E.shim, s, out[e].data());
                auto t1 = Clock::now();
                for (uint32_t i = 0; i < sourceCount; ++i)
                    E.runToTargets(E.shim, sources[i], targets.data(), bounds.data() + i * kTargets, kTargets, out[e].data());
                auto t2 = Clock::now();
                took[e][0] = std::chrono::duration<double, std::milli>(t1 - t0).count();
                took[e][1] = std::chrono::duration<double, std::milli>(t2 - t1).count();
            }
            // Bits: the last source's whole run and run to targets on both.
            const uint32_t last = sources.back();
            for (int e = 0; e < 2; ++e) engines[e].run(engines[e].shim, last, out[e].data());
            differing += std::memcmp(out[0].data(), out[1].data(), n * sizeof(double)) != 0;
            for (int e = 0; e < 2; ++e)
                engines[e].runToTargets(engines[e].shim, last, targets.data(), bounds.data() + (sourceCount - 1) * kTargets,
                                        kTargets, out[e].data());
            differing += std::memcmp(out[0].data(), out[1].data(), kTargets * sizeof(double)) != 0;
            for (int e = 0; e < 2; ++e) {
                whole[e].push_back(took[e][0]);
                targeted[e].push_back(took[e][1]);
            }
            wholeRatio.push_back(took[0][0] / took[1][0]);
            targetRatio.push_back(took[0][1] / took[1][1]);
            runs += 2 * sourceCount;
        }
        std::printf("| %u | %llu | %.3f, %.3f | %.3f | %.3f, %.3f | %.3f | %llu of %u |\n", want,
                    (unsigned long long)runs, median(whole[0]), median(whole[1]), median(wholeRatio),
                    median(targeted[0]), median(targeted[1]), median(targetRatio), (unsigned long long)differing,
                    2 * domains);
    }
    return 0;
}
