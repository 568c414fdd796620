// Limits and interrupted work: bakes that would break the flatbuffers 2 GiB limit or the
// memory budget are refused up front with a message naming the limit; Ctrl-C, SIGTERM and
// SIGKILL during a bake leave no output file (and no temporary one after a clean stop); the
// hub-label stage states its table sizes before computing them, so the limits refuse it early.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "bake.h"
#include "bake_limits.h"
#include "generators.h"
#include "hub_labels.h"
#include "mesh_io.h"
#include "test_helpers.h"
#include "vorogeo_container.h"

using namespace vorogeo;

namespace {

// Names of the files in `dir`, sorted.
std::vector<std::string> filesIn(const test::TempDir& dir) {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir.path()))
        names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

// Starts `vorogeo ARGS...` with stderr to a file; the child gets default signal handling.
pid_t startTool(const std::vector<std::string>& args, const std::string& errPath) {
    const pid_t pid = ::fork();
    if (pid == 0) {
        const int err = ::open(errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int null = ::open("/dev/null", O_WRONLY);
        ::dup2(err, 2);
        ::dup2(null, 1);
        ::signal(SIGINT, SIG_DFL);
        ::signal(SIGTERM, SIG_DFL);
        std::vector<char*> argv;
        argv.push_back(const_cast<char*>(VOROGEO_TOOL_PATH));
        for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::execv(VOROGEO_TOOL_PATH, argv.data());
        ::_exit(127);
    }
    return pid;
}

// Waits until the file contains `marker`. Returns "" once it does, otherwise what went
// wrong: the process ended first, or ten minutes passed. The deadline only guards against a
// hang: the sanitized bake reaches its overlay stage after 26 s alone, but had not after two
// minutes in a CI run with another test on the second core.
std::string waitFor(const std::string& path, const std::string& marker, pid_t pid) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(10);
    while (std::chrono::steady_clock::now() < deadline) {
        if (test::readText(path).find(marker) != std::string::npos) return "";
        int status = 0;
        if (::waitpid(pid, &status, WNOHANG) == pid) return "the bake ended first: " + test::readText(path);
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ::kill(pid, SIGKILL);  // leave no bake running behind a failed test
    ::waitpid(pid, nullptr, 0);
    return "no such line after 10 minutes: " + test::readText(path);
}

}  // namespace

TEST_CASE("limits: a blob over the flatbuffers 2 GiB limit is refused before baking", "[limits]") {
    BakeOptions o;
    CHECK(estimateBake(1000000, o).flatbufferBytes < kMaxFlatbufferBytes);
    CHECK_NOTHROW(checkBakeLimits(1000000, o));
    try {
        checkBakeLimits(40000000, o);
        FAIL("40M vertices accepted");
    } catch (const BakeLimitError& e) {
        const std::string m = e.what();
        CHECK(m.find("2 GiB") != std::string::npos);
        CHECK(m.find("split the mesh") != std::string::npos);
    }
    // Larger patches, larger blobs: the limit comes sooner.
    o.n2 = 1;
    CHECK(estimateBake(1000000, o).flatbufferBytes > estimateBake(1000000, BakeOptions()).flatbufferBytes);
    // The exact check before serialising.
    CHECK_NOTHROW(checkFlatbufferSize(kMaxFlatbufferBytes, 10));
    CHECK_THROWS_AS(checkFlatbufferSize(kMaxFlatbufferBytes + 1, 10), BakeLimitError);
}

TEST_CASE("limits: a memory budget refuses up front and stops a bake that goes over it", "[limits]") {
    const Mesh mesh = bumpyTorus(40, 20);
    BakeOptions o;
    o.maxMemoryBytes = 1 << 20;
    BakeReport report;
    try {
        bakeMesh(mesh, o, report);
        FAIL("a 1 MiB budget was accepted");
    } catch (const BakeLimitError& e) {
        CHECK(std::string(e.what()).find("--max-memory 1 MiB") != std::string::npos);
    }
    o.maxMemoryBytes = 64ull << 30;
    CHECK_FALSE(bakeMesh(mesh, o, report).empty());
    CHECK(residentBytes() > 0);
    BakeOptions tight;
    tight.maxMemoryBytes = 1;
    CHECK_THROWS_WITH(checkMemoryDuringBake(tight, "partition"), Catch::Contains("during partition"));
}

TEST_CASE("limits: vorogeo bake --max-memory refuses with a message and writes nothing", "[limits][cli]") {
    test::TempDir dir;
    std::string error;
    REQUIRE(writeMesh(bumpyTorus(40, 20), dir.file("torus.ply"), error));
    const std::string out = dir.file("torus.vgeo");
    test::ToolResult r = test::runTool("bake '" + dir.file("torus.ply") + "' -o '" + out + "' --max-memory 2M");
    CHECK(r.status == 1);
    CHECK(r.err.find("--max-memory 2 MiB") != std::string::npos);
    CHECK(r.err.find("nothing written") != std::string::npos);
    CHECK(filesIn(dir) == std::vector<std::string>{"torus.ply"});
    r = test::runTool("bake '" + dir.file("torus.ply") + "' -o '" + out + "' --max-memory lots");
    CHECK(r.status == 2);
    CHECK(r.err.find("--max-memory must be a size") != std::string::npos);
    r = test::runTool("bake '" + dir.file("torus.ply") + "' -o '" + out + "' --max-memory 4G --quiet");
    CHECK(r.status == 0);
    CHECK(std::filesystem::exists(out));
}

