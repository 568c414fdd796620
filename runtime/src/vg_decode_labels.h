// Decoding a blob's prediction-coded hub-label tables in place, at vg_open
// (schema/vorogeo_label_coding.h): the reference decoder's values, faster. A row with no
// "no path" entry, below a row with none, is a running sum of its codes' deltas added to
// the detours above (modulo 65535, as the reference's gradient prediction works out);
// other rows take the reference's entry-by-entry rule. An inner table's straight-line
// steps are computed a row at a time from the columns' positions laid out as x, y, z.
#pragma once

#include <stddef.h>
#include <stdint.h>

#include "vg_graph.h"
#include "vorogeo_label_coding.h"

namespace vg {

// Scratch for decodeLabels and decodeLabelTable, 16-byte aligned.
size_t labelDecodeScratchSize();

// Decodes g's hubColumns and (with `inner`; not in a blob that leaves them out) hubInner in
// place (memory the caller owns). g must have passed verifyAndBind, which bounds every tree
// node's blocks and every first-layer patch's inner table (at most 65,536 columns).
void decodeLabels(const vg_graph& g, bool inner, void* scratch);

// One coded table (rows x cols at `table`, cols <= 65,536), decoded in place: exposed for
// the tests, which compare it with the reference decoder.
void decodeLabelTable(uint16_t* table, uint32_t rows, uint32_t cols, const vg_label_sites* sites, void* scratch);

}  // namespace vg
