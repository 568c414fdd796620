// Procedural meshes for tests, the demo and benchmarks, plus deliberately broken face
// soups for validation tests. Every generator except brokenMesh() returns a mesh that
// went through prepareMesh() (connectivity built) and throws std::invalid_argument for
// parameters that cannot make a valid mesh.
#pragma once

#include <cstdint>
#include <random>
#include <string>

#include "mesh.h"
#include "mesh_io.h"  // writeMesh

namespace vorogeo {

// Portable random numbers: std::uniform_real_distribution's algorithm differs between
// standard libraries, so doubles are made from the raw 53 high bits of std::mt19937_64.
class Random {
public:
    explicit Random(uint64_t seed) : engine_(seed) {}
    double uniform() { return double(engine_() >> 11) * 0x1.0p-53; }  // [0, 1)
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

private:
    std::mt19937_64 engine_;
};

// Flat square [0,size]^2 in z=0 with nx*ny cells, two triangles each; jitter (0..0.9)
// moves interior vertices by up to jitter/2 cells in x and y (seeded, deterministic).
Mesh planeGrid(uint32_t nx, uint32_t ny, double size = 1.0, double jitter = 0.0, uint64_t seed = 1);
// Open cylinder around the z axis: 2 boundary loops; rings = number of bands along z.
Mesh openCylinder(double radius, double height, uint32_t segments, uint32_t rings);
// Cone with apex (0,0,height) and open circular base of `radius` at z=0 (a disk).
Mesh cone(double radius, double height, uint32_t segments, uint32_t rings);
// Sphere from a subdivided icosahedron: 10*4^n + 2 vertices.
Mesh icosphere(uint32_t subdivisions, double radius = 1.0);
// Torus around the z axis: nu segments around the big circle, nv around the tube.
Mesh torus(double majorRadius, double minorRadius, uint32_t nu, uint32_t nv);
// Copy of `base` with every vertex moved by a random vector in [-amplitude, amplitude]^3.
Mesh noisy(const Mesh& base, double amplitude, uint64_t seed);
// Genus-1 torus with smooth bumps (saddles and peaks); the demo's default mesh.
// The defaults give 28,800 vertices.
Mesh bumpyTorus(uint32_t nu = 240, uint32_t nv = 120);
// planeGrid(n, n) with `holes` single-cell holes on a lattice (holes + 1 boundary loops).
Mesh gridWithHoles(uint32_t n, uint32_t holes);
// An icosphere and a torus side by side: 2 components, total genus 1.
Mesh twoComponents();
// Strip of needle triangles, each with one angle close to 180 degrees: rows of points
// offset by half a step, `rowHeight` apart (unit horizontal spacing).
Mesh needleMesh(uint32_t nx = 40, uint32_t ny = 6, double rowHeight = 0.02);

// One validation error each, as raw soups (NOT prepared): write them with writeMesh()
// in any format and loading must fail with the matching message.
enum class Defect {
    Empty,                    // vertices but no faces
    NonFiniteCoordinate,      // NaN at vertex 2
    IndexOutOfRange,          // face 1 refers to vertex 7 of 4
    ZeroAreaFace,             // face 2 has three collinear corners
    RepeatedIndexFace,        // face 2 is (0, 1, 1)
    DuplicateFace,            // face 2 repeats face 0
    NonManifoldEdge,          // edge 1-2 shared by three faces
    NonManifoldVertex,        // two triangles touching only at vertex 0
    InconsistentOrientation,  // face 1 flipped against face 0
};
constexpr Defect kAllDefects[] = {Defect::Empty,           Defect::NonFiniteCoordinate, Defect::IndexOutOfRange,
                                  Defect::ZeroAreaFace,    Defect::RepeatedIndexFace,   Defect::DuplicateFace,
                                  Defect::NonManifoldEdge, Defect::NonManifoldVertex,   Defect::InconsistentOrientation};
Mesh brokenMesh(Defect defect);
const char* defectName(Defect defect);

}  // namespace vorogeo
