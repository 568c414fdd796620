#include "blob_reader.h"

#include <cstring>
#include <fstream>
#include <iterator>

#include <zstd.h>

#include "vorogeo_container.h"
#include "vorogeo_distance_coding.h"

namespace vorogeo::tools {

namespace {

// Decodes the distances in place (schema/vorogeo_distance_coding.h) after checking that
// every patch's slots, slot ids and matrix lie inside their arrays; the runtime checks all
// of that and more in vg_validate, the tools only what the decoder reads.
bool decodeDistances(std::vector<uint8_t>& flatbuffer, std::string& error) {
    const fb::Graph* g = fb::GetGraph(flatbuffer.data());
    if (!g->positions() || !g->slots() || !g->node_vertex() || !g->second_patches() || !g->first_patches() ||
        !g->second_distances() || !g->first_distances()) {
        error = "coded distances without the arrays they are decoded from";
        return false;
    }
    const uint64_t vertices = g->positions()->size() / 3, nodes = g->node_vertex()->size();
    const uint64_t slotCount = g->slots()->size();
    for (uint32_t n : *g->node_vertex())
        if (n >= vertices) {
            error = "a node's vertex is out of range";
            return false;
        }
    auto bytesOf = [&](const flatbuffers::Vector<uint8_t>* v) { return flatbuffer.data() + (v->data() - flatbuffer.data()); };
    auto decodeLayer = [&](const flatbuffers::Vector<const fb::PatchRecord*>* patches, const flatbuffers::Vector<uint8_t>* array,
                           bool firstLayer) {
        uint8_t* packed = bytesOf(array);
        const uint64_t capacity = (array->size() / 3) * 2 + (array->size() % 3 == 2 ? 1 : 0);
        for (const fb::PatchRecord* p : *patches) {
            const uint64_t S = p->slot_count(), n = p->node_count();
            const uint64_t entries = firstLayer ? S * S : n * S + (S - n) * (S > n ? S - n - 1 : 0) / 2;
            if (p->slot_begin() + S > slotCount || n > S || S > 65536 || (firstLayer && n != S) ||
                p->matrix_begin() > capacity || entries > capacity - p->matrix_begin()) {
                error = "a patch's slots or matrix lie outside their arrays";
                return false;
            }
            const uint32_t* slots = g->slots()->data() + p->slot_begin();
            for (uint64_t i = 0; i < S; ++i)
                if (i < n ? slots[i] >= nodes : slots[i] >= vertices) {
                    error = "a patch slot is out of range";
                    return false;
                }
            const vg_coding_slots s{g->positions()->data(), slots, g->node_vertex()->data(), uint32_t(n)};
            if (firstLayer)
                vg_code_first_matrix(packed, packed, p->matrix_begin(), uint32_t(S), p->scale(), &s, 1);
            else
                vg_code_second_matrix(packed, packed, p->matrix_begin(), uint32_t(S), uint32_t(n), p->scale(), &s, 1);
        }
        return true;
    };
    return decodeLayer(g->second_patches(), g->second_distances(), false) &&
           decodeLayer(g->first_patches(), g->first_distances(), true);
}

}  // namespace

bool unpackBlob(const std::vector<uint8_t>& bytes, BlobContents& out, std::string& error) {
    if (bytes.size() < VG_CONTAINER_HEADER_SIZE) {
        error = "too short for a vorogeo blob (" + std::to_string(bytes.size()) + " bytes)";
        return false;
    }
    const unsigned char* h = bytes.data();
    if (std::memcmp(h, VG_CONTAINER_MAGIC, 8) != 0) {
        error = "not a vorogeo blob (bad magic)";
        return false;
    }
    out.formatVersion = vg_load_le32(h + 8);
    if (out.formatVersion != VG_FORMAT_VERSION) {
        error = "format version " + std::to_string(out.formatVersion) + " is not supported (this build reads version " +
                std::to_string(VG_FORMAT_VERSION) + ")";
        return false;
    }
    const uint32_t flags = vg_load_le32(h + 12);
    if (flags & ~(VG_FLAG_ZSTD | VG_FLAG_CODED_DISTANCES)) {
        error = "unknown flags " + std::to_string(flags);
        return false;
    }
    out.compressed = (flags & VG_FLAG_ZSTD) != 0;
    out.coded = (flags & VG_FLAG_CODED_DISTANCES) != 0;
    const uint64_t payload = vg_load_le64(h + 16), size = vg_load_le64(h + 24);
    if (payload != bytes.size() - VG_CONTAINER_HEADER_SIZE) {
        error = "payload size " + std::to_string(payload) + " does not match the " +
                std::to_string(bytes.size() - VG_CONTAINER_HEADER_SIZE) + " bytes present (truncated or padded)";
        return false;
    }
    if (vg_checksum64(h + VG_CONTAINER_HEADER_SIZE, payload) != vg_load_le64(h + 32)) {
        error = "checksum mismatch (corrupted blob)";
        return false;
    }
    if (!out.compressed && size != payload) {
        error = "uncompressed blob with flatbuffer size different from its payload";
        return false;
    }
    if (size > (uint64_t(1) << 31)) {
        error = "flatbuffer size " + std::to_string(size) + " is larger than 2 GiB";
        return false;
    }
    out.flatbuffer.resize(size_t(size));
    if (out.compressed) {
        const size_t n = ZSTD_decompress(out.flatbuffer.data(), out.flatbuffer.size(), h + VG_CONTAINER_HEADER_SIZE, payload);
        if (ZSTD_isError(n) || n != size) {
            error = std::string("zstd frame does not decompress to the stated size") +
                    (ZSTD_isError(n) ? std::string(": ") + ZSTD_getErrorName(n) : std::string());
            return false;
        }
    } else if (size) {
        std::memcpy(out.flatbuffer.data(), h + VG_CONTAINER_HEADER_SIZE, size_t(size));
    }
    flatbuffers::Verifier verifier(out.flatbuffer.data(), out.flatbuffer.size());
    if (!fb::VerifyGraphBuffer(verifier)) {
        error = "flatbuffer fails verification (corrupted or not a vorogeo graph)";
        return false;
    }
    return !out.coded || decodeDistances(out.flatbuffer, error);
}

bool readBlobFile(const std::string& path, BlobContents& out, std::string& error) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        error = path + ": cannot open";
        return false;
    }
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!unpackBlob(bytes, out, error)) {
        error = path + ": " + error;
        return false;
    }
    return true;
}

}  // namespace vorogeo::tools
