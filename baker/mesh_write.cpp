// Mesh writers. Text formats print the shortest decimal that reads back to the same
// double (std::to_chars), so OBJ/OFF/ASCII PLY round trips are exact.
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <string>

#include <unistd.h>

#include "mesh_io.h"

namespace vorogeo {
namespace {

class Writer {
public:
    explicit Writer(const std::string& path) : f_(std::fopen(path.c_str(), "wb")) {}
    ~Writer() {
        if (f_) std::fclose(f_);
    }
    bool open() const { return f_ != nullptr; }
    void text(const char* s) { bytes(s, std::strlen(s)); }
    void text(const std::string& s) { bytes(s.data(), s.size()); }
    void number(double v) {
        char buf[32];
        auto r = std::to_chars(buf, buf + sizeof buf, v);
        bytes(buf, size_t(r.ptr - buf));
    }
    void number(uint64_t v) {
        char buf[24];
        auto r = std::to_chars(buf, buf + sizeof buf, v);
        bytes(buf, size_t(r.ptr - buf));
    }
    template <class T>
    void binary(T v) {  // little-endian hosts only, like the formats we write
        bytes(&v, sizeof v);
    }
    void bytes(const void* p, size_t n) { ok_ = ok_ && std::fwrite(p, 1, n, f_) == n; }
    bool close() {
        const bool closed = std::fclose(f_) == 0;
        f_ = nullptr;
        return ok_ && closed;
    }

private:
    FILE* f_;
    bool ok_ = true;
};

// OBJ, OFF and ASCII PLY share their body: one line per vertex, then one per triangle;
// they differ only in the line prefixes and in OBJ counting vertices from 1.
void writeAsciiBody(const Mesh& m, Writer& w, const char* vertexPrefix, const char* facePrefix,
                    uint64_t indexBase) {
    for (const Vec3& p : m.positions) {
        w.text(vertexPrefix);
        w.number(p.x);
        w.text(" ");
        w.number(p.y);
        w.text(" ");
        w.number(p.z);
        w.text("\n");
    }
    for (const Tri& t : m.faces) {
        w.text(facePrefix);
        for (uint32_t v : t) {
            w.text(" ");
            w.number(uint64_t(v) + indexBase);
        }
        w.text("\n");
    }
}

void writeObj(const Mesh& m, Writer& w) {
    w.text("# written by vorogeo\n");
    writeAsciiBody(m, w, "v ", "f", 1);
}

void writeOff(const Mesh& m, Writer& w) {
    w.text("OFF\n" + std::to_string(m.vertexCount()) + " " + std::to_string(m.faceCount()) + " 0\n");
    writeAsciiBody(m, w, "", "3", 0);
}

void writePly(const Mesh& m, Writer& w, bool binary) {
    w.text(std::string("ply\nformat ") + (binary ? "binary_little_endian" : "ascii") +
           " 1.0\ncomment written by vorogeo\nelement vertex " + std::to_string(m.vertexCount()) +
           "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
           std::to_string(m.faceCount()) + "\nproperty list uchar int vertex_indices\nend_header\n");
    if (binary) {
        for (const Vec3& p : m.positions) {
            w.binary(p.x);
            w.binary(p.y);
            w.binary(p.z);
        }
        for (const Tri& t : m.faces) {
            w.binary(uint8_t(3));
            for (uint32_t v : t) w.binary(int32_t(v));
        }
        return;
    }
    writeAsciiBody(m, w, "", "3", 0);
}

Vec3 faceNormal(const Mesh& m, const Tri& t) {
    const uint32_t n = m.vertexCount();
    if (t[0] >= n || t[1] >= n || t[2] >= n) return {};
    Vec3 c = cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
    const double l = length(c);
    return l > 0 ? c * (1 / l) : Vec3{};
}

Vec3 cornerPosition(const Mesh& m, uint32_t v) { return v < m.vertexCount() ? m.positions[v] : Vec3{}; }

void writeStl(const Mesh& m, Writer& w, bool binary) {
    if (binary) {
        char header[80] = {};
        std::snprintf(header, sizeof header, "binary STL written by vorogeo");
        w.bytes(header, 80);
        w.binary(uint32_t(m.faceCount()));
        for (const Tri& t : m.faces) {
            const Vec3 n = faceNormal(m, t);
            for (double c : {n.x, n.y, n.z}) w.binary(float(c));
            for (uint32_t v : t) {
                const Vec3 p = cornerPosition(m, v);
                for (double c : {p.x, p.y, p.z}) w.binary(float(c));
            }
            w.binary(uint16_t(0));
        }
        return;
    }
    w.text("solid vorogeo\n");
    for (const Tri& t : m.faces) {
        const Vec3 n = faceNormal(m, t);
        w.text("facet normal ");
        w.number(n.x);
        w.text(" ");
        w.number(n.y);
        w.text(" ");
        w.number(n.z);
        w.text("\n outer loop\n");
        for (uint32_t v : t) {
            // float precision, as the format intends (and as binary STL stores it)
            const Vec3 p = cornerPosition(m, v);
            w.text("  vertex ");
            w.number(double(float(p.x)));
            w.text(" ");
            w.number(double(float(p.y)));
            w.text(" ");
            w.number(double(float(p.z)));
            w.text("\n");
        }
        w.text(" endloop\nendfacet\n");
    }
    w.text("endsolid vorogeo\n");
}

}  // namespace

bool writeMesh(const Mesh& mesh, const std::string& path, MeshFormat format, std::string& error) {
    // Written next to the destination and renamed into place, so that a failed write
    // (full disk, interrupted tool) never leaves a partial mesh under the final name.
    const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
    {
        Writer w(tmp);
        if (!w.open()) {
            error = path + ": cannot create file (" + std::strerror(errno) + ")";
            return false;
        }
        switch (format) {
            case MeshFormat::Obj: writeObj(mesh, w); break;
            case MeshFormat::Off: writeOff(mesh, w); break;
            case MeshFormat::PlyBinary: writePly(mesh, w, true); break;
            case MeshFormat::PlyAscii: writePly(mesh, w, false); break;
            case MeshFormat::StlAscii: writeStl(mesh, w, false); break;
            case MeshFormat::StlBinary: writeStl(mesh, w, true); break;
        }
        if (!w.close()) {
            error = path + ": write failed (" + std::strerror(errno) + ")";
            std::remove(tmp.c_str());
            return false;
        }
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        error = path + ": cannot rename the written file into place (" + std::strerror(errno) + ")";
        std::remove(tmp.c_str());
        return false;
    }
    return true;
}

bool writeMesh(const Mesh& mesh, const std::string& path, std::string& error) {
    std::string ext;
    if (auto dot = path.find_last_of('.'); dot != std::string::npos) ext = path.substr(dot);
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    MeshFormat format;
    if (ext == ".obj") format = MeshFormat::Obj;
    else if (ext == ".off") format = MeshFormat::Off;
    else if (ext == ".ply") format = MeshFormat::PlyBinary;
    else if (ext == ".stl") format = MeshFormat::StlBinary;
    else {
        error = path + ": cannot write: unknown extension (use .obj, .off, .ply or .stl)";
        return false;
    }
    return writeMesh(mesh, path, format, error);
}

}  // namespace vorogeo
