// Software rendering of a mesh shaded by per-vertex values (no GPU, no display): an
// orthographic z-buffer rasteriser with head-light shading and isolines, as in the
// thesis's figures. The mesh is rasterised once; every panel shades the same pixels.
#pragma once

#include <string>
#include <vector>

#include "image.h"
#include "mesh.h"

namespace vorogeo::tools {

struct View {
    double yawDegrees = 0;    // turn about the vertical (y) axis
    double pitchDegrees = 0;  // then tilt about the horizontal (x) axis
};

// What one panel shows: a colour per vertex, optionally isolines of a per-vertex value
// every `isoSpacing`, and a caption above the picture.
struct Panel {
    std::vector<Rgb> vertexColour;
    std::vector<double> isoValue;  // empty: no isolines; +inf values draw none
    double isoSpacing = 0;
    std::string caption;
    std::vector<Vec3> polyline;  // drawn over the surface where it is visible (e.g. a geodesic path)
    Rgb polylineColour{255, 255, 255};
};

// Renders the panels side by side, each width x height pixels plus a caption strip.
Image renderPanels(const Mesh& mesh, const std::vector<Panel>& panels, int width, int height, const View& view);

// Colour maps. t in [0, 1] (clamped).
Rgb distanceColour(double t);    // blue (near) through green and yellow to red (far)
Rgb errorColour(double t);       // white (no error) to dark red
Rgb categoryColour(uint32_t k);  // well-separated colours for labels
Rgb unreachableColour();         // grey for +inf distances

// Largest finite value of a field (0 when none).
double largestFinite(const std::vector<double>& field);
// Per-vertex colours of a distance field, `scale` mapping to the far end of the ramp.
std::vector<Rgb> colourField(const std::vector<double>& field, double scale);

}  // namespace vorogeo::tools
