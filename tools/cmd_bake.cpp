// vorogeo bake: mesh -> .vgeo blob (partition, patch geodesics, overlay, pruning, blob).
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include <tbb/global_control.h>
#include <tbb/info.h>
#include <unistd.h>

#include "bake.h"
#include "bake_limits.h"
#include "blob_writer.h"
#include "vorogeo_baker.h"
#include "cli.h"
#include "timing.h"
#include "tool_mesh.h"

namespace vorogeo::tools {

namespace {

const char* kUsage =
    "usage: vorogeo bake MESH -o OUT.vgeo [--n1 N] [--n2 N] [--delta F] [--seed S] [--threads N]\n"
    "                    [--no-compress | --compact] [--level L] [--report FILE.json] [--margin-rings R]\n"
    "                    [--exact-first-layer]\n"
    "                    [--landmarks K] [--hub-labels [--inner-rows-at-open]]\n"
    "                    [--max-memory SIZE] [--repair] [--quiet]\n"
    "  Precomputes the two-layer patch graph of MESH and writes it as a blob for the runtime.\n"
    "  --n1       first-layer patches (default: one per ~3,000 vertices)\n"
    "  --n2       second-layer patches per first-layer patch (default: one per ~100 vertices)\n"
    "  --delta    pruning threshold as a fraction of the bounding-box diagonal (default 0:\n"
    "             no pruning; larger is faster and less accurate)\n"
    "  --seed     seed of the sampling (default 1); same mesh, options and seed give the same bytes\n"
    "  --threads  worker threads (default: all cores)\n"
    "  --no-compress  store the flatbuffer uncompressed, for zero-copy mapping\n"
    "  --compact  prediction-code the distances before compressing: about half the bytes\n"
    "             (igea 81 instead of 260 per vertex), ~2x the open time (igea ~80 ms)\n"
    "  --level    zstd level, 1-22 (default: with --compact 19 up to 32 MiB of payload, 17 up\n"
    "             to 1 GiB, 11 above; else 9); higher is smaller and slower to bake\n"
    "  --report   write a JSON report (times, sizes, graph, peak memory)\n"
    "  --margin-rings  rings of faces around each patch for its geodesics (default 1)\n"
    "  --landmarks     landmarks for the query's A* lower bounds, 0-64 (default 12)\n"
    "  --hub-labels    store hub labels: point-to-point queries in microseconds instead of\n"
    "             a graph search (a larger blob, a longer bake)\n"
    "  --inner-rows-at-open  with --compact --hub-labels: leave the labels' inner rows out,\n"
    "             vg_open computes them (igea 41 fewer bytes per vertex, ~0.4 s more to open)\n"
    "  --exact-first-layer  first-layer distances by exact runs, as the thesis (much slower)\n"
    "  --max-memory  refuse the bake up front if it would need more, stop it if it does\n"
    "             (e.g. 8G, 512M; default: the machine's physical memory)\n"
    "  Ctrl-C (SIGINT) or SIGTERM stops the bake at its next step; nothing is written.\n";

// Set by SIGINT/SIGTERM/SIGHUP; the bake polls it at every progress step. A second signal
// while stopping kills the process the default way.
std::atomic<bool> gInterrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void onInterrupt(int signal) {
    if (gInterrupted.exchange(true)) {
        std::signal(signal, SIG_DFL);
        std::raise(signal);
        return;
    }
    const char message[] = "\nvorogeo bake: interrupted, stopping (again to kill)\n";
    const ssize_t ignored = ::write(2, message, sizeof message - 1);
    (void)ignored;
}

// Installs onInterrupt for the lifetime of the bake and restores the previous handlers.
class InterruptGuard {
public:
    InterruptGuard() {
        struct sigaction action {};
        action.sa_handler = onInterrupt;
        sigemptyset(&action.sa_mask);
        for (int i = 0; i < 3; ++i) sigaction(kSignals[i], &action, &previous_[i]);
    }
    ~InterruptGuard() {
        for (int i = 0; i < 3; ++i) sigaction(kSignals[i], &previous_[i], nullptr);
    }

private:
    static constexpr int kSignals[3] = {SIGINT, SIGTERM, SIGHUP};
    struct sigaction previous_[3];
};

// "8G", "512M", "64k", "1000000": bytes (binary multiples).
uint64_t parseSize(const std::string& text) {
    size_t used = 0;
    double value = 0;
    try {
        value = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    std::string unit = text.substr(used);
    if (!unit.empty() && (unit.back() == 'B' || unit.back() == 'b')) unit.pop_back();
    if (unit.size() == 2 && (unit[1] == 'i')) unit.pop_back();
    double scale = 1;
    if (unit == "k" || unit == "K") scale = 1024.0;
    else if (unit == "m" || unit == "M") scale = 1024.0 * 1024;
    else if (unit == "g" || unit == "G") scale = 1024.0 * 1024 * 1024;
    else if (unit == "t" || unit == "T") scale = 1024.0 * 1024 * 1024 * 1024;
    else if (!unit.empty()) used = 0;
    if (used == 0 || !(value > 0) || !std::isfinite(value * scale) || value * scale > 1e18)
        throw cli::UsageError("--max-memory must be a size such as 8G, 512M or 1000000 (bytes), got '" + text + "'");
    return uint64_t(value * scale);
}

uint64_t physicalMemoryBytes() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGESIZE);
    return pages > 0 && pageSize > 0 ? uint64_t(pages) * uint64_t(pageSize) : 0;
}

// Progress on a terminal: one bar per stage, redrawn in place; otherwise one line per stage.
class ProgressPrinter {
public:
    explicit ProgressPrinter(bool quiet) : quiet_(quiet), tty_(::isatty(2) != 0) {}
    void operator()(const char* stage, double fraction) {
        if (quiet_) return;
        const bool newStage = stage_ != stage;
        if (newStage && tty_ && !stage_.empty()) std::fprintf(stderr, "\n");
        if (newStage) {
            stage_ = stage;
            if (!tty_) std::fprintf(stderr, "bake: %s ...\n", stage);
        }
        if (tty_) {
            const int width = 30, filled = int(std::lround(fraction * width));
            std::fprintf(stderr, "\r  %-24s [%s%s] %3d%%", stage, std::string(size_t(filled), '#').c_str(),
                         std::string(size_t(width - filled), ' ').c_str(), int(std::lround(fraction * 100)));
            std::fflush(stderr);
        }
    }
    void finish() {
        if (!quiet_ && tty_ && !stage_.empty()) std::fprintf(stderr, "\n");
    }

private:
    bool quiet_, tty_;
    std::string stage_;
};

uint32_t positiveCount(const cli::Args& args, const char* name) {
    if (!args.has(name)) return 0;
    const long long v = args.integer(name, 0);
    if (v < 1 || v > 0x7fffffffLL) throw cli::UsageError(std::string(name) + " must be at least 1");
    return uint32_t(v);
}

void writeReport(const std::string& path, const BakeReport& r, int threads, double wall, double rss) {
    std::ofstream out(path);
    if (!out) throw std::runtime_error("cannot write report " + path);
    char buf[256];
    out << "{\n";
    auto kv = [&](const char* key, const std::string& value, bool last = false) {
        out << "  \"" << key << "\": " << value << (last ? "\n" : ",\n");
    };
    auto num = [&](double v, const char* fmt = "%.6g") {
        std::snprintf(buf, sizeof buf, fmt, v);
        return std::string(buf);
    };
    kv("vertices", std::to_string(r.vertices));
    kv("faces", std::to_string(r.faces));
    kv("threads", std::to_string(threads));
    kv("wall_s", num(wall, "%.3f"));
    kv("peak_rss_mb", num(rss, "%.1f"));
    kv("blob_bytes", std::to_string(r.blobBytes));
    kv("flatbuffer_bytes", std::to_string(r.flatbufferBytes));
    kv("bytes_per_vertex", num(double(r.blobBytes) / std::max(1u, r.vertices), "%.2f"));
    kv("compressed", r.compressed ? "true" : "false");
    kv("compact", r.compact ? "true" : "false");
    kv("inner_rows_at_open", r.innerRowsAtOpen ? "true" : "false");
    std::string stages = "{";
    for (size_t i = 0; i < r.stages.size(); ++i)
        stages += (i ? ", \"" : "\"") + r.stages[i].name + "\": " + num(r.stages[i].seconds, "%.3f");
    kv("stages_s", stages + "}");
    kv("first_patches", std::to_string(r.firstPatches));
    kv("second_patches", std::to_string(r.secondPatches));
    kv("first_bv", std::to_string(r.firstBorder));
    kv("first_iv", std::to_string(r.firstInterior));
    kv("second_bv", std::to_string(r.secondBorder));
    kv("second_iv", std::to_string(r.secondInterior));
    kv("delta", num(r.delta));
    kv("delta_absolute", num(r.deltaAbsolute));
    kv("delta_second_absolute", num(r.deltaSecond));
    auto prune = [&](const PruneStats& p) {
        return "{\"nodes\": " + std::to_string(p.nodes) + ", \"nodes_pruned\": " + std::to_string(p.prunedNodes) +
               ", \"edges\": " + std::to_string(p.edges) + ", \"edges_pruned\": " + std::to_string(p.prunedEdges) + "}";
    };
    kv("first_graph", prune(r.firstPrune));
    kv("second_graph", prune(r.secondPrune));
    kv("exact_runs", std::to_string(r.sourceRuns));
    kv("quantisation_max_abs_error", num(r.quantisationMaxAbs, "%.3e"));
    kv("quantisation_max_abs_error_per_diagonal", num(r.quantisationMaxAbs / r.bboxDiagonal, "%.3e"), true);
    out << "}\n";
    if (!out) throw std::runtime_error("cannot write report " + path);
}

void printSummary(const BakeReport& r, const std::string& outPath, int threads, double wall, double rss) {
    std::printf("baked %s: %u vertices, %u faces, %d threads, %.2f s, peak memory %.0f MB\n", outPath.c_str(),
                r.vertices, r.faces, threads, wall, rss);
    std::printf("  stages:");
    for (const BakeStage& s : r.stages) std::printf(" %s %.2f s;", s.name.c_str(), s.seconds);
    std::printf("\n  first layer:  %zu patches, Bv %llu, Iv %llu; graph %llu nodes (%llu pruned), %llu edges (%llu pruned)\n",
                r.firstPatches, (unsigned long long)r.firstBorder, (unsigned long long)r.firstInterior,
                (unsigned long long)r.firstPrune.nodes, (unsigned long long)r.firstPrune.prunedNodes,
                (unsigned long long)r.firstPrune.edges, (unsigned long long)r.firstPrune.prunedEdges);
    std::printf("  second layer: %zu patches, Bv %llu, Iv %llu; graph %llu nodes (%llu pruned), %llu edges (%llu pruned)\n",
                r.secondPatches, (unsigned long long)r.secondBorder, (unsigned long long)r.secondInterior,
                (unsigned long long)r.secondPrune.nodes, (unsigned long long)r.secondPrune.prunedNodes,
                (unsigned long long)r.secondPrune.edges, (unsigned long long)r.secondPrune.prunedEdges);
    std::printf("  pruning delta %.3g x diagonal (%.3g; second layer %.3g); 12-bit distances: max error %.2e (%.2e x diagonal)\n",
                r.delta, r.deltaAbsolute, r.deltaSecond, r.quantisationMaxAbs, r.quantisationMaxAbs / r.bboxDiagonal);
    if (r.hubs > 0)
        std::printf("  hub labels: %llu hubs, %llu tree nodes, %llu label entries (%.0f per hub), %llu inner entries\n",
                    (unsigned long long)r.hubs, (unsigned long long)r.hubTreeNodes,
                    (unsigned long long)r.hubLabelEntries, double(r.hubLabelEntries) / double(r.hubs),
                    (unsigned long long)r.hubInnerEntries);
    if (r.innerRowsAtOpen) std::printf("  inner rows left to vg_open (--inner-rows-at-open)\n");
    std::printf("  blob %zu bytes (%.1f bytes per vertex, %s; flatbuffer %zu bytes)\n", r.blobBytes,
                double(r.blobBytes) / std::max(1u, r.vertices),
                r.compressed ? (r.compact ? "zstd, coded distances" : "zstd") : "uncompressed",
                r.flatbufferBytes);
}

}  // namespace

