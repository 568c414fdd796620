// In-process A/B of two builds of the runtime library, for changes whose effect is smaller
// than the machine's drift between two runs (scripts/ab-runtime.sh builds the libraries).
// Both are dlopen'ed into this process, each with its own graph, workspaces and endpoint
// table; they answer the same random queries taking turns, the one going first
// alternating, and each query's two times give a ratio. A ratio above 1 means B is faster.
// usage: ab_runtime LIB_A LIB_B BLOB [--fields N] [--pairs N] [--seed S]
#include <dlfcn.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "task_threads.h"  // tools/: the job-system threads vorogeo bench times fields on
#include "vorogeo.h"

namespace {

[[noreturn]] void fail(const std::string& message) {
    std::fprintf(stderr, "ab_runtime: %s\n", message.c_str());
    std::exit(1);
}

void* allocate(void*, size_t size) { return std::malloc(size); }
void release(void*, void* memory) { std::free(memory); }

// One build of the library, opened on the blob.
struct Library {
    decltype(&vg_open_file) openFile;
    decltype(&vg_close_file) closeFile;
    decltype(&vg_vertex_count) vertexCount;
    decltype(&vg_workspace_size) workspaceSize;
    decltype(&vg_workspace_init) workspaceInit;
    decltype(&vg_endpoint_table_size) tableSize;
    decltype(&vg_endpoint_table_build) tableBuild;
    decltype(&vg_workspace_use_endpoint_table) useTable;
    decltype(&vg_distance) distance;
    decltype(&vg_distance_field) field;
    decltype(&vg_distance_field_parallel) fieldParallel;
    decltype(&vg_status_string) statusString;
    const vg_graph* graph = nullptr;
    std::vector<unsigned char> memory[2], table;
    vg_workspace* workspaces[2] = {nullptr, nullptr};

    template <class F>
    void bind(void* handle, const char* path, const char* name, F& f) {
        f = reinterpret_cast<F>(dlsym(handle, name));
        if (f == nullptr) fail(std::string(path) + " has no " + name);
    }

    Library(const char* path, const char* blob) {
        // RTLD_LOCAL: the two builds' vg_ symbols stay apart.
        void* h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
        if (h == nullptr) fail(std::string("cannot load ") + path + ": " + dlerror());
        bind(h, path, "vg_open_file", openFile);
        bind(h, path, "vg_close_file", closeFile);
        bind(h, path, "vg_vertex_count", vertexCount);
        bind(h, path, "vg_workspace_size", workspaceSize);
        bind(h, path, "vg_workspace_init", workspaceInit);
        bind(h, path, "vg_endpoint_table_size", tableSize);
        bind(h, path, "vg_endpoint_table_build", tableBuild);
        bind(h, path, "vg_workspace_use_endpoint_table", useTable);
        bind(h, path, "vg_distance", distance);
        bind(h, path, "vg_distance_field", field);
        bind(h, path, "vg_distance_field_parallel", fieldParallel);
        bind(h, path, "vg_status_string", statusString);
        const vg_allocator allocator{allocate, release, nullptr};
        const vg_status st = openFile(blob, &allocator, &graph);
        if (st != VG_OK) fail(std::string(path) + " cannot open " + blob + ": " + statusString(st));
        for (int i = 0; i < 2; ++i) {
            memory[i].resize(workspaceSize(graph));
            if (workspaceInit(graph, memory[i].data(), memory[i].size(), &workspaces[i]) != VG_OK)
                fail(std::string(path) + ": vg_workspace_init failed");
        }
        // As vorogeo bench: the label query with the endpoint table where the blob has labels.
        const size_t bytes = tableSize(graph);
        if (bytes > 0) {
            table.resize(bytes);
            const vg_endpoint_table* t = nullptr;
            if (tableBuild(graph, table.data(), table.size(), &t) != VG_OK || useTable(workspaces[0], t) != VG_OK)
                fail(std::string(path) + ": the endpoint table failed");
        }
    }
};

double percentile(std::vector<double> v, double p) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[std::min(v.size() - 1, size_t(p / 100.0 * double(v.size())))];
}

using Clock = std::chrono::steady_clock;

