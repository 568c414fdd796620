/* Prediction coding of the blob's distance matrices (container flag VG_FLAG_CODED_DISTANCES),
 * shared by the baker (encoder) and the runtime (decoder). Plain C99, no dependencies.
 *
 * Why: a 12-bit distance quantum is close to the straight-line distance between the two
 * slots' vertices, in the same quanta, and a symmetric entry equals its mirror. Raw quanta
 * are nearly incompressible for zstd (igea: 149 bytes per vertex before and after); the
 * difference from that prediction is mostly a few quanta and compresses ~3x. Coding is
 * exact: decode(encode(q)) = q for every 12-bit value, so answers are bit for bit those
 * of an uncoded blob.
 *
 * An entry (i, j) of a patch matrix is stored as code = (q - p) mod 4096 with the
 * prediction p:
 *   * i == j (a node x node block's diagonal): 4095 in the second layer ("no path"), 0 in
 *     the first;
 *   * j < i inside a node x node block (the lower half of a symmetric block): the entry
 *     (j, i), which precedes it, decoded;
 *   * otherwise: vg_predicted_quantum of the two slots' positions and the patch's scale.
 * Both walk entries in storage order: the decoder works in place (a mirror is decoded
 * before the entry that reads it), the encoder reads mirrors from its uncoded copy. Any bytes decode to some
 * 12-bit values, so a decoder needs no checks beyond the patch ranges validated before.
 *
 * The prediction must be the same bits in the baker and in every runtime: IEEE single
 * precision, each operation rounded (no fused multiply-add: build with -ffp-contract=off),
 * correctly rounded square root and division. A vector version must perform the same
 * operations in the same order. */
#ifndef VOROGEO_DISTANCE_CODING_H
#define VOROGEO_DISTANCE_CODING_H

#include <stdint.h>
#include <string.h>

#define VG_CODING_MAX_QUANTUM 4094u
#define VG_CODING_NO_PATH 4095u

/* round(|a - b| * (1 / scale)) clamped to [0, 4094] (a product, not a quotient: the
 * decoder's vector loop multiplies by one reciprocal per patch); NaN (a zero scale) and
 * infinities clamp to 4094. */
static inline uint32_t vg_predicted_quantum(const float* a, const float* b, float scale) {
    const float dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    const float sum = (dx * dx + dy * dy) + dz * dz;
    const float inverse = 1.0f / scale;
    float x = __builtin_sqrtf(sum) * inverse;
    x = x < 4094.0f ? x : 4094.0f; /* also NaN -> 4094, as a vector minimum does */
    x = x > 0.0f ? x : 0.0f;
    return (uint32_t)(int32_t)(x + 0.5f);
}

/* Entries a packed 12-bit array of `bytes` bytes holds (two per three bytes). */
static inline uint64_t vg_coding_entries(uint64_t bytes) { return (bytes / 3) * 2 + (bytes % 3 == 2 ? 1 : 0); }

/* Entry k of a packed 12-bit array (two per three bytes, see schema/vorogeo.fbs). */
static inline uint32_t vg_coding_get(const unsigned char* packed, uint64_t k) {
    const unsigned char* p = packed + ((3 * k) >> 1);
    const uint32_t word = (uint32_t)p[0] | ((uint32_t)p[1] << 8);
    return (word >> ((uint32_t)(k & 1u) << 2)) & 0xFFFu;
}

static inline void vg_coding_set(unsigned char* packed, uint64_t k, uint32_t q) {
    unsigned char* p = packed + ((3 * k) >> 1);
    if (k & 1u) {
        p[0] = (unsigned char)((p[0] & 0x0Fu) | ((q & 0x0Fu) << 4));
        p[1] = (unsigned char)(q >> 4);
    } else {
        p[0] = (unsigned char)(q & 0xFFu);
        p[1] = (unsigned char)((p[1] & 0xF0u) | (q >> 8));
    }
}

