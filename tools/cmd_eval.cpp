// vorogeo eval: accuracy and point-to-point speed of the runtime against exact distances
// (a golden pairs file, or the exact engine on random pairs).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "cli.h"
#include "geodesic_exact.h"
#include "golden.h"
#include "runtime_graph.h"
#include "runtime_stats.h"
#include "timing.h"
#include "tool_mesh.h"

namespace vorogeo::tools {

namespace {

const char* kUsage =
    "usage: vorogeo eval MESH BLOB [--golden PAIRS.csv | --pairs N [--seed S]] [--triples N]\n"
    "                   [--search labels|directed|bidirectional] [--no-endpoint-table] [--json]\n"
    "  Accuracy of the runtime's point-to-point distance against exact geodesics: from a\n"
    "  golden 'source,target,distance' file, or from the exact engine on N random pairs\n"
    "  (default 1000, drawn from N/100 sources). Reports mean, median, p99 and max relative\n"
    "  error, the worst pairs, symmetry and triangle-inequality violations (on --triples\n"
    "  random triples, default 2000), the query time (p50, p90, p99 in microseconds) and the\n"
    "  one-to-all time (median over up to 20 sources of the pairs).\n"
    "  --search  the point-to-point mode (vg_workspace_set_search): labels (default: hub\n"
    "            labels where the blob has them, else directed), directed A*, or the\n"
    "            thesis's bidirectional A*\n"
    "  --no-endpoint-table  labels without the runtime's endpoint table (by default the\n"
    "            labels mode reads one, as vorogeo bench does: it answers pairs inside one\n"
    "            first-layer patch from their patch's node distances)\n";

// Random pairs, a hundred targets per source, with exact distances from the exact engine.
std::vector<DistancePair> exactRandomPairs(const Mesh& mesh, size_t count, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<uint32_t> pick(0, mesh.vertexCount() - 1);
    ExactGeodesic geo(mesh);
    ExactWorkspace ws;
    std::vector<DistancePair> pairs;
    std::vector<double> dist;
    while (pairs.size() < count) {
        ExactQuery q;
        q.sources.push_back(GeodesicSource::atVertex(pick(rng)));
        const size_t n = std::min<size_t>(100, count - pairs.size());
        for (size_t i = 0; i < n; ++i) q.targets.push_back(pick(rng));
        ws.run(geo, q, dist);
        for (uint32_t t : q.targets) pairs.push_back({q.sources[0].vertex, t, dist[t]});
    }
    return pairs;
}

}  // namespace

int runEval(int argc, char** argv) {
    cli::Args args(argc, argv, {"--golden", "--pairs", "--seed", "--triples", "--search"}, {"--json", "--help", "--repair", "--no-endpoint-table"});
    if (args.flag("--help")) {
        std::printf("%s", kUsage);
        return 0;
    }
    if (args.positional().size() != 2) throw cli::UsageError(std::string("expected MESH and BLOB\n") + kUsage);
    if (args.has("--golden") && args.has("--pairs")) throw cli::UsageError("--golden and --pairs exclude each other");
    const long long pairCount = args.integer("--pairs", 1000);
    const long long triples = args.integer("--triples", 2000);
    if (pairCount < 1) throw cli::UsageError("--pairs must be >= 1");
    if (triples < 0) throw cli::UsageError("--triples must be >= 0");
    const uint64_t seed = uint64_t(args.integer("--seed", 1));
    const std::string searchName = args.str("--search", "labels");
    vg_search_mode search = VG_SEARCH_HUB_LABELS;
    if (searchName == "bidirectional") search = VG_SEARCH_BIDIRECTIONAL;
    else if (searchName == "directed") search = VG_SEARCH_DIRECTED;
    else if (searchName != "labels") throw cli::UsageError("--search must be labels, directed or bidirectional");

    Mesh mesh;
    if (!loadMeshForCommand("eval", args.positional()[0], args.flag("--repair"), mesh)) return 1;
    RuntimeGraph graph;
    if (!loadBlobForMesh("eval", args.positional()[1], mesh, false, graph)) return 1;

    std::vector<DistancePair> pairs;
    if (args.has("--golden")) {
        std::string error;
        if (!readPairs(args.str("--golden"), pairs, error)) {
            std::fprintf(stderr, "vorogeo eval: %s\n", error.c_str());
            return 1;
        }
        for (const DistancePair& p : pairs)
            if (p.source >= mesh.vertexCount() || p.target >= mesh.vertexCount()) {
                std::fprintf(stderr, "vorogeo eval: %s: vertex %u out of range (mesh has %u vertices)\n",
                             args.str("--golden").c_str(), std::max(p.source, p.target), mesh.vertexCount());
                return 1;
            }
    } else {
        pairs = exactRandomPairs(mesh, size_t(pairCount), seed);
    }

    RuntimeWorkspace ws(graph);
    ws.setSearch(search);
    const bool withTable = search == VG_SEARCH_HUB_LABELS && !args.flag("--no-endpoint-table");
    const EndpointTable table(withTable ? graph.graph() : nullptr);
    ws.useTable(table);
    const AccuracyReport acc = measureAccuracy(ws, pairs);
    const MetricReport metric = checkMetric(ws, mesh.vertexCount(), size_t(triples), seed);
    // One-to-all from the first sources of the pairs (at most 20 distinct).
    std::vector<double> fieldMs;
    std::vector<uint32_t> fieldSources;
    for (const DistancePair& p : pairs)
        if (fieldSources.size() < 20 && std::find(fieldSources.begin(), fieldSources.end(), p.source) == fieldSources.end())
            fieldSources.push_back(p.source);
    std::vector<float> field(mesh.vertexCount());
    for (uint32_t s : fieldSources) {
        const std::vector<uint32_t> source = {s};
        Stopwatch watch;
        ws.field(source, field);
        fieldMs.push_back(watch.seconds() * 1e3);
    }
    const double msadP50 = percentile(fieldMs, 50);
    const double bboxDiag = double(vg_bbox_diagonal(graph.graph()));

    if (args.flag("--json")) {
        std::printf("{\"mesh\":\"%s\",\"search\":\"%s\",\"endpoint_table\":%s,\"vertices\":%u,\"blob_bytes\":%zu,\"open_ms\":%.3f,\"pairs\":%zu,"
                    "\"mean_rel_error\":%.6e,\"median_rel_error\":%.6e,\"p99_rel_error\":%.6e,\"max_rel_error\":%.6e,"
                    "\"pairs_over_1pct\":%zu,\"infinite_mismatches\":%zu,"
                    "\"sssd_p50_us\":%.2f,\"sssd_p90_us\":%.2f,\"sssd_p99_us\":%.2f,\"msad_p50_ms\":%.3f,"
                    "\"symmetry_pairs\":%zu,\"symmetry_violations\":%zu,\"max_symmetry_rel\":%.3e,"
                    "\"triples\":%zu,\"triangle_violations\":%zu,\"max_triangle_excess\":%.3e}\n",
                    args.positional()[0].c_str(), searchName.c_str(), table.get() ? "true" : "false", mesh.vertexCount(), graph.blobBytes(),
                    graph.openSeconds() * 1e3, acc.pairs, acc.meanRel, acc.medianRel, acc.p99Rel, acc.maxRel, acc.overOnePercent,
                    acc.infiniteMismatches, acc.p50Us, acc.p90Us, acc.p99Us, msadP50, metric.symmetryPairs,
                    metric.symmetryViolations, metric.maxSymmetryRel, metric.triples, metric.triangleViolations,
                    metric.maxTriangleExcess / bboxDiag);
        return 0;
    }
    std::printf("%s: %u vertices, blob %zu bytes (%.1f bytes/vertex), opened in %.2f ms\n",
                args.positional()[0].c_str(), mesh.vertexCount(), graph.blobBytes(),
                double(graph.blobBytes()) / mesh.vertexCount(), graph.openSeconds() * 1e3);
    if (table.get())
        std::printf("labels with the endpoint table (%.1f MB, built in %.0f ms)\n", double(table.bytes()) / 1e6,
                    table.buildSeconds() * 1e3);
    std::printf("pairs %zu: relative error mean %.4f%%, median %.4f%%, p99 %.4f%%, max %.4f%%; %zu pairs over 1%%\n",
                acc.pairs, acc.meanRel * 100, acc.medianRel * 100, acc.p99Rel * 100, acc.maxRel * 100,
                acc.overOnePercent);
    if (acc.infiniteMismatches)
        std::printf("  %zu pairs disagree on reachability (finite vs infinite)\n", acc.infiniteMismatches);
    std::printf("worst pairs (source, target, exact, runtime, relative error):\n");
    for (const PairError& w : acc.worst)
        std::printf("  %u %u %.6g %.6g %.4f%%\n", w.source, w.target, w.exact, w.value, w.rel * 100);
    std::printf("point-to-point (%s search): p50 %.1f us, p90 %.1f us, p99 %.1f us\n", searchName.c_str(), acc.p50Us,
                acc.p90Us, acc.p99Us);
    std::printf("one-to-all: p50 %.2f ms (%zu sources)\n", msadP50, fieldMs.size());
    std::printf("symmetry: %zu of %zu pairs differ (max %.2e relative)\n", metric.symmetryViolations,
                metric.symmetryPairs, metric.maxSymmetryRel);
    std::printf("triangle inequality: %zu of %zu triples violated (max excess %.2e of the bbox diagonal)\n",
                metric.triangleViolations, metric.triples, metric.maxTriangleExcess / bboxDiag);
    return 0;
}

}  // namespace vorogeo::tools
