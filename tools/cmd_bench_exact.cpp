// vorogeo bench-exact: single-source all-destinations time of the two exact engines
// (wavefront, MMP) next to plain Dijkstra on the edge graph, in the same run, plus windows
// and memory; and the time per source on patches of the sizes the baker uses.
#include <cstdio>
#include <dirent.h>
#include <algorithm>
#include <queue>
#include <string>
#include <vector>

#include "cli.h"
#include "generators.h"
#include "geodesic_exact.h"
#include "geodesic_wavefront.h"
#include "timing.h"
#include "tool_mesh.h"

namespace vorogeo::tools {

namespace {

const char* kUsage =
    "usage: vorogeo bench-exact [MESH ...] [--meshes DIR] [--sources N] [--seed S] [--json]\n"
    "  For each mesh (default: every .ply in ../shared/meshes): median single-source time of\n"
    "  the wavefront and MMP exact engines and of Dijkstra on the edge graph over the same N\n"
    "  sources (1 thread, alternating), windows per source, workspace memory, and each exact\n"
    "  engine's time per source on patches of 200, 1,000 and 5,000 vertices (setup included).\n";

// Faces of a patch grown breadth-first from `seedFace` until it has `vertices` vertices.
std::vector<uint32_t> growPatch(const Mesh& mesh, uint32_t seedFace, uint32_t vertices) {
    std::vector<uint8_t> inPatch(mesh.faceCount(), 0), vertexSeen(mesh.vertexCount(), 0);
    std::vector<uint32_t> faces;
    std::queue<uint32_t> frontier;
    frontier.push(seedFace);
    inPatch[seedFace] = 1;
    uint32_t count = 0;
    while (!frontier.empty() && count < vertices) {
        uint32_t f = frontier.front();
        frontier.pop();
        faces.push_back(f);
        for (int k = 0; k < 3; ++k) {
            uint32_t v = mesh.faces[f][k];
            if (!vertexSeen[v]) {
                vertexSeen[v] = 1;
                ++count;
            }
            int32_t t = mesh.twin[3 * f + k];
            if (t >= 0 && !inPatch[Mesh::faceOf(t)]) {
                inPatch[Mesh::faceOf(t)] = 1;
                frontier.push(uint32_t(Mesh::faceOf(t)));
            }
        }
    }
    return faces;
}

std::vector<std::string> defaultMeshes(const std::string& dir) {
    std::vector<std::string> out;
    if (DIR* d = opendir(dir.c_str())) {
        while (dirent* e = readdir(d)) {
            std::string name = e->d_name;
            if (name.size() > 4 && name.compare(name.size() - 4, 4, ".ply") == 0) out.push_back(dir + "/" + name);
        }
        closedir(d);
    }
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace

int runBenchExact(int argc, char** argv) {
    cli::Args args(argc, argv, {"--meshes", "--sources", "--seed"}, {"--json", "--help"});
    if (args.flag("--help")) {
        std::printf("%s", kUsage);
        return 0;
    }
    const long long nSources = args.integer("--sources", 5);
    if (nSources < 1) throw cli::UsageError("--sources must be >= 1");
    std::vector<std::string> meshes = args.positional();
    if (meshes.empty()) {
        const std::string dir = args.str("--meshes", "../shared/meshes");
        meshes = defaultMeshes(dir);
        if (meshes.empty()) {
            std::fprintf(stderr, "vorogeo bench-exact: no meshes given and no .ply files in %s\n", dir.c_str());
            return 1;
        }
    }
    const bool json = args.flag("--json");
    if (!json)
        std::printf("%-16s %8s %9s %9s %9s %7s %7s %10s %10s %7s %7s %16s %16s %16s\n", "mesh", "V", "wave_ms",
                    "mmp_ms", "dijk_ms", "mmp/wv", "wv/dijk", "wave_win", "mmp_win", "wv_MB", "mmp_MB",
                    "p200 wv/mmp", "p1000 wv/mmp", "p5000 wv/mmp");
    for (const std::string& path : meshes) {
        Mesh mesh;
        if (!loadMeshForCommand("bench-exact", path, false, mesh)) return 1;
        Random rng(uint64_t(args.integer("--seed", 1)));
        std::vector<uint32_t> sources;
        for (long long i = 0; i < nSources; ++i) sources.push_back(uint32_t(rng.uniform() * mesh.vertexCount()));

        const ExactGeodesic geo(mesh);
        ExactWorkspace ws;
        WavefrontWorkspace wave;
        std::vector<double> dist, waveMs, mmpMs, dijkstraMs;
        double waveWindows = 0, mmpWindows = 0;
        for (uint32_t s : sources) {  // alternate the methods so load affects them alike
            ExactStats stats;
            Stopwatch a;
            wave.run(geo, {s}, dist, &stats);
            waveMs.push_back(a.seconds() * 1e3);
            waveWindows += double(stats.windowsCreated);
            ExactQuery q;
            q.sources.push_back(GeodesicSource::atVertex(s));
            Stopwatch b;
            ws.run(geo, q, dist, &stats);
            mmpMs.push_back(b.seconds() * 1e3);
            mmpWindows += double(stats.windowsCreated);
            Stopwatch c;
            edgeDijkstra(mesh, s, dist);
            dijkstraMs.push_back(c.seconds() * 1e3);
        }
        double patchMs[2][3] = {{0, 0, 0}, {0, 0, 0}};
        const uint32_t sizes[3] = {200, 1000, 5000};
        for (int k = 0; k < 3; ++k) {
            if (sizes[k] > mesh.vertexCount()) continue;
            std::vector<double> times[2];
            for (int rep = 0; rep < 10; ++rep) {  // setup included: patches are built per run in the baker
                auto faces = growPatch(mesh, uint32_t(rng.uniform() * mesh.faceCount()), sizes[k]);
                const uint32_t source = uint32_t(rng.uniform() * double(sizes[k]));
                for (int e = 0; e < 2; ++e) {
                    Stopwatch c;
                    ExactGeodesic patch(mesh, faces);
                    const uint32_t s = std::min(source, patch.vertexCount() - 1);
                    if (e == 0) {
                        wave.run(patch, {s}, dist);
                    } else {
                        ExactQuery q;
                        q.sources.push_back(GeodesicSource::atVertex(s));
                        ws.run(patch, q, dist);
                    }
                    times[e].push_back(c.seconds() * 1e3);
                }
            }
            for (int e = 0; e < 2; ++e) patchMs[e][k] = percentile(times[e], 50);
        }
        const double w50 = percentile(waveMs, 50), m50 = percentile(mmpMs, 50), d50 = percentile(dijkstraMs, 50);
        const double waveMb = double(wave.memoryBytes()) / (1024.0 * 1024.0);
        const double mmpMb = double(ws.memoryBytes()) / (1024.0 * 1024.0);
        const double n = double(sources.size());
        std::string name = path.substr(path.find_last_of('/') + 1);
        if (json) {
            std::printf("{\"mesh\":\"%s\",\"vertices\":%u,\"sources\":%zu,\"exact_ssad_p50_ms\":%.3f,"
                        "\"mmp_ssad_p50_ms\":%.3f,\"dijkstra_ssad_p50_ms\":%.3f,\"mmp_over_wavefront\":%.2f,"
                        "\"exact_over_dijkstra\":%.2f,\"windows_per_source\":%.0f,\"mmp_windows_per_source\":%.0f,"
                        "\"workspace_mb\":%.1f,\"mmp_workspace_mb\":%.1f,\"peak_rss_mb\":%.1f,"
                        "\"patch200_ms\":%.3f,\"patch1000_ms\":%.3f,\"patch5000_ms\":%.3f,"
                        "\"mmp_patch200_ms\":%.3f,\"mmp_patch1000_ms\":%.3f,\"mmp_patch5000_ms\":%.3f}\n",
                        name.c_str(), mesh.vertexCount(), sources.size(), w50, m50, d50, m50 / w50, w50 / d50,
                        waveWindows / n, mmpWindows / n, waveMb, mmpMb, peakRssMb(), patchMs[0][0], patchMs[0][1],
                        patchMs[0][2], patchMs[1][0], patchMs[1][1], patchMs[1][2]);
        } else {
            std::printf("%-16s %8u %9.2f %9.2f %9.2f %7.2f %7.1f %10.0f %10.0f %7.1f %7.1f", name.c_str(),
                        mesh.vertexCount(), w50, m50, d50, m50 / w50, w50 / d50, waveWindows / n, mmpWindows / n,
                        waveMb, mmpMb);
            for (int k = 0; k < 3; ++k)
                patchMs[0][k] > 0 ? std::printf(" %7.3f/%-8.3f", patchMs[0][k], patchMs[1][k])
                                  : std::printf(" %16s", "-");  // mesh too small
            std::printf("\n");
        }
        std::fflush(stdout);
    }
    return 0;
}

}  // namespace vorogeo::tools
