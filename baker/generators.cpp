#include "generators.h"

#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

namespace vorogeo {
namespace {

Mesh prepared(Mesh mesh, const char* what) {
    const LoadReport r = prepareMesh(what, LoadOptions{}, mesh);
    if (!r.ok) throw std::invalid_argument(r.error);
    return mesh;
}

void require(bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(what);
}

// Two triangles per quad a-b-c-d (counter-clockwise seen from the outside).
void addQuad(Mesh& m, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
    m.faces.push_back({a, b, c});
    m.faces.push_back({a, c, d});
}

// Quads between the rings of a (u, v) grid that wraps around in u.
void addWrappedBands(Mesh& m, uint32_t first, uint32_t nu, uint32_t bands, bool wrapV) {
    for (uint32_t j = 0; j < bands; ++j)
        for (uint32_t i = 0; i < nu; ++i) {
            const uint32_t j1 = wrapV ? (j + 1) % bands : j + 1;
            addQuad(m, first + j * nu + i, first + j * nu + (i + 1) % nu, first + j1 * nu + (i + 1) % nu,
                    first + j1 * nu + i);
        }
}

}  // namespace

Mesh planeGrid(uint32_t nx, uint32_t ny, double size, double jitter, uint64_t seed) {
    require(nx >= 1 && ny >= 1 && size > 0, "planeGrid: need nx, ny >= 1 and size > 0");
    require(jitter >= 0 && jitter < 1, "planeGrid: jitter must be in [0, 1)");
    Mesh m;
    Random rng(seed);
    const double hx = size / nx, hy = size / ny;
    for (uint32_t j = 0; j <= ny; ++j)
        for (uint32_t i = 0; i <= nx; ++i) {
            Vec3 p{i * hx, j * hy, 0};
            // Draw for every vertex so that the pattern does not depend on which are interior.
            const double dx = rng.uniform(-0.5, 0.5) * jitter, dy = rng.uniform(-0.5, 0.5) * jitter;
            if (i > 0 && i < nx) p.x += dx * hx;
            if (j > 0 && j < ny) p.y += dy * hy;
            m.positions.push_back(p);
        }
    for (uint32_t j = 0; j < ny; ++j)
        for (uint32_t i = 0; i < nx; ++i) {
            const uint32_t a = j * (nx + 1) + i;
            addQuad(m, a, a + 1, a + nx + 2, a + nx + 1);
        }
    return prepared(std::move(m), "planeGrid");
}

Mesh openCylinder(double radius, double height, uint32_t segments, uint32_t rings) {
    require(radius > 0 && height > 0 && segments >= 3 && rings >= 1,
            "openCylinder: need radius, height > 0, segments >= 3, rings >= 1");
    Mesh m;
    for (uint32_t j = 0; j <= rings; ++j)
        for (uint32_t i = 0; i < segments; ++i) {
            const double t = 2 * M_PI * i / segments;
            m.positions.push_back({radius * std::cos(t), radius * std::sin(t), height * j / rings});
        }
    addWrappedBands(m, 0, segments, rings, false);
    return prepared(std::move(m), "openCylinder");
}

Mesh cone(double radius, double height, uint32_t segments, uint32_t rings) {
    require(radius > 0 && height > 0 && segments >= 3 && rings >= 1,
            "cone: need radius, height > 0, segments >= 3, rings >= 1");
    Mesh m;
    for (uint32_t j = 0; j < rings; ++j)
        for (uint32_t i = 0; i < segments; ++i) {
            const double t = 2 * M_PI * i / segments, s = 1.0 - double(j) / rings;
            m.positions.push_back({radius * s * std::cos(t), radius * s * std::sin(t), height * j / rings});
        }
    const uint32_t apex = m.vertexCount();
    m.positions.push_back({0, 0, height});
    addWrappedBands(m, 0, segments, rings - 1, false);
    const uint32_t top = (rings - 1) * segments;
    for (uint32_t i = 0; i < segments; ++i) m.faces.push_back({top + i, top + (i + 1) % segments, apex});
    return prepared(std::move(m), "cone");
}

Mesh icosphere(uint32_t subdivisions, double radius) {
    require(subdivisions <= 9 && radius > 0, "icosphere: need subdivisions <= 9 and radius > 0");
    const double t = (1 + std::sqrt(5.0)) / 2;
    Mesh m;
    m.positions = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                   {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    m.faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
               {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
               {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (uint32_t s = 0; s < subdivisions; ++s) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoint;
        auto mid = [&](uint32_t a, uint32_t b) {
            auto key = std::make_pair(std::min(a, b), std::max(a, b));
            auto it = midpoint.find(key);
            if (it != midpoint.end()) return it->second;
            m.positions.push_back((m.positions[a] + m.positions[b]) * 0.5);
            return midpoint[key] = m.vertexCount() - 1;
        };
        std::vector<Tri> faces;
        faces.reserve(m.faces.size() * 4);
        for (const Tri& f : m.faces) {
            const uint32_t ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
            faces.push_back({f[0], ab, ca});
            faces.push_back({f[1], bc, ab});
            faces.push_back({f[2], ca, bc});
            faces.push_back({ab, bc, ca});
        }
        m.faces = std::move(faces);
    }
    for (Vec3& p : m.positions) p = p * (radius / length(p));
    return prepared(std::move(m), "icosphere");
}

Mesh torus(double majorRadius, double minorRadius, uint32_t nu, uint32_t nv) {
    require(majorRadius > minorRadius && minorRadius > 0 && nu >= 3 && nv >= 3,
            "torus: need majorRadius > minorRadius > 0 and nu, nv >= 3");
    Mesh m;
    for (uint32_t j = 0; j < nv; ++j)
        for (uint32_t i = 0; i < nu; ++i) {
            const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
            const double r = majorRadius + minorRadius * std::cos(v);
            m.positions.push_back({r * std::cos(u), r * std::sin(u), minorRadius * std::sin(v)});
        }
    addWrappedBands(m, 0, nu, nv, true);
    return prepared(std::move(m), "torus");
}

Mesh noisy(const Mesh& base, double amplitude, uint64_t seed) {
    Mesh m;
    m.positions = base.positions;
    m.faces = base.faces;
    Random rng(seed);
    for (Vec3& p : m.positions)
        p = p + Vec3{rng.uniform(-amplitude, amplitude), rng.uniform(-amplitude, amplitude),
                     rng.uniform(-amplitude, amplitude)};
    return prepared(std::move(m), "noisy");
}

Mesh bumpyTorus(uint32_t nu, uint32_t nv) {
    require(nu >= 3 && nv >= 3, "bumpyTorus: need nu, nv >= 3");
    const double majorRadius = 1.0, minorRadius = 0.4;
    Mesh m;
    for (uint32_t j = 0; j < nv; ++j)
        for (uint32_t i = 0; i < nu; ++i) {
            const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
            // Tube radius modulated by a few smooth waves: bumps, dents and saddles, but
            // never thinner than half the tube, so the surface cannot self-intersect.
            const double tube = minorRadius * (1 + 0.18 * std::sin(7 * u) * std::sin(3 * v) +
                                               0.08 * std::cos(13 * u + 2 * v) + 0.05 * std::sin(5 * v - 3 * u));
            const double r = majorRadius + tube * std::cos(v);
            m.positions.push_back({r * std::cos(u), r * std::sin(u), tube * std::sin(v)});
        }
    addWrappedBands(m, 0, nu, nv, true);
    return prepared(std::move(m), "bumpyTorus");
}

Mesh gridWithHoles(uint32_t n, uint32_t holes) {
    // Holes sit on a lattice with two cells between them and the border, so no two
    // holes (or a hole and the border) share a vertex.
    const uint32_t perRow = n >= 3 ? (n - 1) / 3 : 0;
    require(holes <= perRow * perRow, "gridWithHoles: grid too small for that many holes");
    Mesh m = planeGrid(n, n);
    std::vector<uint8_t> drop(m.faceCount(), 0);
    for (uint32_t h = 0; h < holes; ++h) {
        const uint32_t i = 2 + 3 * (h % perRow) - 1, j = 2 + 3 * (h / perRow) - 1;
        const uint32_t cell = j * n + i;
        drop[2 * cell] = drop[2 * cell + 1] = 1;
    }
    Mesh out;
    out.positions = m.positions;
    for (uint32_t f = 0; f < m.faceCount(); ++f)
        if (!drop[f]) out.faces.push_back(m.faces[f]);
    return prepared(std::move(out), "gridWithHoles");
}

Mesh twoComponents() {
    Mesh a = icosphere(2, 1.0), b = torus(1.0, 0.3, 24, 12);
    Mesh m;
    m.positions = a.positions;
    m.faces = a.faces;
    const uint32_t offset = m.vertexCount();
    for (const Vec3& p : b.positions) m.positions.push_back(p + Vec3{4, 0, 0});
    for (const Tri& t : b.faces) m.faces.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    return prepared(std::move(m), "twoComponents");
}

Mesh needleMesh(uint32_t nx, uint32_t ny, double rowHeight) {
    require(nx >= 1 && ny >= 1 && rowHeight > 0, "needleMesh: need nx, ny >= 1 and rowHeight > 0");
    Mesh m;
    for (uint32_t j = 0; j <= ny; ++j)
        for (uint32_t i = 0; i <= nx; ++i) m.positions.push_back({i + 0.5 * (j % 2), j * rowHeight, 0});
    for (uint32_t j = 0; j < ny; ++j) {
        const uint32_t lo = j * (nx + 1), up = lo + nx + 1;
        for (uint32_t i = 0; i < nx; ++i) {
            if (j % 2 == 0) {  // lower row starts half a step left of the upper one
                m.faces.push_back({lo + i, lo + i + 1, up + i});
                m.faces.push_back({up + i, lo + i + 1, up + i + 1});
            } else {
                m.faces.push_back({lo + i, up + i + 1, up + i});
                m.faces.push_back({lo + i, lo + i + 1, up + i + 1});
            }
        }
    }
    return prepared(std::move(m), "needleMesh");
}

Mesh brokenMesh(Defect defect) {
    // A unit square split along 1-2 as the healthy base (faces 0 and 1).
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    m.faces = {{0, 1, 2}, {2, 1, 3}};
    switch (defect) {
        case Defect::Empty: m.faces.clear(); break;
        case Defect::NonFiniteCoordinate: m.positions[2].y = std::numeric_limits<double>::quiet_NaN(); break;
        case Defect::IndexOutOfRange: m.faces[1][2] = 7; break;
        case Defect::ZeroAreaFace:
            m.positions.push_back({0.5, 0, 0});  // on edge 0-1
            m.faces.push_back({0, 4, 1});
            break;
        case Defect::RepeatedIndexFace: m.faces.push_back({0, 1, 1}); break;
        case Defect::DuplicateFace: m.faces.push_back({0, 1, 2}); break;
        case Defect::NonManifoldEdge:
            m.positions.push_back({0.5, 0.5, 1});
            m.faces.push_back({1, 2, 4});
            break;
        case Defect::NonManifoldVertex:
            m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
            m.faces = {{0, 1, 2}, {0, 3, 4}};
            break;
        case Defect::InconsistentOrientation: m.faces[1] = {1, 2, 3}; break;
    }
    return m;
}

const char* defectName(Defect defect) {
    switch (defect) {
        case Defect::Empty: return "empty";
        case Defect::NonFiniteCoordinate: return "non-finite coordinate";
        case Defect::IndexOutOfRange: return "index out of range";
        case Defect::ZeroAreaFace: return "zero-area face";
        case Defect::RepeatedIndexFace: return "repeated-index face";
        case Defect::DuplicateFace: return "duplicate face";
        case Defect::NonManifoldEdge: return "non-manifold edge";
        case Defect::NonManifoldVertex: return "non-manifold vertex";
        case Defect::InconsistentOrientation: return "inconsistent orientation";
    }
    return "?";
}

}  // namespace vorogeo
