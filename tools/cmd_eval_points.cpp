// vorogeo eval-points: accuracy and speed of the runtime's surface-point queries against
// the exact engine with surface-point sources, on random point pairs.
#include <cmath>
#include <algorithm>
#include <cstdio>
#include <random>

#include "cli.h"
#include "runtime_graph.h"
#include "runtime_stats.h"
#include "surface_points.h"
#include "timing.h"
#include "tool_mesh.h"

namespace vorogeo::tools {

namespace {

const char* kUsage =
    "usage: vorogeo eval-points MESH BLOB [--pairs N] [--per-source K] [--seed S] [--json]\n"
    "  Accuracy of vg_point_distance on N random surface-point pairs (default 10000; points\n"
    "  uniform over the area, K targets per source, default 100) against the exact engine\n"
    "  run from each source point. Also times the point queries and, interleaved with them,\n"
    "  vertex-to-vertex queries on as many random vertex pairs (p50 and the ratio), and the\n"
    "  k-nearest query (16 of 1,000 random points) next to 16 point-to-point queries.\n";

}  // namespace

int runEvalPoints(int argc, char** argv) {
    cli::Args args(argc, argv, {"--pairs", "--per-source", "--seed"}, {"--json", "--help", "--repair"});
    if (args.flag("--help")) {
        std::printf("%s", kUsage);
        return 0;
    }
    if (args.positional().size() != 2) throw cli::UsageError(std::string("expected MESH and BLOB\n") + kUsage);
    const long long pairCount = args.integer("--pairs", 10000);
    const long long perSource = args.integer("--per-source", 100);
    if (pairCount < 1) throw cli::UsageError("--pairs must be >= 1");
    if (perSource < 1) throw cli::UsageError("--per-source must be >= 1");
    const uint64_t seed = uint64_t(args.integer("--seed", 1));

    Mesh mesh;
    if (!loadMeshForCommand("eval-points", args.positional()[0], args.flag("--repair"), mesh)) return 1;
    RuntimeGraph graph;
    if (!loadBlobForMesh("eval-points", args.positional()[1], mesh, true, graph)) return 1;

    Stopwatch exactWatch;
    const std::vector<PointPair> pairs = exactPointPairs(mesh, size_t(pairCount), size_t(perSource), seed);
    const double exactSeconds = exactWatch.seconds();

    RuntimeWorkspace ws(graph);
    std::mt19937_64 rng(seed ^ 0xB0Bull);
    std::uniform_int_distribution<uint32_t> pickVertex(0, mesh.vertexCount() - 1);
    std::vector<DistancePair> asPairs(pairs.size());
    std::vector<double> values(pairs.size()), pointUs, vertexUs;
    for (size_t i = 0; i < pairs.size(); ++i) {
        const vg_point s = toRuntimePoint(pairs[i].source), t = toRuntimePoint(pairs[i].target);
        float d = 0;
        Stopwatch pointWatch;
        const vg_status st = vg_point_distance(graph.graph(), ws.get(), &s, &t, &d);
        pointUs.push_back(pointWatch.seconds() * 1e6);
        if (st != VG_OK) {
            std::fprintf(stderr, "vorogeo eval-points: vg_point_distance: %s\n", vg_status_string(st));
            return 1;
        }
        values[i] = d;
        asPairs[i] = DistancePair{pairs[i].source.face, pairs[i].target.face, pairs[i].distance};
        const uint32_t a = pickVertex(rng), b = pickVertex(rng);
        Stopwatch vertexWatch;
        ws.distance(a, b);
        vertexUs.push_back(vertexWatch.seconds() * 1e6);
    }
    const AccuracyReport acc = errorStatistics(asPairs, values);

    // k nearest: 16 of 1,000 random candidate points, against 16 point-to-point queries
    // (what answering it one target at a time would cost at least), interleaved.
    const size_t kCandidates = 1000, k = 16;
    std::vector<vg_point> candidates;
    for (const SurfacePoint& p : randomSurfacePoints(mesh, kCandidates, seed ^ 0xC0FFEEull)) candidates.push_back(toRuntimePoint(p));
    std::vector<double> kNearestUs, sixteenUs;
    std::vector<size_t> kIndex(k);
    std::vector<float> kDist(k);
    for (size_t q = 0; q < std::min<size_t>(200, pairs.size()); ++q) {
        const vg_point s = toRuntimePoint(pairs[q * pairs.size() / std::min<size_t>(200, pairs.size())].source);
        size_t found = 0;
        Stopwatch kWatch;
        vg_point_k_nearest(graph.graph(), ws.get(), &s, candidates.data(), candidates.size(), k, kIndex.data(),
                           kDist.data(), &found);
        kNearestUs.push_back(kWatch.seconds() * 1e6);
        Stopwatch sixteenWatch;
        for (size_t i = 0; i < k; ++i) {
            float d = 0;
            vg_point_distance(graph.graph(), ws.get(), &s, &candidates[(q * 37 + i * 61) % kCandidates], &d);
        }
        sixteenUs.push_back(sixteenWatch.seconds() * 1e6);
    }
    const double kP50 = percentile(kNearestUs, 50), sixteenP50 = percentile(sixteenUs, 50);
    const double pointP50 = percentile(pointUs, 50), vertexP50 = percentile(vertexUs, 50);

    if (args.flag("--json")) {
        std::printf("{\"mesh\":\"%s\",\"vertices\":%u,\"pairs\":%zu,\"mean_rel_error\":%.6e,\"median_rel_error\":%.6e,"
                    "\"p99_rel_error\":%.6e,\"max_rel_error\":%.6e,\"pairs_over_1pct\":%zu,\"infinite_mismatches\":%zu,"
                    "\"point_p50_us\":%.2f,\"point_p99_us\":%.2f,\"vertex_p50_us\":%.2f,\"point_over_vertex_p50\":%.3f,"
                    "\"k_nearest_16_of_1000_p50_us\":%.2f,\"k_nearest_16_of_1000_p99_us\":%.2f,"
                    "\"sixteen_point_queries_p50_us\":%.2f,\"exact_seconds\":%.2f}\n",
                    args.positional()[0].c_str(), mesh.vertexCount(), acc.pairs, acc.meanRel, acc.medianRel,
                    acc.p99Rel, acc.maxRel, acc.overOnePercent, acc.infiniteMismatches, pointP50,
                    percentile(pointUs, 99), vertexP50, pointP50 / vertexP50, kP50, percentile(kNearestUs, 99),
                    sixteenP50, exactSeconds);
        return 0;
    }
    std::printf("%s: %u vertices; %zu point pairs (exact engine: %.1f s)\n", args.positional()[0].c_str(),
                mesh.vertexCount(), acc.pairs, exactSeconds);
    std::printf("relative error mean %.4f%%, median %.4f%%, p99 %.4f%%, max %.4f%%; %zu pairs over 1%%\n",
                acc.meanRel * 100, acc.medianRel * 100, acc.p99Rel * 100, acc.maxRel * 100, acc.overOnePercent);
    if (acc.infiniteMismatches)
        std::printf("  %zu pairs disagree on reachability (finite vs infinite)\n", acc.infiniteMismatches);
    std::printf("worst pairs (source face, target face, exact, runtime, relative error):\n");
    for (const PairError& w : acc.worst)
        std::printf("  %u %u %.6g %.6g %.4f%%\n", w.source, w.target, w.exact, w.value, w.rel * 100);
    std::printf("point-to-point: p50 %.1f us, p99 %.1f us; vertex-to-vertex (interleaved) p50 %.1f us; ratio %.2f\n",
                pointP50, percentile(pointUs, 99), vertexP50, pointP50 / vertexP50);
    std::printf("k nearest (16 of 1000 points): p50 %.1f us, p99 %.1f us; 16 point-to-point queries p50 %.1f us\n", kP50,
                percentile(kNearestUs, 99), sixteenP50);
    return 0;
}

}  // namespace vorogeo::tools
