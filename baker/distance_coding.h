// Prediction coding of a finished flatbuffer's distance matrices, for compressed blobs
// (schema/vorogeo_distance_coding.h says what and why; the runtime decodes at vg_open).
#pragma once

#include <cstdint>
#include <vector>

namespace vorogeo {

// Replaces the quanta of second_distances and first_distances in `flatbuffer` (a verified
// Graph buffer) by their codes, and the steps of the hub-label tables hub_columns and
// hub_inner by theirs (schema/vorogeo_label_coding.h), and the mesh topology's indices by
// their differences (schema/vorogeo_topology_coding.h); nothing else changes.
void codeDistances(std::vector<uint8_t>& flatbuffer);

}  // namespace vorogeo
