// One revision's wavefront engine behind a small C interface, for scripts/ab-wavefront.sh:
// the script builds this file against each revision's baker into a shared library of its
// own (symbols kept local), so that the driver can load two engines into one process and
// time them in turns on the same domains.
#include "geodesic_wavefront.h"
#include "mesh_io.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

namespace {

using namespace vorogeo;

struct Shim {
    Mesh mesh;
    std::vector<std::vector<uint32_t>> vertexFaces;
    std::unique_ptr<ExactGeodesic> domain;
    WavefrontWorkspace workspace;
    std::vector<double> distances;
    std::vector<WavefrontWorkspace::Target> targets;
};

// The faces met by a breadth-first walk from `seed` until about `want` vertices are
// reached: a disk-like patch, as the baker's (the same faces for any revision, as this
// code is the same on both sides).
std::vector<uint32_t> facesAround(const Shim& s, uint32_t seed, uint32_t want) {
    std::vector<uint8_t> seenVertex(s.mesh.vertexCount()), seenFace(s.mesh.faceCount());
    std::vector<uint32_t> faces, queue{seed};
    seenVertex[seed] = 1;
    uint32_t reached = 1;
    for (size_t head = 0; head < queue.size() && reached < want; ++head)
        for (uint32_t f : s.vertexFaces[queue[head]]) {
            if (!seenFace[f]) {
                seenFace[f] = 1;
                faces.push_back(f);
            }
            for (int k = 0; k < 3; ++k) {
                const uint32_t u = s.mesh.faces[f][k];
                if (!seenVertex[u]) {
                    seenVertex[u] = 1;
                    ++reached;
                    queue.push_back(u);
                }
            }
        }
    std::sort(faces.begin(), faces.end());
    return faces;
}

}  // namespace

#define ABW_EXPORT extern "C" __attribute__((visibility("default")))

// Loads a mesh; null with the reason in `error` on failure.
ABW_EXPORT void* abw_open(const char* path, char* error, size_t errorSize) {
    auto shim = std::make_unique<Shim>();
    const LoadReport report = loadMesh(path, LoadOptions{}, shim->mesh);
    if (!report.ok) {
        std::snprintf(error, errorSize, "%s", report.error.c_str());
        return nullptr;
    }
    shim->vertexFaces.resize(shim->mesh.vertexCount());
    for (uint32_t f = 0; f < shim->mesh.faceCount(); ++f)
        for (int k = 0; k < 3; ++k) shim->vertexFaces[shim->mesh.faces[f][k]].push_back(f);
    return shim.release();
}

ABW_EXPORT uint32_t abw_mesh_vertices(void* shim) { return static_cast<Shim*>(shim)->mesh.vertexCount(); }

// Makes the patch of about `want` vertices around `seed` the domain; its vertex count.
ABW_EXPORT uint32_t abw_domain(void* shim, uint32_t seed, uint32_t want) {
    Shim& s = *static_cast<Shim*>(shim);
    s.domain = std::make_unique<ExactGeodesic>(s.mesh, facesAround(s, seed, want));
    return s.domain->vertexCount();
}

// A whole run from domain vertex `source`; its distances into `out` (the domain's count).
ABW_EXPORT void abw_run(void* shim, uint32_t source, double* out) {
    Shim& s = *static_cast<Shim*>(shim);
    s.workspace.run(*s.domain, {source}, s.distances);
    std::memcpy(out, s.distances.data(), s.distances.size() * sizeof(double));
}

// A run to `count` targets with a bound each; their distances into `out` (count entries).
ABW_EXPORT void abw_run_to_targets(void* shim, uint32_t source, const uint32_t* targets, const double* bounds,
                                   uint32_t count, double* out) {
    Shim& s = *static_cast<Shim*>(shim);
    s.targets.resize(count);
    for (uint32_t i = 0; i < count; ++i) s.targets[i] = WavefrontWorkspace::Target{targets[i], bounds[i]};
    s.workspace.runToTargets(*s.domain, source, s.targets, s.distances);
    for (uint32_t i = 0; i < count; ++i) out[i] = s.distances[targets[i]];
}

ABW_EXPORT void abw_close(void* shim) { delete static_cast<Shim*>(shim); }
