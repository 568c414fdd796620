// The real test meshes in ../shared/meshes load cleanly and computeStats agrees with the
// reference statistics in stats.jsonl. Skipped when the shared folder is absent.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>
#include <map>

#include "mesh_io.h"
#include "mesh_stats.h"
#include "test_helpers.h"

using namespace vorogeo;

namespace {

// Top-level "key": value pairs of one JSON object line, values as raw text (strings
// without quotes). Nested objects and arrays are skipped: their keys repeat top-level names.
std::map<std::string, std::string> topLevelFields(const std::string& line) {
    std::map<std::string, std::string> fields;
    int depth = 0;
    size_t i = 0;
    auto readString = [&](size_t& k) {
        std::string s;
        for (++k; k < line.size() && line[k] != '"'; ++k) {
            if (line[k] == '\\') ++k;
            s += line[k];
        }
        ++k;
        return s;
    };
    while (i < line.size()) {
        const char c = line[i];
        if (c == '"') {
            const std::string s = readString(i);
            if (depth == 1 && i < line.size() && line[i] == ':') {
                size_t v = ++i;
                if (line[v] == '"') {
                    fields[s] = readString(v);
                    i = v;
                } else if (line[v] != '{' && line[v] != '[') {
                    while (v < line.size() && line[v] != ',' && line[v] != '}') ++v;
                    fields[s] = line.substr(i, v - i);
                    i = v;
                }
            }
            continue;
        }
        if (c == '{' || c == '[') ++depth;
        if (c == '}' || c == ']') --depth;
        ++i;
    }
    return fields;
}

}  // namespace

TEST_CASE("shared meshes match stats.jsonl", "[shared][stats]") {
    const std::string dir = test::sharedMeshDir();
    if (dir.empty()) {
        WARN("skipped: no shared meshes at " << VOROGEO_SHARED_DIR << "/meshes");
        return;
    }
    std::ifstream in(dir + "/stats.jsonl");
    std::string line;
    int meshes = 0;
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        auto f = topLevelFields(line);
        REQUIRE(f.count("file"));
        const std::string path = dir + "/" + f["file"];
        INFO(path);
        Mesh m;
        const LoadReport r = loadMesh(path, LoadOptions{}, m);
        INFO(r.error);
        REQUIRE(r.ok);
        CHECK(r.notices.empty());
        const MeshStats s = computeStats(m);
        auto integer = [&](const char* key) { return std::strtoll(f.at(key).c_str(), nullptr, 10); };
        auto real = [&](const char* key) { return std::strtod(f.at(key).c_str(), nullptr); };
        CHECK(int64_t(s.vertices) == integer("vertices"));
        CHECK(int64_t(s.faces) == integer("faces"));
        CHECK(int64_t(s.edges) == integer("edges"));
        CHECK(int64_t(s.boundaryEdges) == integer("boundary_edges"));
        CHECK(int64_t(s.boundaryLoops) == integer("boundary_loops"));
        CHECK(int64_t(s.components) == integer("components"));
        CHECK(s.euler == integer("euler"));
        CHECK(s.genus == integer("genus"));
        CHECK(s.bboxDiag == Approx(real("bbox_diag")).epsilon(1e-4));
        CHECK(s.edgeLenMin == Approx(real("edge_len_min")).epsilon(1e-4));
        CHECK(s.edgeLenMean == Approx(real("edge_len_mean")).epsilon(1e-4));
        CHECK(s.edgeLenMax == Approx(real("edge_len_max")).epsilon(1e-4));
        CHECK(s.area == Approx(real("area")).epsilon(1e-4));
        ++meshes;
    }
    CHECK(meshes >= 7);
}
