#include "gi/volumetric/phase_plot.h"

#include "gi/render/strokes.h"
#include "gi/util/error.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace gi {

float PhasePlotScale::radius(double value) const {
    if (!(value > 0.0) || !(pMax > 0.0)) return 0.0f;
    double r = logScale ? 1.0 + std::log10(value / pMax) / kPhaseLogDecades : value / pMax;
    return float(std::clamp(r, 0.0, 1.0));
}

PhasePlotScale phasePlotScale(const PhaseParams& p, bool logScale) {
    PhasePlotScale s;
    s.pMax = std::max(phase(p, 1.0), phase(p, -1.0));
    s.logScale = logScale;
    return s;
}

std::vector<glm::vec2> phaseLobe(const PhaseParams& p, bool logScale, int segments) {
    GI_ASSERT(segments >= 4, "phaseLobe: too few segments for a closed curve");
    PhasePlotScale scale = phasePlotScale(p, logScale);
    std::vector<glm::vec2> points(static_cast<size_t>(segments));
    for (int i = 0; i < segments; ++i) {
        double theta = 2.0 * glm::pi<double>() * double(i) / double(segments);
        float r = scale.radius(phase(p, std::cos(theta)));
        points[size_t(i)] = r * glm::vec2(float(std::cos(theta)), float(std::sin(theta)));
    }
    return points;
}

const char* phaseFunctionLabel(PhaseFunction f) {
    switch (f) {
        case PhaseFunction::Isotropic: return "isotropic";
        case PhaseFunction::HenyeyGreenstein: return "Henyey-Greenstein";
        case PhaseFunction::Schlick: return "Schlick";
        case PhaseFunction::Rayleigh: return "Rayleigh";
        case PhaseFunction::MieHazy: return "Mie (hazy)";
        case PhaseFunction::MieMurky: return "Mie (murky)";
    }
    return "?";
}

PhasePlotLayout phasePlotLayout(int size) {
    // Room around radius 1 for the axis and its arrowhead.
    return {glm::vec2(0.5f * float(size)), 0.4f * float(size)};
}

std::vector<uint8_t> phasePlotImage(const PhaseParams& p, int size, bool logScale) {
    GI_ASSERT(size >= 16, "phasePlotImage: image too small to read");
    std::vector<uint8_t> rgba(size_t(size) * size_t(size) * 4, 255);
    for (size_t i = 0; i < rgba.size(); i += 4)
        for (int k = 0; k < 3; ++k) rgba[i + k] = uint8_t(std::lround(255.0f * kPhasePlotBackground[k]));

    const PhasePlotLayout layout = phasePlotLayout(size);
    const glm::vec2 c = layout.centre;
    const float R = layout.radius;
    const float line = std::max(1.0f, float(size) / 256.0f);  // 1 px at 256, thicker for larger images
    auto toPixels = [&](std::vector<glm::vec2> points, float scale) {
        for (glm::vec2& q : points) q = c + scale * R * q;
        return points;
    };
    std::vector<glm::vec2> unitCircle = phaseLobe(PhaseParams{}, false, 128);  // isotropic: radius 1

    // Reference circles and the x axis, faint, under everything else.
    const glm::vec4 grid(0.26f, 0.26f, 0.29f, 1.0f);
    drawPolyline(rgba, size, size, toPixels(unitCircle, 0.5f), true, grid, line);
    drawPolyline(rgba, size, size, toPixels(unitCircle, 1.0f), true, grid, line);
    const glm::vec4 axis(0.5f, 0.5f, 0.54f, 1.0f);
    const float tipX = c.x + 1.2f * R, head = 0.05f * float(size);
    drawStrokes(rgba, size, size, {{c - glm::vec2(1.2f * R, 0.0f), glm::vec2(tipX - 0.5f * head, c.y), axis, line}});
    fillPolygon(rgba, size, size,
                {glm::vec2(tipX, c.y), glm::vec2(tipX - head, c.y + 0.45f * head), glm::vec2(tipX - head, c.y - 0.45f * head)},
                axis);

    // The lobe's fill, the isotropic circle on the lobe's scale, then the lobe's outline on top.
    std::vector<glm::vec2> lobe = toPixels(phaseLobe(p, logScale), 1.0f);
    fillPolygon(rgba, size, size, lobe, glm::vec4(kPhasePlotLobe, 0.16f));
    float iso = phasePlotScale(p, logScale).radius(1.0 / (4.0 * glm::pi<double>()));
    if (iso > 0.0f) drawPolyline(rgba, size, size, toPixels(unitCircle, iso), true, glm::vec4(kPhasePlotIsotropic, 0.9f), line);
    drawPolyline(rgba, size, size, lobe, true, glm::vec4(kPhasePlotLobe, 1.0f), 2.0f * line);
    return rgba;
}

}  // namespace gi
