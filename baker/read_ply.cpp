// PLY reader (ASCII, binary little and big endian). Reads x/y/z of "vertex", the index
// list of "face" and decodes "tristrips" (as in the original igea.ply, which OpenMesh's
// reader ignores); other properties and elements are skipped.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "mesh_soup.h"
#include "text_scan.h"

namespace vorogeo {
namespace {

enum class PType { I8, U8, I16, U16, I32, U32, F32, F64, Bad };

PType parseType(std::string_view t) {
    if (t == "char" || t == "int8") return PType::I8;
    if (t == "uchar" || t == "uint8") return PType::U8;
    if (t == "short" || t == "int16") return PType::I16;
    if (t == "ushort" || t == "uint16") return PType::U16;
    if (t == "int" || t == "int32") return PType::I32;
    if (t == "uint" || t == "uint32") return PType::U32;
    if (t == "float" || t == "float32") return PType::F32;
    if (t == "double" || t == "float64") return PType::F64;
    return PType::Bad;
}

size_t typeSize(PType t) {
    switch (t) {
        case PType::I8: case PType::U8: return 1;
        case PType::I16: case PType::U16: return 2;
        case PType::I32: case PType::U32: case PType::F32: return 4;
        case PType::F64: return 8;
        default: return 0;
    }
}

bool isFloat(PType t) { return t == PType::F32 || t == PType::F64; }

struct Property {
    std::string name;
    bool list = false;
    PType countType = PType::Bad;
    PType type = PType::Bad;
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> props;
};

enum class Encoding { Ascii, BinaryLE, BinaryBE };

bool hostIsLittleEndian() {
    const uint16_t one = 1;
    unsigned char b;
    std::memcpy(&b, &one, 1);
    return b == 1;
}

// Reads scalar values from the body, either as binary records or as ASCII tokens.
class BodyReader {
public:
    BodyReader(std::string_view body, Encoding enc)
        : enc_(enc), p_(body.data()), end_(body.data() + body.size()), text_(body),
          swap_(enc != Encoding::Ascii && (enc == Encoding::BinaryLE) != hostIsLittleEndian()) {}

    // A scalar of type t as double (coordinates) or int64 (counts and indices).
    bool readDouble(PType t, double& out) {
        if (enc_ == Encoding::Ascii) return TextScanner::parseDouble(text_.anyToken(), out);
        if (isFloat(t)) {
            if (t == PType::F32) {
                float f;
                if (!raw(&f, 4)) return false;
                out = f;
            } else if (!raw(&out, 8)) {
                return false;
            }
            return true;
        }
        int64_t i;
        if (!readInt(t, i)) return false;
        out = double(i);
        return true;
    }
    // A whole number in int64's range (converting anything else is undefined behaviour).
    static bool integral(double d, int64_t& out) {
        if (!(d >= -9.0e18 && d <= 9.0e18) || d != std::floor(d)) return false;
        out = int64_t(d);
        return true;
    }
    bool readInt(PType t, int64_t& out) {
        if (enc_ == Encoding::Ascii) {
            std::string_view tok = text_.anyToken();
            if (TextScanner::parseInt(tok, out)) return true;
            double d;  // some writers print integral values as "3.0"
            return TextScanner::parseDouble(tok, d) && integral(d, out);
        }
        switch (t) {
            case PType::I8: { int8_t v; if (!raw(&v, 1)) return false; out = v; return true; }
            case PType::U8: { uint8_t v; if (!raw(&v, 1)) return false; out = v; return true; }
            case PType::I16: { int16_t v; if (!raw(&v, 2)) return false; out = v; return true; }
            case PType::U16: { uint16_t v; if (!raw(&v, 2)) return false; out = v; return true; }
            case PType::I32: { int32_t v; if (!raw(&v, 4)) return false; out = v; return true; }
            case PType::U32: { uint32_t v; if (!raw(&v, 4)) return false; out = v; return true; }
            case PType::F32: { float v; return raw(&v, 4) && integral(v, out); }
            case PType::F64: { double v; return raw(&v, 8) && integral(v, out); }
            default: return false;
        }
    }
    bool skip(PType t) {
        if (enc_ == Encoding::Ascii) return !text_.anyToken().empty();
        size_t n = typeSize(t);
        if (size_t(end_ - p_) < n) return false;
        p_ += n;
        return true;
    }
    // Bytes (binary) or characters (ASCII) left: bounds absurd element counts.
    size_t remaining() const { return size_t(end_ - (enc_ == Encoding::Ascii ? text_.cursor() : p_)); }
    bool ascii() const { return enc_ == Encoding::Ascii; }

private:
    bool raw(void* dst, size_t n) {
        if (size_t(end_ - p_) < n) return false;
        std::memcpy(dst, p_, n);
        if (swap_) std::reverse(static_cast<unsigned char*>(dst), static_cast<unsigned char*>(dst) + n);
        p_ += n;
        return true;
    }

