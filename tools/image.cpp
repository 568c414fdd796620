#include "image.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <vector>

// Debian's libstb compiles the implementation of stb_image_write into libstb; the easy
// font is a header of static functions.
#include <stb_easy_font.h>
#include <stb_image_write.h>

namespace vorogeo::tools {

void Image::fillRect(int x0, int y0, int x1, int y1, Rgb c) {
    x0 = std::max(x0, 0);
    y0 = std::max(y0, 0);
    x1 = std::min(x1, width);
    y1 = std::min(y1, height);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) at(x, y) = c;
}

void Image::paste(const Image& src, int x, int y) {
    for (int sy = 0; sy < src.height; ++sy)
        for (int sx = 0; sx < src.width; ++sx) {
            const int tx = x + sx, ty = y + sy;
            if (tx >= 0 && ty >= 0 && tx < width && ty < height) at(tx, ty) = src.at(sx, sy);
        }
}

void drawText(Image& image, int x, int y, const std::string& text, Rgb colour, int scale) {
    // The font emits axis-aligned quads (4 vertices of 16 bytes: x, y, z, colour).
    struct FontVertex {
        float x, y, z;
        unsigned char rgba[4];
    };
    std::vector<FontVertex> quads(text.size() * 70 * 4 + 4);
    std::vector<char> mutableText(text.begin(), text.end());
    mutableText.push_back('\0');
    const int count = stb_easy_font_print(0, 0, mutableText.data(), nullptr, quads.data(),
                                          int(quads.size() * sizeof(FontVertex)));
    for (int q = 0; q < count; ++q) {
        const FontVertex* v = &quads[size_t(q) * 4];
        const float qx0 = std::min(v[0].x, v[2].x), qx1 = std::max(v[0].x, v[2].x);
        const float qy0 = std::min(v[0].y, v[2].y), qy1 = std::max(v[0].y, v[2].y);
        image.fillRect(x + int(qx0 * scale), y + int(qy0 * scale), x + int(qx1 * scale), y + int(qy1 * scale), colour);
    }
}

bool writePng(const Image& image, const std::string& path, std::string& error) {
    if (image.width <= 0 || image.height <= 0) {
        error = "empty image";
        return false;
    }
    const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
    static_assert(sizeof(Rgb) == 3, "pixels are packed RGB");
    if (!stbi_write_png(tmp.c_str(), image.width, image.height, 3, image.pixels.data(), image.width * 3)) {
        std::remove(tmp.c_str());
        error = "cannot write " + path;
        return false;
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        std::remove(tmp.c_str());
        error = "cannot write " + path + " (rename failed)";
        return false;
    }
    return true;
}

}  // namespace vorogeo::tools
