// OFF reader (Geomview Object File Format, ASCII): "OFF", counts "V F E", V vertex lines,
// F face lines "n i1 .. in [colour]". COFF/NOFF/STOFF variants carry extra per-vertex
// values after x y z, which are skipped.
#include <algorithm>
#include <cstring>

#include "mesh_soup.h"
#include "text_scan.h"

namespace vorogeo {
namespace {

// The first token of the next record, skipping blank lines and '#' comments.
std::string_view recordToken(TextScanner& s) {
    for (;;) {
        std::string_view t = s.anyToken();
        if (t.empty() || t[0] != '#') return t;
        s.nextLine();
    }
}

bool isOffKeyword(std::string_view t) {
    if (t.size() < 3 || t.substr(t.size() - 3) != "OFF") return false;
    std::string_view prefix = t.substr(0, t.size() - 3);
    for (char c : prefix)
        if (!std::strchr("STCNn4", c)) return false;
    return true;
}

}  // namespace

bool looksLikeOff(std::string_view data) {
    TextScanner s(data.substr(0, 4096));
    return isOffKeyword(recordToken(s));
}

bool readOff(std::string_view data, PolygonSoup& soup, std::string& error) {
    if (std::memchr(data.data(), '\0', std::min<size_t>(data.size(), 4096))) {
        error = "contains binary data; binary OFF is not supported";
        return false;
    }
    TextScanner s(data);
    std::string_view key = recordToken(s);
    if (!isOffKeyword(key)) {
        error = "not an OFF file (first keyword is '" + std::string(key.substr(0, 20)) + "', expected OFF)";
        return false;
    }
    if (key.find('4') != std::string_view::npos || key.find('n') != std::string_view::npos) {
        error = "'" + std::string(key) + "' (non-3D OFF) is not supported";
        return false;
    }
    std::string_view t = s.token();
    if (t == "BINARY") {
        error = "binary OFF is not supported";
        return false;
    }
    if (t.empty() || t[0] == '#') t = recordToken(s);  // counts on their own line
    int64_t counts[3] = {0, 0, 0};
    for (int i = 0; i < 3; ++i) {
        if (i > 0) t = s.token();
        if (i == 2 && (t.empty() || t[0] == '#')) break;  // edge count is optional
        if (!TextScanner::parseInt(t, counts[i]) || counts[i] < 0) {
            error = s.where() + ": expected vertex, face and edge counts, got '" + std::string(t) + "'";
            return false;
        }
    }
    s.nextLine();
    const int64_t nv = counts[0], nf = counts[1];
    // Every record needs at least a few bytes: do not trust absurd counts with memory.
    if (nv > int64_t(data.size()) || nf > int64_t(data.size())) {
        error = "counts (" + std::to_string(nv) + " vertices, " + std::to_string(nf) +
                " faces) exceed what the file can hold";
        return false;
    }
    soup.positions.reserve(size_t(nv));
    for (int64_t v = 0; v < nv; ++v) {
        double c[3];
        for (int k = 0; k < 3; ++k) {
            t = k == 0 ? recordToken(s) : s.token();
            if (!TextScanner::parseDouble(t, c[k])) {
                error = s.where() + ": vertex " + std::to_string(v) + " needs three numeric coordinates" +
                        (t.empty() ? " (file ends early)" : ", got '" + std::string(t) + "'");
                return false;
            }
        }
        soup.positions.push_back({c[0], c[1], c[2]});
        s.nextLine();
    }
    for (int64_t f = 0; f < nf; ++f) {
        int64_t n;
        t = recordToken(s);
        if (!TextScanner::parseInt(t, n) || n < 0) {
            error = s.where() + ": face " + std::to_string(f) + " needs a vertex count" +
                    (t.empty() ? " (file ends early)" : ", got '" + std::string(t) + "'");
            return false;
        }
        for (int64_t k = 0; k < n; ++k) {
            int64_t i;
            t = s.token();
            if (!TextScanner::parseInt(t, i)) {
                error = s.where() + ": face " + std::to_string(f) + " lists " + std::to_string(n) +
                        " vertices but index " + std::to_string(k) + " is '" + std::string(t) + "'";
                return false;
            }
            soup.indices.push_back(i);
        }
        soup.endPolygon();
        s.nextLine();  // optional colour values
    }
    return true;
}

}  // namespace vorogeo
