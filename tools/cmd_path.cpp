// vorogeo path: the geodesic path between two surface points (vg_path), printed, checked
// against the mesh and optionally drawn over the distance field; or statistics of many
// random paths (length against distance, surface checks, time next to the distance query).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "cli.h"
#include "path_check.h"
#include "render.h"
#include "runtime_graph.h"
#include "surface_points.h"
#include "timing.h"
#include "tool_mesh.h"

namespace vorogeo::tools {

namespace {

const char* kUsage =
    "usage: vorogeo path MESH BLOB --from F,U,V --to F,U,V [--png OUT.png] [--size WxH] [--view YAW,PITCH]\n"
    "       vorogeo path MESH BLOB --random N [--seed S] [--exact] [--json]\n"
    "  A point F,U,V is face F at barycentric weights (1-U-V, U, V) of its three vertices.\n"
    "  Prints the path from vg_path (face, weights and position per point), its length, the\n"
    "  distance returned with it and their relative difference, and checks that it lies on\n"
    "  the surface. --png draws it (white) over the runtime distance field from the source.\n"
    "  --random N takes N random point pairs (uniform over the area): relative difference of\n"
    "  length and the distance returned with it, and of length and vg_point_distance (mean,\n"
    "  p99, max), points per path, surface checks, and the time of vg_path next to\n"
    "  vg_point_distance on the same pair (both after an untimed distance query on the pair,\n"
    "  so on equally warm caches; alternating which goes first; p50, p90, ratio; extraction =\n"
    "  the per-pair difference).\n"
    "  --exact also runs the exact engine from the sources (50 targets each) and compares the\n"
    "  path length and vg_point_distance with the exact geodesic distance.\n";

vg_point parsePoint(const std::string& text, const std::string& option, uint32_t faceCount) {
    char* end = nullptr;
    const char* s = text.c_str();
    const unsigned long face = std::strtoul(s, &end, 10);
    double uv[2] = {0, 0};
    bool ok = end != s && *end == ',';
    for (int i = 0; ok && i < 2; ++i) {
        s = end + 1;
        uv[i] = std::strtod(s, &end);
        ok = end != s && (i == 0 ? *end == ',' : *end == '\0') && std::isfinite(uv[i]);
    }
    if (!ok) throw cli::UsageError(option + " expects F,U,V (face index and two barycentric weights), got '" + text + "'");
    if (face >= faceCount)
        throw cli::UsageError(option + ": face " + std::to_string(face) + " out of range (the mesh has " +
                              std::to_string(faceCount) + " faces)");
    return vg_point{uint32_t(face), {float(1.0 - uv[0] - uv[1]), float(uv[0]), float(uv[1])}};
}

// vg_path into a vector: size query, then the call.
vg_status pathInto(const vg_graph* g, vg_workspace* ws, const vg_point& s, const vg_point& t,
                   std::vector<vg_path_point>& out, float& distance) {
    size_t count = 0;
    vg_status st = vg_path(g, ws, &s, &t, out.empty() ? nullptr : out.data(), out.size(), &count, &distance);
    if (st == VG_ERR_BUFFER_TOO_SMALL || (st == VG_OK && count > out.size())) {  // too small, or a size query
        out.resize(count);
        st = vg_path(g, ws, &s, &t, out.data(), out.size(), &count, &distance);
    }
    if (st == VG_OK) out.resize(count);
    return st;
}

double relativeDifference(double length, double distance) {
    return distance > 0 ? std::fabs(length - distance) / distance : std::fabs(length);
}

int randomPaths(const cli::Args& args, const Mesh& mesh, const RuntimeGraph& graph) {
    const long long count = args.integer("--random", 1000);
    if (count < 1) throw cli::UsageError("--random must be >= 1");
    const uint64_t seed = uint64_t(args.integer("--seed", 1));
    const bool withExact = args.flag("--exact");
    std::vector<PointPair> pairs;
    if (withExact) {
        pairs = exactPointPairs(mesh, size_t(count), 50, seed);
    } else {
        const std::vector<SurfacePoint> points = randomSurfacePoints(mesh, 2 * size_t(count), seed);
        pairs.resize(size_t(count));
        for (size_t i = 0; i < pairs.size(); ++i) {
            pairs[i].source = points[2 * i];
            pairs[i].target = points[2 * i + 1];
        }
    }
    RuntimeWorkspace ws(graph);
    const PathChecker checker(mesh);
    std::vector<vg_path_point> path(4096);
    std::vector<double> diffs, pathUs, distanceUs, extraUs, sizes, pathVsExact, distanceVsExact;
    std::vector<double> vsPoint;
    size_t unreachable = 0, offSurface = 0, over01 = 0, pathVsPoint01 = 0;
    std::string firstProblem;
    for (long long i = 0; i < count; ++i) {
        const vg_point s = toRuntimePoint(pairs[size_t(i)].source), t = toRuntimePoint(pairs[size_t(i)].target);
        float d = 0, dp = 0;
        vg_status st = VG_OK, pst = VG_OK;
        double distanceTime = 0, pathTime = 0;
        auto timeDistance = [&] {
            Stopwatch watch;
            st = vg_point_distance(graph.graph(), ws.get(), &s, &t, &d);
            distanceTime = watch.seconds() * 1e6;
        };
        auto timePath = [&] {
            path.resize(path.capacity());
            Stopwatch watch;
            pst = pathInto(graph.graph(), ws.get(), s, t, path, dp);
            pathTime = watch.seconds() * 1e6;
        };
        // Both timed on caches this pair's search has warmed (an untimed distance query
        // first): otherwise whichever goes first pays the cold misses and the difference
        // measures the cache, not the extraction. Alternating which goes first as well.
        float warm = 0;
        vg_point_distance(graph.graph(), ws.get(), &s, &t, &warm);
        if (i % 2 == 0) {
            timeDistance();
            timePath();
        } else {
            timePath();
            timeDistance();
        }
        if (st != VG_OK || pst != VG_OK) {
            std::fprintf(stderr, "vorogeo path: pair %lld (faces %u, %u): %s\n", i, s.face, t.face,
                         vg_status_string(st != VG_OK ? st : pst));
            return 1;
        }
        if (!std::isfinite(d)) {
            ++unreachable;
            continue;
        }
        const PathCheck c = checker.check(path);
        if (!c.ok && offSurface++ == 0) firstProblem = "pair " + std::to_string(i) + ": " + c.problem;
        const double diff = relativeDifference(c.length, dp);
        over01 += diff > 1e-3;
        const double vsSearch = relativeDifference(c.length, d);  // against vg_point_distance
        vsPoint.push_back(vsSearch);
        pathVsPoint01 += vsSearch > 1e-3;
        if (withExact && pairs[size_t(i)].distance > 0) {
            const double exact = pairs[size_t(i)].distance;
            pathVsExact.push_back((c.length - exact) / exact);
            distanceVsExact.push_back(std::fabs(d - exact) / exact);
        }
        diffs.push_back(diff);
        sizes.push_back(double(path.size()));
        pathUs.push_back(pathTime);
        distanceUs.push_back(distanceTime);
        extraUs.push_back(pathTime - distanceTime);
    }
    const auto meanOf = [](const std::vector<double>& v) {
        double sum = 0;
        for (double x : v) sum += x;
        return v.empty() ? 0.0 : sum / double(v.size());
    };
    const auto maxOf = [](const std::vector<double>& v) { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); };
    const auto minOf = [](const std::vector<double>& v) { return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end()); };
    const double mean = meanOf(diffs), maxDiff = maxOf(diffs);
    char exactJson[512] = "", exactText[512] = "";
    if (withExact) {
        std::snprintf(exactJson, sizeof exactJson,
                      ",\"path_vs_exact_mean\":%.6e,\"path_vs_exact_p99\":%.6e,\"path_vs_exact_max\":%.6e,"
                      "\"path_vs_exact_min\":%.6e,\"point_distance_vs_exact_mean\":%.6e,"
                      "\"point_distance_vs_exact_max\":%.6e",
                      meanOf(pathVsExact), percentile(pathVsExact, 99), maxOf(pathVsExact), minOf(pathVsExact),
                      meanOf(distanceVsExact), maxOf(distanceVsExact));
        std::snprintf(exactText, sizeof exactText,
                      "path length over the exact distance: mean %.4f%%, p99 %.4f%%, max %.4f%%, min %.4f%%; "
                      "vg_point_distance vs exact: mean %.4f%%, max %.4f%%\n",
                      meanOf(pathVsExact) * 100, percentile(pathVsExact, 99) * 100, maxOf(pathVsExact) * 100,
                      minOf(pathVsExact) * 100, meanOf(distanceVsExact) * 100, maxOf(distanceVsExact) * 100);
    }
    if (args.flag("--json")) {
        std::printf("{\"mesh\":\"%s\",\"vertices\":%u,\"paths\":%zu,\"unreachable\":%zu,\"off_surface\":%zu,"
                    "\"mean_length_rel_diff\":%.6e,\"p99_length_rel_diff\":%.6e,\"max_length_rel_diff\":%.6e,"
                    "\"paths_over_0_1pct\":%zu,\"points_p50\":%.0f,\"points_max\":%.0f,\"path_p50_us\":%.2f,"
                    "\"path_p90_us\":%.2f,\"distance_p50_us\":%.2f,\"distance_p90_us\":%.2f,"
                    "\"extraction_p50_us\":%.2f,\"extraction_p90_us\":%.2f,\"path_over_distance_p50\":%.3f,"
                    "\"vs_point_distance_mean\":%.6e,\"vs_point_distance_p99\":%.6e,\"vs_point_distance_max\":%.6e,"
                    "\"vs_point_distance_over_0_1pct\":%zu%s}\n",
                    args.positional()[0].c_str(), mesh.vertexCount(), diffs.size(), unreachable, offSurface, mean,
                    percentile(diffs, 99), maxDiff, over01, percentile(sizes, 50),
                    sizes.empty() ? 0.0 : *std::max_element(sizes.begin(), sizes.end()), percentile(pathUs, 50),
                    percentile(pathUs, 90), percentile(distanceUs, 50), percentile(distanceUs, 90),
                    percentile(extraUs, 50), percentile(extraUs, 90), percentile(pathUs, 50) / percentile(distanceUs, 50),
                    meanOf(vsPoint), percentile(vsPoint, 99), maxOf(vsPoint), pathVsPoint01, exactJson);
    } else {
        std::printf("%s: %u vertices; %zu paths (%zu unreachable pairs)\n", args.positional()[0].c_str(),
                    mesh.vertexCount(), diffs.size(), unreachable);
        std::printf("length vs distance: mean %.4f%%, p99 %.4f%%, max %.4f%%; %zu paths over 0.1%%\n", mean * 100,
                    percentile(diffs, 99) * 100, maxDiff * 100, over01);
        std::printf("points per path: p50 %.0f; surface checks failed: %zu\n", percentile(sizes, 50), offSurface);
        std::printf("vg_path p50 %.1f us, p90 %.1f us; vg_point_distance p50 %.1f us, p90 %.1f us; extraction "
                    "(path - distance) p50 %.1f us, p90 %.1f us; ratio %.2f\n",
                    percentile(pathUs, 50), percentile(pathUs, 90), percentile(distanceUs, 50),
                    percentile(distanceUs, 90), percentile(extraUs, 50), percentile(extraUs, 90),
                    percentile(pathUs, 50) / percentile(distanceUs, 50));
        std::printf("length vs vg_point_distance: mean %.4f%%, p99 %.4f%%, max %.4f%%; %zu paths over 0.1%%\n",
                    meanOf(vsPoint) * 100, percentile(vsPoint, 99) * 100, maxOf(vsPoint) * 100, pathVsPoint01);
        std::printf("%s", exactText);
        if (offSurface) std::printf("first surface problem: %s\n", firstProblem.c_str());
    }
    return offSurface == 0 ? 0 : 1;
}

}  // namespace

