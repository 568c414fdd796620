// Loading: read file -> pick format -> parse into a polygon soup -> range checks ->
// triangulate -> prepareMesh (validate, repair, connectivity).
#include "mesh_io.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include <sys/stat.h>

#include "mesh_check.h"
#include "mesh_repair.h"
#include "mesh_soup.h"
#include "triangulate.h"

namespace vorogeo {
namespace {

std::string plural(uint64_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

bool readFile(const std::string& path, std::string& data, std::string& error) {
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) {
        error = std::string("cannot open file (") + std::strerror(errno) + ")";
        return false;
    }
    struct stat info;
    if (fstat(fileno(f), &info) == 0 && S_ISDIR(info.st_mode)) {
        std::fclose(f);
        error = "cannot read file (it is a directory)";
        return false;
    }
    // Read in chunks rather than trusting a size: pipes and devices have none.
    if (fstat(fileno(f), &info) == 0 && S_ISREG(info.st_mode)) data.reserve(size_t(info.st_size));
    char chunk[1 << 16];
    size_t n;
    while ((n = std::fread(chunk, 1, sizeof chunk, f)) > 0) data.append(chunk, n);
    const bool ok = !std::ferror(f);
    if (!ok) error = std::string("cannot read file (") + std::strerror(errno ? errno : EIO) + ")";
    std::fclose(f);
    return ok;
}

enum class Format { Obj, Off, Ply, Stl, Unknown };

std::string lowerExtension(const std::string& path) {
    const size_t slash = path.find_last_of("/\\");
    const size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot);
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

Format formatFromExtension(const std::string& ext) {
    if (ext == ".obj") return Format::Obj;
    if (ext == ".off") return Format::Off;
    if (ext == ".ply") return Format::Ply;
    if (ext == ".stl") return Format::Stl;
    return Format::Unknown;
}

Format formatFromContent(std::string_view data) {
    if (looksLikePly(data)) return Format::Ply;
    if (looksLikeOff(data)) return Format::Off;
    if (looksLikeBinaryStl(data) || looksLikeAsciiStl(data)) return Format::Stl;
    if (looksLikeObj(data)) return Format::Obj;
    return Format::Unknown;
}

const char* formatName(Format f) {
    switch (f) {
        case Format::Obj: return "OBJ";
        case Format::Off: return "OFF";
        case Format::Ply: return "PLY";
        case Format::Stl: return "STL";
        default: return "unknown";
    }
}

// Checks indices, turns polygons into triangles and remembers each triangle's polygon
// number so that messages can name the face as the file numbers it.
bool soupToMesh(PolygonSoup& soup, Mesh& mesh, std::vector<uint32_t>& sourceFace, std::vector<std::string>& notices,
                std::string& error) {
    const int64_t nv = int64_t(soup.positions.size());
    const uint32_t np = soup.polygonCount();
    uint64_t outOfRange = 0, shortPolygons = 0, bigPolygons = 0, fallbacks = 0;
    for (uint32_t p = 0; p < np; ++p) {
        for (uint32_t k = soup.polygonStart[p]; k < soup.polygonStart[p + 1]; ++k) {
            const int64_t i = soup.indices[k];
            if (i >= 0 && i < nv) continue;
            if (!outOfRange++)
                error = "face index out of range: face " + std::to_string(p) + " refers to vertex " +
                        std::to_string(i) + " but vertices are numbered 0.." + std::to_string(nv - 1);
            break;
        }
    }
    if (outOfRange) {
        if (outOfRange > 1) error += " (" + plural(outOfRange, "face is", "faces are") + " affected)";
        return false;
    }
    mesh.positions = std::move(soup.positions);
    mesh.faces.reserve(np);
    sourceFace.reserve(np);
    std::vector<uint32_t> poly;
    for (uint32_t p = 0; p < np; ++p) {
        const uint32_t b = soup.polygonStart[p], n = soup.polygonStart[p + 1] - b;
        poly.resize(n);
        for (uint32_t k = 0; k < n; ++k) poly[k] = uint32_t(soup.indices[b + k]);
        if (n < 3) {
            // Kept as a triangle with a repeated index, so that validation reports it as
            // degenerate (and --repair drops it) instead of it vanishing here.
            ++shortPolygons;
            const uint32_t a = n ? poly[0] : 0;
            mesh.faces.push_back({a, n > 1 ? poly[1] : a, a});
        } else {
            bigPolygons += n > 3;
            fallbacks += !triangulatePolygon(mesh.positions, poly.data(), n, mesh.faces);
        }
        sourceFace.resize(mesh.faces.size(), p);
    }
    if (bigPolygons)
        notices.push_back("triangulated " + plural(bigPolygons, "polygon", "polygons") +
                          " with more than 3 vertices (now " + std::to_string(mesh.faceCount()) + " triangles)");
    if (fallbacks)
        notices.push_back(plural(fallbacks, "polygon", "polygons") +
                           " were fan-triangulated (no proper ear: self-intersecting, degenerate or very large)");
    if (shortPolygons)
        notices.push_back(plural(shortPolygons, "face has", "faces have") + " fewer than 3 vertices");
    return true;
}

// Validation messages, in the order they are checked. `faceName` maps a triangle to its
// face number in the input.
struct Problem {
    std::string message;  // full sentence
    std::string brief;    // short form for the "also:" list
};

std::vector<Problem> describe(const MeshDefects& d, const std::vector<uint32_t>& sourceFace, const Mesh& mesh) {
    auto face = [&](int64_t f) { return std::to_string(sourceFace.empty() ? uint64_t(f) : sourceFace[size_t(f)]); };
    auto edge = [](const uint32_t e[2]) {
        return "vertex " + std::to_string(e[0]) + " (edge " + std::to_string(e[0]) + "-" + std::to_string(e[1]) + ")";
    };
    std::vector<Problem> out;
    if (d.outOfRangeFaces)
        out.push_back({"face index out of range: face " + face(d.firstOutOfRangeFace) + " refers to vertex " +
                           std::to_string(d.badIndex) + " but vertices are numbered 0.." +
                           std::to_string(int64_t(mesh.vertexCount()) - 1) +
                           (d.outOfRangeFaces > 1 ? " (" + plural(d.outOfRangeFaces, "face", "faces") + " affected)" : ""),
                       plural(d.outOfRangeFaces, "face", "faces") + " with out-of-range indices"});
    if (d.nonFiniteVertices)
        out.push_back({"non-finite coordinate (NaN or Inf) at vertex " + std::to_string(d.firstNonFiniteVertex) +
                           (d.nonFiniteVertices > 1
                                ? " (" + plural(d.nonFiniteVertices, "vertex", "vertices") + " affected)"
                                : ""),
                       plural(d.nonFiniteVertices, "vertex", "vertices") + " with NaN/Inf"});
    if (d.degenerateFaces)
        out.push_back({plural(d.degenerateFaces, "degenerate face", "degenerate faces") +
                           " (zero area or a repeated vertex), first is face " + face(d.firstDegenerateFace) +
                           "; rerun with --repair to drop " + (d.degenerateFaces == 1 ? "it" : "them"),
                       plural(d.degenerateFaces, "degenerate face", "degenerate faces")});
    if (d.duplicateFaces)
        out.push_back({plural(d.duplicateFaces, "duplicate face", "duplicate faces") +
                           " (same vertices as an earlier face), first is face " + face(d.firstDuplicateFace) +
                           "; rerun with --repair to drop " + (d.duplicateFaces == 1 ? "it" : "them"),
                       plural(d.duplicateFaces, "duplicate face", "duplicate faces")});
    if (d.misorientedEdges)
        out.push_back({"inconsistent face orientation: " + plural(d.misorientedEdges, "edge is", "edges are") +
                           " traversed in the same direction by both of its faces, first at " +
                           edge(d.firstMisorientedEdge) + "; rerun with --repair to re-orient the faces",
                       plural(d.misorientedEdges, "inconsistently oriented edge", "inconsistently oriented edges")});
    if (d.nonManifoldEdges)
        out.push_back({plural(d.nonManifoldEdges, "non-manifold edge", "non-manifold edges") +
                           " (shared by more than two faces), first at " + edge(d.firstNonManifoldEdge) +
                           "; rerun with --repair to split " + (d.nonManifoldEdges == 1 ? "it" : "them"),
                       plural(d.nonManifoldEdges, "non-manifold edge", "non-manifold edges")});
    if (d.nonManifoldVertices)
        out.push_back({plural(d.nonManifoldVertices, "non-manifold vertex", "non-manifold vertices") +
                           " (faces around it form separate fans), first is vertex " +
                           std::to_string(d.firstNonManifoldVertex) + "; rerun with --repair to split " +
                           (d.nonManifoldVertices == 1 ? "it" : "them"),
                       plural(d.nonManifoldVertices, "non-manifold vertex", "non-manifold vertices")});
    return out;
}

std::string joinProblems(const std::string& name, const std::vector<Problem>& problems, const char* prefix) {
    std::string line = name + ": " + prefix + problems[0].message;
    for (size_t i = 1; i < problems.size(); ++i) line += (i == 1 ? " (also: " : ", ") + problems[i].brief;
    if (problems.size() > 1) line += ")";
    return line;
}

LoadReport prepare(const std::string& name, const LoadOptions& options, Mesh& mesh, std::vector<uint32_t>& sourceFace,
                   std::vector<std::string> notices) {
    LoadReport report;
    report.notices = std::move(notices);
    mesh.twin.clear();
    mesh.vertexOut.clear();
    mesh.boundaryVertex.clear();
    if (mesh.positions.empty() || mesh.faces.empty()) {
        report.error = name + ": empty mesh (" + plural(mesh.positions.size(), "vertex", "vertices") + ", " +
                       plural(mesh.faces.size(), "face", "faces") + ")";
        return report;
    }
    MeshDefects defects = checkMesh(mesh);
    if (!defects.clean()) {
        // Bad indices and coordinates cannot be repaired: nothing sensible replaces them.
        const bool repairable = !defects.outOfRangeFaces && !defects.nonFiniteVertices;
        if (!options.repair || !repairable) {
            report.error = joinProblems(name, describe(defects, sourceFace, mesh), "");
            return report;
        }
        repairMesh(mesh, sourceFace, report.notices);
        if (mesh.faces.empty()) {
            report.error = name + ": empty mesh after repair (every face was degenerate or a duplicate)";
            return report;
        }
        defects = checkMesh(mesh);
        if (!defects.clean()) {
            report.error = joinProblems(name, describe(defects, sourceFace, mesh), "still invalid after repair: ");
            return report;
        }
    }
    if (defects.unreferencedVertices)
        report.notices.push_back(plural(defects.unreferencedVertices, "vertex is", "vertices are") +
                                 " used by no face (kept as isolated vertices)");
    const ConnectivityReport c = buildConnectivity(mesh);
    if (!c.ok) {  // cannot happen after a clean check; kept as a guard for future checks
        report.error = name + ": connectivity failed (" + std::to_string(c.nonManifoldEdges) +
                       " non-manifold edges, " + std::to_string(c.nonManifoldVertices) +
                       " non-manifold vertices, first at vertex " + std::to_string(c.firstBadVertex) + ")";
        return report;
    }
    report.ok = true;
    return report;
}

}  // namespace

LoadReport prepareMesh(const std::string& name, const LoadOptions& options, Mesh& inout) {
    std::vector<uint32_t> sourceFace;  // identity
    return prepare(name, options, inout, sourceFace, {});
}

LoadReport loadMesh(const std::string& path, const LoadOptions& options, Mesh& out) {
    LoadReport report;
    std::string data;
    if (!readFile(path, data, report.error)) {
        report.error = path + ": " + report.error;
        return report;
    }
    return loadMeshFromMemory(path, std::move(data), options, out);
}

LoadReport loadMeshFromMemory(const std::string& path, std::string data, const LoadOptions& options, Mesh& out) {
    LoadReport report;
    std::string error;
    const std::string ext = lowerExtension(path);
    Format format = formatFromExtension(ext);
    const Format sniffed = formatFromContent(data);
    std::vector<std::string> notices;
    if (format == Format::Unknown) {
        if (sniffed == Format::Unknown) {
            report.error = path + ": unknown mesh format (" +
                           (ext.empty() ? std::string("no file extension") : "extension '" + ext + "'") +
                           ", and the content is not recognised as OBJ, PLY, OFF or STL)";
            return report;
        }
        format = sniffed;
        notices.push_back(std::string("format detected from content: ") + formatName(format));
    } else if (format == Format::Ply && sniffed != Format::Ply) {
        // The one format with a mandatory magic line: a mismatch is a wrong file, not a quirk.
        report.error = path + ": not a PLY file (does not start with 'ply'" +
                       (sniffed != Format::Unknown ? std::string("; looks like ") + formatName(sniffed) : "") + ")";
        return report;
    }

    PolygonSoup soup;
    bool parsed = false;
    switch (format) {
        case Format::Obj: parsed = readObj(data, soup, error); break;
        case Format::Off: parsed = readOff(data, soup, error); break;
        case Format::Ply: parsed = readPly(data, soup, error); break;
        case Format::Stl: parsed = readStl(data, soup, error); break;
        case Format::Unknown: break;
    }
    if (!parsed) {
        report.error = path + ": invalid " + formatName(format) + " file: " + error;
        return report;
    }
    std::string().swap(data);
    notices.insert(notices.end(), soup.notices.begin(), soup.notices.end());

    if (soup.positions.empty() || soup.polygonCount() == 0) {
        report.error = path + ": empty mesh (" + plural(soup.positions.size(), "vertex", "vertices") + ", " +
                       plural(soup.polygonCount(), "face", "faces") + ")";
        return report;
    }
    out = Mesh();
    std::vector<uint32_t> sourceFace;
    if (!soupToMesh(soup, out, sourceFace, notices, error)) {
        report.error = path + ": " + error;
        return report;
    }
    // Keep the mapping only where it differs from identity (triangulated files).
    if (sourceFace.size() == soup.polygonCount()) sourceFace.clear();
    return prepare(path, options, out, sourceFace, std::move(notices));
}

}  // namespace vorogeo
