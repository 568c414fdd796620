#include "mesh_report.h"

#include <cinttypes>

namespace vorogeo::tools {
namespace {

std::string jsonString(const std::string& s) {
    std::string out = "\"";
    for (unsigned char c : s) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += char(c);
        } else if (c < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            out += buf;
        } else {
            out += char(c);
        }
    }
    return out + "\"";
}

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.12g", v);
    return buf;
}

std::string vec(Vec3 v) { return "[" + num(v.x) + "," + num(v.y) + "," + num(v.z) + "]"; }

}  // namespace

void printStatsText(FILE* out, const MeshStats& s) {
    std::fprintf(out, "  vertices          %" PRIu64 " (%" PRIu64 " isolated)\n", s.vertices, s.isolatedVertices);
    std::fprintf(out, "  faces             %" PRIu64 "\n", s.faces);
    std::fprintf(out, "  edges             %" PRIu64 " (%" PRIu64 " on a boundary)\n", s.edges, s.boundaryEdges);
    std::fprintf(out, "  boundary loops    %" PRIu64 "\n", s.boundaryLoops);
    std::fprintf(out, "  components        %" PRIu64 "\n", s.components);
    std::fprintf(out, "  euler / genus     %" PRId64 " / %" PRId64 "\n", s.euler, s.genus);
    std::fprintf(out, "  bbox              [%.6g, %.6g, %.6g] .. [%.6g, %.6g, %.6g], diagonal %.6g\n", s.bboxMin.x,
                 s.bboxMin.y, s.bboxMin.z, s.bboxMax.x, s.bboxMax.y, s.bboxMax.z, s.bboxDiag);
    std::fprintf(out, "  edge length       min %.6g, mean %.6g, max %.6g\n", s.edgeLenMin, s.edgeLenMean, s.edgeLenMax);
    std::fprintf(out, "  saddle vertices   %.2f%% of %" PRIu64 " interior vertices\n", 100 * s.saddleRatio,
                 s.interiorVertices);
    std::fprintf(out, "  near-flat saddles %.2f%% (angle sum below 2 pi x %.3f: thin shadows, many exact windows)\n",
                 100 * s.nearFlatSaddleRatio, 1 + kNearFlatSaddleExcess);
    std::fprintf(out, "  area              %.6g\n", s.area);
}

std::string statsJson(const std::string& file, const MeshStats& s, double loadSeconds,
                      const std::vector<std::string>& notices) {
    std::string j = "{\"file\":" + jsonString(file);
    j += ",\"vertices\":" + std::to_string(s.vertices);
    j += ",\"faces\":" + std::to_string(s.faces);
    j += ",\"edges\":" + std::to_string(s.edges);
    j += ",\"boundary_edges\":" + std::to_string(s.boundaryEdges);
    j += ",\"boundary_loops\":" + std::to_string(s.boundaryLoops);
    j += ",\"components\":" + std::to_string(s.components);
    j += ",\"genus\":" + std::to_string(s.genus);
    j += ",\"euler\":" + std::to_string(s.euler);
    j += ",\"bbox_min\":" + vec(s.bboxMin);
    j += ",\"bbox_max\":" + vec(s.bboxMax);
    j += ",\"bbox_diag\":" + num(s.bboxDiag);
    j += ",\"edge_len_min\":" + num(s.edgeLenMin);
    j += ",\"edge_len_mean\":" + num(s.edgeLenMean);
    j += ",\"edge_len_max\":" + num(s.edgeLenMax);
    j += ",\"saddle_ratio\":" + num(s.saddleRatio);
    j += ",\"near_flat_saddle_ratio\":" + num(s.nearFlatSaddleRatio);
    j += ",\"area\":" + num(s.area);
    j += ",\"isolated_vertices\":" + std::to_string(s.isolatedVertices);
    j += ",\"load_seconds\":" + num(loadSeconds);
    j += ",\"notices\":[";
    for (size_t i = 0; i < notices.size(); ++i) j += (i ? "," : "") + jsonString(notices[i]);
    return j + "]}";
}

}  // namespace vorogeo::tools
