#include "render.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vorogeo::tools {

namespace {

constexpr int kCaptionHeight = 26;
const Rgb kBackground{248, 248, 246};

// The rotated mesh: camera space x right, y up, z towards the viewer.
struct CameraSpace {
    std::vector<Vec3> position, normal;  // per vertex
};

// The view's turn: yaw about y, then pitch about x.
struct ViewRotation {
    double cy, sy, cp, sp;
    explicit ViewRotation(const View& view)
        : cy(std::cos(view.yawDegrees * M_PI / 180)), sy(std::sin(view.yawDegrees * M_PI / 180)),
          cp(std::cos(view.pitchDegrees * M_PI / 180)), sp(std::sin(view.pitchDegrees * M_PI / 180)) {}
    Vec3 operator()(Vec3 p) const {
        const double x = cy * p.x + sy * p.z, z = -sy * p.x + cy * p.z;
        return Vec3{x, cp * p.y - sp * z, sp * p.y + cp * z};
    }
};

CameraSpace toCamera(const Mesh& mesh, const View& view) {
    const ViewRotation rotate(view);
    CameraSpace c;
    c.position.reserve(mesh.vertexCount());
    for (const Vec3& p : mesh.positions) c.position.push_back(rotate(p));
    // Area-weighted vertex normals, for smooth shading of coarse meshes.
    c.normal.assign(mesh.vertexCount(), Vec3{0, 0, 0});
    for (const Tri& t : mesh.faces) {
        const Vec3 n = cross(c.position[t[1]] - c.position[t[0]], c.position[t[2]] - c.position[t[0]]);
        for (int k = 0; k < 3; ++k) c.normal[t[k]] = c.normal[t[k]] + n;
    }
    for (Vec3& n : c.normal) {
        const double l = length(n);
        n = l > 0 ? n * (1.0 / l) : Vec3{0, 0, 1};
    }
    return c;
}

// The front-most face under each pixel, with its barycentric coordinates.
struct Fragment {
    int32_t face = -1;
    float w1 = 0, w2 = 0;
    float depth = -std::numeric_limits<float>::infinity();
};

// Camera space to pixels: x' = offX + (x - minX) scale, y' = offY + (maxY - y) scale.
struct Projection {
    double scale = 1, offX = 0, offY = 0, minX = 0, maxY = 0;
    double x(const Vec3& p) const { return offX + (p.x - minX) * scale; }
    double y(const Vec3& p) const { return offY + (maxY - p.y) * scale; }
};

std::vector<Fragment> rasterise(const Mesh& mesh, const CameraSpace& cam, int width, int height, double& depthScale,
                                Projection& proj) {
    double minX = INFINITY, maxX = -INFINITY, minY = INFINITY, maxY = -INFINITY, minZ = INFINITY, maxZ = -INFINITY;
    for (const Vec3& p : cam.position) {
        minX = std::min(minX, p.x), maxX = std::max(maxX, p.x);
        minY = std::min(minY, p.y), maxY = std::max(maxY, p.y);
        minZ = std::min(minZ, p.z), maxZ = std::max(maxZ, p.z);
    }
    const double margin = 0.05;
    const double spanX = std::max(maxX - minX, 1e-12), spanY = std::max(maxY - minY, 1e-12);
    const double scale = (1 - 2 * margin) * std::min(width / spanX, height / spanY);
    const double offX = 0.5 * (width - scale * spanX), offY = 0.5 * (height - scale * spanY);
    depthScale = std::max(maxZ - minZ, 1e-12);
    proj = Projection{scale, offX, offY, minX, maxY};
    std::vector<double> sx(cam.position.size()), sy(cam.position.size());
    for (size_t v = 0; v < cam.position.size(); ++v) {
        sx[v] = proj.x(cam.position[v]);
        sy[v] = proj.y(cam.position[v]);
    }
    std::vector<Fragment> frags(size_t(width) * size_t(height));
    for (uint32_t f = 0; f < mesh.faceCount(); ++f) {
        const Tri& t = mesh.faces[f];
        const double x0 = sx[t[0]], y0 = sy[t[0]], x1 = sx[t[1]], y1 = sy[t[1]], x2 = sx[t[2]], y2 = sy[t[2]];
        const double area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0);
        if (std::fabs(area) < 1e-12) continue;
        const int px0 = std::max(0, int(std::floor(std::min({x0, x1, x2}))));
        const int px1 = std::min(width - 1, int(std::ceil(std::max({x0, x1, x2}))));
        const int py0 = std::max(0, int(std::floor(std::min({y0, y1, y2}))));
        const int py1 = std::min(height - 1, int(std::ceil(std::max({y0, y1, y2}))));
        const double z0 = cam.position[t[0]].z, z1 = cam.position[t[1]].z, z2 = cam.position[t[2]].z;
        for (int py = py0; py <= py1; ++py)
            for (int px = px0; px <= px1; ++px) {
                const double cx = px + 0.5, cy = py + 0.5;
                // Barycentric coordinates from edge functions; both windings are drawn.
                const double b1 = ((cx - x0) * (y2 - y0) - (x2 - x0) * (cy - y0)) / area;
                const double b2 = ((x1 - x0) * (cy - y0) - (cx - x0) * (y1 - y0)) / area;
                const double b0 = 1 - b1 - b2;
                if (b0 < 0 || b1 < 0 || b2 < 0) continue;
                const float depth = float(b0 * z0 + b1 * z1 + b2 * z2);
                Fragment& fr = frags[size_t(py) * size_t(width) + size_t(px)];
                if (depth <= fr.depth) continue;
                fr = Fragment{int32_t(f), float(b1), float(b2), depth};
            }
    }
    return frags;
}

