// The path-traced reference's single scattering (gi/volumetric/medium.h, gi/reference/path_tracer.h):
// nothing changes without a medium, the in-scattered light equals a quadrature of the medium's
// integral (point, spot and directional lights, isotropic and anisotropic phases, shadows), the
// camera leg fades the scene by exp(-sigma_t x distance in the box) in every mode, a spot's cone
// clips the lit part of the ray, the medium's shadow rays are counted, and renders repeat.
//
// Most cases look into an open-topped room of black walls: nothing reflects or glows there, so
// a pixel holds only the in-scattered light, and the medium (the scene's bounds) is the room.
#include "gi/reference/path_tracer.h"
#include "gi/reference/reference_cache.h"
#include "gi/scene/camera.h"
#include "gi/scene/mesh_builder.h"
#include "gi/volumetric/medium.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace gi {
namespace {

constexpr float kRoom = 5.0f;  // the room is [-5, 5]^3
constexpr float kInf = std::numeric_limits<float>::infinity();

// Black floor and four black walls, open at the top so the sun shines in. With `roof`, a black
// roof at y = 4 over x < 0 shadows that half from the sun.
Scene blackRoom(bool roof = false) {
    Scene s;
    MeshBuilder b(s);
    int black = b.material("black", glm::vec3(0.0f), 1.0f);
    const float r = kRoom, w = 2.0f * kRoom;
    b.quad(black, {-r, -r, r}, {w, 0, 0}, {0, 0, -w});   // floor
    b.quad(black, {-r, -r, -r}, {w, 0, 0}, {0, w, 0});   // z = -5
    b.quad(black, {-r, -r, r}, {0, w, 0}, {w, 0, 0});    // z = +5
    b.quad(black, {-r, -r, -r}, {0, w, 0}, {0, 0, w});   // x = -5
    b.quad(black, {r, -r, -r}, {0, 0, w}, {0, w, 0});    // x = +5
    if (roof) b.quad(black, {-r, 4.0f, r}, {r, 0, 0}, {0, 0, -w});
    s.finalize();
    return s;
}

FrameSettings frame(glm::vec3 eye, glm::vec3 target, int size, float fovY) {
    FrameSettings fs;
    fs.camera.eye = eye;
    fs.camera.target = target;
    fs.camera.fovY = fovY;
    fs.camera.near = 0.01f;
    fs.render.specular = false;  // black walls then reflect exactly nothing
    fs.width = fs.height = size;
    return fs;
}

LightSettings spotDown(glm::vec3 position, float intensity, float innerDeg, float outerDeg, float range) {
    LightSettings l;
    l.type = LightType::Spot;
    l.position = position;
    l.direction = {0.0f, -1.0f, 0.0f};
    l.intensity = intensity;
    l.innerConeDeg = innerDeg;
    l.outerConeDeg = outerDeg;
    l.range = range;
    return l;
}

VolumetricSettings coefficients(float density, float absorption, PhaseFunction phase = PhaseFunction::Isotropic, float g = 0.0f) {
    VolumetricSettings v;
    v.enabled = true;
    v.attenuation = VolumeAttenuation::Coefficients;
    v.density = density;
    v.absorption = absorption;
    v.phase = phase;
    v.g = g;
    return v;
}

float red(const ImageRGB& img, int x, int y) { return img.rgb[(size_t(y) * img.width + x) * 3]; }

// ---- The expected value, by quadrature ------------------------------------------------------

// The light's radiance at x (white light) written out afresh from the contract: 1/d^2, the glTF
// range window, the smoothstep spot cone; `travel` is the light's direction of travel at x.
double lightAt(const LightSettings& l, glm::dvec3 x, glm::dvec3& travel) {
    if (l.type == LightType::Directional) {
        travel = glm::normalize(glm::dvec3(l.direction));
        return l.intensity;
    }
    glm::dvec3 v = x - glm::dvec3(l.position);
    double d = glm::length(v);
    travel = v / d;
    double E = l.intensity / (d * d);
    if (l.range > 0.0f) {
        double r = d / l.range, w = std::clamp(1.0 - r * r * r * r, 0.0, 1.0);
        E *= w * w;
    }
    if (l.type == LightType::Spot) {
        double cosOuter = std::cos(glm::radians(double(l.outerConeDeg)));
        double cosInner = std::cos(glm::radians(double(l.innerConeDeg)));
        double cd = glm::dot(travel, glm::normalize(glm::dvec3(l.direction)));
        double s = std::clamp((cd - cosOuter) / (cosInner - cosOuter), 0.0, 1.0);
        E *= s * s * (3.0 - 2.0 * s);
    }
    return E;
}

// Moments of the tracer's one-sample estimator (t1 - t0) f(t), t uniform on the lit part
// [t0, t1] of a ray: mean = integral of f, second = (t1 - t0) integral of f^2, by Simpson's rule.
// `cosSign` -1 evaluates the phase at the opposite angle (the wrong convention), to show the
// test tells them apart; `visible` is the shadow test, written out for the scene.
struct Moments {
    double mean = 0.0, second = 0.0;
};

template <class Visible>
Moments rayMoments(const Medium& m, const LightSettings& l, glm::vec3 eye, glm::vec3 d, const Visible& visible, double cosSign) {
    float t0, t1;
    if (!clipRayToBox(m.box, eye, d, kInf, t0, t1)) return {};
    const double tEnter = t0;
    if (!clipRayToLight(l, eye, d, t0, t1)) return {};
    auto f = [&](double t) {
        glm::dvec3 x = glm::dvec3(eye) + t * glm::dvec3(d);
        if (!visible(x)) return 0.0;
        glm::dvec3 travel;
        double Li = lightAt(l, x, travel);
        double cosTheta = cosSign * glm::dot(travel, -glm::dvec3(d));
        double Tlight = std::exp(-double(m.sigmaT) * lightPathInBox(m.box, l, glm::vec3(x)));
        double Tview = std::exp(-double(m.sigmaT) * (t - tEnter));
        return double(m.intensity) * m.sigmaS * phase(m.phase, cosTheta) * Li * Tlight * Tview;
    };
    const int n = 2000;  // even
    const double h = (double(t1) - t0) / n;
    double s1 = 0.0, s2 = 0.0;
    for (int i = 0; i <= n; ++i) {
        double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0), v = f(t0 + i * h);
        s1 += w * v;
        s2 += w * v * v;
    }
    return {s1 * h / 3.0, (double(t1) - t0) * s2 * h / 3.0};
}

