// Small argument parser shared by the vorogeo subcommands: positional arguments,
// --flag, --key value. Unknown or malformed options are errors, never ignored.
#pragma once

#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace vorogeo::cli {

// Thrown for bad command lines; main() prints "vorogeo <cmd>: <message>" and exits 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class Args {
public:
    // valueOptions take one value ("--out F"); flagOptions take none ("--json").
    Args(int argc, char** argv, const std::set<std::string>& valueOptions,
         const std::set<std::string>& flagOptions);

    const std::vector<std::string>& positional() const { return positional_; }
    bool flag(const std::string& name) const { return flags_.count(name) != 0; }
    bool has(const std::string& name) const { return values_.count(name) != 0; }
    std::string str(const std::string& name, const std::string& fallback = "") const;
    // Parse as integer / double; a malformed number is a UsageError naming the option.
    long long integer(const std::string& name, long long fallback) const;
    double number(const std::string& name, double fallback) const;

private:
    std::vector<std::string> positional_;
    std::set<std::string> flags_;
    std::map<std::string, std::string> values_;
};

// Picture options of render and voronoi: --size WxH (each side 16..8192, default kept when
// absent) and --view YAW,PITCH in degrees (default 0,0). Malformed values are UsageErrors.
void pictureOptions(const Args& args, int& width, int& height, double& yawDegrees, double& pitchDegrees);

// Parses "a,b,c" integer lists such as vertex ids.
std::vector<long long> parseIntegerList(const std::string& text, const std::string& what);

}  // namespace vorogeo::cli
