// The phase function's polar plot (gi/volumetric/phase_plot.h): the lobe's geometry on both
// scales, the CPU image gi-render writes, and the strokes (gi/render/strokes.h) it is drawn with.
#include "gi/render/image_io.h"
#include "gi/render/strokes.h"
#include "gi/volumetric/phase_plot.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace gi {
namespace {

PhaseParams params(PhaseFunction f, float g) { return {f, g, schlickKFromG(g)}; }

float largestRadius(const std::vector<glm::vec2>& lobe) {
    float r = 0.0f;
    for (const glm::vec2& q : lobe) r = std::max(r, glm::length(q));
    return r;
}

// Isotropic scattering is the same every way: a circle of radius 1 about the origin, on both
// scales, with its points at the angles 2 pi i / n.
TEST(PhasePlot, IsotropicIsTheUnitCircle) {
    for (bool logScale : {false, true}) {
        std::vector<glm::vec2> lobe = phaseLobe(params(PhaseFunction::Isotropic, 0.0f), logScale, 72);
        ASSERT_EQ(lobe.size(), 72u);
        glm::vec2 mean(0.0f);
        for (size_t i = 0; i < lobe.size(); ++i) {
            EXPECT_NEAR(glm::length(lobe[i]), 1.0f, 1e-6f) << i;
            float theta = 2.0f * glm::pi<float>() * float(i) / 72.0f;
            EXPECT_NEAR(lobe[i].x, std::cos(theta), 1e-5f);
            EXPECT_NEAR(lobe[i].y, std::sin(theta), 1e-5f);
            mean += lobe[i];
        }
        EXPECT_NEAR(glm::length(mean / 72.0f), 0.0f, 1e-5f) << "centred at the origin";
    }
}

// Henyey-Greenstein at g = 0.7 peaks forward: the lobe reaches x = 1 at theta = 0 and its back
// (theta = pi, at x < 0) has radius p(180) / p(0) = ((1 - g) / (1 + g))^3, about 0.0055.
TEST(PhasePlot, HenyeyGreensteinReachesForwardAndScalesBack) {
    PhaseParams p = params(PhaseFunction::HenyeyGreenstein, 0.7f);
    std::vector<glm::vec2> lobe = phaseLobe(p, false, 360);
    ASSERT_EQ(lobe.size(), 360u);
    EXPECT_NEAR(lobe[0].x, 1.0f, 1e-6f);
    EXPECT_NEAR(lobe[0].y, 0.0f, 1e-6f);
    EXPECT_NEAR(largestRadius(lobe), 1.0f, 1e-6f);
    double ratio = phase(p, -1.0) / phase(p, 1.0);
    EXPECT_NEAR(ratio, std::pow(0.3 / 1.7, 3.0), 1e-6);
    EXPECT_NEAR(lobe[180].x, -float(ratio), 1e-6f);
    EXPECT_NEAR(std::abs(lobe[180].y), 0.0f, 1e-6f);
    // Symmetric about the x axis: theta and 2 pi - theta mirror each other.
    for (int i = 1; i < 180; ++i) {
        EXPECT_NEAR(lobe[size_t(i)].x, lobe[size_t(360 - i)].x, 1e-6f) << i;
        EXPECT_NEAR(lobe[size_t(i)].y, -lobe[size_t(360 - i)].y, 1e-6f) << i;
    }
    // Negative g scatters backwards: the peak (radius 1) moves to x = -1.
    std::vector<glm::vec2> back = phaseLobe(params(PhaseFunction::HenyeyGreenstein, -0.7f), false, 360);
    EXPECT_NEAR(back[180].x, -1.0f, 1e-6f);
    EXPECT_NEAR(back[0].x, float(ratio), 1e-6f);
}

// The log scale keeps every radius in [0, 1], reaches 1 at the peak, follows r = 1 + log10(p /
// pMax) / 3, and keeps the narrow lobes' backs readable (HG 0.7's back, 1/181 of the peak, at
// about 0.25 instead of 0.0055; murky Mie's, 1/34, at about 0.49).
TEST(PhasePlot, LogScaleKeepsRadiiInTheUnitDisc) {
    for (const auto& [f, name] : EnumNames<PhaseFunction>::values)
        for (float g : {-0.95f, -0.3f, 0.0f, 0.3f, 0.7f, 0.99f}) {
            std::vector<glm::vec2> lobe = phaseLobe(params(f, g), true, 360);
            float lo = 2.0f, hi = -1.0f;
            for (const glm::vec2& q : lobe) {
                float r = glm::length(q);
                EXPECT_TRUE(std::isfinite(r)) << name << " g " << g;
                lo = std::min(lo, r);
                hi = std::max(hi, r);
            }
            EXPECT_GE(lo, 0.0f) << name << " g " << g;
            EXPECT_NEAR(hi, 1.0f, 1e-6f) << name << " g " << g;
        }
    PhaseParams hg = params(PhaseFunction::HenyeyGreenstein, 0.7f);
    std::vector<glm::vec2> lobe = phaseLobe(hg, true, 360);
    double expected = 1.0 + std::log10(phase(hg, -1.0) / phase(hg, 1.0)) / kPhaseLogDecades;
    EXPECT_NEAR(-lobe[180].x, float(expected), 1e-5f);
    EXPECT_GT(-lobe[180].x, 0.2f);
    EXPECT_NEAR(-phaseLobe(params(PhaseFunction::MieMurky, 0.0f), true, 360)[180].x, 1.0f - std::log10(34.0f) / 3.0f, 1e-5f);
    // Past three decades below the peak the lobe sits at the centre: HG 0.99's back is 8e6 times
    // below its front.
    EXPECT_NEAR(glm::length(phaseLobe(params(PhaseFunction::HenyeyGreenstein, 0.99f), true, 360)[180]), 0.0f, 1e-6f);
    // The isotropic comparison on HG 0.7's linear scale is p_iso / p(0).
    PhasePlotScale s = phasePlotScale(hg, false);
    EXPECT_NEAR(s.radius(1.0 / (4.0 * glm::pi<double>())), float(1.0 / (4.0 * glm::pi<double>()) / phase(hg, 1.0)), 1e-6f);
}

// Rayleigh is even in cos theta: as large backwards as forwards, half that at 90 degrees.
TEST(PhasePlot, RayleighIsSymmetricFrontToBack) {
    std::vector<glm::vec2> lobe = phaseLobe(params(PhaseFunction::Rayleigh, 0.0f), false, 360);
    EXPECT_NEAR(lobe[0].x, 1.0f, 1e-6f);
    EXPECT_NEAR(lobe[180].x, -1.0f, 1e-6f);
    EXPECT_NEAR(lobe[90].y, 0.5f, 1e-6f);
}

// The image: lobe-coloured pixels where the lobe reaches forward, the background far from
// everything, the isotropic circle's colour where HG 0.7's lobe is inside it (sideways), and a
// faint fill inside the lobe.
TEST(PhasePlot, ImageShowsTheLobeWhereItReaches) {
    const int size = 256;
    PhaseParams p = params(PhaseFunction::HenyeyGreenstein, 0.7f);
    std::vector<uint8_t> img = phasePlotImage(p, size, false);
    ASSERT_EQ(img.size(), size_t(size) * size * 4);
    auto rgb = [&](glm::vec2 at) {
        glm::ivec2 px(glm::floor(at));
        const uint8_t* q = &img[(size_t(px.y) * size + size_t(px.x)) * 4];
        EXPECT_EQ(q[3], 255);
        return glm::vec3(q[0], q[1], q[2]) / 255.0f;
    };
    auto near = [](glm::vec3 a, glm::vec3 b, float tol) { return glm::all(glm::lessThan(glm::abs(a - b), glm::vec3(tol))); };
    PhasePlotLayout layout = phasePlotLayout(size);
    glm::vec2 forward = layout.centre + glm::vec2(layout.radius, 0.0f);
    EXPECT_TRUE(near(rgb(forward), kPhasePlotLobe, 0.02f)) << "forward point " << glm::length(rgb(forward));
    EXPECT_TRUE(near(rgb(forward - glm::vec2(0.0f, 0.5f)), kPhasePlotLobe, 0.02f));
    EXPECT_TRUE(near(rgb({2.0f, 2.0f}), kPhasePlotBackground, 0.01f)) << "corner";
    EXPECT_TRUE(near(rgb({float(size) - 3.0f, float(size) - 3.0f}), kPhasePlotBackground, 0.01f)) << "corner";
    // Straight up from the centre, the isotropic circle at p_iso / p(0) of the radius (the lobe
    // is much closer to the axis there).
    float iso = phasePlotScale(p, false).radius(1.0 / (4.0 * glm::pi<double>()));
    glm::vec2 up = layout.centre + glm::vec2(0.0f, iso * layout.radius);
    EXPECT_GT(rgb(up).b, rgb(up).r) << "isotropic circle is blue";
    EXPECT_GT(rgb(up).b, 0.6f);
    // Inside the lobe, off the axis: the faint fill, orange over the background.
    glm::vec2 inside = layout.centre + glm::vec2(0.6f * layout.radius, 0.04f * layout.radius);
    glm::vec3 fill = rgb(inside);
    EXPECT_GT(fill.r, kPhasePlotBackground.r + 0.05f);
    EXPECT_LT(fill.r, 0.5f) << "faint";
    // Isotropic: the lobe is the full circle, so it is lobe-coloured straight behind too.
    std::vector<uint8_t> isoImg = phasePlotImage(params(PhaseFunction::Isotropic, 0.0f), size, false);
    img = isoImg;
    EXPECT_TRUE(near(rgb(layout.centre - glm::vec2(layout.radius, 0.0f)), kPhasePlotLobe, 0.02f));
    EXPECT_TRUE(near(rgb(layout.centre + glm::vec2(0.0f, layout.radius)), kPhasePlotLobe, 0.02f));
}

// A translucent closed polyline is blended once per pixel, so its joins look like the rest of it,
// where separate strokes (drawStrokes) lay the colour twice; a filled polygon covers its inside
// fully, its outside not at all and its edge in part.
TEST(Strokes, PolylineJoinsAndPolygonFill) {
    const int w = 64, h = 64;
    std::vector<glm::vec2> square = {{16.0f, 16.0f}, {48.0f, 16.0f}, {48.0f, 48.0f}, {16.0f, 48.0f}};
    std::vector<uint8_t> img(size_t(w) * h * 4, 0);
    drawPolyline(img, w, h, square, true, glm::vec4(1.0f, 1.0f, 1.0f, 0.5f), 3.0f);
    auto red = [&](const std::vector<uint8_t>& im, int x, int y) { return int(im[(size_t(y) * w + x) * 4]); };
    EXPECT_NEAR(red(img, 32, 16), 128, 1) << "edge";
    EXPECT_NEAR(red(img, 16, 16), 128, 1) << "corner blended once";
    EXPECT_NEAR(red(img, 47, 47), 128, 1) << "corner blended once";
    EXPECT_EQ(red(img, 32, 32), 0) << "inside untouched";
    std::vector<Stroke> separate;
    for (size_t i = 0; i < 4; ++i) separate.push_back({square[i], square[(i + 1) % 4], glm::vec4(1.0f, 1.0f, 1.0f, 0.5f), 3.0f});
    std::vector<uint8_t> strokes(size_t(w) * h * 4, 0);
    drawStrokes(strokes, w, h, separate);
    EXPECT_NEAR(red(strokes, 32, 16), 128, 1);
    EXPECT_GT(red(strokes, 16, 16), 180) << "separate strokes overlap at the corner";

    std::vector<uint8_t> fill(size_t(w) * h * 4, 0);
    fillPolygon(fill, w, h, square, glm::vec4(1.0f));
    EXPECT_EQ(red(fill, 32, 32), 255);
    EXPECT_EQ(red(fill, 16, 30), 255) << "the column whose centre is just inside";
    EXPECT_EQ(red(fill, 15, 30), 0) << "the column whose centre is half a pixel outside";
    EXPECT_EQ(red(fill, 10, 30), 0);
    EXPECT_EQ(red(fill, 32, 50), 0);
    // A diagonal edge is soft: pixels it halves are about half covered.
    std::vector<glm::vec2> triangle = {{0.0f, 0.0f}, {64.0f, 0.0f}, {0.0f, 64.0f}};
    std::vector<uint8_t> tri(size_t(w) * h * 4, 0);
    fillPolygon(tri, w, h, triangle, glm::vec4(1.0f));
    EXPECT_NEAR(red(tri, 31, 32), 128, 40) << "on the hypotenuse x + y = 64";
    EXPECT_EQ(red(tri, 10, 10), 255);
    EXPECT_EQ(red(tri, 50, 50), 0);
}

// gi-render --views writes the plot of the preset's phase function when volumetric lighting is
// on, and none when it is off.
TEST(PhasePlot, RenderViewsWriteThePlot) {
    std::string preset = (std::filesystem::path(GI_PRESET_DIR) / "volumetric_cornell.json").string();
    auto out = test::tempDir();
    auto r = test::runCommand(std::string(GI_RENDER_EXE) + " " + preset + " --out " + (out / "on").string() +
                              " --width 96 --height 64 --views --set volumetric.phase=mieMurky");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    ImageRGBA8 plot = readImage8(out / "on" / "views" / "volumetric.phase.png");
    EXPECT_EQ(plot.width, 256);
    EXPECT_EQ(plot.height, 256);
    r = test::runCommand(std::string(GI_RENDER_EXE) + " " + preset + " --out " + (out / "off").string() +
                         " --width 96 --height 64 --views --set volumetric.enabled=false");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_FALSE(std::filesystem::exists(out / "off" / "views" / "volumetric.phase.png"));
}

}  // namespace
}  // namespace gi
