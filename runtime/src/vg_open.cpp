// vg_open_size / vg_open: container header, checksum, decompression into caller memory
// (static zstd context), flatbuffers verification, the meaning checks of vg_validate.cpp,
// then the decoding of prediction-coded distances and hub-label tables (vg_decode.h,
// vg_decode_labels.h) and the inner rows a blob leaves out (vg_inner_rows.h). Nothing is
// allocated; on failure nothing refers to the memory.
#include <string.h>

#include "vg_graph.h"
#include "vg_decode.h"
#include "vg_decode_labels.h"
#include "vg_field_kernels.h"
#include "vg_huge_pages.h"
#include "vg_inner_rows.h"
#include "vg_validate.h"
#include "vorogeo_container.h"

#if VG_WITH_ZSTD
#define ZSTD_STATIC_LINKING_ONLY
#include <zstd.h>
#endif

namespace {

// Everything vg_open needs to know from the 48-byte header.
struct Header {
    bool compressed;
    bool coded;  // distances prediction-coded: decoded in caller memory, never used in place
    bool innerRowsAtOpen;  // the hub_inner table is zeros, computed here (vg_inner_rows.h)
    uint64_t payloadSize;
    uint64_t flatbufferSize;
    uint64_t tableBytes;    // the hub-label tables after the flatbuffer
    uint64_t unpackedSize;  // the flatbuffer, then (with tables) up to 64 bytes of zeros and the tables
    uint64_t checksum;
};

constexpr size_t kAlign = 64;  // a cache line: the hub-label rows are 32-byte aligned in the buffer
// flatbuffers offsets are 32-bit: a larger buffer cannot be a valid flatbuffer.
constexpr uint64_t kMaxFlatbuffer = 0x7FFFFFFFull;
// Table bytes beyond any memory a process can have: refused before any arithmetic on them.
constexpr uint64_t kMaxTableBytes = uint64_t(1) << 48;

size_t alignUp(size_t n) { return (n + kAlign - 1) & ~(kAlign - 1); }

#if VG_WITH_ZSTD
// What the payload's zstd frames unpack to together, as they state it; ZSTD_CONTENTSIZE_ERROR
// or _UNKNOWN (both above any real size) for bytes that are no such frames or a frame that
// does not state its size.
unsigned long long unpackedBytes(const void* frames, size_t size) { return ZSTD_findDecompressedSize(frames, size); }
#endif

vg_status readHeader(const void* blob, size_t blobSize, Header& h) {
    if (blob == nullptr) return VG_ERR_INVALID_ARGUMENT;
    if (blobSize < VG_CONTAINER_HEADER_SIZE) return VG_ERR_TRUNCATED;
    const unsigned char* p = static_cast<const unsigned char*>(blob);
    if (memcmp(p, VG_CONTAINER_MAGIC, 8) != 0) return VG_ERR_BAD_MAGIC;
    if (vg_load_le32(p + 8) != VG_FORMAT_VERSION) return VG_ERR_UNSUPPORTED_VERSION;
    const uint32_t flags = vg_load_le32(p + 12);
    if ((flags & ~(VG_FLAG_ZSTD | VG_FLAG_CODED_DISTANCES | VG_FLAG_INNER_ROWS_AT_OPEN)) != 0)
        return VG_ERR_UNSUPPORTED_FLAGS;
    h.compressed = (flags & VG_FLAG_ZSTD) != 0;
    h.coded = (flags & VG_FLAG_CODED_DISTANCES) != 0;
    h.innerRowsAtOpen = (flags & VG_FLAG_INNER_ROWS_AT_OPEN) != 0;
    // Only a coded blob leaves its inner rows out (its tables are decoded in caller memory).
    if (h.innerRowsAtOpen && !h.coded) return VG_ERR_CORRUPT_STRUCTURE;
#if !VG_WITH_ZSTD
    if (h.compressed) return VG_ERR_UNSUPPORTED_FLAGS;
#endif
    h.payloadSize = vg_load_le64(p + 16);
    h.flatbufferSize = vg_load_le64(p + 24);
    h.tableBytes = vg_load_le64(p + 32);
    h.checksum = vg_load_le64(p + 40);
    const uint64_t present = blobSize - VG_CONTAINER_HEADER_SIZE;
    if (h.payloadSize > present) return VG_ERR_TRUNCATED;
    if (h.payloadSize < present) return VG_ERR_CORRUPT_STRUCTURE;  // trailing bytes
    if (h.flatbufferSize == 0 || h.flatbufferSize > kMaxFlatbuffer) return VG_ERR_CORRUPT_STRUCTURE;
    if (h.tableBytes > kMaxTableBytes || h.tableBytes % 64 != 0) return VG_ERR_CORRUPT_STRUCTURE;
    if (h.innerRowsAtOpen && h.tableBytes == 0) return VG_ERR_CORRUPT_STRUCTURE;  // no labels
    h.unpackedSize = h.tableBytes ? vg_align64(h.flatbufferSize) + h.tableBytes : h.flatbufferSize;
    if (h.unpackedSize > SIZE_MAX - 4 * kAlign) return VG_ERR_OUT_OF_MEMORY;  // a 32-bit process
    if (!h.compressed && h.unpackedSize != h.payloadSize) return VG_ERR_CORRUPT_STRUCTURE;
#if VG_WITH_ZSTD
    // The frames state their sizes too: a header that claims more than they hold together
    // is refused before anyone sizes memory by it (the header is outside the checksum).
    if (h.compressed && unpackedBytes(p + VG_CONTAINER_HEADER_SIZE, size_t(h.payloadSize)) != h.unpackedSize)
        return VG_ERR_DECOMPRESSION;
#endif
    return VG_OK;
}

size_t decompressionContextSize() {
#if VG_WITH_ZSTD
    return ZSTD_estimateDCtxSize();
#else
    return 0;
#endif
}

// An uncompressed payload is used in place when 8-byte aligned; otherwise it is copied.
bool usableInPlace(const void* blob) {
    return ((reinterpret_cast<uintptr_t>(blob) + VG_CONTAINER_HEADER_SIZE) & 7u) == 0;
}

// Coded distances are decoded where they lie, so such a payload is always copied.
bool copied(const void* blob, const Header& h) { return !h.compressed && (h.coded || !usableInPlace(blob)); }

// Layout of the caller memory: [graph][payload copy][zstd context or decoding scratch],
// each aligned (the scratch is needed only after decompression, so they share the space).
size_t memoryNeeded(const void* blob, const Header& h) {
    size_t n = kAlign - 1 + alignUp(sizeof(vg_graph));
    if (h.compressed || copied(blob, h)) n += alignUp(size_t(h.unpackedSize));
    size_t scratch = h.compressed ? decompressionContextSize() : 0;
    if (h.coded && vg::decodeScratchSize() > scratch) scratch = vg::decodeScratchSize();
    if (h.coded && vg::labelDecodeScratchSize() > scratch) scratch = vg::labelDecodeScratchSize();
    if (h.innerRowsAtOpen && vg::innerRowsScratchSize() > scratch) scratch = vg::innerRowsScratchSize();
    return n + alignUp(scratch);
}

}  // namespace

