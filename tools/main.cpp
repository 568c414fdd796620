// vorogeo: git-style front end; each subcommand lives in its own cmd_*.cpp.
#include <cstdio>
#include <cstring>
#include <exception>

#include "cli.h"
#include "commands.h"
#include "vorogeo.h"

namespace vorogeo::tools {
// Declarations of the subcommands (one file each).
// (keep in the same order as the table below)
int runInfo(int argc, char** argv);
int runDemo(int argc, char** argv);
int runExact(int argc, char** argv);
int runBenchExact(int argc, char** argv);
int runBake(int argc, char** argv);
int runEval(int argc, char** argv);
int runEvalPoints(int argc, char** argv);
int runPath(int argc, char** argv);
int runRender(int argc, char** argv);
int runBench(int argc, char** argv);
int runVoronoi(int argc, char** argv);
int runSubdivide(int argc, char** argv);
}  // namespace vorogeo::tools

namespace {

using vorogeo::tools::Command;

const Command kCommands[] = {
    {"info", "load and validate a mesh, print its statistics", vorogeo::tools::runInfo},
    {"demo", "run the pipeline on a built-in mesh", vorogeo::tools::runDemo},
    {"exact", "exact geodesic distances (MMP); check against golden pairs", vorogeo::tools::runExact},
    {"bake", "precompute a mesh's patch graph into a .vgeo blob", vorogeo::tools::runBake},
    {"eval", "accuracy and query time of a baked blob against exact distances", vorogeo::tools::runEval},
    {"eval-points", "accuracy and query time of surface-point queries against the exact engine",
     vorogeo::tools::runEvalPoints},
    {"path", "geodesic path between two surface points (printed, optionally drawn over the distance field)",
     vorogeo::tools::runPath},
    {"bench", "runtime vs exact engine vs edge Dijkstra on the same queries, with ratios", vorogeo::tools::runBench},
    {"voronoi", "geodesic Voronoi cells by growing spheres (thesis 3.8) vs one labelling query", vorogeo::tools::runVoronoi},
    {"render", "picture of a distance field (runtime, exact, error) as PNG or coloured PLY", vorogeo::tools::runRender},
    {"bench-exact", "benchmark the exact engine against edge Dijkstra", vorogeo::tools::runBenchExact},
    {"subdivide", "Loop subdivision (4x the faces per round), for scaling measurements", vorogeo::tools::runSubdivide},
    {nullptr, nullptr, nullptr},  // sentinel, keeps the array non-empty
};

void printUsage(FILE* out) {
    std::fprintf(out, "usage: vorogeo <command> [arguments]\n\ncommands:\n");
    for (const Command& c : kCommands)
        if (c.name) std::fprintf(out, "  %-12s %s\n", c.name, c.summary);
    std::fprintf(out, "\nvorogeo <command> --help shows the arguments of a command.\n");
}

}  // namespace

const Command* vorogeo::tools::commands() { return kCommands; }
int vorogeo::tools::commandCount() { return int(sizeof(kCommands) / sizeof(kCommands[0])) - 1; }

int main(int argc, char** argv) {
    if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") ||
        !std::strcmp(argv[1], "help")) {
        printUsage(argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    if (!std::strcmp(argv[1], "--version")) {
        std::printf("vorogeo %s\n", vg_version_string());
        return 0;
    }
    for (const Command& c : kCommands) {
        if (!c.name || std::strcmp(c.name, argv[1])) continue;
        try {
            return c.run(argc - 2, argv + 2);
        } catch (const vorogeo::cli::UsageError& e) {
            std::fprintf(stderr, "vorogeo %s: %s\n", c.name, e.what());
            return 2;
        } catch (const std::exception& e) {
            std::fprintf(stderr, "vorogeo %s: error: %s\n", c.name, e.what());
            return 1;
        }
    }
    std::fprintf(stderr, "vorogeo: unknown command '%s'\n", argv[1]);
    printUsage(stderr);
    return 2;
}
