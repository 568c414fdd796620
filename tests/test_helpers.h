// Shared by the mesh tests: a private temporary directory, running the vorogeo tool,
// and locating the optional shared test data.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace vorogeo::test {

// A fresh directory per test case, removed afterwards. ctest runs test cases as
// separate processes in parallel, so the name includes the process id.
class TempDir {
public:
    TempDir() {
        static int counter = 0;
        path_ = std::filesystem::temp_directory_path() /
                ("vorogeo-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    const std::filesystem::path& path() const { return path_; }
    std::string file(const std::string& name) const { return (path_ / name).string(); }
    std::string write(const std::string& name, const std::string& content) const {
        std::ofstream(file(name), std::ios::binary) << content;
        return file(name);
    }

private:
    std::filesystem::path path_;
};

// The whole content of a file ("" if it cannot be read).
inline std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

struct ToolResult {
    int status = -1;
    std::string out, err;
};

// Runs `vorogeo ARGS` (ARGS already shell-quoted) and captures stdout, stderr and the exit status.
inline ToolResult runTool(const std::string& args) {
    TempDir dir;
    const std::string outFile = dir.file("stdout"), errFile = dir.file("stderr");
    const std::string cmd = std::string("'") + VOROGEO_TOOL_PATH + "' " + args + " >'" + outFile + "' 2>'" + errFile + "'";
    const int raw = std::system(cmd.c_str());
    ToolResult r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = readText(outFile);
    r.err = readText(errFile);
    return r;
}

inline std::string quote(const std::string& s) { return "'" + s + "'"; }

// The shared meshes folder, or "" when this checkout has none (tests then skip).
inline std::string sharedMeshDir() {
    const std::filesystem::path dir = std::filesystem::path(VOROGEO_SHARED_DIR) / "meshes";
    return std::filesystem::exists(dir / "stats.jsonl") ? dir.string() : "";
}

}  // namespace vorogeo::test