// The same over pixel (px, py)'s footprint (the tracer's box filter), on a sub x sub grid of
// rays made as the tracer makes them.
template <class Visible>
Moments pixelMoments(const FrameSettings& fs, const Medium& m, const LightSettings& l, int px, int py, const Visible& visible,
                     double cosSign = 1.0, int sub = 8) {
    const glm::mat4 invViewProj =
        glm::inverse(projectionMatrix(fs.camera, float(fs.width) / float(fs.height)) * viewMatrix(fs.camera));
    Moments sum;
    for (int j = 0; j < sub; ++j)
        for (int i = 0; i < sub; ++i) {
            float jx = (i + 0.5f) / sub, jy = (j + 0.5f) / sub;
            glm::vec2 ndc(2.0f * (px + jx) / fs.width - 1.0f, 1.0f - 2.0f * (py + jy) / fs.height);
            glm::vec4 pn = invViewProj * glm::vec4(ndc, -1.0f, 1.0f), pf = invViewProj * glm::vec4(ndc, 1.0f, 1.0f);
            glm::vec3 d = glm::normalize(glm::vec3(pf) / pf.w - glm::vec3(pn) / pn.w);
            Moments r = rayMoments(m, l, fs.camera.eye, d, visible, cosSign);
            sum.mean += r.mean / (sub * sub);
            sum.second += r.second / (sub * sub);
        }
    return sum;
}