/* Where slot i of a patch is: nodes (i < node_count) are node ids, other slots vertex ids. */
typedef struct {
    const float* positions;      /* 3 per vertex */
    const uint32_t* slots;       /* the patch's slots */
    const uint32_t* node_vertex; /* per node: its vertex */
    uint32_t node_count;
} vg_coding_slots;

static inline const float* vg_coding_position(const vg_coding_slots* s, uint32_t i) {
    const uint32_t id = s->slots[i];
    return s->positions + 3 * (uint64_t)(i < s->node_count ? s->node_vertex[id] : id);
}

/* One entry: encode (decode = 0) or decode it in place, given its prediction. */
static inline void vg_coding_apply(unsigned char* packed, uint64_t k, uint32_t prediction, int decode) {
    const uint32_t v = vg_coding_get(packed, k);
    vg_coding_set(packed, k, (decode ? v + prediction : v - prediction) & 0xFFFu);
}

static inline uint32_t vg_coding_chord(const vg_coding_slots* s, uint32_t i, uint32_t j, float scale) {
    return vg_predicted_quantum(vg_coding_position(s, i), vg_coding_position(s, j), scale);
}

/* Codes a square block of a patch matrix: rows and columns [0, rows), row i at packed
 * index begin + i * rows. `plain` holds the uncoded quanta of the mirrors: the array being
 * decoded itself (mirrors come first), or the encoder's uncoded copy. */
static inline void vg_code_block(const unsigned char* plain, unsigned char* packed, uint64_t begin, uint32_t rows,
                                 uint32_t diagonal, const vg_coding_slots* s, float scale, int decode) {
    uint32_t i, j;
    for (i = 0; i < rows; ++i) {
        const uint64_t row = begin + (uint64_t)i * rows;
        for (j = 0; j < i; ++j) vg_coding_apply(packed, row + j, vg_coding_get(plain, begin + (uint64_t)j * rows + i), decode);
        vg_coding_apply(packed, row + i, diagonal, decode);
        for (j = i + 1; j < rows; ++j) vg_coding_apply(packed, row + j, vg_coding_chord(s, i, j, scale), decode);
    }
}

/* Codes one second-layer patch matrix (S slots, the first n of them nodes) starting at
 * packed index `begin`: node x node block whole, node x other block, other triangle
 * (runtime/src/vg_graph.h). Encode: `packed` is a copy of `plain`; decode: the same array.
 * The reference the runtime's fast decoder must agree with. */
static inline void vg_code_second_matrix(const unsigned char* plain, unsigned char* packed, uint64_t begin, uint32_t S,
                                         uint32_t n, float scale, const vg_coding_slots* s, int decode) {
    uint64_t k = begin + (uint64_t)n * n;
    uint32_t i, j;
    vg_code_block(plain, packed, begin, n, VG_CODING_NO_PATH, s, scale, decode);
    for (i = 0; i < n; ++i)
        for (j = n; j < S; ++j) vg_coding_apply(packed, k++, vg_coding_chord(s, i, j, scale), decode);
    for (i = n; i < S; ++i)
        for (j = i + 1; j < S; ++j) vg_coding_apply(packed, k++, vg_coding_chord(s, i, j, scale), decode);
}

/* Codes one first-layer patch matrix (S x S whole, zero diagonal, every slot a node). */
static inline void vg_code_first_matrix(const unsigned char* plain, unsigned char* packed, uint64_t begin, uint32_t S,
                                        float scale, const vg_coding_slots* s, int decode) {
    vg_code_block(plain, packed, begin, S, 0u, s, scale, decode);
}

