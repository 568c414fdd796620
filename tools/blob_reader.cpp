#include "blob_reader.h"

#include <cstring>
#include <fstream>
#include <iterator>

#include <zstd.h>

#include "vorogeo_container.h"

namespace vorogeo::tools {

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
    if (flags & ~VG_FLAG_ZSTD) {
        error = "unknown flags " + std::to_string(flags);
        return false;
    }
    out.compressed = (flags & VG_FLAG_ZSTD) != 0;
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
    return true;
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
