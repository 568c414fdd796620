// vorogeo subdivide MESH -o OUT [--rounds N]: Loop subdivision (4x the faces per round),
// for the scaling measurements (igea x4, x16) without committing large meshes.
#include <chrono>
#include <cstdio>
#include <string>

#include "cli.h"
#include "mesh_io.h"
#include "subdivide.h"
#include "tool_mesh.h"

namespace vorogeo::tools {

int runSubdivide(int argc, char** argv) {
    const cli::Args args(argc, argv, {"-o", "--out", "--rounds"}, {"--repair", "--help"});
    if (args.flag("--help")) {
        std::printf(
            "usage: vorogeo subdivide MESH -o OUT [--rounds N] [--repair]\n\n"
            "Loop subdivision (OpenMesh's uniform Loop subdivider): each round splits every\n"
            "triangle into four and smooths the surface, so N rounds give ~4^N x the vertices.\n"
            "  -o, --out  output mesh; the format follows the extension (.ply binary, .obj, .off, .stl)\n"
            "  --rounds   rounds of subdivision, 1-8 (default 1)\n"
            "  --repair   repair the input first (as vorogeo info --repair)\n"
            "Exit status: 0 ok, 1 the mesh cannot be loaded or written, 2 bad arguments.\n");
        return 0;
    }
    if (args.positional().size() != 1) throw cli::UsageError("expected exactly one mesh file (usage: vorogeo subdivide MESH -o OUT [--rounds N])");
    const std::string out = args.has("-o") ? args.str("-o") : args.str("--out");
    if (out.empty()) throw cli::UsageError("missing the output file (-o OUT)");
    const long long rounds = args.integer("--rounds", 1);
    if (rounds < 1 || rounds > 8) throw cli::UsageError("--rounds must be between 1 and 8");

    Mesh mesh;
    if (!loadMeshForCommand("subdivide", args.positional()[0], args.flag("--repair"), mesh)) return 1;
    const auto start = std::chrono::steady_clock::now();
    Mesh fine;
    std::string error;
    if (!loopSubdivide(mesh, unsigned(rounds), fine, error)) {
        std::fprintf(stderr, "vorogeo subdivide: %s: %s\n", args.positional()[0].c_str(), error.c_str());
        return 1;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!writeMesh(fine, out, error)) {
        std::fprintf(stderr, "vorogeo subdivide: %s\n", error.c_str());
        return 1;
    }
    std::printf("%s: %u vertices, %u faces -> %s: %u vertices, %u faces (%lld rounds, %.2f s)\n",
                args.positional()[0].c_str(), mesh.vertexCount(), mesh.faceCount(), out.c_str(), fine.vertexCount(),
                fine.faceCount(), rounds, seconds);
    return 0;
}

}  // namespace vorogeo::tools
