// vorogeo exact: exact geodesic distances (the wavefront engine, or MMP), and checks
// against a reference (golden pairs or a one-to-all field).
#include <cmath>
#include <cstdio>
#include <fstream>

#include "cli.h"
#include "exact_check.h"
#include "geodesic_exact.h"
#include "mesh_stats.h"
#include "timing.h"
#include "tool_mesh.h"

namespace vorogeo::tools {

namespace {

const char* kUsage =
    "usage: vorogeo exact MESH --source V [--target W] [--out field.csv] [--max-distance D] [--engine E]\n"
    "       vorogeo exact MESH --pairs PAIRS.csv [--json] [--threads N] [--engine E]\n"
    "       vorogeo exact MESH --source V --field FIELD.csv [--json] [--engine E]\n"
    "  Exact polyhedral geodesic distances by window propagation.\n"
    "  --engine: wavefront (default: window lists crossing a face at once) or mmp (windows\n"
    "  one at a time, kept on their edges; a single --target uses it, to stop there).\n"
    "  --pairs: recompute every 'source,target,distance' row and report the relative error\n"
    "  and the single-source time; exits 1 if a pair disagrees beyond 1e-6 relative\n"
    "  (or 1e-9 x bounding-box diagonal near zero). --field: the same for one-to-all values.\n"
    "  --repair: repair a defective mesh instead of refusing it (see vorogeo info).\n";

void printDistance(FILE* out, double d) {
    if (std::isinf(d)) std::fprintf(out, "inf");
    else std::fprintf(out, "%.17g", d);
}

ExactEngine engineOf(const cli::Args& args) {
    ExactEngine engine = ExactEngine::Wavefront;
    if (args.has("--engine") && !parseEngine(args.str("--engine"), engine))
        throw cli::UsageError("--engine must be wavefront or mmp, not '" + args.str("--engine") + "'");
    return engine;
}

int runPairs(const Mesh& mesh, const ExactGeodesic& geo, const cli::Args& args, const Tolerance& tol) {
    std::vector<DistancePair> pairs;
    std::string error;
    if (!readPairs(args.str("--pairs"), pairs, error)) {
        std::fprintf(stderr, "vorogeo exact: %s\n", error.c_str());
        return 1;
    }
    const int threads = int(args.integer("--threads", 0));
    if (threads < 0) throw cli::UsageError("--threads must be >= 0");
    Stopwatch wall;
    const ExactEngine engine = engineOf(args);
    const PairCheckResult r = checkPairs(geo, pairs, tol, threads, engine);
    const double p50 = percentile(r.sourceSeconds, 50) * 1e3, p90 = percentile(r.sourceSeconds, 90) * 1e3;
    if (args.flag("--json")) {
        std::printf("{\"mesh\":\"%s\",\"engine\":\"%s\",\"vertices\":%u,\"pairs\":%zu,\"sources\":%zu,"
                    "\"failures\":%zu,\"max_rel_error\":%.3e,\"mean_rel_error\":%.3e,\"max_abs_error\":%.3e,"
                    "\"ssad_p50_ms\":%.3f,\"ssad_p90_ms\":%.3f,\"windows_per_source\":%.0f,"
                    "\"threads\":%d,\"wall_s\":%.3f,\"peak_rss_mb\":%.1f}\n",
                    args.positional()[0].c_str(), engineName(engine), mesh.vertexCount(), r.pairs, r.sources,
                    r.failures,
                    r.maxRelError, r.meanRelError, r.maxAbsError, p50, p90,
                    r.sources ? double(r.windows) / double(r.sources) : 0.0, threads, wall.seconds(), peakRssMb());
    } else {
        std::printf("pairs %zu from %zu sources: max relative error %.3e, mean %.3e, max absolute %.3e\n",
                    r.pairs, r.sources, r.maxRelError, r.meanRelError, r.maxAbsError);
        std::printf("single source, all destinations (%s): median %.2f ms, p90 %.2f ms (%.0f windows per source)\n",
                    engineName(engine), p50, p90, r.sources ? double(r.windows) / double(r.sources) : 0.0);
    }
    if (r.failures) {
        std::fprintf(stderr, "vorogeo exact: %zu of %zu pairs disagree; worst %u -> %u: ", r.failures, r.pairs,
                     r.worst.source, r.worst.target);
        printDistance(stderr, r.worstValue);
        std::fprintf(stderr, " vs reference ");
        printDistance(stderr, r.worst.distance);
        std::fprintf(stderr, "\n");
        return 1;
    }
    return 0;
}

int runField(const Mesh& mesh, const ExactGeodesic& geo, uint32_t source, const cli::Args& args,
             const Tolerance& tol) {
    std::vector<double> reference;
    std::string error;
    if (!readField(args.str("--field"), reference, error)) {
        std::fprintf(stderr, "vorogeo exact: %s\n", error.c_str());
        return 1;
    }
    const ExactEngine engine = engineOf(args);
    const FieldCheckResult r = checkField(geo, source, reference, tol, engine);
    if (args.flag("--json"))
        std::printf("{\"mesh\":\"%s\",\"engine\":\"%s\",\"vertices\":%u,\"source\":%u,\"values\":%zu,"
                    "\"failures\":%zu,\"max_rel_error\":%.3e,\"mean_rel_error\":%.3e,\"max_abs_error\":%.3e,"
                    "\"ssad_ms\":%.3f}\n",
                    args.positional()[0].c_str(), engineName(engine), mesh.vertexCount(), source, r.values,
                    r.failures,
                    r.maxRelError, r.meanRelError, r.maxAbsError, r.seconds * 1e3);
    else
        std::printf("field of %u (%s): %zu values, max relative error %.3e, mean %.3e, max absolute %.3e, %.2f ms\n",
                    source, engineName(engine), r.values, r.maxRelError, r.meanRelError, r.maxAbsError, r.seconds * 1e3);
    if (r.failures) {
        std::fprintf(stderr, "vorogeo exact: %zu of %zu values disagree (worst at vertex %u)\n", r.failures,
                     r.values, r.worstVertex);
        return 1;
    }
    return 0;
}

}  // namespace

int runExact(int argc, char** argv) {
    cli::Args args(argc, argv, {"--source", "--target", "--out", "--pairs", "--field", "--threads", "--max-distance", "--engine"},
                   {"--json", "--repair", "--help"});
    if (args.flag("--help")) {
        std::printf("%s", kUsage);
        return 0;
    }
    if (args.positional().size() != 1) throw cli::UsageError("expected one MESH argument\n" + std::string(kUsage));
    if (!args.has("--pairs") && !args.has("--source"))
        throw cli::UsageError("give --source V or --pairs PAIRS.csv\n" + std::string(kUsage));
    if (args.has("--pairs") && (args.has("--source") || args.has("--field")))
        throw cli::UsageError("--pairs cannot be combined with --source or --field");

    Mesh mesh;
    if (!loadMeshForCommand("exact", args.positional()[0], args.flag("--repair"), mesh)) return 1;
    const ExactGeodesic geo(mesh);
    Tolerance tol;
    tol.absTol = 1e-9 * computeStats(mesh).bboxDiag;

    if (args.has("--pairs")) return runPairs(mesh, geo, args, tol);

    const long long source = args.integer("--source", -1);
    if (source < 0 || source >= mesh.vertexCount())
        throw cli::UsageError("--source " + args.str("--source") + " is not a vertex of the mesh (0.." +
                              std::to_string(mesh.vertexCount() - 1) + ")");
    if (args.has("--field")) return runField(mesh, geo, uint32_t(source), args, tol);

    ExactQuery query;
    query.sources.push_back(GeodesicSource::atVertex(uint32_t(source)));
    query.maxDistance = args.number("--max-distance", kInfinity);
    if (!(query.maxDistance >= 0)) throw cli::UsageError("--max-distance must be >= 0");
    long long target = -1;
    if (args.has("--target")) {
        target = args.integer("--target", -1);
        if (target < 0 || target >= mesh.vertexCount())
            throw cli::UsageError("--target " + args.str("--target") + " is not a vertex of the mesh");
        if (!args.has("--out")) query.targets.push_back(uint32_t(target));
    }
    // MMP can stop once one target's value is final; the wavefront runs to the end (of
    // the distance bound, if any).
    ExactEngine engine = engineOf(args);
    const bool early = !query.targets.empty();
    if (early && args.has("--engine") && engine == ExactEngine::Wavefront)
        throw cli::UsageError("--target without --out needs --engine mmp (it stops at the target)");
    if (early) engine = ExactEngine::Mmp;
    ExactWorkspace ws;
    WavefrontWorkspace wavefront;
    std::vector<double> dist;
    ExactStats stats;
    Stopwatch clock;
    if (engine == ExactEngine::Mmp) ws.run(geo, query, dist, &stats);
    else wavefront.run(geo, {uint32_t(source)}, dist, &stats, query.maxDistance);
    const double ms = clock.seconds() * 1e3;

    if (args.has("--out")) {
        // Write to a temporary name and rename, so a failure never leaves a partial file.
        const std::string out = args.str("--out"), tmp = out + ".tmp";
        FILE* f = std::fopen(tmp.c_str(), "w");
        if (!f) {
            std::fprintf(stderr, "vorogeo exact: %s: cannot open for writing\n", out.c_str());
            return 1;
        }
        for (double d : dist) {
            printDistance(f, d);
            std::fputc('\n', f);
        }
        const bool ok = std::fflush(f) == 0 && !std::ferror(f);
        std::fclose(f);
        if (!ok || std::rename(tmp.c_str(), out.c_str()) != 0) {
            std::remove(tmp.c_str());
            std::fprintf(stderr, "vorogeo exact: %s: write failed\n", out.c_str());
            return 1;
        }
    }
    if (target >= 0) {
        printDistance(stdout, dist[size_t(target)]);
        std::printf("\n");
    }
    std::fprintf(stderr, "vorogeo exact: %u vertices, %.2f ms, %llu windows (%s)\n", mesh.vertexCount(), ms,
                 (unsigned long long)stats.windowsCreated, engineName(engine));
    return 0;
}

}  // namespace vorogeo::tools
