// Reading a .vgeo blob on the tool side: container checks (magic, format version, flags,
// sizes, checksum), zstd decompression, the flatbuffers verifier and the decoding of
// prediction-coded arrays (after the runtime's own validation of the blob, and checking
// the ranges it reads), so that `flatbuffer` holds plain values (unless asked not to
// decode, below). The engine-side
// reader is the runtime's; this one serves the tools and the tests.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vorogeo_generated.h"

namespace vorogeo::tools {

struct BlobContents {
    uint32_t formatVersion = 0;
    bool compressed = false;
    bool coded = false;               // the file's distances were prediction-coded
    bool innerRowsAtOpen = false;     // hubInner is the zeros of a blob that leaves it to vg_open
    std::vector<uint8_t> flatbuffer;  // verified
    // The hub-label tables after the flatbuffer (decoded; empty without labels).
    std::vector<uint16_t> hubColumns, hubInner;
    const fb::Graph* graph() const { return fb::GetGraph(flatbuffer.data()); }
};

// False with a one-line reason ("not a vorogeo blob (bad magic)", "format version 2 is
// not supported (this build reads version 1)", "checksum mismatch", ...). With `decode`
// false, a coded blob's arrays stay as stored (and unchecked beyond the verifier): enough
// for its sizes, counts and bake parameters, which `vorogeo info` prints, without the
// runtime's open (igea x16: 75 s and 9.6 GB).
bool unpackBlob(const std::vector<uint8_t>& bytes, BlobContents& out, std::string& error, bool decode = true);
bool readBlobFile(const std::string& path, BlobContents& out, std::string& error, bool decode = true);

}  // namespace vorogeo::tools