struct QuadratureCase {
    const char* name;
    bool roof;
    LightSettings light;
    VolumetricSettings volume;
    glm::vec3 eye, target;
};

// The centre pixel of a 5 x 5 image at 65536 spp against the quadrature. The tolerance is five
// standard deviations of the pixel's mean (from the estimator's moments: the variance of one
// sample is second - mean^2) plus 0.5 % for the quadrature over the footprint.
struct Outcome {
    double traced, expected, tolerance, flipped;
};

Outcome traceAndIntegrate(const QuadratureCase& c) {
    Scene scene = blackRoom(c.roof);
    FrameSettings fs = frame(c.eye, c.target, 5, 12.0f);
    fs.lights = {c.light};
    fs.volumetric = c.volume;
    PathTracer pt(scene);
    ReferenceSettings rs;
    rs.spp = 65536;
    rs.maxBounces = 1;
    ImageRGB img = pt.render(fs, rs);
    const Medium m = makeMedium(c.volume, scene.bounds);
    // The roof (y = 4, x < 0) is the only occluder; the sun shines straight down.
    auto visible = [&](glm::dvec3 x) { return !(c.roof && x.x < 0.0 && x.y < 4.0); };
    Moments mo = pixelMoments(fs, m, c.light, 2, 2, visible);
    Moments flipped = pixelMoments(fs, m, c.light, 2, 2, visible, -1.0);
    double sigma = std::sqrt(std::max(mo.second - mo.mean * mo.mean, 0.0) / rs.spp);
    Outcome o{red(img, 2, 2), mo.mean, 5.0 * sigma + 0.005 * mo.mean, flipped.mean};
    std::printf("%-28s traced %.6f expected %.6f (%+.2f%%, tolerance %.2f%%); wrong cos convention %.6f\n", c.name, o.traced,
                o.expected, 100.0 * (o.traced - o.expected) / o.expected, 100.0 * o.tolerance / o.expected, o.flipped);
    return o;
}

// ---- Tests ----------------------------------------------------------------------------------

// A lit diffuse wall at z = 0 (x, y in [-2, 2]) and a floor in front of it (y = -2, z in [0, 3])
// that bounces light onto it; the bounds are [-2, 2] x [-2, 2] x [0, 3].
Scene wallScene() {
    Scene s;
    MeshBuilder b(s);
    int wall = b.material("wall", glm::vec3(0.5f), 1.0f);
    int floor = b.material("floor", glm::vec3(0.8f), 1.0f);
    b.quad(wall, {-2, -2, 0}, {4, 0, 0}, {0, 4, 0});
    b.quad(floor, {-2, -2, 3}, {4, 0, 0}, {0, 0, -3});
    s.finalize();
    return s;
}

FrameSettings wallFrame() {
    // 5 m from the wall, 3 m of it inside the box; a 10 degree view sees only the wall.
    FrameSettings fs = frame({0, 0, 5}, {0, 0, 0}, 15, 10.0f);
    LightSettings sun;
    sun.direction = glm::normalize(glm::vec3(0.2f, -0.5f, -1.0f));
    sun.intensity = 3.0f;
    fs.lights = {sun, test::pointLight({1.0f, 0.5f, 2.0f}, 2.0f)};
    return fs;
}