Rgb lerp(Rgb a, Rgb b, double t) {
    auto mix = [t](uint8_t x, uint8_t y) { return uint8_t(std::lround(x + (double(y) - x) * t)); };
    return Rgb{mix(a.r, b.r), mix(a.g, b.g), mix(a.b, b.b)};
}

Rgb ramp(const Rgb* stops, int count, double t) {
    t = std::clamp(std::isnan(t) ? 0.0 : t, 0.0, 1.0) * (count - 1);
    const int i = std::min(int(t), count - 2);
    return lerp(stops[i], stops[i + 1], t - i);
}

// Draws the panel's polyline, 3 pixels wide, where it is not hidden behind the surface
// (it lies on it, so it is compared with the front-most depth with some slack).
void drawPolyline(Image& img, const std::vector<Fragment>& frags, const Panel& panel, const View& view,
                  const Projection& proj, int width, int height, double depthScale) {
    const ViewRotation rotate(view);
    auto plot = [&](double px, double py, double depth) {
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int x = int(std::floor(px)) + dx, y = int(std::floor(py)) + dy;
                if (x < 0 || y < 0 || x >= width || y >= height) continue;
                const Fragment& fr = frags[size_t(y) * size_t(width) + size_t(x)];
                if (fr.face >= 0 && depth < fr.depth - 0.02 * depthScale) continue;
                img.at(x, y + kCaptionHeight) = panel.polylineColour;
            }
    };
    for (size_t i = 0; i + 1 < panel.polyline.size(); ++i) {
        const Vec3 a = rotate(panel.polyline[i]), b = rotate(panel.polyline[i + 1]);
        const double ax = proj.x(a), ay = proj.y(a), bx = proj.x(b), by = proj.y(b);
        const int steps = std::max(1, int(std::ceil(std::max(std::fabs(bx - ax), std::fabs(by - ay)) * 2)));
        for (int k = 0; k <= steps; ++k) {
            const double t = double(k) / steps;
            plot(ax + t * (bx - ax), ay + t * (by - ay), a.z + t * (b.z - a.z));
        }
    }
}

