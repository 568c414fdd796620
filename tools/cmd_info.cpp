// vorogeo info MESH [--json] [--repair]: load, validate and describe a mesh.
#include <chrono>
#include <cstdio>

#include "blob_info.h"
#include "cli.h"
#include "mesh_io.h"
#include "mesh_report.h"
#include "mesh_stats.h"

namespace vorogeo::tools {

int runInfo(int argc, char** argv) {
    const cli::Args args(argc, argv, {}, {"--json", "--repair", "--help"});
    if (args.flag("--help")) {
        std::printf(
            "usage: vorogeo info MESH [--json] [--repair]\n"
            "       vorogeo info BLOB.vgeo [--json]\n\n"
            "Loads MESH (.obj, .ply, .off, .stl), validates it and prints its statistics.\n"
            "For a baked blob: verifies it and prints its sizes and bake parameters.\n"
            "  --json     one JSON object on stdout instead of text\n"
            "  --repair   drop degenerate/duplicate faces, re-orient, split non-manifold parts\n"
            "Exit status: 0 ok, 1 the mesh cannot be loaded or is invalid, 2 bad arguments.\n");
        return 0;
    }
    if (args.positional().size() != 1) throw cli::UsageError("expected exactly one mesh file (usage: vorogeo info MESH [--json] [--repair])");
    const std::string& path = args.positional()[0];
    if (looksLikeBlob(path)) return printBlobInfo(path, args.flag("--json"));

    LoadOptions options;
    options.repair = args.flag("--repair");
    Mesh mesh;
    const auto start = std::chrono::steady_clock::now();
    const LoadReport report = loadMesh(path, options, mesh);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!report.ok) {
        std::fprintf(stderr, "vorogeo info: %s\n", report.error.c_str());
        return 1;
    }
    const MeshStats stats = computeStats(mesh);
    if (args.flag("--json")) {
        std::printf("%s\n", statsJson(path, stats, seconds, report.notices).c_str());
        return 0;
    }
    std::printf("%s: valid mesh, loaded in %.3f s\n", path.c_str(), seconds);
    for (const std::string& n : report.notices) std::printf("  note: %s\n", n.c_str());
    printStatsText(stdout, stats);
    return 0;
}

}  // namespace vorogeo::tools
