// Both exact engines (wavefront and MMP) against CGAL's exact distances in ../shared/golden
// (an independent implementation): every pair and field value within 1e-6 relative (1e-9 x
// bounding-box diagonal near zero). The larger meshes are checked by `vorogeo exact --pairs`
// (scripts/check-exact.sh) because they take minutes.
#include <catch2/catch.hpp>

#include <filesystem>

#include "exact_check.h"
#include "mesh_io.h"
#include "mesh_stats.h"
#include "test_helpers.h"

using namespace vorogeo;

namespace {

void checkGoldenMesh(const std::string& name) {
    const std::string dir = test::sharedMeshDir();
    if (dir.empty()) {
        WARN("skipped: ../shared/meshes is absent, no golden distances to compare with");
        return;
    }
    const std::string golden = (std::filesystem::path(dir).parent_path() / "golden").string();
    Mesh mesh;
    LoadReport rep = loadMesh(dir + "/" + name + ".ply", LoadOptions{}, mesh);
    REQUIRE(rep.ok);
    ExactGeodesic geo(mesh);
    tools::Tolerance tol;
    tol.absTol = 1e-9 * computeStats(mesh).bboxDiag;

    std::vector<tools::DistancePair> pairs;
    std::string error;
    REQUIRE(tools::readPairs(golden + "/" + name + ".pairs.csv", pairs, error));
    REQUIRE(pairs.size() == 10000);
    for (tools::ExactEngine engine : {tools::ExactEngine::Wavefront, tools::ExactEngine::Mmp}) {
        const tools::PairCheckResult r = tools::checkPairs(geo, pairs, tol, 0, engine);
        INFO(name << " (" << tools::engineName(engine) << "): worst pair " << r.worst.source << ","
                  << r.worst.target << " = " << r.worstValue << " vs " << r.worst.distance);
        CHECK(r.failures == 0);
        CHECK(r.maxRelError <= 1e-6);
    }

    size_t fields = 0;
    for (const auto& entry : std::filesystem::directory_iterator(golden)) {
        const std::string file = entry.path().filename().string();
        const std::string prefix = name + ".field.";
        if (file.rfind(prefix, 0) != 0) continue;
        const uint32_t source = uint32_t(std::stoul(file.substr(prefix.size())));
        std::vector<double> values;
        REQUIRE(tools::readField(entry.path().string(), values, error));
        for (tools::ExactEngine engine : {tools::ExactEngine::Wavefront, tools::ExactEngine::Mmp}) {
            const tools::FieldCheckResult f = tools::checkField(geo, source, values, tol, engine);
            INFO(file << " (" << tools::engineName(engine) << "): worst vertex " << f.worstVertex);
            CHECK(f.failures == 0);
        }
        ++fields;
    }
    CHECK(fields == 2);
}

}  // namespace

TEST_CASE("golden distances: spot", "[exact][golden]") { checkGoldenMesh("spot"); }
TEST_CASE("golden distances: fandisk", "[exact][golden]") { checkGoldenMesh("fandisk"); }
TEST_CASE("golden distances: rocker-arm", "[exact][golden]") { checkGoldenMesh("rocker-arm"); }
