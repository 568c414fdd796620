// libFuzzer target: a mesh file is untrusted input. The first byte chooses the file name's
// extension (OBJ, OFF, PLY, STL, or none so that the content is sniffed) and whether
// --repair is on; the rest is the file's content. Loading must give a mesh or a one-line
// error naming the file, and a loaded mesh must be a valid prepared mesh: its statistics
// are computed and its connectivity is checked.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "mesh_io.h"
#include "mesh_stats.h"

namespace {

void require(bool ok) {
    if (!ok) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    static const char* const names[] = {"fuzz.obj", "fuzz.off", "fuzz.ply", "fuzz.stl", "fuzz"};
    const std::string name = names[(data[0] & 0x7F) % 5];
    vorogeo::LoadOptions options;
    options.repair = (data[0] & 0x80) != 0;
    vorogeo::Mesh mesh;
    const vorogeo::LoadReport report =
        vorogeo::loadMeshFromMemory(name, std::string(reinterpret_cast<const char*>(data + 1), size - 1), options, mesh);
    if (!report.ok) {
        require(!report.error.empty() && report.error.compare(0, name.size(), name) == 0);
        require(report.error.find('\n') == std::string::npos);
        return 0;
    }
    require(mesh.faceCount() > 0);
    require(mesh.twin.size() == mesh.halfedgeCount() && mesh.vertexOut.size() == mesh.vertexCount());
    for (uint32_t h = 0; h < mesh.halfedgeCount(); ++h) {
        const int32_t t = mesh.twin[h];
        require(t == -1 || (t >= 0 && uint32_t(t) < mesh.halfedgeCount() && mesh.twin[size_t(t)] == int32_t(h)));
    }
    const vorogeo::MeshStats stats = vorogeo::computeStats(mesh);
    require(stats.components >= 1);
    return 0;
}
