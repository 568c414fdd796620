/* Prediction coding of the hub-label tables (hub_columns and hub_inner of schema/vorogeo.fbs)
 * in a blob whose container has VG_FLAG_CODED_DISTANCES, shared by the baker (encoder),
 * the runtime and the tools (decoders). Plain C99, no dependencies.
 *
 * Why: a label entry is a 16-bit step count, and zstd keeps raw steps nearly as they are
 * (igea: 24 of 26 MB). Both tables are smooth in both directions: a label block's rows are
 * consecutive hubs of one separator chain (neighbours), its 16 columns too; an inner row's
 * columns are the first-layer patch's nodes. So an entry is predicted from its decoded
 * neighbours above, to the left and above-left (a + l - al, the "gradient" predictor), in
 * the inner table after subtracting the straight-line distance between the two nodes
 * (what is smooth there is the detour, not the distance). The residuals are mostly one
 * byte; the coded table is then stored in chunks of VG_LABEL_CHUNK entries, each as its
 * low bytes followed by its high bytes, which zstd compresses 3-4x.
 *
 * Exact: decode(encode(x)) = x for any 16-bit values. 65535 ("no path") is kept as it is and
 * never used for a prediction; other values are coded modulo 65535 into [0, 65534], so any
 * coded bytes decode to some table of valid values: a decoder needs no checks beyond the
 * table ranges validated before.
 *
 * The straight-line step count must be the same bits in baker and runtime: IEEE single
 * precision, each operation rounded (build with -ffp-contract=off), correctly rounded square
 * root (as vorogeo_distance_coding.h). */
#ifndef VOROGEO_LABEL_CODING_H
#define VOROGEO_LABEL_CODING_H

#include <stdint.h>

#define VG_LABEL_NO_PATH 65535u
#define VG_LABEL_CHUNK 2048u

/* round(|a - b| * inverse_scale) clamped to [0, 65534]; NaN clamps to 65534. */
static inline int32_t vg_label_chord(const float* a, const float* b, float inverse_scale) {
    const float dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    const float sum = (dx * dx + dy * dy) + dz * dz;
    float x = __builtin_sqrtf(sum) * inverse_scale;
    x = x < 65534.0f ? x : 65534.0f;
    x = x > 0.0f ? x : 0.0f;
    return (int32_t)(x + 0.5f);
}

/* Where an inner table's rows and columns are: node ids, their vertices' positions. NULL
 * for a label block (no straight-line term). */
typedef struct {
    const float* positions;      /* 3 per vertex */
    const uint32_t* node_vertex; /* per node: its vertex */
    const uint32_t* row_nodes;   /* per row: a node id */
    const uint32_t* col_nodes;   /* per column: a node id */
    float inverse_scale;         /* steps per distance unit */
} vg_label_sites;

/* The straight-line steps of entry (r, c), 0 without sites. */
static inline int32_t vg_label_site_chord(const vg_label_sites* s, uint32_t r, uint32_t c) {
    if (!s) return 0;
    return vg_label_chord(s->positions + 3 * (uint64_t)s->node_vertex[s->row_nodes[r]],
                          s->positions + 3 * (uint64_t)s->node_vertex[s->col_nodes[c]], s->inverse_scale);
}

/* The prediction of entry (r, c) from the detours (value - chord) of its decoded neighbours
 * above, left and above-left, each given as INT32_MIN where it is missing or "no path". */
static inline int32_t vg_label_predict_detour(int32_t above, int32_t left, int32_t above_left) {
    if (above != INT32_MIN && left != INT32_MIN && above_left != INT32_MIN) return above + left - above_left;
    if (above != INT32_MIN) return above;
    if (left != INT32_MIN) return left;
    return 0;
}

/* x mod 65535 in [0, 65534], for |x| < 2^30. */
static inline uint32_t vg_label_mod(int32_t x) {
    const int32_t m = x % 65535;
    return (uint32_t)(m < 0 ? m + 65535 : m);
}

/* One entry's code from its value and prediction, and back. */
static inline uint16_t vg_label_encode(uint32_t value, int32_t prediction) {
    uint32_t delta;
    if (value == VG_LABEL_NO_PATH) return (uint16_t)VG_LABEL_NO_PATH;
    delta = vg_label_mod((int32_t)value - (int32_t)vg_label_mod(prediction)); /* [0, 65534] */
    return (uint16_t)(delta <= 32767u ? 2u * delta : 2u * (65535u - delta) - 1u);
}

static inline uint16_t vg_label_decode(uint32_t code, int32_t prediction) {
    uint32_t delta;
    if (code == VG_LABEL_NO_PATH) return (uint16_t)VG_LABEL_NO_PATH;
    delta = (code & 1u) ? 65535u - (code + 1u) / 2u : code / 2u;
    return (uint16_t)vg_label_mod((int32_t)(vg_label_mod(prediction) + delta));
}

/* Codes one rows x cols table, row-major from `begin` (encode: `plain` holds the values and
 * `coded` receives the codes; decode: both the same array, decoded in place, front to back).
 * `detours` is scratch for 2 * cols int32 (a row of detours and the row above). */
static inline void vg_code_label_table(const uint16_t* plain, uint16_t* coded, uint64_t begin, uint32_t rows,
                                       uint32_t cols, const vg_label_sites* sites, int32_t* detours, int decode) {
    uint32_t r, c;
    int32_t* above = detours;
    int32_t* here = detours + cols;
    for (r = 0; r < rows; ++r) {
        const uint64_t row = begin + (uint64_t)r * cols;
        int32_t left = INT32_MIN;
        int32_t* t;
        for (c = 0; c < cols; ++c) {
            const int32_t chord = vg_label_site_chord(sites, r, c);
            const int32_t a = r ? above[c] : INT32_MIN;
            const int32_t al = r && c ? above[c - 1] : INT32_MIN;
            const int32_t prediction = chord + vg_label_predict_detour(a, left, al);
            uint32_t value;
            if (decode) {
                value = vg_label_decode(coded[row + c], prediction);
                coded[row + c] = (uint16_t)value;
            } else {
                value = plain[row + c];
                coded[row + c] = vg_label_encode(value, prediction);
            }
            left = value == VG_LABEL_NO_PATH ? INT32_MIN : (int32_t)value - chord;
            here[c] = left;
        }
        t = above;
        above = here;
        here = t;
    }
}

/* Splits (split = 1) or joins (split = 0) the byte planes of `count` 16-bit entries at
 * `bytes` (little-endian, as in a flatbuffer), chunk by chunk: a chunk of n entries is
 * stored as its n low bytes, then its n high bytes. `scratch` holds 2 * VG_LABEL_CHUNK
 * bytes. */
static inline void vg_label_planes(unsigned char* bytes, uint64_t count, unsigned char* scratch, int split) {
    uint64_t begin, i;
    for (begin = 0; begin < count; begin += VG_LABEL_CHUNK) {
        const uint64_t n = count - begin < VG_LABEL_CHUNK ? count - begin : VG_LABEL_CHUNK;
        unsigned char* chunk = bytes + 2 * begin;
        for (i = 0; i < 2 * n; ++i) scratch[i] = chunk[i];
        for (i = 0; i < n; ++i) {
            if (split) {
                chunk[i] = scratch[2 * i];
                chunk[n + i] = scratch[2 * i + 1];
            } else {
                chunk[2 * i] = scratch[i];
                chunk[2 * i + 1] = scratch[n + i];
            }
        }
    }
}

#endif /* VOROGEO_LABEL_CODING_H */