    Encoding enc_;
    const char* p_;
    const char* end_;
    TextScanner text_;
    bool swap_;
};

bool parseHeader(std::string_view data, Encoding& enc, std::vector<Element>& elements, size_t& bodyStart,
                 std::string& error) {
    TextScanner s(data);
    if (s.token() != "ply") {
        error = "not a PLY file (missing 'ply' magic on the first line)";
        return false;
    }
    bool haveFormat = false;
    for (s.nextLine(); !s.atEnd(); s.nextLine()) {
        std::string_view key = s.token();
        if (key.empty() || key == "comment" || key == "obj_info") continue;
        if (key == "format") {
            std::string_view f = s.token();
            if (f == "ascii") enc = Encoding::Ascii;
            else if (f == "binary_little_endian") enc = Encoding::BinaryLE;
            else if (f == "binary_big_endian") enc = Encoding::BinaryBE;
            else {
                error = s.where() + ": unknown PLY format '" + std::string(f) + "'";
                return false;
            }
            haveFormat = true;
        } else if (key == "element") {
            Element e;
            e.name = std::string(s.token());
            int64_t n;
            if (e.name.empty() || !TextScanner::parseInt(s.token(), n) || n < 0) {
                error = s.where() + ": malformed element line";
                return false;
            }
            e.count = uint64_t(n);
            elements.push_back(std::move(e));
        } else if (key == "property") {
            if (elements.empty()) {
                error = s.where() + ": property before any element";
                return false;
            }
            Property p;
            std::string_view t = s.token();
            if (t == "list") {
                p.list = true;
                p.countType = parseType(s.token());
                t = s.token();
                if (p.countType == PType::Bad || isFloat(p.countType)) {
                    error = s.where() + ": bad list count type";
                    return false;
                }
            }
            p.type = parseType(t);
            p.name = std::string(s.token());
            if (p.type == PType::Bad || p.name.empty()) {
                error = s.where() + ": malformed property line (unknown type '" + std::string(t) + "'?)";
                return false;
            }
            elements.back().props.push_back(std::move(p));
        } else if (key == "end_header") {
            s.nextLine();  // the body starts right after the end_header line
            bodyStart = size_t(s.cursor() - data.data());
            if (!haveFormat) {
                error = "PLY header has no format line";
                return false;
            }
            return true;
        } else {
            error = s.where() + ": unknown PLY header keyword '" + std::string(key.substr(0, 40)) + "'";
            return false;
        }
    }
    error = "PLY header has no end_header line";
    return false;
}

int findScalar(const Element& e, const char* name) {
    for (size_t i = 0; i < e.props.size(); ++i)
        if (!e.props[i].list && e.props[i].name == name) return int(i);
    return -1;
}

int findIndexList(const Element& e) {
    for (size_t i = 0; i < e.props.size(); ++i)
        if (e.props[i].list && (e.props[i].name == "vertex_indices" || e.props[i].name == "vertex_index"))
            return int(i);
    return -1;
}

std::string truncated(const Element& e, uint64_t record) {
    return "file ends inside element '" + e.name + "' (record " + std::to_string(record) + " of " +
           std::to_string(e.count) + ")";
}

bool readIndexList(BodyReader& r, const Property& p, std::vector<int64_t>& out) {
    int64_t n;
    if (!r.readInt(p.countType, n) || n < 0) return false;
    for (int64_t k = 0; k < n; ++k) {
        int64_t i;
        if (!r.readInt(p.type, i)) return false;
        out.push_back(i);
    }
    return true;
}

bool skipProperty(BodyReader& r, const Property& p) {
    if (!p.list) return r.skip(p.type);
    int64_t n;
    if (!r.readInt(p.countType, n) || n < 0) return false;
    for (int64_t k = 0; k < n; ++k)
        if (!r.skip(p.type)) return false;
    return true;
}

// Triangle i of a strip is (s[i], s[i+1], s[i+2]) for even i and (s[i+1], s[i], s[i+2])
// for odd i, so that all triangles share the strip's orientation; -1 restarts the strip.
uint64_t decodeStrip(const std::vector<int64_t>& strip, PolygonSoup& soup) {
    uint64_t triangles = 0;
    size_t start = 0;
    for (size_t i = 0; i <= strip.size(); ++i) {
        if (i < strip.size() && strip[i] != -1) continue;
        for (size_t k = start; k + 2 < i; ++k) {
            const bool odd = (k - start) % 2;
            soup.indices.push_back(strip[odd ? k + 1 : k]);
            soup.indices.push_back(strip[odd ? k : k + 1]);
            soup.indices.push_back(strip[k + 2]);
            soup.endPolygon();
            ++triangles;
        }
        start = i + 1;
    }
    return triangles;
}

}  // namespace

bool looksLikePly(std::string_view data) {
    return data.substr(0, 4) == "ply\n" || data.substr(0, 5) == "ply\r\n";
}

bool readPly(std::string_view data, PolygonSoup& soup, std::string& error) {
    Encoding enc = Encoding::Ascii;
    std::vector<Element> elements;
    size_t bodyStart = 0;
    if (!parseHeader(data, enc, elements, bodyStart, error)) return false;

    const Element* vertexElement = nullptr;
    for (const Element& e : elements) {
        if (e.name != "vertex") continue;
        if (vertexElement) {
            error = "PLY header declares the 'vertex' element twice";
            return false;
        }
        vertexElement = &e;
    }
    if (!vertexElement) {
        error = "PLY header declares no 'vertex' element";
        return false;
    }
    int xyz[3] = {findScalar(*vertexElement, "x"), findScalar(*vertexElement, "y"),
                  findScalar(*vertexElement, "z")};
    if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0) {
        error = "PLY 'vertex' element lacks one of the properties x, y, z";
        return false;
    }

