/* The vorogeo blob container (format version 12), shared by the baker and the runtime.
 *
 *   offset  size  field
 *        0     8  magic "VOROGEO\0"
 *        8     4  format version (little-endian uint32) = VG_FORMAT_VERSION
 *       12     4  flags: bit 0 = payload is zstd frames; bit 1 = the flatbuffer's distance
 *                  matrices (vorogeo_distance_coding.h) and hub-label tables
 *                  (vorogeo_label_coding.h) are prediction-coded, its topology, positions
 *                  and index sequences delta-coded, its patch edge lengths left to the
 *                  readers (vorogeo_topology_coding.h); bit 2 (with bits 0, 1 and hub
 *                  labels only) = the hub_inner table is zeros, its readers compute it
 *                  (vorogeo_inner_rows.h); other bits 0
 *       16     8  payload size in bytes (what follows the header)
 *       24     8  flatbuffer size in bytes
 *       32     8  table bytes: the hub-label tables after the flatbuffer (0 without labels)
 *       40     8  checksum of the payload bytes (vg_checksum64 below)
 *       48        payload: the flatbuffer of schema/vorogeo.fbs, then (with hub labels) its
 *                  tables, or zstd frames holding both, one after another
 *
 * Compressed, the unpacked payload is cut into pieces of VG_CONTAINER_FRAME_BYTES (the last
 * one shorter), each a zstd frame that states its content size, so that the baker compresses
 * them on all its threads and still writes the same bytes for any thread count (a frame of
 * zstd's own multithreaded mode may differ with the thread count). A reader decompresses the
 * frames back to back (ZSTD_decompress takes them as one input) and needs no piece size.
 *
 * The tables lie outside the flatbuffer because a flatbuffer's 32-bit offsets end at 2 GiB,
 * which the labels of a 2-million-vertex mesh pass alone. Unpacked, the payload is the
 * flatbuffer, zeros up to the next multiple of 64 bytes, hub_columns (the flatbuffer's
 * hub_columns_count 16-bit entries) padded with zeros to a multiple of 64 bytes, then
 * hub_inner (hub_inner_count entries) padded the same way (vg_label_tables below).
 *
 * The header is 48 bytes, so an uncompressed flatbuffer starts 8-byte aligned in a mapped
 * file and can be used in place. Plain C99, no dependencies. */
#ifndef VOROGEO_CONTAINER_H
#define VOROGEO_CONTAINER_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#define VG_CONTAINER_MAGIC "VOROGEO"
#define VG_CONTAINER_HEADER_SIZE 48u
#define VG_FORMAT_VERSION 12u
#define VG_FLAG_ZSTD 1u
#define VG_FLAG_CODED_DISTANCES 2u
#define VG_FLAG_INNER_ROWS_AT_OPEN 4u
/* Unpacked bytes per zstd frame of a compressed payload (the baker's choice, 8 MiB: with the
 * 256 KB window of coded blobs, the cuts cost igea's blob 0.02% at level 9, 0.24% at 19). */
#define VG_CONTAINER_FRAME_BYTES (8u << 20)

static inline uint64_t vg_load_le64(const unsigned char* p) {
    uint64_t v = 0;
    int i;
    for (i = 7; i >= 0; --i) v = (v << 8) | p[i];
    return v;
}

static inline uint32_t vg_load_le32(const unsigned char* p) {
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static inline void vg_store_le64(unsigned char* p, uint64_t v) {
    int i;
    for (i = 0; i < 8; ++i) p[i] = (unsigned char)(v >> (8 * i));
}

static inline void vg_store_le32(unsigned char* p, uint32_t v) {
    int i;
    for (i = 0; i < 4; ++i) p[i] = (unsigned char)(v >> (8 * i));
}

static inline uint64_t vg_rotl64(uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }

/* A 64-bit checksum over 8-byte words (two multiplies per word, a murmur-style final mix):
 * it catches truncation, flipped bits and swapped blocks; it is not cryptographic. */
static inline uint64_t vg_checksum64(const void* data, size_t size) {
    const unsigned char* p = (const unsigned char*)data;
    const uint64_t k1 = 0x9E3779B185EBCA87ull, k2 = 0xC2B2AE3D27D4EB4Full;
    uint64_t h = 0x27D4EB2F165667C5ull ^ ((uint64_t)size * k1);
    size_t i = 0;
    for (; i + 8 <= size; i += 8) {
        uint64_t w;
        memcpy(&w, p + i, 8); /* the checksum is defined on little-endian words */
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
        w = vg_load_le64(p + i);
#endif
        h ^= vg_rotl64(w * k2, 31) * k1;
        h = vg_rotl64(h, 27) * k1 + 0x52DCE729u;
    }
    {
        uint64_t tail = 0;
        int shift = 0;
        for (; i < size; ++i, shift += 8) tail |= (uint64_t)p[i] << shift;
        h ^= vg_rotl64(tail * k2, 31) * k1;
    }
    h ^= h >> 33;
    h *= 0xFF51AFD7ED558CCDull;
    h ^= h >> 33;
    h *= 0xC4CEB9FE1A85EC53ull;
    h ^= h >> 33;
    return h;
}

/* Where the hub-label tables lie in an unpacked payload whose flatbuffer takes
 * flatbuffer_size bytes and names column_count and inner_count entries: byte offsets of
 * hub_columns and hub_inner from the payload's start, and the table bytes the header
 * states. 0 (with every output 0) when a count passes 2^60 (no such blob is valid). */
typedef struct vg_label_tables {
    uint64_t columns_offset, inner_offset, table_bytes, payload_size;
} vg_label_tables;

static inline uint64_t vg_align64(uint64_t n) { return (n + 63u) & ~(uint64_t)63u; }

static inline int vg_label_tables_at(uint64_t flatbuffer_size, uint64_t column_count, uint64_t inner_count,
                                     vg_label_tables* out) {
    const uint64_t limit = (uint64_t)1 << 60;
    memset(out, 0, sizeof *out);
    if (flatbuffer_size > limit || column_count > limit || inner_count > limit) return 0;
    out->columns_offset = vg_align64(flatbuffer_size);
    out->inner_offset = out->columns_offset + vg_align64(2 * column_count);
    out->table_bytes = vg_align64(2 * column_count) + vg_align64(2 * inner_count);
    out->payload_size = out->table_bytes ? out->columns_offset + out->table_bytes : flatbuffer_size;
    return 1;
}

#endif /* VOROGEO_CONTAINER_H */
