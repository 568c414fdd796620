// Reading and writing every format: exact round trips, format details (polygons,
// negative OBJ indices, PLY variants, STL welding), content sniffing.
#include <catch2/catch.hpp>

#include <cstring>

#include "generators.h"
#include "mesh_io.h"
#include "mesh_stats.h"
#include "test_helpers.h"

using namespace vorogeo;

namespace {

Mesh load(const std::string& path, LoadReport* report = nullptr) {
    Mesh m;
    LoadReport r = loadMesh(path, LoadOptions{}, m);
    INFO(r.error);
    REQUIRE(r.ok);
    if (report) *report = r;
    return m;
}

bool hasNotice(const LoadReport& r, const std::string& fragment) {
    for (const std::string& n : r.notices)
        if (n.find(fragment) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST_CASE("OBJ, OFF and PLY round trips are exact", "[io]") {
    test::TempDir dir;
    const Mesh original = noisy(torus(1.0, 0.35, 20, 12), 0.01, 7);
    const std::pair<MeshFormat, const char*> formats[] = {{MeshFormat::Obj, "m.obj"},
                                                          {MeshFormat::Off, "m.off"},
                                                          {MeshFormat::PlyAscii, "a.ply"},
                                                          {MeshFormat::PlyBinary, "b.ply"}};
    for (const auto& [format, name] : formats) {
        INFO(name);
        std::string error;
        REQUIRE(writeMesh(original, dir.file(name), format, error));
        const Mesh m = load(dir.file(name));
        REQUIRE(m.vertexCount() == original.vertexCount());
        REQUIRE(m.faces == original.faces);
        for (uint32_t v = 0; v < m.vertexCount(); ++v) {
            CHECK(m.positions[v].x == original.positions[v].x);
            CHECK(m.positions[v].y == original.positions[v].y);
            CHECK(m.positions[v].z == original.positions[v].z);
        }
    }
}

TEST_CASE("STL round trips keep the surface, at float precision", "[io]") {
    test::TempDir dir;
    const Mesh original = noisy(torus(1.0, 0.35, 20, 12), 0.01, 7);
    for (MeshFormat format : {MeshFormat::StlAscii, MeshFormat::StlBinary}) {
        std::string error;
        const std::string path = dir.file(format == MeshFormat::StlAscii ? "a.stl" : "b.stl");
        REQUIRE(writeMesh(original, path, format, error));
        LoadReport report;
        const Mesh m = load(path, &report);
        CHECK(hasNotice(report, "STL: identified 1440 triangle corners with 240 distinct vertices"));
        REQUIRE(m.vertexCount() == original.vertexCount());
        REQUIRE(m.faceCount() == original.faceCount());
        for (uint32_t f = 0; f < m.faceCount(); ++f)
            for (int k = 0; k < 3; ++k) {
                const Vec3 a = m.positions[m.faces[f][k]], b = original.positions[original.faces[f][k]];
                CHECK(distance(a, b) < 1e-6);
            }
        const MeshStats s = computeStats(m);
        CHECK(s.genus == 1);
        CHECK(s.components == 1);
    }
}

TEST_CASE("writeMesh picks the format by extension", "[io]") {
    test::TempDir dir;
    const Mesh m = icosphere(1);
    std::string error;
    for (const char* name : {"s.obj", "s.off", "s.ply", "s.stl", "S.PLY"}) {
        INFO(name);
        REQUIRE(writeMesh(m, dir.file(name), error));
        CHECK(load(dir.file(name)).faceCount() == m.faceCount());
    }
    CHECK_FALSE(writeMesh(m, dir.file("s.xyz"), error));
    CHECK_THAT(error, Catch::Contains("unknown extension"));
    CHECK_FALSE(writeMesh(m, dir.file("no/such/dir/s.obj"), error));
    CHECK_THAT(error, Catch::Contains("cannot create file"));
}

TEST_CASE("OBJ quads are triangulated with a notice, other records are ignored", "[io]") {
    test::TempDir dir;
    // A cube of quads, with texture coordinates, normals, groups and negative indices.
    const std::string path = dir.write("cube.obj",
                                       "# cube\n"
                                       "mtllib cube.mtl\no cube\n"
                                       "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                                       "vt 0 0\nvn 0 0 1\ng sides\nusemtl red\ns off\n"
                                       "f 1/1/1 4/1/1 3/1/1 2/1/1\n"
                                       "f 5//1 6//1 7//1 8//1 # top\n"
                                       "f 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\n"
                                       "f -4 -1 -5 -8\n"  // 5 8 4 1 via negative indices
                                       "l 1 2\n");
    LoadReport report;
    const Mesh m = load(path, &report);
    CHECK(m.vertexCount() == 8);
    CHECK(m.faceCount() == 12);
    CHECK(hasNotice(report, "triangulated 6 polygons"));
    const MeshStats s = computeStats(m);
    CHECK(s.genus == 0);
    CHECK(s.boundaryLoops == 0);
    CHECK(s.area == Approx(6.0));
}

TEST_CASE("non-convex polygons are cut inside by ear clipping", "[io]") {
    test::TempDir dir;
    // An L-shaped hexagon (area 3): a fan from vertex 0 would leave the polygon.
    const std::string path = dir.write("l.off",
                                       "OFF\n# L shape\n6 1 0\n"
                                       "0 0 0\n2 0 0\n2 1 0\n1 1 0\n1 2 0\n0 2 0\n"
                                       "6 0 1 2 3 4 5  255 0 0\n");
    // Start the polygon at the reflex corner, where a fan would fail.
    const std::string path2 = dir.write("l2.off", "OFF\n6 1 0\n0 0 0\n2 0 0\n2 1 0\n1 1 0\n1 2 0\n0 2 0\n6 3 4 5 0 1 2\n");
    for (const std::string& p : {path, path2}) {
        const Mesh m = load(p);
        CHECK(m.faceCount() == 4);
        const MeshStats s = computeStats(m);
        CHECK(s.area == Approx(3.0));
        CHECK(s.boundaryLoops == 1);
        for (const Tri& t : m.faces)  // every triangle keeps the polygon's orientation (+z)
            CHECK(cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]).z > 0);
    }
}

TEST_CASE("faces with fewer than three vertices are reported as degenerate", "[io][validation]") {
    test::TempDir dir;
    const std::string path = dir.write("two.off", "OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 2 1 3\n2 0 1\n");
    Mesh m;
    LoadReport r = loadMesh(path, LoadOptions{}, m);
    CHECK_FALSE(r.ok);
    CHECK_THAT(r.error, Catch::Contains("1 degenerate face") && Catch::Contains("first is face 2"));
    r = loadMesh(path, LoadOptions{true}, m);
    CHECK(r.ok);
    CHECK(m.faceCount() == 2);
}

TEST_CASE("PLY variants: big endian, extra properties and elements, strips", "[io]") {
    test::TempDir dir;
    auto be32 = [](uint32_t v) {
        std::string s(4, '\0');
        for (int i = 0; i < 4; ++i) s[i] = char(v >> (24 - 8 * i));
        return s;
    };
    auto beFloat = [&](float f) {
        uint32_t u;
        std::memcpy(&u, &f, 4);
        return be32(u);
    };
    // Big endian, with a normal per vertex, a flags byte per face and an unrelated element.
    std::string ply =
        "ply\nformat binary_big_endian 1.0\ncomment test\nelement vertex 4\nproperty float x\nproperty float y\n"
        "property float z\nproperty float nx\nelement face 2\nproperty uchar flags\n"
        "property list uchar uint vertex_index\nelement material 1\nproperty list uchar uchar name\nend_header\n";
    const float xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    for (const auto& p : xyz) ply += beFloat(p[0]) + beFloat(p[1]) + beFloat(p[2]) + beFloat(0.5f);
    const uint32_t faces[2][3] = {{0, 1, 2}, {2, 1, 3}};
    for (const auto& f : faces) ply += std::string(1, '\7') + "\3" + be32(f[0]) + be32(f[1]) + be32(f[2]);
    ply += std::string("\2ab");
    Mesh m = load(dir.write("be.ply", ply));
    CHECK(m.vertexCount() == 4);
    REQUIRE(m.faceCount() == 2);
    CHECK(m.faces[1] == Tri{2, 1, 3});
    CHECK(m.positions[3].x == 1.0);

    // Triangle strips as in the original igea.ply: -1 restarts, odd triangles swap.
    LoadReport report;
    m = load(dir.write("strips.ply",
                       "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
                       "element tristrips 1\nproperty list int int vertex_indices\nend_header\n"
                       "0 0 0\n0 1 0\n1 0 0\n1 1 0\n2 0 0\n2 1 0\n"
                       "7 0 2 1 3 -1 2 4\n"),
             &report);
    CHECK(hasNotice(report, "decoded 1 triangle strips into 2 triangles"));
    REQUIRE(m.faceCount() == 2);
    CHECK(m.faces[0] == Tri{0, 2, 1});
    CHECK(m.faces[1] == Tri{1, 2, 3});  // odd: (s1, s0, s2) of the strip 2 1 3
}

TEST_CASE("an unknown extension is accepted when the content is recognisable", "[io]") {
    test::TempDir dir;
    LoadReport report;
    const Mesh m = load(dir.write("tri.mesh", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), &report);
    CHECK(m.faceCount() == 1);
    CHECK(hasNotice(report, "format detected from content: OFF"));
}

TEST_CASE("vertices used by no face are kept as isolated vertices", "[io]") {
    Mesh m = brokenMesh(Defect::NonManifoldVertex);
    m.positions.push_back({5, 5, 5});
    m.faces = {{0, 1, 2}};
    const LoadReport r = prepareMesh("iso", LoadOptions{}, m);
    REQUIRE(r.ok);
    CHECK(m.vertexCount() == 6);
    REQUIRE(r.notices.size() == 1);
    CHECK_THAT(r.notices[0], Catch::Contains("3 vertices are used by no face"));
    const MeshStats s = computeStats(m);
    CHECK(s.isolatedVertices == 3);
    CHECK(s.components == 1);
    CHECK(s.euler == 1);
}
