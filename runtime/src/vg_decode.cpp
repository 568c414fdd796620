// Decodes prediction-coded distance matrices in place (vg_decode.h). Per patch: its slots'
// positions into x, y, z arrays, then row by row the predictions of a run of entries at
// once, added to the codes. The sums are the reference decoder's (vorogeo_distance_coding.h)
// operation for operation, so the quanta are the baker's bit for bit on any CPU.
#include "vg_decode.h"

#include "vorogeo_distance_coding.h"

#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define VG_DECODE_AVX2 1
#include "vg_packed_avx2.h"
#else
#define VG_DECODE_AVX2 0
#endif

namespace vg {
namespace {

constexpr uint32_t kMaxSlots = 65536;  // vg_validate bounds a patch's slots by this
constexpr uint32_t kPad = 16;
// The mirrors of a block's lower half are read a tile of kTile columns at a time from the
// rows above (contiguous runs) instead of one strided entry at a time; rows past
// kTileRows (blocks larger than any bake makes) are read one entry at a time.
constexpr uint32_t kTile = 16, kTileRows = 4096;

struct Scratch {
    float* x;
    float* y;
    float* z;
    uint16_t* prediction;  // per column of the row at hand
    uint16_t* tile;        // kTileRows x kTile: rows' entries in the current columns
};

Scratch carve(void* memory) {
    float* f = static_cast<float*>(memory);
    const uint32_t n = kMaxSlots + kPad;
    uint16_t* prediction = reinterpret_cast<uint16_t*>(f + 3 * n);
    return Scratch{f, f + n, f + 2 * n, prediction, prediction + n};
}

}  // namespace

namespace portable {
#define VG_DECODE_BODY_AVX2 0
#include "vg_decode_body.h"
#undef VG_DECODE_BODY_AVX2
}  // namespace portable

#if VG_DECODE_AVX2
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2")
#endif
namespace avx2 {
#define VG_DECODE_BODY_AVX2 1
#include "vg_decode_body.h"
#undef VG_DECODE_BODY_AVX2
}  // namespace avx2
#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif
#endif

size_t decodeScratchSize() {
    const size_t carved = 3 * size_t(kMaxSlots + kPad) * sizeof(float) + size_t(kMaxSlots + kPad) * sizeof(uint16_t) +
                          size_t(kTileRows) * kTile * sizeof(uint16_t);
    return carved > VG_CODING_PLANE_SCRATCH ? carved : VG_CODING_PLANE_SCRATCH;  // planes first, then the carved arrays
}

void predictRow(bool useAvx2, const float* x, const float* y, const float* z, uint32_t i, uint32_t j0, uint32_t j1,
                float scale, uint16_t* out) {
#if VG_DECODE_AVX2
    if (useAvx2) return avx2::predictRow(x, y, z, i, j0, j1, scale, out);
#endif
    (void)useAvx2;
    portable::predictRow(x, y, z, i, j0, j1, scale, out);
}

void decodeDistances(const vg_graph& g, bool useAvx2, void* scratch) {
#if VG_DECODE_AVX2
    if (useAvx2) return avx2::decodeAll(g, scratch);
#endif
    (void)useAvx2;
    portable::decodeAll(g, scratch);
}

}  // namespace vg
