#include "partition.h"


#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>

#include "geodesic_exact.h"
#include "mesh_stats.h"
#include "patch_topology.h"
#include "seed_sampling.h"
#include "voronoi_domain.h"
#include "parallel.h"

namespace vorogeo {
namespace {

// Independent, well-mixed seeds for the layers and patches (splitmix64).
uint64_t mixSeed(uint64_t seed, uint64_t stream) {
    uint64_t z = seed + 0x9E3779B97F4A7C15ull * (stream + 1);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Patches from per-face labels: sorted faces, and each vertex as border (faces of more
// than one patch around it, or on a mesh boundary) or interior.
std::vector<Patch> buildPatches(const Mesh& mesh, const std::vector<uint32_t>& faceLabel,
                                const std::vector<uint32_t>& seeds, const std::vector<uint32_t>& parents) {
    std::vector<Patch> patches(seeds.size());
    for (size_t i = 0; i < seeds.size(); ++i) {
        patches[i].seedVertex = seeds[i];
        patches[i].parent = parents.empty() ? UINT32_MAX : parents[i];
    }
    for (uint32_t f = 0; f < mesh.faceCount(); ++f) patches[faceLabel[f]].faces.push_back(f);
    std::vector<uint32_t> around;
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        const int32_t h0 = mesh.vertexOut[v];
        if (h0 < 0) continue;
        around.clear();
        int32_t h = h0;
        do {
            const uint32_t p = faceLabel[h / 3];
            if (std::find(around.begin(), around.end(), p) == around.end()) around.push_back(p);
            h = mesh.nextAroundVertex(h);
        } while (h >= 0 && h != h0);
        const bool border = around.size() > 1 || mesh.boundaryVertex[v];
        for (uint32_t p : around) (border ? patches[p].border : patches[p].interior).push_back(v);
    }
    return patches;
}

}  // namespace

Partition partitionMesh(const Mesh& mesh, const PartitionOptions& options, const PartitionProgress& progress) {
    if (mesh.twin.size() != mesh.halfedgeCount() || mesh.vertexOut.size() != mesh.vertexCount())
        throw std::invalid_argument("partition: the mesh has no connectivity (prepare it first)");
    if (mesh.faceCount() == 0) throw std::invalid_argument("partition: the mesh has no faces");
    if (options.sampling != PartitionOptions::Sampling::FarthestPoint &&
        options.sampling != PartitionOptions::Sampling::Random)
        throw std::invalid_argument("partition: unknown sampling method");
    uint32_t used = 0;
    for (int32_t h : mesh.vertexOut) used += h >= 0;
    if (options.firstLayerSeeds > used)
        throw std::invalid_argument("partition: " + std::to_string(options.firstLayerSeeds) +
                                    " first-layer seeds for " + std::to_string(used) + " vertices");
    if (options.secondLayerSeeds > used)
        throw std::invalid_argument("partition: " + std::to_string(options.secondLayerSeeds) +
                                    " second-layer seeds for " + std::to_string(used) + " vertices");
    std::mutex progressMutex;
    auto report = [&](const char* stage, double fraction) {
        if (!progress) return;
        std::lock_guard<std::mutex> lock(progressMutex);
        progress(stage, fraction);
    };

    Partition out;
    // ---- first layer over the whole mesh
    const auto start1 = std::chrono::steady_clock::now();
    report("first layer", 0.0);
    const uint32_t components = componentCount(vertexComponents(mesh));
    uint32_t n1 = options.firstLayerSeeds;
    if (n1 == 0) n1 = std::max<uint32_t>(1, uint32_t(std::lround(used / 3000.0)));
    n1 = std::max(n1, components);
    DomainPartition layer1;
    {
        const ExactGeodesic geo(mesh);
        layer1 = partitionDomain(geo, n1, options.sampling, mixSeed(options.seed, 0),
                                 [&](double f) { report("first layer", f); });
    }
    out.faceFirst = layer1.faceRegion;
    out.first = buildPatches(mesh, out.faceFirst, layer1.seeds, {});
    out.stats.firstSeeds = layer1.sampledSeeds;
    out.stats.firstDiskSeeds = layer1.diskSeeds;
    out.stats.firstDiskRounds = layer1.diskRounds;
    out.stats.firstCutPatches = layer1.cutRegions;
    out.stats.firstLayerSeconds = secondsSince(start1);
    report("first layer", 1.0);

    // ---- second layer inside every first-layer patch, in parallel, into fixed slots
    const auto start2 = std::chrono::steady_clock::now();
    report("second layer", 0.0);
    const size_t n = out.first.size();
    std::vector<DomainPartition> slots(n);
    std::vector<std::vector<uint32_t>> slotSeeds(n);  // mesh vertex ids
    size_t done = 0;
    parallelFor(n, [&](size_t i) {
        const Patch& p = out.first[i];
        const ExactGeodesic geo(mesh, p.faces);
        const uint32_t nv = geo.vertexCount();
        uint32_t n2 = options.secondLayerSeeds;
        n2 = n2 == 0 ? std::max<uint32_t>(1, uint32_t(std::lround(nv / 100.0))) : std::min(n2, nv);
        slots[i] = partitionDomain(geo, n2, options.sampling, mixSeed(options.seed, i + 1));
        for (uint32_t s : slots[i].seeds) slotSeeds[i].push_back(geo.globalVertex(s));
        if (progress) {
            std::lock_guard<std::mutex> lock(progressMutex);
            progress("second layer", double(++done) / double(n));
        }
    });
    out.faceSecond.assign(mesh.faceCount(), 0);
    std::vector<uint32_t> seeds2, parents2;
    for (size_t i = 0; i < n; ++i) {
        const uint32_t offset = uint32_t(seeds2.size());
        const std::vector<uint32_t>& faces = out.first[i].faces;  // local face j is faces[j]
        for (size_t j = 0; j < faces.size(); ++j) out.faceSecond[faces[j]] = offset + slots[i].faceRegion[j];
        seeds2.insert(seeds2.end(), slotSeeds[i].begin(), slotSeeds[i].end());
        parents2.insert(parents2.end(), slotSeeds[i].size(), uint32_t(i));
        out.stats.secondSeeds += slots[i].sampledSeeds;
        out.stats.secondDiskSeeds += slots[i].diskSeeds;
        out.stats.secondCutPatches += slots[i].cutRegions;
    }
    out.second = buildPatches(mesh, out.faceSecond, seeds2, parents2);
    out.stats.secondLayerSeconds = secondsSince(start2);
    return out;
}

PatchSizeStats patchSizeStats(const std::vector<Patch>& patches) {
    PatchSizeStats s;
    s.patches = patches.size();
    if (patches.empty()) return s;
    s.minVertices = SIZE_MAX;
    double sum = 0, sum2 = 0;
    for (const Patch& p : patches) {
        const size_t v = p.border.size() + p.interior.size();
        s.minVertices = std::min(s.minVertices, v);
        s.maxVertices = std::max(s.maxVertices, v);
        sum += double(v);
        sum2 += double(v) * double(v);
    }
    s.meanVertices = sum / double(patches.size());
    s.stddevVertices = std::sqrt(std::max(0.0, sum2 / double(patches.size()) - s.meanVertices * s.meanVertices));
    return s;
}

}  // namespace vorogeo
