// Prediction coding of a finished flatbuffer's distance matrices, for compressed blobs
// (schema/vorogeo_distance_coding.h says what and why; the runtime decodes at vg_open).
#pragma once

#include <cstdint>
#include <vector>

namespace vorogeo {

// Replaces the quanta of second_distances and first_distances in the flatbuffer that
// `payload` begins with (a verified Graph buffer of flatbufferSize bytes, all of it by
// default) by their codes, the steps of the hub-label tables after it (hub_columns and
// hub_inner, schema/vorogeo_container.h) by theirs (schema/vorogeo_label_coding.h), and the
// mesh topology's indices by their differences (schema/vorogeo_topology_coding.h); nothing
// else changes; without codeInner, hub_inner stays as it is (the zeros of a blob that
// leaves it to its readers). Throws std::runtime_error when the payload's size is not that
// of the flatbuffer's tables.
void codeDistances(std::vector<uint8_t>& payload, uint64_t flatbufferSize = UINT64_MAX, bool codeInner = true);

}  // namespace vorogeo
