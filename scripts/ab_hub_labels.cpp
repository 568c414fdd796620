// Two builds of the baker's hub-label stage in one process (scripts/ab-hub-labels.sh): on
// the graph buffer of one uncompressed blob, computeHubLabels of A and of B taking turns
// (which goes first alternates), with each turn's seconds, the medians, the median of the
// per-pair time ratios A/B (above 1: B is faster) and whether the two made the same tables.
//
// usage: ab_hub_labels A.so B.so BLOB [--turns N] [--threads N]
#include <dlfcn.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "vorogeo_container.h"

namespace {

using Labels = double (*)(const uint8_t*, size_t, int, uint64_t*, char*, size_t);

Labels load(const char* path) {
    // DEEPBIND: each library's C++ symbols resolve inside it, never in the other one.
    void* lib = dlopen(path, RTLD_NOW | RTLD_LOCAL | RTLD_DEEPBIND);
    if (lib == nullptr) {
        std::fprintf(stderr, "ab_hub_labels: %s\n", dlerror());
        std::exit(1);
    }
    auto f = reinterpret_cast<Labels>(dlsym(lib, "abh_labels"));
    if (f == nullptr) {
        std::fprintf(stderr, "ab_hub_labels: %s lacks abh_labels\n", path);
        std::exit(1);
    }
    return f;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

// The graph buffer of an uncompressed, uncoded blob; exits naming the problem otherwise.
std::vector<uint8_t> graphBuffer(const char* path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        std::fprintf(stderr, "ab_hub_labels: cannot read %s\n", path);
        std::exit(1);
    }
    const std::vector<uint8_t> blob((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (blob.size() < VG_CONTAINER_HEADER_SIZE || std::memcmp(blob.data(), VG_CONTAINER_MAGIC, 8) != 0) {
        std::fprintf(stderr, "ab_hub_labels: %s is not a vorogeo blob\n", path);
        std::exit(1);
    }
    const uint32_t flags = vg_load_le32(blob.data() + 12);
    const uint64_t flatbufferBytes = vg_load_le64(blob.data() + 24);
    if (flags != 0 || flatbufferBytes > blob.size() - VG_CONTAINER_HEADER_SIZE) {
        std::fprintf(stderr, "ab_hub_labels: %s is compressed or coded (bake it with --no-compress)\n", path);
        std::exit(1);
    }
    return std::vector<uint8_t>(blob.begin() + VG_CONTAINER_HEADER_SIZE,
                                blob.begin() + VG_CONTAINER_HEADER_SIZE + int64_t(flatbufferBytes));
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: ab_hub_labels A.so B.so BLOB [--turns N] [--threads N]\n");
        return 2;
    }
    int turns = 3, threads = 2;
    for (int i = 4; i < argc; i += 2) {
        const std::string flag = argv[i];
        if (i + 1 >= argc) {
            std::fprintf(stderr, "ab_hub_labels: %s needs a value\n", flag.c_str());
            return 2;
        }
        if (flag == "--turns") turns = std::atoi(argv[i + 1]);
        else if (flag == "--threads") threads = std::atoi(argv[i + 1]);
        else {
            std::fprintf(stderr, "ab_hub_labels: unknown option %s\n", flag.c_str());
            return 2;
        }
    }
    if (turns < 1 || threads < 1) {
        std::fprintf(stderr, "ab_hub_labels: --turns and --threads take a positive number\n");
        return 2;
    }
    const Labels stage[2] = {load(argv[1]), load(argv[2])};
    const std::vector<uint8_t> buffer = graphBuffer(argv[3]);
    std::vector<double> seconds[2], ratio;
    uint64_t hash[2] = {0, 0};
    bool differ = false;
    std::printf("| turn | first | A (s) | B (s) | A/B |\n|---:|---|---:|---:|---:|\n");
    for (int turn = 0; turn < turns; ++turn) {
        double took[2];
        for (int k = 0; k < 2; ++k) {
            const int e = (turn + k) % 2;
            char error[512] = "";
            uint64_t h = 0;
            took[e] = stage[e](buffer.data(), buffer.size(), threads, &h, error, sizeof error);
            if (took[e] < 0) {
                std::fprintf(stderr, "ab_hub_labels: %s: %s\n", e == 0 ? "A" : "B", error);
                return 1;
            }
            if (turn > 0 && h != hash[e]) {
                std::fprintf(stderr, "ab_hub_labels: %s made other tables on turn %d\n", e == 0 ? "A" : "B", turn + 1);
                return 1;
            }
            hash[e] = h;
        }
        differ = differ || hash[0] != hash[1];
        seconds[0].push_back(took[0]);
        seconds[1].push_back(took[1]);
        ratio.push_back(took[0] / took[1]);
        std::printf("| %d | %s | %.3f | %.3f | %.3f |\n", turn + 1, turn % 2 ? "B" : "A", took[0], took[1],
                    ratio.back());
        std::fflush(stdout);
    }
    std::printf("medians over %d turns, %d threads: A %.3f s, B %.3f s, A/B %.3f; tables %s\n", turns, threads,
                median(seconds[0]), median(seconds[1]), median(ratio), differ ? "DIFFER" : "the same");
    return 0;
}