int runPath(int argc, char** argv) {
    cli::Args args(argc, argv, {"--from", "--to", "--png", "--size", "--view", "--random", "--seed"},
                   {"--json", "--help", "--repair", "--exact"});
    if (args.flag("--help")) {
        std::printf("%s", kUsage);
        return 0;
    }
    if (args.positional().size() != 2) throw cli::UsageError(std::string("expected MESH and BLOB\n") + kUsage);
    const bool random = args.has("--random");
    if (!random && (!args.has("--from") || !args.has("--to")))
        throw cli::UsageError(std::string("give --from and --to, or --random N\n") + kUsage);
    int width = 640, height = 640;
    View view;
    cli::pictureOptions(args, width, height, view.yawDegrees, view.pitchDegrees);

    Mesh mesh;
    if (!loadMeshForCommand("path", args.positional()[0], args.flag("--repair"), mesh)) return 1;
    RuntimeGraph graph;
    if (!loadBlobForMesh("path", args.positional()[1], mesh, true, graph)) return 1;
    if (random) return randomPaths(args, mesh, graph);

    const vg_point s = parsePoint(args.str("--from"), "--from", mesh.faceCount());
    const vg_point t = parsePoint(args.str("--to"), "--to", mesh.faceCount());
    RuntimeWorkspace ws(graph);
    std::vector<vg_path_point> path;
    float distance = 0;
    Stopwatch watch;
    const vg_status st = pathInto(graph.graph(), ws.get(), s, t, path, distance);
    const double seconds = watch.seconds();
    if (st != VG_OK) {
        std::fprintf(stderr, "vorogeo path: %s\n", vg_status_string(st));
        return 1;
    }
    if (!std::isfinite(distance)) {
        std::printf("no path: the points are on different connected components (distance +inf)\n");
        return 0;
    }
    const PathCheck check = PathChecker(mesh).check(path);
    std::printf("# point face w0 w1 w2 x y z\n");
    for (size_t i = 0; i < path.size(); ++i) {
        const vg_path_point& p = path[i];
        std::printf("%zu %u %.6f %.6f %.6f %.9g %.9g %.9g\n", i, p.point.face, p.point.bary[0], p.point.bary[1],
                    p.point.bary[2], p.position[0], p.position[1], p.position[2]);
    }
    std::printf("distance %.9g, path length %.9g (%.4f%% apart), %zu points, %.1f us (size query and path)\n", distance,
                check.length, relativeDifference(check.length, distance) * 100, path.size(), seconds * 1e6);
    std::printf("on the surface: %s\n", check.ok ? "yes" : check.problem.c_str());

    if (args.has("--png")) {
        std::vector<float> field(mesh.vertexCount());
        const vg_status fst = vg_point_distance_field(graph.graph(), ws.get(), &s, 1, field.data(), nullptr);
        if (fst != VG_OK) {
            std::fprintf(stderr, "vorogeo path: vg_point_distance_field: %s\n", vg_status_string(fst));
            return 1;
        }
        const std::vector<double> values(field.begin(), field.end());
        Panel panel;
        const double scale = largestFinite(values);
        panel.vertexColour = colourField(values, scale);
        panel.isoValue = values;
        panel.isoSpacing = scale / 20;
        char caption[128];
        std::snprintf(caption, sizeof caption, "geodesic path, length %.4g", check.length);
        panel.caption = caption;
        for (const vg_path_point& p : path) panel.polyline.push_back(Vec3{p.position[0], p.position[1], p.position[2]});
        const Image image = renderPanels(mesh, {panel}, width, height, view);
        std::string error;
        if (!writePng(image, args.str("--png"), error)) {
            std::fprintf(stderr, "vorogeo path: %s\n", error.c_str());
            return 1;
        }
        std::printf("wrote %s (%dx%d)\n", args.str("--png").c_str(), image.width, image.height);
    }
    return check.ok ? 0 : 1;
}

}  // namespace vorogeo::tools