extern "C" vg_status vg_open_size(const void* blob, size_t blob_size, size_t* out_memory_size) {
    if (out_memory_size == nullptr) return VG_ERR_INVALID_ARGUMENT;
    *out_memory_size = 0;
    Header h;
    const vg_status st = readHeader(blob, blob_size, h);
    if (st != VG_OK) return st;
    *out_memory_size = memoryNeeded(blob, h);
    return VG_OK;
}

extern "C" vg_status vg_open(const void* blob, size_t blob_size, void* memory, size_t memory_size,
                             const vg_graph** out_graph) {
    if (out_graph == nullptr) return VG_ERR_INVALID_ARGUMENT;
    *out_graph = nullptr;
    if (memory == nullptr) return VG_ERR_INVALID_ARGUMENT;
    Header h;
    vg_status st = readHeader(blob, blob_size, h);
    if (st != VG_OK) return st;
    if (memory_size < memoryNeeded(blob, h)) return VG_ERR_BUFFER_TOO_SMALL;

    const unsigned char* payload = static_cast<const unsigned char*>(blob) + VG_CONTAINER_HEADER_SIZE;
    if (vg_checksum64(payload, size_t(h.payloadSize)) != h.checksum) return VG_ERR_CHECKSUM;

    // Before the first write: a compressed or copied graph is then laid out in huge pages.
    vg::adviseHugePages(memory, memory_size);
    unsigned char* cursor = reinterpret_cast<unsigned char*>(
        (reinterpret_cast<uintptr_t>(memory) + kAlign - 1) & ~uintptr_t(kAlign - 1));
    vg_graph* graph = reinterpret_cast<vg_graph*>(cursor);
    cursor += alignUp(sizeof(vg_graph));

    const unsigned char* unpacked = payload;
    if (h.compressed) {
#if VG_WITH_ZSTD
        unsigned char* target = cursor;
        cursor += alignUp(size_t(h.unpackedSize));
        // readHeader has checked that the frames state the unpacked size between them.
        ZSTD_DCtx* dctx = ZSTD_initStaticDCtx(cursor, decompressionContextSize());
        if (dctx == nullptr) return VG_ERR_DECOMPRESSION;
        const size_t got = ZSTD_decompressDCtx(dctx, target, size_t(h.unpackedSize), payload, size_t(h.payloadSize));
        if (ZSTD_isError(got) || got != h.unpackedSize) return VG_ERR_DECOMPRESSION;
        unpacked = target;
#endif
    } else if (copied(blob, h)) {
        memcpy(cursor, payload, size_t(h.unpackedSize));
        unpacked = cursor;
        cursor += alignUp(size_t(h.unpackedSize));
    }

    const vg::Tables tables{h.tableBytes ? unpacked + vg_align64(h.flatbufferSize) : nullptr, h.tableBytes};
    st = vg::verifyAndBind(unpacked, size_t(h.flatbufferSize), tables, *graph, h.coded);
    if (st != VG_OK) return st;
    const bool avx2 = vg::cpuHasAvx2();
    if (h.coded) {
        vg::decodeDistances(*graph, avx2, cursor);
        vg::decodeLabels(*graph, !h.innerRowsAtOpen, cursor);
        if (h.innerRowsAtOpen) {
            if (graph->hubTreeCount == 0) return VG_ERR_CORRUPT_CONTENT;
            st = vg::computeInnerRows(*graph, avx2, cursor);
            if (st != VG_OK) return st;
        }
    }
    graph->fileAllocator = vg_allocator{nullptr, nullptr, nullptr};
    graph->fileMemory = nullptr;
    graph->fileMapping = nullptr;
    graph->fileMappingSize = 0;
    graph->avx2 = avx2;
    graph->avx512 = avx2 && vg::cpuHasAvx512();
    *out_graph = graph;
    return VG_OK;
}

extern "C" int vg_supports_compression(void) { return VG_WITH_ZSTD ? 1 : 0; }

extern "C" uint32_t vg_vertex_count(const vg_graph* graph) { return graph ? graph->vertexCount : 0; }
extern "C" int vg_has_hub_labels(const vg_graph* graph) { return graph && graph->hubTreeCount > 0 ? 1 : 0; }
extern "C" uint32_t vg_node_count(const vg_graph* graph) { return graph ? graph->nodeCount : 0; }
extern "C" float vg_bbox_diagonal(const vg_graph* graph) { return graph ? graph->bboxDiagonal : 0.0f; }
