// The phase function as a polar plot: the lobe r(theta) in a plane through the light's direction
// of travel, which lies along +x (theta = 0, forward scattering, is to the right; theta = pi,
// back towards the light, to the left). The phase functions depend on theta only, so the lobe is
// symmetric about the x axis and the plane shows all of it. The editor's "Phase function" window
// draws phaseLobe with ImGui; gi-render --views writes phasePlotImage as views/volumetric.phase.png.
//
// Scales (choices; the seed draws no plots):
//   - linear: r = p(theta) / pMax, so the largest radius is 1 and a radius reads as the fraction
//     of the peak. pMax is the larger of p(0) and p(pi): each of the six functions is monotonic in
//     cos theta, or even in it (Rayleigh), so its peak is at one end.
//   - log: r = (log10 p - log10 pMin) / (log10 pMax - log10 pMin), clamped at 0, with pMin always
//     kPhaseLogDecades (3) decades below pMax, i.e. r = 1 + log10(p / pMax) / 3. A fixed range
//     rather than the lobe's own minimum keeps the shape honest: Rayleigh's 2:1 would otherwise
//     fill the whole radius and pinch to the centre at 90 degrees, while a narrow lobe (mieMurky,
//     34:1; Henyey-Greenstein at g = 0.9, 6859:1) keeps a readable back side instead of a spike.
//     Only values past 1000:1 below the peak reach the centre (clamped).
//   - The isotropic circle drawn for comparison is p = 1 / (4 pi) on the same scale: the lobe
//     is outside it where the medium scatters more than isotropic in that direction.
#pragma once

#include "gi/volumetric/phase.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace gi {

constexpr double kPhaseLogDecades = 3.0;  // range of the log scale below the peak

// How the plot turns a phase value into a radius.
struct PhasePlotScale {
    double pMax = 1.0;  // per steradian; radius 1
    bool logScale = false;
    float radius(double value) const;  // 0..1
};
PhasePlotScale phasePlotScale(const PhaseParams& p, bool logScale);

// The closed lobe: `segments` points r(theta) (cos theta, sin theta) for theta = 2 pi i / segments,
// i = 0 .. segments - 1 (the last joins the first); the largest radius is 1. segments >= 4.
std::vector<glm::vec2> phaseLobe(const PhaseParams& p, bool logScale, int segments = 360);

// A readable name of the function ("Henyey-Greenstein", "Mie (murky)", ...).
const char* phaseFunctionLabel(PhaseFunction f);

// Where phasePlotImage puts the plot: radius 1 is `radius` pixels from `centre` (pixels, y up).
struct PhasePlotLayout {
    glm::vec2 centre{0.0f};
    float radius = 0.0f;
};
PhasePlotLayout phasePlotLayout(int size);

// Colours of phasePlotImage (display-encoded RGB).
inline const glm::vec3 kPhasePlotBackground{0.075f, 0.075f, 0.085f};
inline const glm::vec3 kPhasePlotLobe{1.0f, 0.62f, 0.2f};
inline const glm::vec3 kPhasePlotIsotropic{0.38f, 0.62f, 1.0f};

// The polar plot as a size x size RGBA8 image, bottom row first (as gi::writePNG takes it): a
// dark background, faint circles at r = 0.5 and 1, the x axis with an arrowhead at +x (the light's
// direction of travel), the isotropic circle in blue, and the lobe as an orange line over a faint
// fill. Drawn on the CPU with gi/render/strokes.h.
std::vector<uint8_t> phasePlotImage(const PhaseParams& p, int size, bool logScale);

}  // namespace gi
