// vorogeo demo [--out DIR]: the whole pipeline on a built-in mesh, one step at a time.
// Every module adds its step to kDemoSteps; steps for modules that do not exist yet say so.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "bake.h"
#include "blob_reader.h"
#include "blob_writer.h"
#include "cli.h"
#include "generators.h"
#include "geodesic_exact.h"
#include "mesh_io.h"
#include "mesh_report.h"
#include "mesh_stats.h"
#include "runtime_graph.h"
#include "timing.h"
#include "vorogeo.h"

namespace vorogeo::tools {
namespace {

// State handed from step to step.
struct DemoContext {
    std::string outDir;  // empty: write nothing
    Mesh mesh;           // prepared (connectivity built) after the "mesh" step
    MeshStats stats;
    std::vector<double> exactFromZero;  // exact distances from vertex 0
    std::vector<uint8_t> blob;          // the baked blob
};

// A step prints its own results and returns false to stop the demo with exit status 1.
struct DemoStep {
    const char* title;
    bool (*run)(DemoContext&);
};

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool generateMesh(DemoContext& c) {
    const auto start = std::chrono::steady_clock::now();
    c.mesh = bumpyTorus();
    std::printf("  bumpy torus: %u vertices, %u faces (%.3f s)\n", c.mesh.vertexCount(), c.mesh.faceCount(),
                secondsSince(start));
    return true;
}

bool validateMesh(DemoContext& c) {
    // Re-validate from the raw arrays, as a file would be; with --out, through a real file.
    Mesh check;
    LoadReport report;
    if (!c.outDir.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(c.outDir, ec);
        const std::string path = (std::filesystem::path(c.outDir) / "bumpy-torus.ply").string();
        std::string error;
        if (!writeMesh(c.mesh, path, error)) {
            std::fprintf(stderr, "vorogeo demo: %s\n", error.c_str());
            return false;
        }
        std::printf("  wrote %s\n", path.c_str());
        report = loadMesh(path, LoadOptions{}, check);
    } else {
        check.positions = c.mesh.positions;
        check.faces = c.mesh.faces;
        report = prepareMesh("bumpy torus", LoadOptions{}, check);
    }
    if (!report.ok) {
        std::fprintf(stderr, "vorogeo demo: %s\n", report.error.c_str());
        return false;
    }
    std::printf("  valid: manifold, consistently oriented, no degenerate or duplicate faces\n");
    return true;
}

bool showStats(DemoContext& c) {
    c.stats = computeStats(c.mesh);
    printStatsText(stdout, c.stats);
    return true;
}

bool bakeBlob(DemoContext& ctx) {
    BakeReport report;
    const auto start = std::chrono::steady_clock::now();
    const std::vector<uint8_t> blob = bakeMesh(ctx.mesh, BakeOptions(), report);
    std::printf("  %zu first-layer and %zu second-layer patches, %llu graph nodes, %llu exact runs\n",
                report.firstPatches, report.secondPatches, (unsigned long long)report.secondPrune.nodes,
                (unsigned long long)report.sourceRuns);
    std::printf("  blob: %zu bytes (%.1f bytes per vertex), baked in %.2f s\n", blob.size(),
                double(blob.size()) / ctx.mesh.vertexCount(), secondsSince(start));
    tools::BlobContents contents;
    std::string error;
    if (!tools::unpackBlob(blob, contents, error)) {
        std::printf("  blob does not read back: %s\n", error.c_str());
        return false;
    }
    std::printf("  reads back: container checksum and flatbuffers verifier pass\n");
    ctx.blob = blob;
    if (!ctx.outDir.empty()) {
        const std::string path = ctx.outDir + "/bumpy-torus.vgeo";
        writeFileAtomically(path, blob);
        std::printf("  wrote %s\n", path.c_str());
    }
    return true;
}

bool queryRuntime(DemoContext& c) {
    RuntimeGraph graph;
    std::string error;
    if (!graph.open(c.blob, error)) {
        std::printf("  the runtime refuses the blob: %s\n", error.c_str());
        return false;
    }
    RuntimeWorkspace ws(graph);
    std::printf("  opened in %.2f ms; workspace %zu bytes per thread\n", graph.openSeconds() * 1e3,
                vg_workspace_size(graph.graph()));
    // Point-to-point from vertex 0 against the exact field of step 4, timed one by one.
    std::vector<double> micros;
    double sumRel = 0, maxRel = 0;
    size_t n = 0;
    for (uint32_t t = 1; t < c.mesh.vertexCount(); t += 97) {
        const auto start = std::chrono::steady_clock::now();
        const double d = ws.distance(0, t);
        micros.push_back(secondsSince(start) * 1e6);
        const double rel = std::fabs(d - c.exactFromZero[t]) / c.exactFromZero[t];
        sumRel += rel;
        maxRel = std::max(maxRel, rel);
        ++n;
    }
    const auto start = std::chrono::steady_clock::now();
    const std::vector<float> field = ws.field({0});
    const double fieldMs = secondsSince(start) * 1e3;
    double fieldMax = 0;
    for (uint32_t v = 1; v < c.mesh.vertexCount(); ++v)
        fieldMax = std::max(fieldMax, std::fabs(field[v] - c.exactFromZero[v]) / c.exactFromZero[v]);
    std::printf("  point-to-point from vertex 0 (%zu targets): median %.1f us; error against exact mean %.3f%%, max %.3f%%\n",
                n, percentile(micros, 50), 100.0 * sumRel / double(n), 100.0 * maxRel);
    std::printf("  one-to-all from vertex 0: %.2f ms; error against exact max %.3f%%\n", fieldMs, 100.0 * fieldMax);
    if (maxRel > 0.05 || fieldMax > 0.05) {
        std::fprintf(stderr, "vorogeo demo: runtime distances are off by more than 5%%\n");
        return false;
    }
    return true;
}

bool exactField(DemoContext& c) {
    // One source to all vertices, next to Dijkstra on the edge graph, which is what the
    // exact engine improves on; then the reverse run checks symmetry on the farthest pair.
    const ExactGeodesic geo(c.mesh);
    ExactWorkspace ws;
    ExactQuery query;
    query.sources.push_back(GeodesicSource::atVertex(0));
    std::vector<double> exact, edges;
    ExactStats stats;
    auto start = std::chrono::steady_clock::now();
    ws.run(geo, query, exact, &stats);
    const double exactSeconds = secondsSince(start);
    c.exactFromZero = exact;
    start = std::chrono::steady_clock::now();
    edgeDijkstra(c.mesh, 0, edges);
    const double dijkstraSeconds = secondsSince(start);
    uint32_t far = 0;
    double worstOver = 0, sumOver = 0;
    for (uint32_t v = 0; v < c.mesh.vertexCount(); ++v) {
        if (exact[v] > exact[far]) far = v;
        if (exact[v] > 0) {
            const double over = edges[v] / exact[v] - 1.0;
            worstOver = std::max(worstOver, over);
            sumOver += over;
        }
    }
    std::printf("  exact field from vertex 0: %.1f ms, %llu windows; edge Dijkstra %.1f ms\n", exactSeconds * 1e3,
                (unsigned long long)stats.windowsCreated, dijkstraSeconds * 1e3);
    std::printf("  farthest vertex %u at %.6f; edge paths are longer by %.2f%% on average, %.2f%% at worst\n", far,
                exact[far], 100.0 * sumOver / double(c.mesh.vertexCount() - 1), 100.0 * worstOver);
    query.sources = {GeodesicSource::atVertex(far)};
    std::vector<double> back;
    ws.run(geo, query, back);
    const double asym = std::fabs(back[0] - exact[far]) / exact[far];
    std::printf("  symmetry: d(0,%u) and d(%u,0) differ by %.1e (relative)\n", far, far, asym);
    if (asym > 1e-9) {
        std::fprintf(stderr, "vorogeo demo: exact distances are not symmetric\n");
        return false;
    }
    return true;
}

const DemoStep kDemoSteps[] = {
    {"mesh: generate the built-in bumpy torus", generateMesh},
    {"validate: the checks every loaded mesh goes through", validateMesh},
    {"info: mesh statistics", showStats},
    {"exact geodesics from one source vertex", exactField},
    {"baker: precomputation into a blob", bakeBlob},
    {"runtime: queries on the blob, against the exact field", queryRuntime},
};

}  // namespace

int runDemo(int argc, char** argv) {
    const cli::Args args(argc, argv, {"--out"}, {"--help"});
    if (args.flag("--help")) {
        std::printf(
            "usage: vorogeo demo [--out DIR]\n\n"
            "Runs the pipeline on a built-in bumpy torus (28,800 vertices).\n"
            "  --out DIR  also write the mesh to DIR/bumpy-torus.ply (validated from there) and the\n"
            "             blob to DIR/bumpy-torus.vgeo\n");
        return 0;
    }
    if (!args.positional().empty()) throw cli::UsageError("unexpected argument '" + args.positional()[0] + "'");
    if (args.has("--out") && args.str("--out").empty()) throw cli::UsageError("--out needs a directory");

    DemoContext context;
    context.outDir = args.str("--out");
    const int count = int(sizeof(kDemoSteps) / sizeof(kDemoSteps[0]));
    for (int i = 0; i < count; ++i) {
        std::printf("[%d/%d] %s\n", i + 1, count, kDemoSteps[i].title);
        std::fflush(stdout);
        if (!kDemoSteps[i].run(context)) return 1;
    }
    return 0;
}

}  // namespace vorogeo::tools
