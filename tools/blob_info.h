// `vorogeo info` on a .vgeo blob: what was baked, with which parameters, and its sizes.
#pragma once

#include <string>

namespace vorogeo::tools {

// True if the file starts with the blob magic (so `info` describes a blob, not a mesh).
bool looksLikeBlob(const std::string& path);

// Reads and verifies the blob, prints its description (text or one JSON object);
// returns the exit status (1 after printing the reason if the blob is rejected).
int printBlobInfo(const std::string& path, bool json);

}  // namespace vorogeo::tools
