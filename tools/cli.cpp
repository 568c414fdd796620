#include "cli.h"

#include <cstdio>

#include <cerrno>
#include <cstdlib>
#include <sstream>

namespace vorogeo::cli {

Args::Args(int argc, char** argv, const std::set<std::string>& valueOptions,
           const std::set<std::string>& flagOptions) {
    for (int i = 0; i < argc; ++i) {
        std::string a = argv[i];
        if (a.size() > 1 && a[0] == '-' && !(a[1] >= '0' && a[1] <= '9')) {
            std::string value;
            bool inlineValue = false;
            if (auto eq = a.find('='); eq != std::string::npos) {
                value = a.substr(eq + 1);
                a = a.substr(0, eq);
                inlineValue = true;
            }
            if (valueOptions.count(a)) {
                if (!inlineValue) {
                    if (i + 1 >= argc) throw UsageError("option " + a + " needs a value");
                    value = argv[++i];
                }
                values_[a] = value;
            } else if (flagOptions.count(a) && !inlineValue) {
                flags_.insert(a);
            } else {
                throw UsageError("unknown option " + a);
            }
        } else {
            positional_.push_back(a);
        }
    }
}

std::string Args::str(const std::string& name, const std::string& fallback) const {
    auto it = values_.find(name);
    return it == values_.end() ? fallback : it->second;
}

long long Args::integer(const std::string& name, long long fallback) const {
    auto it = values_.find(name);
    if (it == values_.end()) return fallback;
    const char* s = it->second.c_str();
    char* end = nullptr;
    errno = 0;
    long long v = std::strtoll(s, &end, 10);
    if (errno || end == s || *end) throw UsageError(name + " expects an integer, got '" + it->second + "'");
    return v;
}

double Args::number(const std::string& name, double fallback) const {
    auto it = values_.find(name);
    if (it == values_.end()) return fallback;
    const char* s = it->second.c_str();
    char* end = nullptr;
    errno = 0;
    double v = std::strtod(s, &end);
    if (errno || end == s || *end) throw UsageError(name + " expects a number, got '" + it->second + "'");
    return v;
}

void pictureOptions(const Args& args, int& width, int& height, double& yawDegrees, double& pitchDegrees) {
    if (args.has("--size")) {
        const std::string t = args.str("--size");
        if (std::sscanf(t.c_str(), "%dx%d", &width, &height) != 2 || width < 16 || height < 16 || width > 8192 ||
            height > 8192)
            throw UsageError("--size must be WxH with each side in 16..8192, got '" + t + "'");
    }
    if (args.has("--view")) {
        const std::string t = args.str("--view");
        if (std::sscanf(t.c_str(), "%lf,%lf", &yawDegrees, &pitchDegrees) != 2)
            throw UsageError("--view must be YAW,PITCH in degrees, got '" + t + "'");
    }
}

std::vector<long long> parseIntegerList(const std::string& text, const std::string& what) {
    std::vector<long long> out;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        char* end = nullptr;
        errno = 0;
        long long v = std::strtoll(item.c_str(), &end, 10);
        if (item.empty() || errno || *end) throw UsageError(what + ": '" + item + "' is not an integer");
        out.push_back(v);
    }
    if (out.empty()) throw UsageError(what + ": empty list");
    return out;
}

}  // namespace vorogeo::cli
