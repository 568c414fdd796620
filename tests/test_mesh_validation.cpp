// Every validation error: its message (in memory and from every file format) and the
// exit status of `vorogeo info`.
#include <catch2/catch.hpp>

#include "generators.h"
#include "mesh_io.h"
#include "test_helpers.h"

using namespace vorogeo;

namespace {

struct Expectation {
    Defect defect;
    std::vector<std::string> fragments;  // all must appear in the message
    bool repairable;
};

const std::vector<Expectation>& expectations() {
    static const std::vector<Expectation> all = {
        {Defect::Empty, {"empty mesh", "0 faces"}, false},
        {Defect::NonFiniteCoordinate, {"non-finite coordinate (NaN or Inf) at vertex 2"}, false},
        {Defect::IndexOutOfRange, {"face index out of range", "face 1 refers to vertex 7"}, false},
        {Defect::ZeroAreaFace, {"1 degenerate face", "first is face 2", "--repair"}, true},
        {Defect::RepeatedIndexFace, {"1 degenerate face", "repeated vertex", "first is face 2", "--repair"}, true},
        {Defect::DuplicateFace, {"1 duplicate face", "first is face 2", "--repair"}, true},
        {Defect::NonManifoldEdge, {"1 non-manifold edge", "more than two faces", "vertex 1 (edge 1-2)", "--repair"}, true},
        {Defect::NonManifoldVertex, {"1 non-manifold vertex", "first is vertex 0", "--repair"}, true},
        {Defect::InconsistentOrientation, {"inconsistent face orientation", "vertex 1 (edge 1-2)", "--repair"}, true},
    };
    return all;
}

struct FormatCase {
    MeshFormat format;
    const char* extension;
    const char* name;
};

const FormatCase kFormats[] = {
    {MeshFormat::Obj, ".obj", "OBJ"},          {MeshFormat::Off, ".off", "OFF"},
    {MeshFormat::PlyAscii, ".ply", "PLY ascii"}, {MeshFormat::PlyBinary, ".ply", "PLY binary"},
    {MeshFormat::StlAscii, ".stl", "STL ascii"}, {MeshFormat::StlBinary, ".stl", "STL binary"},
};

bool isStl(MeshFormat f) { return f == MeshFormat::StlAscii || f == MeshFormat::StlBinary; }

void checkMessage(const std::string& message, const std::string& prefix, const Expectation& e) {
    INFO(message);
    CHECK(message.rfind(prefix + ": ", 0) == 0);
    CHECK(message.find('\n') == std::string::npos);
    for (const std::string& f : e.fragments) CHECK(message.find(f) != std::string::npos);
    if (!e.repairable) CHECK(message.find("--repair") == std::string::npos);
}

}  // namespace

TEST_CASE("every defect is reported for an in-memory soup", "[validation]") {
    for (const Expectation& e : expectations()) {
        SECTION(defectName(e.defect)) {
            Mesh m = brokenMesh(e.defect);
            const LoadReport r = prepareMesh("soup", LoadOptions{}, m);
            CHECK_FALSE(r.ok);
            checkMessage(r.error, "soup", e);
        }
    }
}

TEST_CASE("every defect is reported from every file format", "[validation][io]") {
    test::TempDir dir;
    for (const FormatCase& fc : kFormats) {
        for (const Expectation& e : expectations()) {
            // STL has no indices, so it cannot refer to a missing vertex.
            if (isStl(fc.format) && e.defect == Defect::IndexOutOfRange) continue;
            INFO(fc.name << ": " << defectName(e.defect));
            const std::string path = dir.file(std::string("broken") + fc.extension);
            std::string error;
            REQUIRE(writeMesh(brokenMesh(e.defect), path, fc.format, error));
            Mesh m;
            const LoadReport r = loadMesh(path, LoadOptions{}, m);
            CHECK_FALSE(r.ok);
            Expectation expected = e;
            if (isStl(fc.format) && e.defect == Defect::Empty)  // no faces means no vertices either
                expected.fragments = {"empty mesh", "0 vertices"};
            checkMessage(r.error, path, expected);
        }
    }
}

TEST_CASE("several defects: the first is explained, the others listed on the same line", "[validation]") {
    Mesh m = brokenMesh(Defect::NonManifoldEdge);
    m.faces.push_back({0, 1, 2});  // duplicate of face 0
    m.faces.push_back({3, 3, 1});  // degenerate
    const LoadReport r = prepareMesh("multi", LoadOptions{}, m);
    REQUIRE_FALSE(r.ok);
    INFO(r.error);
    CHECK(r.error.find("1 degenerate face") != std::string::npos);
    CHECK(r.error.find("(also: 1 duplicate face, 1 non-manifold edge)") != std::string::npos);
    CHECK(r.error.find('\n') == std::string::npos);
}

