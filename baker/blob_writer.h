// Serialising a baked graph: the flatbuffer of schema/vorogeo.fbs, the container around it
// (schema/vorogeo_container.h), and writing a file so that a failure never leaves a
// partial output behind.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hub_labels.h"
#include "landmarks.h"
#include "mesh.h"
#include "partition.h"
#include "patch_geodesics.h"

namespace vorogeo {

struct BlobParams {
    uint64_t seed = 1;
    uint32_t n1 = 0, n2 = 0, marginRings = 0;
    double delta = 0;         // fraction of the bounding-box diagonal
    double bboxDiagonal = 0;
};

// The flatbuffer. `first` holds the first-layer matrices over active nodes only;
// `secondInactive` flags (per vertex) the nodes merged away in the second layer.
// `quantisationMaxAbs` receives the largest absolute error of the 12-bit distances.
// `landmarks` and `hubs` may be empty (both are computed from a first buffer without them).
std::vector<uint8_t> buildGraphBuffer(const Mesh& mesh, const Partition& partition,
                                      const std::vector<PatchMatrix>& first, const std::vector<PatchMatrix>& second,
                                      const std::vector<uint8_t>& secondInactive, const BlobParams& params,
                                      const Landmarks& landmarks, double& quantisationMaxAbs,
                                      const HubLabels& hubs = HubLabels());

// A blob's payload unpacked: the flatbuffer (its first flatbufferSize bytes), then, with
// hub labels, the label tables (schema/vorogeo_container.h: they lie outside the
// flatbuffer, whose offsets end at 2 GiB).
struct Payload {
    std::vector<uint8_t> bytes;
    uint64_t flatbufferSize = 0;
};

// The payload of a flatbuffer that buildGraphBuffer wrote with `hubs` (the flatbuffer
// alone when `hubs` is empty).
Payload withLabelTables(std::vector<uint8_t> flatbuffer, const HubLabels& hubs);

// Header + payload: the payload as is, or zstd-compressed (compress), optionally with its
// distances and label tables prediction-coded first (compact: distance_coding.h). The
// flatbuffer must be a verified Graph buffer (taken by value: a caller done with it moves
// it in, and coding needs no copy). The second form takes a flatbuffer without labels.
// innerRowsAtOpen (compact, with labels whose inner table is zeros): the table stays zeros
// and the container says so (schema/vorogeo_inner_rows.h).
std::vector<uint8_t> packContainer(Payload payload, bool compress, bool compact, int level,
                                   bool innerRowsAtOpen = false);
std::vector<uint8_t> packContainer(std::vector<uint8_t> flatbuffer, bool compress, bool compact, int level);

// Header + payload for any bytes, with the given container flags (VG_FLAG_ZSTD compresses
// them; VG_FLAG_CODED_DISTANCES only says they are coded): what packContainer uses, and
// how the fuzzers seal mutated flatbuffers. The flatbuffer is the first flatbufferSize
// bytes (all of them by default), the rest from the next multiple of 64 bytes the tables.
// Compressed, every `frameBytes` of payload become a zstd frame (0: the format's
// VG_CONTAINER_FRAME_BYTES; other sizes, for the tests, open the same).
std::vector<uint8_t> sealContainer(const std::vector<uint8_t>& payload, uint32_t flags, int level,
                                   uint64_t flatbufferSize = UINT64_MAX,
                                   uint64_t frameBytes = 0);

// Throws std::runtime_error ("cannot write PATH: reason") if `path` cannot be created, by
// creating and removing its temporary file: a bake checks this before its long work.
void checkWritable(const std::string& path);

// Writes to "<path>.tmp-<pid>" then renames it over `path`; on any failure the temporary
// file is removed and std::runtime_error names the path and the reason.
void writeFileAtomically(const std::string& path, const std::vector<uint8_t>& bytes);

}  // namespace vorogeo
