#include "subdivide.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace vorogeo {
namespace {

// Double positions, so that a subdivided mesh is as precise as the loaded one.
struct DoubleTraits : public OpenMesh::DefaultTraits {
    typedef OpenMesh::Vec3d Point;
    typedef OpenMesh::Vec3d Normal;
};
using OmMesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

}  // namespace

bool loopSubdivide(const Mesh& in, unsigned rounds, Mesh& out, std::string& error) {
    // Each round adds one vertex per edge (at most three per face) and quadruples the faces.
    double vertices = in.vertexCount(), faces = in.faceCount();
    for (unsigned r = 0; r < rounds; ++r) {
        vertices += 3.0 * faces;
        faces *= 4.0;
    }
    if (vertices > double(UINT32_MAX) || 3.0 * faces > double(INT32_MAX)) {
        error = "subdivision: " + std::to_string(rounds) + " rounds of a mesh with " +
                std::to_string(in.faceCount()) + " faces would pass the 32-bit vertex or half-edge limit";
        return false;
    }

    OmMesh om;
    om.reserve(in.vertexCount(), 3 * in.faceCount() / 2, in.faceCount());
    for (const Vec3& p : in.positions) om.add_vertex(OmMesh::Point(p.x, p.y, p.z));
    size_t maxValence = 0;
    std::vector<uint32_t> valence(in.vertexCount(), 0);
    for (uint32_t f = 0; f < in.faceCount(); ++f) {
        const Tri& t = in.faces[f];
        const OmMesh::FaceHandle fh =
            om.add_face(OmMesh::VertexHandle(int(t[0])), OmMesh::VertexHandle(int(t[1])), OmMesh::VertexHandle(int(t[2])));
        if (!fh.is_valid()) {
            error = "subdivision: OpenMesh refused face " + std::to_string(f) + " (not a manifold mesh)";
            return false;
        }
        for (uint32_t v : t) maxValence = std::max<size_t>(maxValence, ++valence[v]);
    }

    OpenMesh::Subdivider::Uniform::LoopT<OmMesh, double> loop;
    // Its weight table is indexed by valence (50 by default); a boundary vertex has one
    // more neighbour than faces, and old vertices keep their valence in every round.
    loop.init_weights(std::max<size_t>(maxValence + 2, 7));
    loop.attach(om);
    loop(rounds);
    loop.detach();

    out = Mesh{};
    out.positions.resize(om.n_vertices());
    for (const OmMesh::VertexHandle vh : om.vertices()) {
        const OmMesh::Point& p = om.point(vh);
        out.positions[size_t(vh.idx())] = Vec3{p[0], p[1], p[2]};
    }
    // The subdivider leaves isolated vertices' positions undefined: keep the input's.
    for (uint32_t v = 0; v < in.vertexCount(); ++v)
        if (valence[v] == 0) out.positions[v] = in.positions[v];
    out.faces.reserve(om.n_faces());
    for (const OmMesh::FaceHandle fh : om.faces()) {
        Tri t{};
        int k = 0;
        for (const OmMesh::VertexHandle vh : om.fv_range(fh)) t[size_t(k++)] = uint32_t(vh.idx());
        out.faces.push_back(t);
    }
    const ConnectivityReport report = buildConnectivity(out);
    if (!report.ok) {
        error = "subdivision produced a non-manifold mesh (" + std::to_string(report.nonManifoldEdges) + " edges, " +
                std::to_string(report.nonManifoldVertices) + " vertices)";
        return false;
    }
    return true;
}

}  // namespace vorogeo
