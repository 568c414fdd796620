// An asset-pipeline step that bakes in-process with the baker library instead of running
// `vorogeo bake`: load and validate a mesh, bake with a progress display and a cancel
// flag, write the blob atomically, then check it with the runtime.
//   bake_asset MESH OUT.vgeo
#include <atomic>
#include <cstdio>
#include <string>

#include "vorogeo.h"
#include "vorogeo_baker.h"

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: bake_asset MESH OUT.vgeo\n");
        return 2;
    }
    vorogeo::Mesh mesh;
    const vorogeo::LoadReport loaded = vorogeo::loadMesh(argv[1], vorogeo::LoadOptions(), mesh);
    if (!loaded.ok) {
        std::fprintf(stderr, "bake_asset: %s\n", loaded.error.c_str());
        return 1;
    }
    std::atomic<bool> cancel{false};  // an editor would set this from its UI thread
    std::string lastStage;
    try {
        const vorogeo::BakeResult r = vorogeo::bake(
            mesh, vorogeo::BakeOptions(),
            [&](const char* stage, double fraction) {
                if (lastStage != stage || fraction >= 1.0) std::printf("  %-24s %3.0f%%\n", stage, 100 * fraction);
                lastStage = stage;
            },
            &cancel);
        vorogeo::writeFileAtomically(argv[2], r.blob);
        std::printf("baked %u vertices into %zu bytes\n", r.report.vertices, r.blob.size());

        // The runtime opens what the baker wrote.
        size_t need = 0;
        std::vector<unsigned char> memory;
        const vg_graph* g = nullptr;
        vg_status st = vg_open_size(r.blob.data(), r.blob.size(), &need);
        memory.resize(need);
        if (st == VG_OK) st = vg_open(r.blob.data(), r.blob.size(), memory.data(), need, &g);
        if (st != VG_OK) {
            std::fprintf(stderr, "bake_asset: %s\n", vg_status_string(st));
            return 1;
        }
        std::printf("runtime opened it: %u vertices\n", vg_vertex_count(g));
    } catch (const vorogeo::BakeCancelled&) {
        std::fprintf(stderr, "bake_asset: cancelled, nothing written\n");
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bake_asset: %s\n", e.what());
        return 1;
    }
    return 0;
}
