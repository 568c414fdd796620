// vorogeo voronoi: geodesic Voronoi partition by growing spheres with bounded
// point-to-point queries (thesis 3.8), timed against one multi-source labelling query.
#include <cmath>
#include <cstdio>
#include <string>

#include "blob_writer.h"
#include "cli.h"
#include "render.h"
#include "runtime_graph.h"
#include "timing.h"
#include "tool_mesh.h"
#include "voronoi.h"

namespace vorogeo::tools {

namespace {

const char* kUsage =
    "usage: vorogeo voronoi MESH BLOB --seeds K --out LABELS.csv [--png OUT.png] [--seed S]\n"
    "                       [--growth G] [--size WxH] [--view YAW,PITCH]\n"
    "  Places K Poisson-disk seeds and labels every vertex with its geodesically nearest\n"
    "  seed by growing spheres (thesis 3.8: radius r/2, then +G per round, default 0.25)\n"
    "  with bounded point-to-point queries; then labels again with one multi-source query\n"
    "  (vg_distance_field_nearest) and reports both times and how far they agree.\n"
    "  LABELS.csv: vertex,seed,seed_vertex,distance (seed = K where no seed is reachable).\n"
    "  --png renders the cells.\n";

}  // namespace

int runVoronoi(int argc, char** argv) {
    cli::Args args(argc, argv, {"--seeds", "--out", "--png", "--seed", "--growth", "--size", "--view"},
                   {"--help", "--repair"});
    if (args.flag("--help")) {
        std::printf("%s", kUsage);
        return 0;
    }
    if (args.positional().size() != 2) throw cli::UsageError(std::string("expected MESH and BLOB\n") + kUsage);
    if (!args.has("--seeds")) throw cli::UsageError("--seeds K is required");
    if (!args.has("--out")) throw cli::UsageError("--out LABELS.csv is required");
    const long long k = args.integer("--seeds", 0);
    if (k < 1 || k > 100000) throw cli::UsageError("--seeds must be in 1..100000");
    const double growth = args.number("--growth", 0.25);
    if (!(growth > 0.01 && growth <= 10)) throw cli::UsageError("--growth must be in (0.01, 10]");
    int width = 640, height = 640;
    View view;
    cli::pictureOptions(args, width, height, view.yawDegrees, view.pitchDegrees);

    Mesh mesh;
    if (!loadMeshForCommand("voronoi", args.positional()[0], args.flag("--repair"), mesh)) return 1;
    RuntimeGraph graph;
    if (!loadBlobForMesh("voronoi", args.positional()[1], mesh, false, graph)) return 1;
    checkWritable(args.str("--out"));

    double radius = 0;
    const std::vector<uint32_t> seeds = poissonDiskSeeds(mesh, uint32_t(k), uint64_t(args.integer("--seed", 1)), radius);
    RuntimeWorkspace ws(graph);
    Stopwatch sphereWatch;
    const VoronoiResult spheres = growingSpheres(mesh, graph.graph(), ws.get(), seeds, radius, growth);
    const double sphereSeconds = sphereWatch.seconds();

    const uint32_t V = mesh.vertexCount();
    std::vector<float> fieldDistance(V);
    std::vector<uint32_t> fieldLabel(V);
    Stopwatch fieldWatch;
    const vg_status st = vg_distance_field_nearest(graph.graph(), ws.get(), seeds.data(), seeds.size(),
                                                   fieldDistance.data(), fieldLabel.data());
    const double fieldSeconds = fieldWatch.seconds();
    if (st != VG_OK) {
        std::fprintf(stderr, "vorogeo voronoi: vg_distance_field_nearest: %s\n", vg_status_string(st));
        return 1;
    }
    // Labels differ only between near-equidistant seeds (point-to-point and the field
    // unfold border crossings at different places); count those separately.
    size_t same = 0, nearTie = 0;
    for (uint32_t v = 0; v < V; ++v) {
        if (spheres.label[v] == fieldLabel[v]) {
            ++same;
        } else if (std::fabs(double(spheres.distance[v]) - fieldDistance[v]) <= 0.01 * fieldDistance[v]) {
            ++nearTie;
        }
    }

    std::string csv = "vertex,seed,seed_vertex,distance\n";
    char line[96];
    for (uint32_t v = 0; v < V; ++v) {
        const uint32_t l = spheres.label[v];
        std::snprintf(line, sizeof line, "%u,%u,%lld,%.9g\n", v, l, l < seeds.size() ? (long long)seeds[l] : -1LL,
                      double(spheres.distance[v]));
        csv += line;
    }
    writeFileAtomically(args.str("--out"), std::vector<uint8_t>(csv.begin(), csv.end()));

    std::printf("%s: %u vertices, %zu Poisson-disk seeds (radius %.4g)\n", args.positional()[0].c_str(), V,
                seeds.size(), radius);
    std::printf("growing spheres:       %9.1f ms, %u rounds, %llu point-to-point queries (%llu bounded)\n",
                sphereSeconds * 1e3, spheres.rounds, (unsigned long long)spheres.queries,
                (unsigned long long)spheres.boundedQueries);
    std::printf("multi-source labels:   %9.2f ms (%.0fx faster)\n", fieldSeconds * 1e3, sphereSeconds / fieldSeconds);
    std::printf("labels agree on %.3f%% of the vertices; %zu of the others are ties within 1%%\n",
                100.0 * double(same) / V, nearTie);
    std::printf("wrote %s\n", args.str("--out").c_str());

    if (args.has("--png")) {
        Panel p;
        for (uint32_t v = 0; v < V; ++v) {
            const uint32_t l = spheres.label[v];
            p.vertexColour.push_back(l < seeds.size() ? categoryColour(l) : unreachableColour());
            p.isoValue.push_back(l < seeds.size() ? double(l) : INFINITY);  // a line where the label changes
        }
        for (uint32_t s : seeds) p.vertexColour[s] = Rgb{20, 20, 20};
        p.isoSpacing = 1;
        p.caption = "geodesic Voronoi cells of " + std::to_string(seeds.size()) + " seeds";
        std::string error;
        if (!writePng(renderPanels(mesh, {p}, width, height, view), args.str("--png"), error)) {
            std::fprintf(stderr, "vorogeo voronoi: %s\n", error.c_str());
            return 1;
        }
        std::printf("wrote %s\n", args.str("--png").c_str());
    }
    return 0;
}

}  // namespace vorogeo::tools
