// Writes the fuzzers' seed corpora (committed under tests/fuzz/corpus/): small blobs baked
// from generated meshes, in the five presentations fuzz_blob.cpp understands, and small
// mesh files of every format, valid and broken, for fuzz_mesh.cpp. Rerun it when the blob
// format changes:  build/tests/vorogeo_fuzz_corpus tests/fuzz/corpus
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "bake.h"
#include "distance_coding.h"
#include "generators.h"
#include "mesh_io.h"
#include "vorogeo_container.h"
#include "vorogeo_generated.h"

using namespace vorogeo;

namespace {

void writeSeed(const std::filesystem::path& path, uint8_t first, const std::vector<uint8_t>& body) {
    std::ofstream out(path, std::ios::binary);
    out.put(char(first));
    out.write(reinterpret_cast<const char*>(body.data()), std::streamsize(body.size()));
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

// A payload seed (modes 1-4): the flatbuffer's size, then the payload.
void writePayloadSeed(const std::filesystem::path& path, uint8_t first, const std::vector<uint8_t>& payload,
                      uint32_t flatbufferSize) {
    std::vector<uint8_t> body(4);
    vg_store_le32(body.data(), flatbufferSize);
    body.insert(body.end(), payload.begin(), payload.end());
    writeSeed(path, first, body);
}

// The payload of an uncompressed blob, and the size of its flatbuffer (from the header).
std::vector<uint8_t> payloadOf(const std::vector<uint8_t>& blob, uint32_t& flatbufferSize) {
    flatbufferSize = uint32_t(vg_load_le64(blob.data() + 24));
    return std::vector<uint8_t>(blob.begin() + VG_CONTAINER_HEADER_SIZE, blob.end());
}

std::vector<uint8_t> bakeSmall(const Mesh& mesh, uint32_t n2, bool compact, uint32_t hubPatches = 0) {
    BakeOptions o;
    o.n1 = hubPatches;
    o.hubLabels = hubPatches > 0;
    o.compress = compact;
    o.compact = compact;
    o.n2 = n2;
    o.landmarks = 2;
    BakeReport report;
    return bakeMesh(mesh, o, report);
}

void blobSeeds(const std::filesystem::path& dir, const std::string& name, const Mesh& mesh, uint32_t n2) {
    const std::vector<uint8_t> blob = bakeSmall(mesh, n2, false);
    uint32_t size = 0;
    const std::vector<uint8_t> payload = payloadOf(blob, size);
    writeSeed(dir / (name + "-file"), 0, blob);
    writeSeed(dir / (name + "-file-zstd"), 0, bakeSmall(mesh, n2, true));
    writePayloadSeed(dir / (name + "-flatbuffer"), 1, payload, size);
    writePayloadSeed(dir / (name + "-zstd"), 2, payload, size);
    std::vector<uint8_t> coded = payload;
    codeDistances(coded, size);
    writePayloadSeed(dir / (name + "-coded-zstd"), 3, coded, size);
    writePayloadSeed(dir / (name + "-coded"), 4, coded, size);
}

std::vector<uint8_t> meshFile(const Mesh& mesh, MeshFormat format, const std::filesystem::path& scratch) {
    std::string error;
    if (!writeMesh(mesh, scratch.string(), format, error)) throw std::runtime_error(error);
    std::ifstream in(scratch, std::ios::binary);
    return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: vorogeo_fuzz_corpus OUT_DIR (writes OUT_DIR/blob and OUT_DIR/mesh)\n");
        return 2;
    }
    try {
        const std::filesystem::path root(argv[1]), blobs = root / "blob", meshes = root / "mesh";
        std::filesystem::create_directories(blobs);
        std::filesystem::create_directories(meshes);

        blobSeeds(blobs, "grid", planeGrid(5, 5, 1.0, 0.1, 2), 2);
        blobSeeds(blobs, "torus", torus(1.0, 0.4, 8, 6), 3);
        {  // hub labels: several first-layer patches, as a file and as a bare flatbuffer
            const std::vector<uint8_t> blob = bakeSmall(planeGrid(9, 9, 1.0, 0.1, 3), 2, false, 4);
            writeSeed(blobs / "hubs-file", 0, blob);
            uint32_t size = 0;
            const std::vector<uint8_t> payload = payloadOf(blob, size);
            writePayloadSeed(blobs / "hubs-flatbuffer", 1, payload, size);
            std::vector<uint8_t> coded = payload;  // distances and label tables coded
            codeDistances(coded, size);
            writePayloadSeed(blobs / "hubs-coded-zstd", 3, coded, size);
            writePayloadSeed(blobs / "hubs-coded", 4, coded, size);
            // The inner rows left to the readers: their table zeros, the rest coded.
            std::vector<uint8_t> atOpen = payload;
            const fb::Graph* g = fb::GetGraph(atOpen.data());
            vg_label_tables at;
            if (!vg_label_tables_at(size, g->hub_columns_count(), g->hub_inner_count(), &at))
                throw std::runtime_error("hub-label tables out of range");
            std::fill(atOpen.begin() + int64_t(at.inner_offset), atOpen.begin() + int64_t(at.inner_offset + 2 * g->hub_inner_count()), 0);
            codeDistances(atOpen, size, false);
            writePayloadSeed(blobs / "hubs-inner-at-open", 5, atOpen, size);
        }
        Mesh pair = planeGrid(3, 3, 1.0);
        const Mesh other = planeGrid(2, 2, 1.0);
        const uint32_t offset = pair.vertexCount();
        for (const Vec3& p : other.positions) pair.positions.push_back(p + Vec3{3, 0, 0});
        for (const Tri& t : other.faces) pair.faces.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
        if (!buildConnectivity(pair).ok) throw std::runtime_error("two grids: bad connectivity");
        blobSeeds(blobs, "two-grids", pair, 2);

        // First byte: extension index (obj, off, ply, stl, sniffed) + 0x80 for --repair.
        const std::filesystem::path scratch = root / "scratch.tmp";
        struct Format {
            MeshFormat format;
            uint8_t index;
            const char* name;
        };
        const Format formats[] = {{MeshFormat::Obj, 0, "obj"},          {MeshFormat::Off, 1, "off"},
                                  {MeshFormat::PlyAscii, 2, "ply-ascii"}, {MeshFormat::PlyBinary, 2, "ply-binary"},
                                  {MeshFormat::StlAscii, 3, "stl-ascii"}, {MeshFormat::StlBinary, 3, "stl-binary"}};
        const Mesh valid = planeGrid(2, 2, 1.0, 0.1, 5);
        for (const Format& f : formats) {
            writeSeed(meshes / (std::string("grid-") + f.name), f.index, meshFile(valid, f.format, scratch));
            writeSeed(meshes / (std::string("grid-sniffed-") + f.name), 4, meshFile(valid, f.format, scratch));
        }
        for (Defect d : kAllDefects) {
            const Mesh broken = brokenMesh(d);
            std::string name = std::string("broken-") + defectName(d);
            for (char& c : name) c = c == ' ' ? '-' : c;
            writeSeed(meshes / (name + "-obj"), 0x80, meshFile(broken, MeshFormat::Obj, scratch));
            writeSeed(meshes / (name + "-ply"), 0x82, meshFile(broken, MeshFormat::PlyBinary, scratch));
        }
        const std::string polygons = "# quads and a pentagon\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0.5 0\n"
                                     "vt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1 4/1/1\nf 2 5 3\n";
        writeSeed(meshes / "polygons-obj", 0, std::vector<uint8_t>(polygons.begin(), polygons.end()));
        std::filesystem::remove(scratch);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vorogeo_fuzz_corpus: %s\n", e.what());
        return 1;
    }
    return 0;
}