TEST_CASE("interrupts: SIGINT or SIGTERM stop a bake cleanly, SIGKILL leaves no output", "[limits][cli]") {
    test::TempDir dir;
    std::string error;
    const std::string mesh = dir.file("torus.ply"), out = dir.file("torus.vgeo"), err = dir.file("err.txt");
    REQUIRE(writeMesh(bumpyTorus(), mesh, error));  // 28,800 vertices: a few seconds of bake
    struct Case {
        int signal;
        const char* after;  // progress line to wait for
    };
    for (Case c : {Case{SIGINT, "bake: first layer"}, Case{SIGTERM, "bake: second-layer geodesics"},
                   Case{SIGINT, "bake: first-layer overlay"}, Case{SIGKILL, "bake: second-layer geodesics"}}) {
        INFO("signal " << c.signal << " after '" << c.after << "'");
        const pid_t pid = startTool({"bake", mesh, "-o", out, "--threads", "2"}, err);
        REQUIRE(pid > 0);
        REQUIRE(waitFor(err, c.after, pid) == "");
        ::kill(pid, c.signal);
        int status = 0;
        REQUIRE(::waitpid(pid, &status, 0) == pid);
        if (c.signal == SIGKILL) {
            CHECK(WIFSIGNALED(status));
        } else {
            REQUIRE(WIFEXITED(status));
            CHECK(WEXITSTATUS(status) == 130);
            CHECK(test::readText(err).find("interrupted; nothing written") != std::string::npos);
        }
        // No output, and no temporary file either (the blob is written only at the end).
        CHECK(filesIn(dir) == std::vector<std::string>{"err.txt", "torus.ply"});
    }
}

TEST_CASE("limits: the hub-label stage states its table sizes before computing them, and a refusal stops it",
          "[limits][hub]") {
    BakeOptions o;
    o.n1 = 10;
    o.compress = false;
    BakeReport report;
    const std::vector<uint8_t> blob = bakeMesh(bumpyTorus(120, 40), o, report);
    const std::vector<uint8_t> graph(blob.begin() + VG_CONTAINER_HEADER_SIZE, blob.end());
    HubLabelSizes planned;
    int plans = 0, progressBeforePlan = -1, progressCalls = 0;
    const HubLabels hubs = computeHubLabels(
        graph, [&](double) { ++progressCalls; },
        [&](const HubLabelSizes& sizes) {
            planned = sizes;
            ++plans;
            progressBeforePlan = progressCalls;
        });
    CHECK(plans == 1);
    CHECK(progressBeforePlan == 0);
    CHECK(progressCalls > 0);
    REQUIRE(!hubs.columns.empty());
    REQUIRE(!hubs.inner.empty());
    CHECK(planned.labelEntries == hubs.columns.size());
    CHECK(planned.innerEntries == hubs.inner.size());
    CHECK(planned.innerNodes == hubs.innerNode.size());

    // A refusal leaves before any label is computed.
    progressCalls = 0;
    CHECK_THROWS_AS(computeHubLabels(graph, [&](double) { ++progressCalls; },
                                     [](const HubLabelSizes&) { throw BakeLimitError("refused"); }),
                    BakeLimitError);
    CHECK(progressCalls == 0);

    // The limits on those sizes: the flatbuffer's 2 GiB (the label tables lie outside it,
    // the inner rows' node ids inside), and the stage's memory under --max-memory.
    CHECK_NOTHROW(checkHubLabelLimits(graph.size(), planned, 4800, BakeOptions(), residentBytes()));
    HubLabelSizes huge;
    huge.labelEntries = 1ull << 30;  // 2 GiB of steps: after the flatbuffer, so within its limit
    BakeOptions roomy;
    roomy.maxMemoryBytes = 64ull << 30;
    CHECK_NOTHROW(checkHubLabelLimits(1 << 20, huge, 2000000, roomy, 0));
    huge.innerNodes = 1ull << 29;  // 2 GiB of node ids inside the flatbuffer
    CHECK_THROWS_WITH(checkHubLabelLimits(1 << 20, huge, 2000000, roomy, 0),
                      Catch::Contains("2 GiB limit") && Catch::Contains("without --hub-labels"));
    BakeOptions tight;
    tight.maxMemoryBytes = 1ull << 30;
    HubLabelSizes large;
    large.labelEntries = 200000000;  // computed as floats: 800 MB, and 400 MB of steps after
    CHECK_THROWS_WITH(checkHubLabelLimits(1 << 20, large, 1000000, tight, 1 << 20), Catch::Contains("--max-memory 1.0 GiB"));
    large.labelEntries = 100000000;  // 600 MB
    CHECK_NOTHROW(checkHubLabelLimits(1 << 20, large, 1000000, tight, 1 << 20));
    CHECK_NOTHROW(checkHubLabelLimits(1 << 20, planned, 4800, tight, 1 << 20));
}