    BodyReader r(data.substr(bodyStart), enc);
    uint64_t stripCount = 0, stripTriangles = 0;
    std::vector<int64_t> strip;
    for (const Element& e : elements) {
        // Bound the count by what the rest of the file can hold before reserving memory:
        // a binary record takes at least its fixed-size parts, an ASCII value two characters.
        uint64_t minRecord = 0;
        for (const Property& p : e.props) minRecord += r.ascii() ? 2 : typeSize(p.list ? p.countType : p.type);
        if (minRecord && e.count > (r.remaining() + 1) / minRecord) {
            error = "element '" + e.name + "' claims " + std::to_string(e.count) +
                    " records but the file is too short for them";
            return false;
        }
        if (&e == vertexElement) {
            soup.positions.reserve(e.count);
            for (uint64_t v = 0; v < e.count; ++v) {
                double c[3] = {0, 0, 0};
                for (size_t k = 0; k < e.props.size(); ++k) {
                    const int which = int(k) == xyz[0] ? 0 : int(k) == xyz[1] ? 1 : int(k) == xyz[2] ? 2 : -1;
                    const bool ok = which >= 0 ? r.readDouble(e.props[k].type, c[which]) : skipProperty(r, e.props[k]);
                    if (!ok) {
                        error = truncated(e, v);
                        return false;
                    }
                }
                soup.positions.push_back({c[0], c[1], c[2]});
            }
        } else if (e.name == "face" || e.name == "tristrips") {
            const int list = findIndexList(e);
            if (list < 0) {
                error = "PLY '" + e.name + "' element has no vertex_indices list";
                return false;
            }
            const bool strips = e.name == "tristrips";
            if (!strips) soup.polygonStart.reserve(soup.polygonStart.size() + e.count);
            for (uint64_t f = 0; f < e.count; ++f) {
                for (size_t k = 0; k < e.props.size(); ++k) {
                    bool ok;
                    if (int(k) != list) {
                        ok = skipProperty(r, e.props[k]);
                    } else if (strips) {
                        strip.clear();
                        ok = readIndexList(r, e.props[k], strip);
                        stripTriangles += decodeStrip(strip, soup);
                        ++stripCount;
                    } else {
                        ok = readIndexList(r, e.props[k], soup.indices);
                        soup.endPolygon();
                    }
                    if (!ok) {
                        error = truncated(e, f);
                        return false;
                    }
                }
            }
        } else if (!e.props.empty()) {  // an element without properties takes no bytes, whatever its count
            for (uint64_t i = 0; i < e.count; ++i)
                for (const Property& p : e.props)
                    if (!skipProperty(r, p)) {
                        error = truncated(e, i);
                        return false;
                    }
        }
    }
    if (stripCount)
        soup.notices.push_back("decoded " + std::to_string(stripCount) + " triangle strips into " +
                               std::to_string(stripTriangles) + " triangles");
    return true;
}

}  // namespace vorogeo