Image shadePanel(const Mesh& mesh, const CameraSpace& cam, const std::vector<Fragment>& frags, const Panel& panel,
                 int width, int height, double depthScale) {
    Image img(width, height + kCaptionHeight, kBackground);
    std::vector<double> value(frags.size(), INFINITY);
    const bool iso = !panel.isoValue.empty() && panel.isoSpacing > 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const size_t i = size_t(y) * size_t(width) + size_t(x);
            const Fragment& fr = frags[i];
            if (fr.face < 0) continue;
            const Tri& t = mesh.faces[size_t(fr.face)];
            const double w[3] = {1.0 - fr.w1 - fr.w2, fr.w1, fr.w2};
            double r = 0, g = 0, b = 0, nz = 0;
            for (int k = 0; k < 3; ++k) {
                const Rgb c = panel.vertexColour[t[k]];
                r += w[k] * c.r, g += w[k] * c.g, b += w[k] * c.b;
                nz += w[k] * cam.normal[t[k]].z;
            }
            const double light = 0.35 + 0.65 * std::min(1.0, std::fabs(nz));  // two-sided head light
            img.at(x, y + kCaptionHeight) =
                Rgb{uint8_t(std::min(255.0, r * light)), uint8_t(std::min(255.0, g * light)),
                    uint8_t(std::min(255.0, b * light))};
            if (iso) {
                double v = 0;
                for (int k = 0; k < 3; ++k) v += w[k] * panel.isoValue[t[k]];
                value[i] = v;
            }
        }
    if (iso) {
        // A pixel is on an isoline where its band differs from a neighbour's on the same
        // sheet of surface (close in depth, so silhouettes draw no false lines).
        auto band = [&](size_t i) { return std::floor(value[i] / panel.isoSpacing); };
        for (int y = 0; y + 1 < height; ++y)
            for (int x = 0; x + 1 < width; ++x) {
                const size_t i = size_t(y) * size_t(width) + size_t(x);
                if (!std::isfinite(value[i])) continue;
                for (const size_t j : {i + 1, i + size_t(width)}) {
                    if (!std::isfinite(value[j]) || band(j) == band(i)) continue;
                    if (std::fabs(frags[j].depth - frags[i].depth) > 0.02 * depthScale) continue;
                    Rgb& c = img.at(x, y + kCaptionHeight);
                    c = Rgb{uint8_t(c.r / 5), uint8_t(c.g / 5), uint8_t(c.b / 5)};
                    break;
                }
            }
    }
    drawText(img, 8, 6, panel.caption, Rgb{30, 30, 30});
    return img;
}

}  // namespace

Image renderPanels(const Mesh& mesh, const std::vector<Panel>& panels, int width, int height, const View& view) {
    const CameraSpace cam = toCamera(mesh, view);
    double depthScale = 1;
    Projection proj;
    const std::vector<Fragment> frags = rasterise(mesh, cam, width, height, depthScale, proj);
    Image out(width * int(panels.size()), height + kCaptionHeight, kBackground);
    for (size_t k = 0; k < panels.size(); ++k) {
        Image img = shadePanel(mesh, cam, frags, panels[k], width, height, depthScale);
        if (!panels[k].polyline.empty()) drawPolyline(img, frags, panels[k], view, proj, width, height, depthScale);
        out.paste(img, int(k) * width, 0);
    }
    return out;
}

Rgb distanceColour(double t) {
    static const Rgb stops[] = {{40, 30, 150}, {30, 120, 225}, {40, 190, 140}, {245, 215, 60}, {205, 45, 35}};
    return ramp(stops, 5, t);
}

Rgb errorColour(double t) {
    static const Rgb stops[] = {{250, 250, 250}, {250, 175, 70}, {150, 0, 0}};
    return ramp(stops, 3, t);
}

Rgb categoryColour(uint32_t k) {
    // Hues spaced by the golden angle, so neighbouring labels differ.
    const double h = std::fmod(k * 0.618033988749895, 1.0) * 6, s = 0.55, v = 0.95;
    const int i = int(h) % 6;
    const double f = h - std::floor(h), p = v * (1 - s), q = v * (1 - s * f), u = v * (1 - s * (1 - f));
    double r = v, g = u, b = p;
    switch (i) {
        case 1: r = q, g = v, b = p; break;
        case 2: r = p, g = v, b = u; break;
        case 3: r = p, g = q, b = v; break;
        case 4: r = u, g = p, b = v; break;
        case 5: r = v, g = p, b = q; break;
        default: break;
    }
    return Rgb{uint8_t(r * 255), uint8_t(g * 255), uint8_t(b * 255)};
}

Rgb unreachableColour() { return Rgb{150, 150, 150}; }

double largestFinite(const std::vector<double>& field) {
    double m = 0;
    for (double d : field)
        if (std::isfinite(d)) m = std::max(m, d);
    return m;
}

std::vector<Rgb> colourField(const std::vector<double>& field, double scale) {
    std::vector<Rgb> colours;
    colours.reserve(field.size());
    for (double d : field)
        colours.push_back(std::isfinite(d) ? distanceColour(scale > 0 ? d / scale : 0) : unreachableColour());
    return colours;
}

}  // namespace vorogeo::tools
