// One layer of the partition over one domain (the whole mesh, or one first-layer patch):
// seeds, exact geodesic Voronoi labels, faces, and the rounds that make every region a
// topological disk. partition.h describes the method; this is its engine room.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "geodesic_exact.h"
#include "partition.h"
#include "seed_sampling.h"

namespace vorogeo {

// Rounds of adding seeds to regions that are not disks before the fallback cut.
constexpr uint32_t kMaxDiskRounds = 32;

// Indices are the domain's (ExactGeodesic local vertices and faces; for a patch domain
// local face i is the i-th smallest patch face).
struct DomainPartition {
    std::vector<uint32_t> seeds;       // per region: its seed vertex
    std::vector<uint32_t> faceRegion;  // per domain face: its region
    uint32_t sampledSeeds = 0;         // seeds from sampling
    uint32_t diskSeeds = 0;            // seeds added to make regions disks
    uint32_t diskRounds = 0;
    uint32_t cutRegions = 0;           // regions made by the fallback cut
};

// `seedCount` must lie between the domain's number of components and its used vertices.
// `progress` (optional) receives the fraction done. `maxDiskRounds` below the default is
// for tests of the fallback cut.
DomainPartition partitionDomain(const ExactGeodesic& geo, uint32_t seedCount, PartitionOptions::Sampling sampling,
                                uint64_t rngSeed, const std::function<void(double)>& progress = {},
                                uint32_t maxDiskRounds = kMaxDiskRounds);

}  // namespace vorogeo