// One-to-all from each source on both libraries in turns; threads 1 or 2.
void compareFields(Library* lib[2], const std::vector<uint32_t>& sources, uint32_t vertices, int threads) {
    std::vector<float> out[2] = {std::vector<float>(vertices), std::vector<float>(vertices)};
    std::vector<double> ms[2], ratio;
    size_t differing = 0;
    vorogeo::tools::TaskThreads helpers(unsigned(threads - 1));  // as vorogeo bench's
    for (size_t i = 0; i < sources.size(); ++i) {
        double t[2];
        for (int k = 0; k < 2; ++k) {
            const int which = (k == 0) == (i % 2 == 0) ? 0 : 1;
            Library& L = *lib[which];
            const auto start = Clock::now();
            const vg_status st = threads == 1 ? L.field(L.graph, L.workspaces[0], &sources[i], 1, out[which].data())
                                              : L.fieldParallel(L.graph, L.workspaces, 2, &sources[i], 1, out[which].data(),
                                                                nullptr, vorogeo::tools::TaskThreads::parallelFor, &helpers);
            t[which] = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
            if (st != VG_OK) fail(std::string("one-to-all failed: ") + L.statusString(st));
        }
        for (int k = 0; k < 2; ++k) ms[k].push_back(t[k]);
        ratio.push_back(t[0] / t[1]);
        if (std::memcmp(out[0].data(), out[1].data(), vertices * sizeof(float)) != 0) ++differing;
    }
    std::printf("one-to-all, %d thread%s, %zu sources: A %.3f ms, B %.3f ms (medians); median A/B %.3f; "
                "fields with other bits %zu\n",
                threads, threads == 1 ? "" : "s", sources.size(), percentile(ms[0], 50), percentile(ms[1], 50), percentile(ratio, 50), differing);
}

// Point-to-point on both libraries in turns of 500 pairs.
void comparePairs(Library* lib[2], const std::vector<std::pair<uint32_t, uint32_t>>& pairs) {
    std::vector<double> us[2];
    size_t differing = 0, unanswered = 0;
    std::vector<vg_status> status[2] = {std::vector<vg_status>(pairs.size()), std::vector<vg_status>(pairs.size())};
    const size_t turn = 500;
    std::vector<float> d[2] = {std::vector<float>(pairs.size()), std::vector<float>(pairs.size())};
    for (size_t begin = 0; begin < pairs.size(); begin += turn) {
        const size_t end = std::min(pairs.size(), begin + turn);
        for (int k = 0; k < 2; ++k) {
            const int which = (k == 0) == ((begin / turn) % 2 == 0) ? 0 : 1;
            Library& L = *lib[which];
            for (size_t i = begin; i < end; ++i) {
                const auto start = Clock::now();
                status[which][i] = L.distance(L.graph, L.workspaces[0], pairs[i].first, pairs[i].second, &d[which][i]);
                us[which].push_back(std::chrono::duration<double, std::micro>(Clock::now() - start).count());
            }
        }
    }
    // (A vertex on no face has no distance: both builds must say so alike.)
    for (size_t i = 0; i < pairs.size(); ++i) {
        if (status[0][i] != status[1][i])
            fail("pair " + std::to_string(pairs[i].first) + "-" + std::to_string(pairs[i].second) + ": A says " +
                 lib[0]->statusString(status[0][i]) + ", B " + lib[1]->statusString(status[1][i]));
        if (status[0][i] != VG_OK) ++unanswered;
        else if (std::memcmp(&d[0][i], &d[1][i], sizeof(float)) != 0) ++differing;
    }
    const double a50 = percentile(us[0], 50), b50 = percentile(us[1], 50);
    std::printf("point-to-point, %zu pairs: A p50 %.2f / p99 %.2f us, B p50 %.2f / p99 %.2f us; A/B at p50 %.3f; "
                "distances with other bits %zu (unanswered by both: %zu)\n",
                pairs.size(), a50, percentile(us[0], 99), b50, percentile(us[1], 99), a50 / b50, differing, unanswered);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) fail("usage: ab_runtime LIB_A LIB_B BLOB [--fields N] [--pairs N] [--seed S]");
    long fields = 200, pairCount = 20000, seed = 1;
    for (int i = 4; i < argc; ++i) {
        const std::string a = argv[i];
        if (i + 1 >= argc) fail(a + " needs a value");
        char* end = nullptr;
        const long v = std::strtol(argv[++i], &end, 10);
        if (end == argv[i] || *end != '\0' || v < 0) fail(a + ": not a count: " + argv[i]);
        if (a == "--fields") fields = v;
        else if (a == "--pairs") pairCount = v;
        else if (a == "--seed") seed = v;
        else fail("unknown option " + a);
    }
    Library a(argv[1], argv[3]), b(argv[2], argv[3]);
    Library* lib[2] = {&a, &b};
    const uint32_t vertices = a.vertexCount(a.graph);
    if (vertices == 0 || b.vertexCount(b.graph) != vertices) fail("the two libraries read different graphs");
    std::mt19937 rng(static_cast<uint32_t>(seed));
    std::vector<uint32_t> sources(static_cast<size_t>(fields));
    for (uint32_t& s : sources) s = rng() % vertices;
    std::vector<std::pair<uint32_t, uint32_t>> pairs(static_cast<size_t>(pairCount));
    for (auto& p : pairs) p = {rng() % vertices, rng() % vertices};
    std::printf("A: %s\nB: %s\n", argv[1], argv[2]);
    if (!pairs.empty()) comparePairs(lib, pairs);
    if (!sources.empty()) {
        compareFields(lib, sources, vertices, 1);
        compareFields(lib, sources, vertices, 2);
    }
    a.closeFile(a.graph);
    b.closeFile(b.graph);
    return 0;
}
