// Locale-independent scanning of text mesh formats (OBJ, OFF, ASCII PLY and STL).
// std::from_chars is used because strtod depends on the C locale and is slower.
#pragma once

#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>

namespace vorogeo {

class TextScanner {
public:
    explicit TextScanner(std::string_view text) : p_(text.data()), end_(text.data() + text.size()) {}

    bool atEnd() const { return p_ >= end_; }
    uint64_t line() const { return line_; }
    const char* cursor() const { return p_; }
    std::string where() const { return "line " + std::to_string(line_); }

    // Skips blanks but stays on the current line.
    void skipBlanks() {
        while (p_ < end_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\r' || *p_ == '\f' || *p_ == '\v')) ++p_;
    }
    // Skips blanks and newlines.
    void skipWhitespace() {
        for (; p_ < end_; ++p_) {
            if (*p_ == '\n') ++line_;
            else if (!(*p_ == ' ' || *p_ == '\t' || *p_ == '\r' || *p_ == '\f' || *p_ == '\v')) break;
        }
    }
    bool atLineEnd() {
        skipBlanks();
        return p_ >= end_ || *p_ == '\n';
    }
    // Moves to the start of the next line.
    void nextLine() {
        while (p_ < end_ && *p_ != '\n') ++p_;
        if (p_ < end_) {
            ++p_;
            ++line_;
        }
    }
    // The next run of non-blank characters on the current line (empty at line end).
    std::string_view token() {
        skipBlanks();
        const char* s = p_;
        while (p_ < end_ && !isSpace(*p_)) ++p_;
        return {s, size_t(p_ - s)};
    }
    // The next token anywhere (crossing newlines), for whitespace-separated formats.
    std::string_view anyToken() {
        skipWhitespace();
        return token();
    }

    static bool isSpace(char c) {
        return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
    }

    static bool parseDouble(std::string_view t, double& v) {
        if (!t.empty() && t[0] == '+') t.remove_prefix(1);
        if (t.empty()) return false;
        auto r = std::from_chars(t.data(), t.data() + t.size(), v);
        return r.ec == std::errc() && r.ptr == t.data() + t.size();
    }
    static bool parseInt(std::string_view t, int64_t& v) {
        if (!t.empty() && t[0] == '+') t.remove_prefix(1);
        if (t.empty()) return false;
        auto r = std::from_chars(t.data(), t.data() + t.size(), v);
        return r.ec == std::errc() && r.ptr == t.data() + t.size();
    }

private:
    const char* p_;
    const char* end_;
    uint64_t line_ = 1;
};

}  // namespace vorogeo
