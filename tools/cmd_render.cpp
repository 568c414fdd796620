// vorogeo render: a picture of a distance field (runtime, exact, and their error), and a
// vertex-coloured PLY of it.
#include <cmath>
#include <cstdio>

#include "cli.h"
#include "coloured_ply.h"
#include "geodesic_exact.h"
#include "render.h"
#include "runtime_graph.h"
#include "timing.h"
#include "tool_mesh.h"

namespace vorogeo::tools {

namespace {

const char* kUsage =
    "usage: vorogeo render MESH [--blob BLOB] --source V [--exact] [--out FIELD.png] [--ply OUT.ply]\n"
    "                      [--size WxH] [--view YAW,PITCH] [--isolines N] [--error-scale PERCENT]\n"
    "  Renders the geodesic distance field from vertex V, shaded with isolines (N of them\n"
    "  over the farthest distance, default 20). With --blob the field comes from the\n"
    "  runtime; --exact adds the exact field (MMP) beside it and a map of the relative\n"
    "  error (dark red = --error-scale percent, default 1). Without --blob the exact field\n"
    "  is drawn. --ply writes the mesh coloured by the first field. --size is per panel\n"
    "  (default 640x640); --view turns the mesh (degrees, default 0,0: looking down -z).\n";

}  // namespace

int runRender(int argc, char** argv) {
    cli::Args args(argc, argv, {"--blob", "--source", "--out", "--ply", "--size", "--view", "--isolines", "--error-scale"},
                   {"--exact", "--help", "--repair"});
    if (args.flag("--help")) {
        std::printf("%s", kUsage);
        return 0;
    }
    if (args.positional().size() != 1) throw cli::UsageError(std::string("expected one MESH\n") + kUsage);
    if (!args.has("--source")) throw cli::UsageError("--source V is required");
    if (!args.has("--out") && !args.has("--ply")) throw cli::UsageError("nothing to write: give --out and/or --ply");
    int width = 640, height = 640;
    View view;
    cli::pictureOptions(args, width, height, view.yawDegrees, view.pitchDegrees);
    const long long isolines = args.integer("--isolines", 20);
    if (isolines < 0 || isolines > 1000) throw cli::UsageError("--isolines must be in 0..1000");
    const double errorScale = args.number("--error-scale", 1.0) / 100.0;
    if (!(errorScale > 0)) throw cli::UsageError("--error-scale must be > 0");

    Mesh mesh;
    if (!loadMeshForCommand("render", args.positional()[0], args.flag("--repair"), mesh)) return 1;
    const long long source = args.integer("--source", 0);
    if (source < 0 || source >= mesh.vertexCount()) {
        std::fprintf(stderr, "vorogeo render: --source %lld out of range (the mesh has %u vertices)\n", source,
                     mesh.vertexCount());
        return 1;
    }

    std::vector<double> runtime, exact;
    if (args.has("--blob")) {
        RuntimeGraph graph;
        if (!loadBlobForMesh("render", args.str("--blob"), mesh, false, graph)) return 1;
        RuntimeWorkspace ws(graph);
        Stopwatch watch;
        const std::vector<float> f = ws.field({uint32_t(source)});
        std::printf("runtime field: %.2f ms\n", watch.seconds() * 1e3);
        runtime.assign(f.begin(), f.end());
    }
    if (!args.has("--blob") || args.flag("--exact")) {
        Stopwatch watch;
        exact = exactDistancesFrom(mesh, uint32_t(source));
        std::printf("exact field: %.2f ms\n", watch.seconds() * 1e3);
    }

    // One colour scale and one isoline spacing for every panel: the exact field's when there is one.
    std::vector<Panel> panels;
    const double maxFinite = largestFinite(exact.empty() ? runtime : exact);
    auto fieldPanel = [&](const std::vector<double>& field, const std::string& caption) {
        Panel p;
        p.vertexColour = colourField(field, maxFinite);
        p.isoValue = field;
        p.isoSpacing = isolines > 0 ? maxFinite / double(isolines) : 0;
        p.caption = caption;
        return p;
    };
    if (!runtime.empty()) panels.push_back(fieldPanel(runtime, "vorogeo runtime, source " + std::to_string(source)));
    if (!exact.empty()) panels.push_back(fieldPanel(exact, "exact (MMP), source " + std::to_string(source)));
    if (!runtime.empty() && !exact.empty()) {
        Panel err;
        double sum = 0, worst = 0;
        size_t counted = 0;
        for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
            double rel = 0;
            if (std::isfinite(exact[v]) && exact[v] > 0) {
                rel = std::fabs(runtime[v] - exact[v]) / exact[v];
                sum += rel, worst = std::max(worst, rel), ++counted;
            } else if (std::isfinite(exact[v]) != std::isfinite(runtime[v])) {
                rel = INFINITY;
            }
            err.vertexColour.push_back(errorColour(rel / errorScale));
        }
        char caption[128];
        std::snprintf(caption, sizeof caption, "relative error (dark red = %g%%)", errorScale * 100);
        err.caption = caption;
        panels.push_back(err);
        std::printf("relative error over %zu vertices: mean %.4f%%, max %.4f%%\n", counted,
                    counted ? 100 * sum / double(counted) : 0.0, 100 * worst);
    }

    if (args.has("--out")) {
        const Image image = renderPanels(mesh, panels, width, height, view);
        std::string error;
        if (!writePng(image, args.str("--out"), error)) {
            std::fprintf(stderr, "vorogeo render: %s\n", error.c_str());
            return 1;
        }
        std::printf("wrote %s (%dx%d, %zu panels)\n", args.str("--out").c_str(), image.width, image.height,
                    panels.size());
    }
    if (args.has("--ply")) {
        writeColouredPly(mesh, panels[0].vertexColour, args.str("--ply"));
        std::printf("wrote %s (vertex colours of the %s field)\n", args.str("--ply").c_str(),
                    runtime.empty() ? "exact" : "runtime");
    }
    return 0;
}

}  // namespace vorogeo::tools