TEST_CASE("repairable defects load with --repair, the others still fail", "[validation][repair]") {
    for (const Expectation& e : expectations()) {
        SECTION(defectName(e.defect)) {
            Mesh m = brokenMesh(e.defect);
            const LoadReport r = prepareMesh("soup", LoadOptions{true}, m);
            CHECK(r.ok == e.repairable);
            if (!e.repairable) checkMessage(r.error, "soup", e);
            else CHECK_FALSE(r.notices.empty());
        }
    }
}

TEST_CASE("file-level errors name the file and the problem", "[validation][io]") {
    test::TempDir dir;
    Mesh m;
    auto errorOf = [&](const std::string& path) {
        const LoadReport r = loadMesh(path, LoadOptions{}, m);
        CHECK_FALSE(r.ok);
        CHECK(r.error.rfind(path + ": ", 0) == 0);
        CHECK(r.error.find('\n') == std::string::npos);
        return r.error;
    };
    CHECK_THAT(errorOf(dir.file("missing.obj")), Catch::Contains("cannot open file"));
    std::filesystem::create_directories(dir.file("folder.obj"));
    CHECK_THAT(errorOf(dir.file("folder.obj")), Catch::Contains("it is a directory"));
    CHECK_THAT(errorOf(dir.write("mesh.xyz", "hello world\n")), Catch::Contains("unknown mesh format"));
    CHECK_THAT(errorOf(dir.write("fake.ply", "v 0 0 0\n")), Catch::Contains("not a PLY file"));
    CHECK_THAT(errorOf(dir.write("bad.obj", "v 0 zero 0\nf 1 2 3\n")), Catch::Contains("line 1") &&
                                                                            Catch::Contains("three numeric coordinates"));
    CHECK_THAT(errorOf(dir.write("bad2.obj", "v 0 0 0\nf 1 x 3\n")), Catch::Contains("bad face index"));
    CHECK_THAT(errorOf(dir.write("bin.obj", std::string("v 0 0 0\0\1\2", 10))), Catch::Contains("binary data"));
    CHECK_THAT(errorOf(dir.write("short.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n")), Catch::Contains("file ends early"));
    CHECK_THAT(errorOf(dir.write("four.off", "4OFF\n")), Catch::Contains("not supported"));
    CHECK_THAT(errorOf(dir.write("nothing.off", "")), Catch::Contains("not an OFF file"));
    CHECK_THAT(errorOf(dir.write("bad.stl", "garbage that is not an stl file at all")), Catch::Contains("not an STL file") ||
                                                                                              Catch::Contains("too short"));
    CHECK_THAT(errorOf(dir.write("loop.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n")),
               Catch::Contains("outer loop"));
    CHECK_THAT(errorOf(dir.write("empty.obj", "# nothing\n")), Catch::Contains("empty mesh"));
    CHECK_THAT(errorOf(dir.write("noz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1\n")),
               Catch::Contains("lacks one of the properties x, y, z"));
    CHECK_THAT(errorOf(dir.write("hdr.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty flot x\nend_header\n")),
               Catch::Contains("line 4"));
    CHECK_THAT(errorOf(dir.write("huge.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n"
                                             "property float x\nproperty float y\nproperty float z\nend_header\n")),
               Catch::Contains("too short"));

    // A truncated binary PLY: the face records stop half way.
    std::string error;
    const std::string full = dir.file("full.ply");
    REQUIRE(writeMesh(torus(1, 0.3, 8, 6), full, MeshFormat::PlyBinary, error));
    std::ifstream in(full, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    CHECK_THAT(errorOf(dir.write("cut.ply", bytes.substr(0, bytes.size() - 20))),
               Catch::Contains("file ends inside element 'face'"));
}

TEST_CASE("vorogeo info exits 1 with the one-line message for every defect", "[validation][cli]") {
    test::TempDir dir;
    for (const Expectation& e : expectations()) {
        INFO(defectName(e.defect));
        const std::string path = dir.file("broken.obj");
        std::string error;
        REQUIRE(writeMesh(brokenMesh(e.defect), path, error));
        const test::ToolResult r = test::runTool("info " + test::quote(path));
        CHECK(r.status == 1);
        CHECK(r.out.empty());
        INFO(r.err);
        CHECK(r.err.rfind("vorogeo info: " + path + ": ", 0) == 0);
        CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
        for (const std::string& f : e.fragments) CHECK(r.err.find(f) != std::string::npos);

        const test::ToolResult repaired = test::runTool("info --repair --json " + test::quote(path));
        CHECK(repaired.status == (e.repairable ? 0 : 1));
        if (e.repairable) CHECK(repaired.out.find("\"notices\":[\"repair: ") != std::string::npos);
    }
}

TEST_CASE("vorogeo info reports file-level errors with exit status 1", "[validation][cli]") {
    test::TempDir dir;
    test::ToolResult r = test::runTool("info " + test::quote(dir.file("nope.ply")));
    CHECK(r.status == 1);
    CHECK_THAT(r.err, Catch::Contains("nope.ply: cannot open file"));
    r = test::runTool("info " + test::quote(dir.write("x.abc", "just text\n")));
    CHECK(r.status == 1);
    CHECK_THAT(r.err, Catch::Contains("unknown mesh format"));
}
