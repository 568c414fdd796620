#include "golden.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>

namespace vorogeo::tools {

namespace {

bool parseDistance(const std::string& text, double& out) {
    if (text == "inf" || text == "+inf" || text == "Infinity") {
        out = std::numeric_limits<double>::infinity();
        return true;
    }
    char* end = nullptr;
    errno = 0;
    out = std::strtod(text.c_str(), &end);
    return !text.empty() && !errno && *end == '\0' && !std::isnan(out) && out >= 0;
}

bool parseIndex(const std::string& text, uint32_t& out) {
    char* end = nullptr;
    errno = 0;
    unsigned long long v = std::strtoull(text.c_str(), &end, 10);
    if (text.empty() || errno || *end || text[0] == '-' || v > 0xffffffffull) return false;
    out = uint32_t(v);
    return true;
}

std::string trimmed(std::string s) {
    while (!s.empty() && (s.back() == '\r' || s.back() == ' ')) s.pop_back();
    return s;
}

}  // namespace

bool readPairs(const std::string& path, std::vector<DistancePair>& pairs, std::string& error) {
    std::ifstream in(path);
    if (!in) {
        error = path + ": cannot open file";
        return false;
    }
    pairs.clear();
    std::string line;
    size_t lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        line = trimmed(line);
        if (line.empty()) continue;
        if (lineNo == 1 && line.find("source") != std::string::npos) continue;
        size_t c1 = line.find(','), c2 = c1 == std::string::npos ? c1 : line.find(',', c1 + 1);
        DistancePair p{};
        if (c2 == std::string::npos || !parseIndex(line.substr(0, c1), p.source) ||
            !parseIndex(line.substr(c1 + 1, c2 - c1 - 1), p.target) ||
            !parseDistance(line.substr(c2 + 1), p.distance)) {
            error = path + ":" + std::to_string(lineNo) + ": expected 'source,target,distance', got '" + line + "'";
            return false;
        }
        pairs.push_back(p);
    }
    if (pairs.empty()) {
        error = path + ": no pairs";
        return false;
    }
    return true;
}

bool readField(const std::string& path, std::vector<double>& values, std::string& error) {
    std::ifstream in(path);
    if (!in) {
        error = path + ": cannot open file";
        return false;
    }
    values.clear();
    std::string line;
    size_t lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        line = trimmed(line);
        double d;
        if (!parseDistance(line, d)) {
            error = path + ":" + std::to_string(lineNo) + ": expected a distance, got '" + line + "'";
            return false;
        }
        values.push_back(d);
    }
    return true;
}

double relativeError(double value, double reference) {
    if (std::isinf(value) || std::isinf(reference))
        return value == reference ? 0.0 : std::numeric_limits<double>::infinity();
    const double diff = std::fabs(value - reference);
    return reference > 0 ? diff / reference : (diff > 0 ? std::numeric_limits<double>::infinity() : 0.0);
}

bool agrees(double value, double reference, const Tolerance& tol) {
    if (std::isinf(value) || std::isinf(reference)) return value == reference;
    if (std::isnan(value)) return false;
    const double diff = std::fabs(value - reference);
    return diff <= tol.relTol * reference || diff <= tol.absTol;
}

}  // namespace vorogeo::tools