TEST(VolumetricReference, ZeroDensityAddsNothing) {
    Scene scene = wallScene();
    PathTracer pt(scene);
    ReferenceSettings rs;
    rs.spp = 8;
    FrameSettings off = wallFrame();
    ImageRGB plain = pt.render(off, rs);
    for (auto attenuation : {VolumeAttenuation::Coefficients, VolumeAttenuation::OpticalThickness}) {
        FrameSettings zero = off;
        zero.volumetric = coefficients(0.0f, 1.0f);
        zero.volumetric.attenuation = attenuation;
        ImageRGB img = pt.render(zero, rs);
        ASSERT_EQ(img.rgb.size(), plain.rgb.size());
        size_t differing = 0;
        for (size_t i = 0; i < img.rgb.size(); ++i) differing += img.rgb[i] != plain.rgb[i];
        EXPECT_EQ(differing, 0u) << enumName(attenuation);
    }
    // The same settings with density do change it (so the comparison above can fail).
    FrameSettings dense = off;
    dense.volumetric = coefficients(0.2f, 1.0f);
    ImageRGB img = pt.render(dense, rs);
    EXPECT_LT(red(img, 7, 7), 0.5f * red(plain, 7, 7));
}

TEST(VolumetricReference, CacheKeyHasVolumetricSettingsOnlyWhenEnabled) {
    Scene scene = wallScene();
    FrameSettings fs = wallFrame();
    ReferenceSettings rs;
    uint64_t key = referenceKey(scene, fs, rs);
    FrameSettings disabled = fs;
    disabled.volumetric.density = 3.0f;
    disabled.volumetric.phase = PhaseFunction::Rayleigh;
    EXPECT_EQ(key, referenceKey(scene, disabled, rs));
    FrameSettings enabled = fs;
    enabled.volumetric.enabled = true;
    uint64_t enabledKey = referenceKey(scene, enabled, rs);
    EXPECT_NE(key, enabledKey);
    FrameSettings denser = enabled;
    denser.volumetric.density *= 2.0f;
    EXPECT_NE(enabledKey, referenceKey(scene, denser, rs));
}

// Isotropic and coefficients; Henyey-Greenstein g = 0.6 with the seed's optical thickness,
// looking towards a point light and away from it; a spot with a range window; the sun through
// the open top with a roof shadowing half the room and a backward lobe; an eye above the room
// looking in through the open top (the view's transmittance starts where the ray enters).
TEST(VolumetricReference, InScatteringMatchesQuadrature) {
    VolumetricSettings hg = coefficients(0.05f, 0.0f, PhaseFunction::HenyeyGreenstein, 0.6f);
    hg.attenuation = VolumeAttenuation::OpticalThickness;
    hg.opticalThickness = 8.0f;
    hg.intensity = 2.0f;
    LightSettings sun;
    sun.direction = {0.0f, -1.0f, 0.0f};
    sun.intensity = 3.0f;
    const QuadratureCase cases[] = {
        {"point, isotropic", false, test::pointLight({0, 0, 0}, 10.0f), coefficients(0.05f, 0.1f), {0, 1, 2}, {0, 1, -8}},
        {"point, HG 0.6, towards", false, test::pointLight({0, 0, 0}, 10.0f), hg, {0, 1, 2}, {0, 1, -8}},
        {"point, HG 0.6, away", false, test::pointLight({0, 0, 0}, 10.0f), hg, {0, 1, 2}, {0, 1, 12}},
        {"spot, HG 0.6, range", false, spotDown({0, 4, 0}, 30.0f, 12.0f, 20.0f, 6.0f),
         coefficients(0.05f, 0.05f, PhaseFunction::HenyeyGreenstein, 0.6f), {0, 0, 4}, {0, 0, -4}},
        {"sun, HG -0.3, roof shadow", true, sun, coefficients(0.08f, 0.02f, PhaseFunction::HenyeyGreenstein, -0.3f),
         {-4.5f, 2, 2}, {4.5f, -3, -2}},
        {"point, eye above the box", false, test::pointLight({0, 0, 0}, 10.0f),
         coefficients(0.05f, 0.1f, PhaseFunction::HenyeyGreenstein, 0.6f), {1, 8, 0.5f}, {-1, -5, 0}},
    };
    Outcome outcomes[6];
    for (int i = 0; i < 6; ++i) {
        Outcome o = outcomes[i] = traceAndIntegrate(cases[i]);
        ASSERT_GT(o.expected, 0.0) << cases[i].name;
        EXPECT_NEAR(o.traced, o.expected, o.tolerance) << cases[i].name;
    }
    // Henyey-Greenstein: looking towards the light sees the forward lobe, away the backward one,
    // in the ratio the quadrature predicts; the opposite cos theta convention predicts far from
    // these pixels (and the sun's), so the comparisons above pin the convention down.
    const Outcome &towards = outcomes[1], &away = outcomes[2];
    double tracedRatio = towards.traced / away.traced, expectedRatio = towards.expected / away.expected;
    std::printf("towards / away: traced %.3f expected %.3f\n", tracedRatio, expectedRatio);
    EXPECT_GT(expectedRatio, 3.0);
    double ratioTolerance = expectedRatio * (towards.tolerance / towards.expected + away.tolerance / away.expected);
    EXPECT_NEAR(tracedRatio, expectedRatio, ratioTolerance);
    for (const Outcome* o : {&towards, &away, static_cast<const Outcome*>(&outcomes[4])})
        EXPECT_GT(std::abs(o->flipped - o->expected), 3.0 * o->tolerance);
}

