// Loading meshes from files (OBJ, PLY, OFF, STL) and making them safe for geodesic code:
// validation with clear one-line errors, optional repair, connectivity. Also writing.
#pragma once

#include <string>
#include <vector>

#include "mesh.h"

namespace vorogeo {

struct LoadOptions {
    bool repair = false;  // drop degenerate/duplicate faces, orient, split non-manifold parts
};

// What loading found and did.
struct LoadReport {
    bool ok = false;
    std::string error;                 // one line "FILE: problem ..." naming the file and the problem
    std::vector<std::string> notices;  // e.g. "triangulated 12 polygons ...", each repair with counts
};

// Reads OBJ, PLY (ASCII and binary), OFF or STL with its own parsers, which keep every
// vertex and face of the file so that defects are seen rather than silently fixed.
// Polygons are triangulated, then the mesh goes through prepareMesh(). Face numbers in
// messages are the file's (0-based) face records. On failure `out` is unspecified.
LoadReport loadMesh(const std::string& path, const LoadOptions& options, Mesh& out);
// The same for a file's content already in memory (an asset pack); `path` gives the
// extension that selects the format and names the mesh in messages.
LoadReport loadMeshFromMemory(const std::string& path, std::string data, const LoadOptions& options, Mesh& out);

// Validation, optional repair and buildConnectivity() for an in-memory triangle soup
// (positions + faces). `name` prefixes error messages. Unreferenced vertices are kept
// as isolated vertices; boundaries and several components are fine.
LoadReport prepareMesh(const std::string& name, const LoadOptions& options, Mesh& inout);

enum class MeshFormat { Obj, Off, PlyAscii, PlyBinary, StlAscii, StlBinary };

// Writes positions and faces (the faces may be invalid: tests write broken soups).
// PLY stores doubles so that a round trip is exact; STL can only hold float32.
// Atomic: written to a temporary file beside PATH and renamed, so a failure leaves no file.
bool writeMesh(const Mesh& mesh, const std::string& path, MeshFormat format, std::string& error);
// Format by extension: .obj, .off, .ply (binary), .stl (binary).
bool writeMesh(const Mesh& mesh, const std::string& path, std::string& error);

}  // namespace vorogeo
