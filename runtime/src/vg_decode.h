// Decoding a blob's prediction-coded distance matrices in place, at vg_open
// (schema/vorogeo_distance_coding.h): the same bits as that header's reference decoder,
// with the predictions of a row computed eight at a time where the CPU has AVX2.
#pragma once

#include <stddef.h>

#include "vg_graph.h"

namespace vg {

// Scratch the decoder needs: a patch's slot positions and a row of predictions.
size_t decodeScratchSize();

// Decodes g's second- and first-layer distances in place (they must lie in memory the
// caller owns); `scratch` holds decodeScratchSize() bytes, 16-byte aligned. g must have
// passed verifyAndBind, which bounds every patch's slots and matrix.
void decodeDistances(const vg_graph& g, bool avx2, void* scratch);

// The predictions of row i against slots [j0, j1) into out[j0..j1), from the slots'
// positions as x, y, z arrays: exposed for the tests, which compare both versions with
// vg_predicted_quantum.
void predictRow(bool avx2, const float* x, const float* y, const float* z, uint32_t i, uint32_t j0, uint32_t j1,
                float scale, uint16_t* out);

}  // namespace vg
