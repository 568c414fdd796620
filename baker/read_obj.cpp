// Wavefront OBJ reader: "v" positions and "f" polygons; everything else (texture
// coordinates, normals, groups, materials, lines) is irrelevant to geodesics and skipped.
#include <algorithm>
#include <cstring>

#include "mesh_soup.h"
#include "text_scan.h"

namespace vorogeo {

bool looksLikeObj(std::string_view data) {
    // Some line starts with "v " or "f ": good enough to tell OBJ from other text.
    TextScanner s(data.substr(0, 1 << 16));
    while (!s.atEnd()) {
        std::string_view t = s.token();
        if (t == "v" || t == "f") return true;
        s.nextLine();
    }
    return false;
}

bool readObj(std::string_view data, PolygonSoup& soup, std::string& error) {
    if (std::memchr(data.data(), '\0', std::min<size_t>(data.size(), 4096))) {
        error = "contains binary data, not a text OBJ file";
        return false;
    }
    TextScanner s(data);
    for (; !s.atEnd(); s.nextLine()) {
        std::string_view key = s.token();
        if (key == "v") {
            double c[3];
            for (double& x : c) {
                std::string_view t = s.token();
                if (!TextScanner::parseDouble(t, x)) {
                    error = s.where() + ": vertex needs three numeric coordinates, got '" + std::string(t) + "'";
                    return false;
                }
            }
            soup.positions.push_back({c[0], c[1], c[2]});
        } else if (key == "f") {
            const int64_t vertexCount = int64_t(soup.positions.size());
            for (std::string_view t = s.token(); !t.empty() && t[0] != '#'; t = s.token()) {
                // "i", "i/t", "i//n" or "i/t/n": only the position index matters.
                std::string_view head = t.substr(0, t.find('/'));
                int64_t i;
                if (!TextScanner::parseInt(head, i)) {
                    error = s.where() + ": bad face index '" + std::string(t) + "'";
                    return false;
                }
                // OBJ counts from 1; negative indices count back from the latest vertex.
                // 0 is invalid and becomes -1 so that validation reports it as out of range.
                soup.indices.push_back(i > 0 ? i - 1 : i < 0 ? vertexCount + i : -1);
            }
            soup.endPolygon();
        }
    }
    return true;
}

}  // namespace vorogeo