int runBake(int argc, char** argv) {
    const cli::Args args(argc, argv, {"-o", "--out", "--n1", "--n2", "--delta", "--seed", "--threads", "--report", "--margin-rings",
                          "--landmarks", "--max-memory", "--level"},
                         {"--no-compress", "--compact", "--exact-first-layer", "--hub-labels", "--inner-rows-at-open", "--repair",
                          "--quiet", "--help"});
    if (args.flag("--help")) {
        std::printf("%s", kUsage);
        return 0;
    }
    if (args.positional().size() != 1) throw cli::UsageError(std::string("expected one mesh file\n") + kUsage);
    const std::string outPath = args.has("-o") ? args.str("-o") : args.str("--out");
    if (outPath.empty()) throw cli::UsageError("missing -o OUT.vgeo");

    BakeOptions o;
    o.n1 = positiveCount(args, "--n1");
    o.n2 = positiveCount(args, "--n2");
    if (args.has("--delta")) {
        o.delta = args.number("--delta", 0);
        if (!(o.delta >= 0 && o.delta < 1)) throw cli::UsageError("--delta must be in [0, 1) (a fraction of the bounding-box diagonal)");
    }
    const long long seed = args.integer("--seed", 1);
    if (seed < 0) throw cli::UsageError("--seed must be >= 0");
    o.seed = uint64_t(seed);
    const long long landmarks = args.integer("--landmarks", 12);
    if (landmarks < 0 || landmarks > 64) throw cli::UsageError("--landmarks must be in [0, 64]");
    o.landmarks = uint32_t(landmarks);
    const long long rings = args.integer("--margin-rings", 1);
    if (rings < 0 || rings > 8) throw cli::UsageError("--margin-rings must be in [0, 8]");
    o.marginRings = uint32_t(rings);
    o.exactFirstLayer = args.flag("--exact-first-layer");
    o.compress = !args.flag("--no-compress");
    o.compact = args.flag("--compact");
    if (args.has("--level")) {
        const long long level = args.integer("--level", 0);
        if (level < 1 || level > 22) throw cli::UsageError("--level must be in [1, 22]");
        if (!o.compress) throw cli::UsageError("--level sets the zstd level: it cannot go with --no-compress");
        o.compressionLevel = int(level);
    }
    o.hubLabels = args.flag("--hub-labels");
    o.innerRowsAtOpen = args.flag("--inner-rows-at-open");
    if (o.innerRowsAtOpen && !(o.compact && o.hubLabels))
        throw cli::UsageError("--inner-rows-at-open needs --compact and --hub-labels");
    o.maxMemoryBytes = args.has("--max-memory") ? parseSize(args.str("--max-memory")) : physicalMemoryBytes();
    const long long threadsArg = args.integer("--threads", 0);
    if (threadsArg < 0 || threadsArg > 1024) throw cli::UsageError("--threads must be in [1, 1024]");
    const int threads = threadsArg > 0 ? int(threadsArg) : tbb::info::default_concurrency();
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));

    Stopwatch wall;
    checkWritable(outPath);  // fail before the bake, not after it
    Mesh mesh;
    if (!loadMeshForCommand("bake", args.positional()[0], args.flag("--repair"), mesh)) return 1;
    ProgressPrinter progress(args.flag("--quiet"));
    InterruptGuard interrupts;
    BakeResult result;
    try {
        result = bake(mesh, o, [&](const char* stage, double f) { progress(stage, f); }, &gInterrupted);
    } catch (const std::invalid_argument& e) {
        progress.finish();
        throw cli::UsageError(e.what());
    } catch (const BakeCancelled&) {
        progress.finish();
        std::fprintf(stderr, "vorogeo bake: interrupted; nothing written\n");
        return 130;
    } catch (const BakeLimitError& e) {
        progress.finish();
        std::fprintf(stderr, "vorogeo bake: %s; nothing written\n", e.what());
        return 1;
    }
    progress.finish();
    if (gInterrupted) {
        std::fprintf(stderr, "vorogeo bake: interrupted; nothing written\n");
        return 130;
    }
    const BakeReport& report = result.report;
    writeFileAtomically(outPath, result.blob);
    const double seconds = wall.seconds(), rss = peakRssMb();
    if (args.has("--report")) writeReport(args.str("--report"), report, threads, seconds, rss);
    if (!args.flag("--quiet")) printSummary(report, outPath, threads, seconds, rss);
    return 0;
}

}  // namespace vorogeo::tools
