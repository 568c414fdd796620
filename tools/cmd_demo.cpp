// vorogeo demo [--out DIR]: the whole pipeline on a built-in mesh, one step at a time.
// Every module adds its step to kDemoSteps; steps for modules that do not exist yet say so.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "cli.h"
#include "generators.h"
#include "mesh_io.h"
#include "mesh_report.h"
#include "mesh_stats.h"

namespace vorogeo::tools {
namespace {

// State handed from step to step.
struct DemoContext {
    std::string outDir;  // empty: write nothing
    Mesh mesh;           // prepared (connectivity built) after the "mesh" step
    MeshStats stats;
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

bool notBuiltYet(DemoContext&) {
    std::printf("  not built yet\n");
    return true;
}

bool exactNotInDemoYet(DemoContext&) {
    std::printf("  not part of the demo yet; try: vorogeo exact MESH --source V\n");
    return true;
}

const DemoStep kDemoSteps[] = {
    {"mesh: generate the built-in bumpy torus", generateMesh},
    {"validate: the checks every loaded mesh goes through", validateMesh},
    {"info: mesh statistics", showStats},
    {"exact geodesics from one source vertex", exactNotInDemoYet},
    {"baker: precomputation into a blob", notBuiltYet},
    {"runtime: distance queries in microseconds", notBuiltYet},
};

}  // namespace

int runDemo(int argc, char** argv) {
    const cli::Args args(argc, argv, {"--out"}, {"--help"});
    if (args.flag("--help")) {
        std::printf(
            "usage: vorogeo demo [--out DIR]\n\n"
            "Runs the pipeline on a built-in bumpy torus (28,800 vertices).\n"
            "  --out DIR  also write the mesh to DIR/bumpy-torus.ply and validate it from there\n");
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
