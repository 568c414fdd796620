#include <catch2/catch.hpp>

#include "mesh.h"

using namespace vorogeo;

namespace {
// Two triangles sharing edge 1-2: a unit square split along its diagonal.
Mesh square() {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    m.faces = {{0, 1, 2}, {2, 1, 3}};
    return m;
}
}  // namespace

TEST_CASE("connectivity of a split square", "[mesh]") {
    Mesh m = square();
    ConnectivityReport r = buildConnectivity(m);
    REQUIRE(r.ok);
    REQUIRE(m.twin.size() == 6);
    // Half-edge 1 (1->2) and half-edge 3 (2->1) are twins; all others are boundary.
    CHECK(m.twin[1] == 3);
    CHECK(m.twin[3] == 1);
    CHECK(m.twin[0] == -1);
    for (uint32_t v = 0; v < 4; ++v) {
        CHECK(m.boundaryVertex[v] == 1);
        REQUIRE(m.vertexOut[v] >= 0);
        CHECK(m.tail(m.vertexOut[v]) == v);
        CHECK(m.twin[m.vertexOut[v]] == -1);
    }
    // Rotation around vertex 1 visits both faces.
    int faces = 0;
    for (int32_t h = m.vertexOut[1]; h >= 0; h = m.nextAroundVertex(h)) ++faces;
    CHECK(faces == 2);
    auto sums = vertexAngleSums(m);
    CHECK(sums[0] == Approx(M_PI / 2));
    CHECK(sums[1] == Approx(M_PI / 2));
}

TEST_CASE("an edge shared by three faces is non-manifold", "[mesh]") {
    Mesh m = square();
    m.positions.push_back({0.5, 0.5, 1});
    m.faces.push_back({1, 2, 4});
    ConnectivityReport r = buildConnectivity(m);
    CHECK_FALSE(r.ok);
    CHECK(r.nonManifoldEdges == 1);
    CHECK(r.firstBadVertex == 1);
}

TEST_CASE("two fans meeting at one vertex are non-manifold", "[mesh]") {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
    m.faces = {{0, 1, 2}, {0, 3, 4}};
    ConnectivityReport r = buildConnectivity(m);
    CHECK_FALSE(r.ok);
    CHECK(r.nonManifoldVertices == 1);
    CHECK(r.firstBadVertex == 0);
}
