// STL reader (binary and ASCII). STL stores every triangle corner as its own coordinates,
// so corners with bit-identical coordinates are identified to recover shared vertices:
// that is the format's meaning, not a repair, and it is reported as a notice. Nothing
// closer than identical is merged.
#include <algorithm>
#include <cstring>
#include <unordered_map>

#include "mesh_soup.h"
#include "text_scan.h"

namespace vorogeo {
namespace {

struct CornerKey {
    uint64_t bits[3];
    bool operator==(const CornerKey& o) const {
        return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
    }
};
struct CornerHash {
    size_t operator()(const CornerKey& k) const {
        uint64_t h = k.bits[0] * 0x9E3779B97F4A7C15ull;
        h ^= (k.bits[1] + 0x632BE59BD9B4E019ull) * 0xC2B2AE3D27D4EB4Full;
        h ^= (k.bits[2] + 0x85157AF5ull) * 0x165667B19E3779F9ull;
        return size_t(h ^ (h >> 29));
    }
};

class CornerWelder {
public:
    explicit CornerWelder(PolygonSoup& soup) : soup_(soup) {}
    void corner(double x, double y, double z) {
        CornerKey key;
        const double c[3] = {x, y, z};
        for (int k = 0; k < 3; ++k) {
            const double v = c[k] == 0 ? 0.0 : c[k];  // -0 and +0 are the same point
            std::memcpy(&key.bits[k], &v, 8);
        }
        auto [it, fresh] = map_.try_emplace(key, uint32_t(soup_.positions.size()));
        if (fresh) soup_.positions.push_back({x, y, z});
        soup_.indices.push_back(it->second);
        ++corners_;
    }
    void notice() {
        soup_.notices.push_back("STL: identified " + std::to_string(corners_) + " triangle corners with " +
                                std::to_string(soup_.positions.size()) +
                                " distinct vertices (exactly equal coordinates only)");
    }
    void reserve(size_t corners) { map_.reserve(corners / 4); }

private:
    PolygonSoup& soup_;
    std::unordered_map<CornerKey, uint32_t, CornerHash> map_;
    uint64_t corners_ = 0;
};

uint32_t binaryTriangleCount(std::string_view data) {
    uint32_t n;
    std::memcpy(&n, data.data() + 80, 4);  // STL is little-endian; so are the targets we build for
    return n;
}

bool readBinary(std::string_view data, PolygonSoup& soup) {
    const uint32_t n = binaryTriangleCount(data);
    CornerWelder weld(soup);
    weld.reserve(size_t(n) * 3);
    soup.polygonStart.reserve(size_t(n) + 1);
    const char* p = data.data() + 84;
    for (uint32_t t = 0; t < n; ++t, p += 50) {
        float f[9];
        std::memcpy(f, p + 12, sizeof f);  // skip the stored normal
        for (int k = 0; k < 3; ++k) weld.corner(f[3 * k], f[3 * k + 1], f[3 * k + 2]);
        soup.endPolygon();
    }
    weld.notice();
    return true;
}

bool readAscii(std::string_view data, PolygonSoup& soup, std::string& error) {
    TextScanner s(data);
    CornerWelder weld(soup);
    bool inLoop = false;
    for (std::string_view t = s.anyToken(); !t.empty(); t = s.anyToken()) {
        if (t == "vertex") {
            double c[3];
            for (double& x : c) {
                std::string_view v = s.anyToken();
                if (!TextScanner::parseDouble(v, x)) {
                    error = s.where() + ": vertex needs three numeric coordinates, got '" + std::string(v) + "'";
                    return false;
                }
            }
            if (!inLoop) {
                error = s.where() + ": vertex outside an 'outer loop'";
                return false;
            }
            weld.corner(c[0], c[1], c[2]);
        } else if (t == "outer") {
            inLoop = true;
        } else if (t == "endloop") {
            if (!inLoop) {
                error = s.where() + ": 'endloop' without 'outer loop'";
                return false;
            }
            inLoop = false;
            soup.endPolygon();
        } else if (t == "solid" || t == "endsolid") {
            s.nextLine();  // the solid's name may contain anything
        }
        // "facet normal nx ny nz", "loop", "endfacet": nothing to keep
    }
    if (inLoop) {
        error = "file ends inside a facet's 'outer loop'";
        return false;
    }
    weld.notice();
    return true;
}

}  // namespace

bool looksLikeBinaryStl(std::string_view data) {
    return data.size() >= 84 && uint64_t(data.size()) == 84 + 50ull * binaryTriangleCount(data);
}

bool looksLikeAsciiStl(std::string_view data) {
    TextScanner s(data.substr(0, 1024));
    return s.anyToken() == "solid" && !std::memchr(data.data(), '\0', std::min<size_t>(data.size(), 4096));
}

bool readStl(std::string_view data, PolygonSoup& soup, std::string& error) {
    // Binary files may also begin with "solid", so the size check decides first.
    if (looksLikeBinaryStl(data)) return readBinary(data, soup);
    if (looksLikeAsciiStl(data)) return readAscii(data, soup, error);
    error = data.size() < 84 ? "too short for a binary STL and does not start with 'solid'"
                             : "not an STL file: its size does not match the binary triangle count and it "
                               "does not start with 'solid'";
    return false;
}

}  // namespace vorogeo
