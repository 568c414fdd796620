// A polygon soup exactly as a mesh file states it, and the per-format readers that
// fill it. Readers only parse: they never merge, drop or reorder vertices or faces,
// so that validation sees every defect the file contains.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "mesh.h"

namespace vorogeo {

struct PolygonSoup {
    std::vector<Vec3> positions;
    // Polygon p uses indices[polygonStart[p] .. polygonStart[p+1]); indices are 0-based
    // and kept as int64 so that negative or too-large values survive until validation.
    std::vector<int64_t> indices;
    std::vector<uint32_t> polygonStart{0};
    // Things the reader did that change the soup's meaning (e.g. STL corner welding,
    // PLY triangle strips decoded); they become LoadReport notices.
    std::vector<std::string> notices;

    uint32_t polygonCount() const { return uint32_t(polygonStart.size() - 1); }
    void endPolygon() { polygonStart.push_back(uint32_t(indices.size())); }
};

// Each reader parses the whole file content `data`. On failure it returns false and sets
// `error` to a short description without the file name ("line 7: ...").
bool readObj(std::string_view data, PolygonSoup& soup, std::string& error);
bool readOff(std::string_view data, PolygonSoup& soup, std::string& error);
bool readPly(std::string_view data, PolygonSoup& soup, std::string& error);
bool readStl(std::string_view data, PolygonSoup& soup, std::string& error);

// True if `data` starts the way the format's files do (used to sniff unknown extensions
// and to reject files whose content contradicts their extension).
bool looksLikePly(std::string_view data);
bool looksLikeOff(std::string_view data);
bool looksLikeBinaryStl(std::string_view data);
bool looksLikeAsciiStl(std::string_view data);
bool looksLikeObj(std::string_view data);

}  // namespace vorogeo