/* Byte planes (format 11). After the codes above, a coded array is stored in chunks of
 * VG_CODING_PLANE_ENTRIES entries (the last one shorter), each chunk in its own packed bytes
 * as two planes: the low 8 bits of every entry's zigzag-coded code (the code read as a
 * difference in [-2048, 2047]), then their high 4 bits, two per byte (the earlier entry in
 * the low nibble). A code is mostly a few quanta either way, so the high plane is mostly
 * zeros and the low one small numbers; packed 12-bit codes mix both in every byte and zstd
 * compressed them 14% worse (igea's second layer, level 19: 9.32 against 8.02 MB with the
 * planes over the whole array). Chunks bound the scratch a reader needs. */
#define VG_CODING_PLANE_ENTRIES 262144u /* even, so that every chunk starts on a byte */

/* The scratch vg_code_planes needs: one chunk's bytes. */
#define VG_CODING_PLANE_SCRATCH (3u * VG_CODING_PLANE_ENTRIES / 2u)

static inline uint32_t vg_coding_zigzag(uint32_t code) {
    const int32_t s = (int32_t)(code << 20) >> 20; /* sign-extend the 12 bits */
    return (((uint32_t)s << 1) ^ (uint32_t)(s >> 31)) & 0xFFFu;
}

static inline uint32_t vg_coding_unzigzag(uint32_t z) { return ((z >> 1) ^ (0u - (z & 1u))) & 0xFFFu; }

/* Turns entries [first, first + count) of a packed array (first even) from packed codes into
 * planes (decode = 0) or back (decode = 1); scratch holds (3 count + 1) / 2 bytes. */
static inline void vg_code_plane_chunk(unsigned char* packed, uint64_t first, uint32_t count, unsigned char* scratch,
                                       int decode) {
    unsigned char* bytes = packed + ((3 * first) >> 1);
    const uint32_t size = (3 * count + 1) / 2, pairs = count / 2;
    unsigned char* low = decode ? scratch : bytes; /* the planes: low bytes, then nibbles */
    unsigned char* high = low + count;
    uint32_t j;
    if (decode) {
        memcpy(scratch, bytes, size);
        for (j = 0; j < pairs; ++j) {
            const uint32_t a = vg_coding_unzigzag(low[2 * j] | ((uint32_t)(high[j] & 0x0Fu) << 8));
            const uint32_t b = vg_coding_unzigzag(low[2 * j + 1] | ((uint32_t)(high[j] >> 4) << 8));
            bytes[3 * j] = (unsigned char)a;
            bytes[3 * j + 1] = (unsigned char)((a >> 8) | (b << 4));
            bytes[3 * j + 2] = (unsigned char)(b >> 4);
        }
        if (count & 1u) { /* a last entry alone: its byte's other nibble is no entry's, 0 */
            const uint32_t a = vg_coding_unzigzag(low[count - 1] | ((uint32_t)(high[pairs] & 0x0Fu) << 8));
            bytes[3 * j] = (unsigned char)a;
            bytes[3 * j + 1] = (unsigned char)(a >> 8);
        }
    } else {
        memcpy(scratch, bytes, size);
        for (j = 0; j < count; ++j) {
            const uint32_t z = vg_coding_zigzag(vg_coding_get(scratch, j));
            low[j] = (unsigned char)z;
            if (j & 1u) high[j / 2] = (unsigned char)(high[j / 2] | ((z >> 8) << 4));
            else high[j / 2] = (unsigned char)(z >> 8);
        }
    }
}

/* Every chunk of a packed array of `entries` entries (see above); scratch holds
 * VG_CODING_PLANE_SCRATCH bytes. */
static inline void vg_code_planes(unsigned char* packed, uint64_t entries, unsigned char* scratch, int decode) {
    uint64_t first;
    for (first = 0; first < entries; first += VG_CODING_PLANE_ENTRIES) {
        const uint64_t left = entries - first;
        vg_code_plane_chunk(packed, first, (uint32_t)(left < VG_CODING_PLANE_ENTRIES ? left : VG_CODING_PLANE_ENTRIES),
                            scratch, decode);
    }
}

#endif /* VOROGEO_DISTANCE_CODING_H */