// With absorption and almost no scattering the wall is faded by exp(-sigma_t 3 m) in every mode
// (the floor's bounce included: later path segments are not attenuated); without
// attenuateScene it is unchanged. Paths draw the same random numbers with and without the
// medium, so the ratios are exact up to the tiny in-scattering.
TEST(VolumetricReference, CameraLegTransmittance) {
    Scene scene = wallScene();
    PathTracer pt(scene);
    const float absorption = 0.3f, density = 1e-5f;
    const double T = std::exp(-double(absorption + density) * 3.0);
    auto centre = [](const ImageRGB& img) {
        double sum = 0.0;
        for (int y = 6; y <= 8; ++y)
            for (int x = 6; x <= 8; ++x) sum += red(img, x, y);
        return sum;
    };
    for (ReferenceMode mode : {ReferenceMode::Full, ReferenceMode::Direct, ReferenceMode::Indirect}) {
        ReferenceSettings rs;
        rs.spp = 16;
        rs.mode = mode;
        FrameSettings fs = wallFrame();
        double plain = centre(pt.render(fs, rs));
        ASSERT_GT(plain, 0.0) << enumName(mode);
        fs.volumetric = coefficients(density, absorption);
        double faded = centre(pt.render(fs, rs)) / plain;
        fs.volumetric.attenuateScene = false;
        double unfaded = centre(pt.render(fs, rs)) / plain;
        std::printf("%-8s ratio %.6f expected %.6f; without attenuateScene %.6f\n", enumName(mode), faded, T, unfaded);
        EXPECT_NEAR(faded, T, 5e-4 * T) << enumName(mode);
        EXPECT_GE(unfaded, 1.0) << enumName(mode);
        EXPECT_NEAR(unfaded, 1.0, 5e-4) << enumName(mode);
    }
}

// A narrow spot straight down at (0, 4, 0): a view along z through its axis gets light; one
// 3 m to the side gets exactly nothing (the cone's radius stays under 1 m in the room, the
// view's rays over 1.4 m from its axis), while a point light in the same place lights it.
TEST(VolumetricReference, SpotConeClipsInScattering) {
    Scene scene = blackRoom();
    PathTracer pt(scene);
    ReferenceSettings rs;
    rs.spp = 16;
    rs.maxBounces = 1;
    auto render = [&](glm::vec3 eye, const LightSettings& l) {
        FrameSettings fs = frame(eye, eye - glm::vec3(0, 0, 8), 9, 20.0f);
        fs.lights = {l};
        fs.volumetric = coefficients(0.1f, 0.0f, PhaseFunction::HenyeyGreenstein, 0.3f);
        return pt.render(fs, rs);
    };
    LightSettings spot = spotDown({0, 4, 0}, 50.0f, 5.0f, 6.0f, 0.0f);
    ImageRGB through = render({0, 0, 4}, spot);
    EXPECT_GT(red(through, 4, 4), 0.0f);
    ImageRGB beside = render({3, 0, 4}, spot);
    float maxBeside = *std::max_element(beside.rgb.begin(), beside.rgb.end());
    EXPECT_EQ(maxBeside, 0.0f);
    ImageRGB pointBeside = render({3, 0, 4}, test::pointLight({0, 4, 0}, 50.0f));
    EXPECT_GT(red(pointBeside, 4, 4), 0.0f);
}

