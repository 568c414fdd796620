// vorogeo bench: the runtime next to the exact engine and edge Dijkstra, on the same
// random pairs and sources in one run, with ratios.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "cli.h"
#include "geodesic_exact.h"
#include "geodesic_wavefront.h"
#include "runtime_graph.h"
#include "task_threads.h"
#include "timing.h"
#include "tool_mesh.h"

namespace vorogeo::tools {

namespace {

const char* kUsage =
    "usage: vorogeo bench MESH BLOB [--pairs N] [--sources M] [--dijkstra-pairs D] [--seed S] [--json]\n"
    "                    [--runtime-only] [--turn T] [--warmup W] [--no-endpoint-table] [--field-threads K]\n"
    "  Times, in one run on the same random vertices (1 thread):\n"
    "    runtime point-to-point on N pairs (default 1000; the workspace's default mode, hub\n"
    "    labels where the blob has them and else the directed search, and the thesis's\n"
    "    bidirectional search, taking turns on blocks of T pairs, default 500) and one-to-all from M\n"
    "    sources (default 5), each mode first answering W other pairs untimed (default 500: a\n"
    "    process's first queries find nothing of the blob in the caches) and one field each way;\n"
    "    the exact engines one-to-all from the M sources (wavefront)\n"
    "    and point-to-point on the first M pairs (per pair the faster of MMP stopping at\n"
    "    the target and a whole wavefront field); Dijkstra on the edge graph one-to-all\n"
    "    from the M sources and point-to-point with early exit on the first D pairs\n"
    "    (default 200). Also the error of the runtime's and of Dijkstra's fields against\n"
    "    the exact ones. Prints each median (p99 for point-to-point), the ratios, and how long\n"
    "    vg_open took on the blob (open_ms: with --inner-rows-at-open it computes the inner rows),\n"
    "    and the p50 and p99 of fixed work as long as the point-to-point p50 (the host's own\n"
    "    timing noise, which lifts every p99: fixed_work_p50_us, fixed_work_p99_us).\n"
    "  --runtime-only  time the runtime's queries alone (meshes too large for the exact engine),\n"
    "    and also one-to-all on K threads (vg_distance_field_parallel, default 2; the two take\n"
    "    turns per source), and how fast the host is: a dependent multiply-add and a dependent\n"
    "    load over 64 MB (host_multiply_add_ns, host_load_ns), to compare figures across hosts\n"
    "  With hub labels the runtime's workspace reads an endpoint table (vg_endpoint_table_build;\n"
    "  its bytes and build time are printed); --no-endpoint-table times the labels without one.\n";

struct Errors {
    double sum = 0, max = 0;
    size_t count = 0;
    void add(double value, double exact) {
        if (!(exact > 0) || !std::isfinite(exact)) return;
        const double rel = std::fabs(value - exact) / exact;
        sum += rel, max = std::max(max, rel), ++count;
    }
    double mean() const { return count ? sum / double(count) : 0.0; }
};

}  // namespace

int runBench(int argc, char** argv) {
    cli::Args args(argc, argv, {"--pairs", "--sources", "--dijkstra-pairs", "--seed", "--turn", "--warmup", "--field-threads"}, {"--json", "--help", "--repair", "--runtime-only", "--no-endpoint-table"});
    if (args.flag("--help")) {
        std::printf("%s", kUsage);
        return 0;
    }
    if (args.positional().size() != 2) throw cli::UsageError(std::string("expected MESH and BLOB\n") + kUsage);
    const long long pairCount = args.integer("--pairs", 1000), sourceCount = args.integer("--sources", 5);
    const long long dijkstraPairs = args.integer("--dijkstra-pairs", 200), turnPairs = args.integer("--turn", 500);
    const long long fieldThreads = args.integer("--field-threads", 2), warmupPairs = args.integer("--warmup", 500);
    if (pairCount < 1 || sourceCount < 1 || dijkstraPairs < 1 || turnPairs < 1)
        throw cli::UsageError("--pairs, --sources, --dijkstra-pairs and --turn must be >= 1");
    if (warmupPairs < 0) throw cli::UsageError("--warmup must be >= 0");
    if (fieldThreads < 1 || fieldThreads > 64) throw cli::UsageError("--field-threads must be 1 to 64");
    const uint64_t seed = uint64_t(args.integer("--seed", 1));

    Mesh mesh;
    if (!loadMeshForCommand("bench", args.positional()[0], args.flag("--repair"), mesh)) return 1;
    RuntimeGraph graph;
    if (!loadBlobForMesh("bench", args.positional()[1], mesh, false, graph)) return 1;
    const uint32_t V = mesh.vertexCount();
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<uint32_t> pick(0, V - 1);
    std::vector<std::pair<uint32_t, uint32_t>> pairs(static_cast<size_t>(pairCount));
    for (auto& p : pairs) p = {pick(rng), pick(rng)};
    std::vector<uint32_t> sources(static_cast<size_t>(sourceCount));
    for (uint32_t& s : sources) s = pick(rng);
    // Drawn after the timed pairs and sources, so that a seed times the same ones whatever W.
    std::vector<std::pair<uint32_t, uint32_t>> warmup(static_cast<size_t>(warmupPairs));
    for (auto& p : warmup) p = {pick(rng), pick(rng)};
    const uint32_t warmupSource = pick(rng);

    RuntimeWorkspace ws(graph), thesisWs(graph);
    thesisWs.setSearch(VG_SEARCH_BIDIRECTIONAL);
    // Built for the fast mode only: the thesis's search never reads it.
    const EndpointTable table(args.flag("--no-endpoint-table") ? nullptr : graph.graph());
    ws.useTable(table);
    char tableNote[96] = "";
    if (table.get() != nullptr)
        std::snprintf(tableNote, sizeof tableNote, " + endpoint table (%.1f MB, built in %.0f ms)", table.bytes() / 1e6,
                      table.buildSeconds() * 1e3);
    // Untimed first: the labels, then the thesis's search, so that the first timed turn (the
    // labels') follows the other mode's queries, as every later turn does.
    volatile float sink = ws.distance(pairs[0].first, pairs[0].second);
    for (const auto& p : warmup) sink = ws.distance(p.first, p.second);
    sink = thesisWs.distance(pairs[0].first, pairs[0].second);
    for (const auto& p : warmup) sink = thesisWs.distance(p.first, p.second);
    std::vector<double> sssdUs, thesisSssdUs, msadMs, exactSsadMs, exactSssdMs, dijkstraSssdUs, dijkstraSsadMs;
    // The two modes take turns on blocks of pairs (which goes first alternates), so that
    // the machine's drift affects both alike while each mode answers a batch of queries
    // with its own data in the caches. Shorter turns time more queries right after the
    // other mode's search has filled the caches with its own data; igea's labels, p50
    // (session 36, BENCHMARKS.md): 24-25.5 us in turns of 500 pairs, 27-28 us in turns of
    // 100, 31-34 us in turns of 10, 22 us alone.
    const size_t turn = size_t(turnPairs);
    for (size_t begin = 0; begin < pairs.size(); begin += turn) {
        const size_t end = std::min(pairs.size(), begin + turn);
        for (int k = 0; k < 2; ++k) {
            const bool directed = (k == 0) == ((begin / turn) % 2 == 0);
            for (size_t i = begin; i < end; ++i) {
                Stopwatch w;
                sink = (directed ? ws : thesisWs).distance(pairs[i].first, pairs[i].second);
                (directed ? sssdUs : thesisSssdUs).push_back(w.seconds() * 1e6);
            }
        }
    }
    const double sssdP50 = percentile(sssdUs, 50), sssdP99 = percentile(sssdUs, 99);
    // The workspace's default point-to-point mode: hub labels where the blob has them.
    const char* mode = vg_has_hub_labels(graph.graph()) ? "hub labels" : "directed";
    const double thesisP50 = percentile(thesisSssdUs, 50), thesisP99 = percentile(thesisSssdUs, 99);
    // How much of the p99 is the host's: the same length of fixed work, timed alike (2,000
    // times, fewer for slow queries: about half a second, at least 200).
    const int hostRuns = int(std::min(2000.0, std::max(200.0, 5e5 / std::max(sssdP50, 1.0))));
    const FixedWorkTiming host = fixedWorkTiming(sssdP50, hostRuns);

    std::vector<float> field(V);  // one output buffer for every timed field
    if (args.flag("--runtime-only")) {
        // One-to-all on one thread and on K (the query's workspace and K - 1 more, tasks on
        // persistent threads as a job system's), taking turns per source.
        TaskThreads helpers(unsigned(fieldThreads - 1));
        std::vector<RuntimeWorkspace> fieldWorkspaces;
        std::vector<vg_workspace*> parallelWs = {ws.get()};
        for (long long i = 1; i < fieldThreads; ++i) fieldWorkspaces.emplace_back(graph);
        for (const RuntimeWorkspace& w : fieldWorkspaces) parallelWs.push_back(w.get());
        std::vector<double> parallelMs;
        // One untimed field each way first (the field's blocks, like the labels, start cold).
        ws.field({warmupSource}, field);
        if (vg_distance_field_parallel(graph.graph(), parallelWs.data(), uint32_t(parallelWs.size()), &warmupSource, 1,
                                       field.data(), nullptr, TaskThreads::parallelFor, &helpers) != VG_OK) {
            std::fprintf(stderr, "vorogeo bench: vg_distance_field_parallel failed on the warm-up source\n");
            return 1;
        }
        for (size_t i = 0; i < sources.size(); ++i) {
            const std::vector<uint32_t> source = {sources[i]};
            for (int k = 0; k < 2; ++k) {
                if ((k == 0) == (i % 2 == 0)) {
                    Stopwatch a;
                    ws.field(source, field);
                    msadMs.push_back(a.seconds() * 1e3);
                } else {
                    Stopwatch a;
                    const vg_status st = vg_distance_field_parallel(graph.graph(), parallelWs.data(), uint32_t(parallelWs.size()),
                                                                    source.data(), 1, field.data(), nullptr,
                                                                    TaskThreads::parallelFor, &helpers);
                    parallelMs.push_back(a.seconds() * 1e3);
                    if (st != VG_OK) {
                        std::fprintf(stderr, "vorogeo bench: vg_distance_field_parallel: %s\n", vg_status_string(st));
                        return 1;
                    }
                }
                sink = field[sources[i]];
            }
        }
        (void)sink;
        const double msad = percentile(msadMs, 50), msadParallel = percentile(parallelMs, 50);
        const HostSpeed speed = hostSpeed();
        if (args.flag("--json"))
            std::printf("{\"mesh\":\"%s\",\"mode\":\"%s\",\"vertices\":%u,\"blob_bytes\":%zu,\"pairs\":%zu,\"turn_pairs\":%zu,\"warmup_pairs\":%zu,\"sources\":%zu,"
                        "\"sssd_p50_us\":%.2f,\"sssd_p99_us\":%.2f,\"bidirectional_sssd_p50_us\":%.2f,"
                        "\"bidirectional_sssd_p99_us\":%.2f,\"msad_p50_ms\":%.3f,\"open_ms\":%.1f,"
                        "\"fixed_work_p50_us\":%.2f,\"fixed_work_p99_us\":%.2f,"
                        "\"endpoint_table_bytes\":%zu,\"endpoint_table_build_ms\":%.1f,"
                        "\"field_threads\":%lld,\"msad_threads_p50_ms\":%.3f,"
                        "\"host_multiply_add_ns\":%.3f,\"host_load_ns\":%.1f}\n",
                        args.positional()[0].c_str(), mode, V, graph.blobBytes(), pairs.size(), turn, warmup.size(),
                        sources.size(), sssdP50, sssdP99, thesisP50, thesisP99, msad, graph.openSeconds() * 1e3, host.p50Us, host.p99Us,
                        table.get() ? table.bytes() : size_t(0), table.buildSeconds() * 1e3, fieldThreads, msadParallel,
                        speed.multiplyAddNs, speed.loadNs);
        else
            std::printf("%s: %u vertices, blob %zu bytes (opened in %.1f ms); %zu pairs (after %zu untimed), %zu sources, runtime only, "
                        "1 thread unless said\n"
                        "point-to-point (%s%s) p50 %.1f us, p99 %.1f us (thesis's bidirectional search: p50 %.1f us, "
                        "p99 %.1f us; %.2fx / %.2fx); one-to-all p50 %.2f ms (on %lld threads: %.2f ms)\n"
                        "host noise: fixed work as long as the p50 takes p50 %.1f us, p99 %.1f us\n"
                        "host speed: a dependent multiply-add %.3f ns, a dependent load over 64 MB %.1f ns\n",
                        args.positional()[0].c_str(), V, graph.blobBytes(), graph.openSeconds() * 1e3, pairs.size(),
                        warmup.size(), sources.size(), mode, tableNote, sssdP50, sssdP99, thesisP50, thesisP99, thesisP50 / sssdP50, thesisP99 / sssdP99,
                        msad, fieldThreads, msadParallel, host.p50Us, host.p99Us, speed.multiplyAddNs, speed.loadNs);
        return 0;
    }

    ExactGeodesic geo(mesh);
    ExactWorkspace exactWs;       // MMP: stops early at a single target
    WavefrontWorkspace waveWs;    // the faster engine for whole fields
    Errors runtimeErr, dijkstraErr;
    std::vector<double> exact, dijkstra;
    ws.field({warmupSource}, field);  // untimed, as in --runtime-only
    for (uint32_t s : sources) {
        const std::vector<uint32_t> source = {s};
        Stopwatch a;
        ws.field(source, field);
        msadMs.push_back(a.seconds() * 1e3);
        Stopwatch b;
        waveWs.run(geo, {s}, exact);
        exactSsadMs.push_back(b.seconds() * 1e3);
        Stopwatch c;
        edgeDijkstra(mesh, s, dijkstra);
        dijkstraSsadMs.push_back(c.seconds() * 1e3);
        for (uint32_t v = 0; v < V; ++v) {
            runtimeErr.add(field[v], exact[v]);
            dijkstraErr.add(dijkstra[v], exact[v]);
        }
    }
    for (size_t i = 0; i < std::min<size_t>(size_t(sourceCount), pairs.size()); ++i) {
        ExactQuery q;
        q.sources.push_back(GeodesicSource::atVertex(pairs[i].first));
        q.targets.push_back(pairs[i].second);
        // The exact engines' best for one pair: MMP stopping at the target, or a whole
        // wavefront field (faster for far pairs).
        Stopwatch w;
        exactWs.run(geo, q, exact);
        const double mmpMs = w.seconds() * 1e3;
        Stopwatch x;
        waveWs.run(geo, {pairs[i].first}, exact);
        exactSssdMs.push_back(std::min(mmpMs, x.seconds() * 1e3));
    }
    for (size_t i = 0; i < std::min<size_t>(size_t(dijkstraPairs), pairs.size()); ++i) {
        Stopwatch w;
        edgeDijkstra(mesh, pairs[i].first, dijkstra, pairs[i].second);
        dijkstraSssdUs.push_back(w.seconds() * 1e6);
    }
    (void)sink;

    const double msad = percentile(msadMs, 50), exactSsad = percentile(exactSsadMs, 50);
    const double exactSssd = percentile(exactSssdMs, 50), dijkstraSssd = percentile(dijkstraSssdUs, 50);
    const double dijkstraSsad = percentile(dijkstraSsadMs, 50);
    if (args.flag("--json")) {
        std::printf("{\"mesh\":\"%s\",\"mode\":\"%s\",\"vertices\":%u,\"blob_bytes\":%zu,\"pairs\":%zu,\"turn_pairs\":%zu,\"warmup_pairs\":%zu,\"sources\":%zu,"
                    "\"sssd_p50_us\":%.2f,\"sssd_p99_us\":%.2f,\"bidirectional_sssd_p50_us\":%.2f,"
                    "\"bidirectional_sssd_p99_us\":%.2f,\"msad_p50_ms\":%.3f,"
                    "\"exact_sssd_p50_ms\":%.3f,\"exact_ssad_p50_ms\":%.3f,"
                    "\"dijkstra_sssd_p50_us\":%.2f,\"dijkstra_ssad_p50_ms\":%.3f,"
                    "\"speedup_sssd_vs_exact\":%.1f,\"speedup_ssad_vs_exact\":%.1f,"
                    "\"speedup_sssd_vs_dijkstra\":%.2f,\"speedup_ssad_vs_dijkstra\":%.2f,"
                    "\"field_mean_rel_error\":%.6e,\"field_max_rel_error\":%.6e,"
                    "\"dijkstra_mean_rel_error\":%.6e,\"dijkstra_max_rel_error\":%.6e,\"open_ms\":%.1f,"
                    "\"fixed_work_p50_us\":%.2f,\"fixed_work_p99_us\":%.2f,"
                    "\"endpoint_table_bytes\":%zu,\"endpoint_table_build_ms\":%.1f}\n",
                    args.positional()[0].c_str(), mode, V, graph.blobBytes(), pairs.size(), turn, warmup.size(), sources.size(),
                    sssdP50, sssdP99, thesisP50, thesisP99, msad, exactSssd, exactSsad, dijkstraSssd, dijkstraSsad, exactSssd * 1e3 / sssdP50,
                    exactSsad / msad, dijkstraSssd / sssdP50, dijkstraSsad / msad, runtimeErr.mean(), runtimeErr.max,
                    dijkstraErr.mean(), dijkstraErr.max, graph.openSeconds() * 1e3, host.p50Us, host.p99Us,
                    table.get() ? table.bytes() : size_t(0), table.buildSeconds() * 1e3);
        return 0;
    }
    std::printf("%s: %u vertices, blob %zu bytes (opened in %.1f ms); %zu pairs (after %zu untimed), %zu sources, 1 thread\n",
                args.positional()[0].c_str(), V, graph.blobBytes(), graph.openSeconds() * 1e3, pairs.size(), warmup.size(),
                sources.size());
    std::printf("runtime point-to-point: %s%s; bidirectional: the thesis's search on the same blob\n", mode, tableNote);
    std::printf("%-34s %12s %12s %12s %14s\n", "", "runtime", "exact", "Dijkstra", "bidirectional");
    std::printf("%-34s %9.1f us %9.1f ms %9.1f us %11.1f us\n", "point-to-point p50", sssdP50, exactSssd, dijkstraSssd,
                thesisP50);
    std::printf("%-34s %9.1f us %12s %12s %11.1f us\n", "point-to-point p99", sssdP99, "", "", thesisP99);
    std::printf("%-34s %9.1f us (p99 %.1f us: the host's own noise)\n", "fixed work as long as the p50", host.p50Us,
                host.p99Us);
    std::printf("%-34s %9.2f ms %9.1f ms %9.2f ms\n", "one-to-all p50", msad, exactSsad, dijkstraSsad);
    std::printf("%-34s %10.4f %% %12s %10.4f %%\n", "one-to-all mean relative error", runtimeErr.mean() * 100, "0",
                dijkstraErr.mean() * 100);
    std::printf("%-34s %10.4f %% %12s %10.4f %%\n", "one-to-all max relative error", runtimeErr.max * 100, "0",
                dijkstraErr.max * 100);
    std::printf("runtime speed-up: point-to-point %.0fx vs exact, %.1fx vs Dijkstra, %.2fx (p99 %.2fx) vs the\n"
                "bidirectional search; one-to-all %.0fx vs exact, %.2fx vs Dijkstra\n",
                exactSssd * 1e3 / sssdP50, dijkstraSssd / sssdP50, thesisP50 / sssdP50, thesisP99 / sssdP99,
                exactSsad / msad, dijkstraSsad / msad);
    return 0;
}

}  // namespace vorogeo::tools
