// The baker as a library, for asset pipelines that would rather call than shell out:
//
//     vorogeo::Mesh mesh;
//     vorogeo::LoadReport loaded = vorogeo::loadMesh("statue.ply", {}, mesh);   // validates
//     if (!loaded.ok) fail(loaded.error);
//     std::atomic<bool> cancel{false};
//     vorogeo::BakeResult r = vorogeo::bake(mesh, vorogeo::BakeOptions{},
//         [](const char* stage, double fraction) { show(stage, fraction); }, &cancel);
//     vorogeo::writeFileAtomically("statue.vgeo", r.blob);
//
// bake() throws std::invalid_argument for bad options (naming the option and its range),
// std::runtime_error when the mesh cannot be baked, and BakeCancelled when `cancel` became
// true (checked at every progress step; nothing is written in any of these cases). The
// progress callback is called from the calling thread or, serialised, from worker
// threads. Same mesh, options and seed give the same bytes for any thread count (TBB's
// global thread limit, e.g. tbb::global_control, sets the count).
#pragma once

#include <atomic>
#include <stdexcept>
#include <vector>

#include "bake.h"
#include "blob_writer.h"
#include "mesh.h"
#include "mesh_io.h"

namespace vorogeo {

#define VOROGEO_BAKER_VERSION_MAJOR 0
#define VOROGEO_BAKER_VERSION_MINOR 1
#define VOROGEO_BAKER_VERSION_PATCH 0

struct BakeCancelled : std::runtime_error {
    BakeCancelled() : std::runtime_error("bake cancelled") {}
};

struct BakeResult {
    std::vector<uint8_t> blob;  // the bytes of a .vgeo file
    BakeReport report;          // sizes and stage times
};

BakeResult bake(const Mesh& mesh, const BakeOptions& options = BakeOptions(),
                const BakeProgress& progress = BakeProgress(), const std::atomic<bool>* cancel = nullptr);

}  // namespace vorogeo