// In-scattering is direct light: the indirect mode leaves the black room black, and the direct
// mode equals the full one (both one bounce, so they draw the same random numbers).
TEST(VolumetricReference, InScatteringCountsAsDirectLight) {
    Scene scene = blackRoom();
    PathTracer pt(scene);
    FrameSettings fs = frame({0, 1, 2}, {0, 1, -8}, 9, 30.0f);
    fs.lights = {test::pointLight({0, 0, 0}, 10.0f)};
    fs.volumetric = coefficients(0.2f, 0.0f);
    ReferenceSettings rs;
    rs.spp = 8;
    rs.maxBounces = 1;
    ImageRGB full = pt.render(fs, rs);
    rs.mode = ReferenceMode::Direct;
    ImageRGB direct = pt.render(fs, rs);
    rs.mode = ReferenceMode::Indirect;
    ImageRGB indirect = pt.render(fs, rs);
    EXPECT_GT(red(full, 4, 4), 0.0f);
    EXPECT_EQ(full.rgb, direct.rgb);
    EXPECT_EQ(*std::max_element(indirect.rgb.begin(), indirect.rgb.end()), 0.0f);
}

// Each in-scattering sample casts one shadow ray: with one unbounded point light inside the
// room every camera ray has a lit interval, so the medium adds exactly pixels x spp rays.
TEST(VolumetricReference, ShadowRaysAreCounted) {
    Scene scene = blackRoom();
    FrameSettings fs = frame({0, 1, 2}, {0, 1, -8}, 9, 30.0f);
    fs.lights = {test::pointLight({0, 0, 0}, 10.0f)};
    ReferenceSettings rs;
    rs.spp = 4;
    rs.maxBounces = 1;
    PathTracer plain(scene), medium(scene);
    plain.render(fs, rs);
    fs.volumetric = coefficients(0.2f, 0.0f);
    medium.render(fs, rs);
    EXPECT_EQ(medium.raysTraced() - plain.raysTraced(), uint64_t(9 * 9 * 4));
}

// The same settings twice give the same pixels; a different seed does not; samples split into
// passes sum to the same image (each sample has its own random stream).
TEST(VolumetricReference, Deterministic) {
    Scene scene = blackRoom(true);
    PathTracer pt(scene);
    FrameSettings fs = frame({-4, 1, 4}, {2, -1, -3}, 16, 50.0f);
    LightSettings sun;
    sun.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
    fs.lights = {sun, test::pointLight({1, 0, -1}, 10.0f), spotDown({-2, 3, 0}, 30.0f, 15.0f, 25.0f, 8.0f)};
    fs.volumetric = coefficients(0.1f, 0.05f, PhaseFunction::HenyeyGreenstein, 0.5f);
    ReferenceSettings rs;
    rs.spp = 8;
    ImageRGB a = pt.render(fs, rs), b = pt.render(fs, rs);
    EXPECT_EQ(a.rgb, b.rgb);
    rs.seed = 2;
    EXPECT_NE(a.rgb, pt.render(fs, rs).rgb);
    rs.seed = 1;
    std::vector<double> whole, split;
    pt.trace(fs, rs, 0, 8, whole);
    pt.trace(fs, rs, 0, 3, split);
    pt.trace(fs, rs, 3, 5, split);
    for (size_t i = 0; i < whole.size(); ++i) EXPECT_NEAR(whole[i], split[i], 1e-9 * std::max(1.0, std::abs(whole[i])));
}

}  // namespace
}  // namespace gi
