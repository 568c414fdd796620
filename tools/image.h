// An RGB picture in memory: captions (stb_easy_font's built-in font) and PNG output
// (stb_image_write from Debian's libstb).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace vorogeo::tools {

struct Rgb {
    uint8_t r = 0, g = 0, b = 0;
};

struct Image {
    int width = 0, height = 0;
    std::vector<Rgb> pixels;  // row-major, top row first

    Image() = default;
    Image(int w, int h, Rgb fill) : width(w), height(h), pixels(size_t(w) * size_t(h), fill) {}
    Rgb& at(int x, int y) { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
    const Rgb& at(int x, int y) const { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
    void fillRect(int x0, int y0, int x1, int y1, Rgb c);  // [x0, x1) x [y0, y1), clipped
    // Copies `src` with its top-left corner at (x, y), clipped.
    void paste(const Image& src, int x, int y);
};

// Draws one line of text with its top-left corner at (x, y), each font pixel `scale` wide.
void drawText(Image& image, int x, int y, const std::string& text, Rgb colour, int scale = 2);

// Writes a PNG; false with a one-line reason. Writes to a temporary name and renames, so
// a failure never leaves a partial file at `path`.
bool writePng(const Image& image, const std::string& path, std::string& error);

}  // namespace vorogeo::tools
