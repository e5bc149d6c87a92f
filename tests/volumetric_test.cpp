// Volumetric lighting: phase functions (normalised, the GLSL twin equal to the C++), the
// medium's clipping, and the raster march.
#include "gi/render/renderer.h"
#include "gi/scene/camera.h"
#include "gi/scene/mesh_builder.h"
#include "gi/volumetric/medium.h"
#include "gi/volumetric/phase.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace gi {
namespace {

// Every phase function integrates to one over the sphere: 2 pi * integral of p(mu) d mu over
// [-1, 1], by Simpson's rule on 20000 intervals (the murky Mie lobe is narrow: ((1+mu)/2)^32).
TEST(Phase, EachIntegratesToOne) {
    for (const auto& [f, name] : EnumNames<PhaseFunction>::values)
        for (float g : {-0.7f, 0.0f, 0.3f, 0.7f, 0.95f}) {
            PhaseParams p{f, g, schlickKFromG(g)};
            const int n = 20000;
            double sum = 0.0;
            for (int i = 0; i <= n; ++i) {
                double mu = -1.0 + 2.0 * i / n;
                double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
                sum += w * phase(p, mu);
            }
            double integral = 2.0 * 3.14159265358979323846 * sum * (2.0 / n) / 3.0;
            EXPECT_NEAR(integral, 1.0, 1e-4) << name << " g " << g;
        }
}

// g > 0 scatters forward for Henyey-Greenstein and for Schlick with k from g (the seed's
// printed Schlick sign would send it backwards); g = 0 and k = 0 are isotropic.
TEST(Phase, ForwardForPositiveAsymmetry) {
    for (PhaseFunction f : {PhaseFunction::HenyeyGreenstein, PhaseFunction::Schlick}) {
        PhaseParams p{f, 0.6f, schlickKFromG(0.6f)};
        EXPECT_GT(phase(p, 1.0), 10.0 * phase(p, -1.0)) << enumName(f);
        PhaseParams iso{f, 0.0f, 0.0f};
        EXPECT_NEAR(phase(iso, 0.3), 1.0 / (4.0 * 3.14159265358979323846), 1e-9);
    }
    // Schlick with k from g follows Henyey-Greenstein loosely: its mean cosine is a little larger
    // (0.53 for g = 0.5, 0.87 for g = 0.8; Blasi et al. fit the shape, not the mean).
    double previous = 0.0;
    for (float g : {0.2f, 0.5f, 0.8f}) {
        double meanHG = 0, meanS = 0;
        const int n = 20000;
        for (int i = 0; i < n; ++i) {
            double mu = -1.0 + 2.0 * (i + 0.5) / n;
            meanHG += mu * phase({PhaseFunction::HenyeyGreenstein, g, 0}, mu);
            meanS += mu * phase({PhaseFunction::Schlick, 0, schlickKFromG(g)}, mu);
        }
        double scale = 2.0 * 3.14159265358979323846 * 2.0 / n;
        EXPECT_NEAR(meanHG * scale, g, 1e-3);
        EXPECT_NEAR(meanS * scale, g, 0.08) << g;
        EXPECT_GT(meanS * scale, previous) << g;
        previous = meanS * scale;
    }
    // Rayleigh and both Mie lobes are symmetric or forward.
    EXPECT_NEAR(phase({PhaseFunction::Rayleigh}, 1.0), phase({PhaseFunction::Rayleigh}, -1.0), 1e-12);
    EXPECT_GT(phase({PhaseFunction::MieMurky}, 1.0), phase({PhaseFunction::MieHazy}, 1.0));
}

// ---- the medium's clipping (C++; march.comp's twin is checked through the renders below) ----

LightSettings spot(glm::vec3 pos, glm::vec3 dir, float outerDeg, float range = 0.0f) {
    LightSettings l;
    l.type = LightType::Spot;
    l.position = pos;
    l.direction = dir;
    l.outerConeDeg = outerDeg;
    l.innerConeDeg = outerDeg * 0.5f;
    l.range = range;
    return l;
}

TEST(Medium, RayClipsToTheSpotConeAndRange) {
    // A spot at the origin pointing down -y with a 45 degree half-angle; a horizontal ray at
    // y = -1 crosses the cone where |x| <= 1.
    LightSettings l = spot({0, 0, 0}, {0, -1, 0}, 45.0f);
    float t0 = 0.0f, t1 = 10.0f;
    ASSERT_TRUE(clipRayToLight(l, {-5, -1, 0}, {1, 0, 0}, t0, t1));
    EXPECT_NEAR(t0, 4.0f, 1e-4f);
    EXPECT_NEAR(t1, 6.0f, 1e-4f);
    // Above the apex (the cone's mirror nappe) nothing is lit.
    t0 = 0.0f, t1 = 10.0f;
    EXPECT_FALSE(clipRayToLight(l, {-5, 1, 0}, {1, 0, 0}, t0, t1));
    // A ray from the apex down the axis is lit from the apex on; a range of 3 cuts it.
    t0 = 0.0f, t1 = 10.0f;
    ASSERT_TRUE(clipRayToLight(l, {0, 0, 0}, {0, -1, 0}, t0, t1));
    EXPECT_NEAR(t0, 0.0f, 1e-5f);
    EXPECT_NEAR(t1, 10.0f, 1e-5f);
    l.range = 3.0f;
    t0 = 0.0f, t1 = 10.0f;
    ASSERT_TRUE(clipRayToLight(l, {0, 0, 0}, {0, -1, 0}, t0, t1));
    EXPECT_NEAR(t1, 3.0f, 1e-5f);
    // A ray that enters the cone and never leaves (parallel to the surface's far side).
    l.range = 0.0f;
    t0 = 0.0f, t1 = 100.0f;
    ASSERT_TRUE(clipRayToLight(l, {-5, -1, 0}, glm::normalize(glm::vec3(1, -1, 0)), t0, t1));
    EXPECT_NEAR(t1, 100.0f, 1e-3f);
    // Point lights: only the range sphere; directional lights: everything.
    LightSettings point;
    point.type = LightType::Point;
    point.position = {0, 0, 0};
    point.range = 2.0f;
    t0 = 0.0f, t1 = 10.0f;
    ASSERT_TRUE(clipRayToLight(point, {-5, 0, 0}, {1, 0, 0}, t0, t1));
    EXPECT_NEAR(t0, 3.0f, 1e-4f);
    EXPECT_NEAR(t1, 7.0f, 1e-4f);
    LightSettings sun;
    t0 = 1.0f, t1 = 2.0f;
    EXPECT_TRUE(clipRayToLight(sun, {0, 0, 0}, {1, 0, 0}, t0, t1));
    EXPECT_EQ(t1, 2.0f);
}

TEST(Medium, BoxClipAndLightPath) {
    Bounds box;
    box.grow({-1, 0, -1});
    box.grow({1, 2, 1});
    float t0, t1;
    ASSERT_TRUE(clipRayToBox(box, {-3, 1, 0}, {1, 0, 0}, 100.0f, t0, t1));
    EXPECT_NEAR(t0, 2.0f, 1e-5f);
    EXPECT_NEAR(t1, 4.0f, 1e-5f);
    ASSERT_TRUE(clipRayToBox(box, {0, 1, 0}, {1, 0, 0}, 0.5f, t0, t1));  // from inside, stopped by a surface
    EXPECT_NEAR(t0, 0.0f, 1e-6f);
    EXPECT_NEAR(t1, 0.5f, 1e-6f);
    EXPECT_FALSE(clipRayToBox(box, {-3, 3, 0}, {1, 0, 0}, 100.0f, t0, t1));
    // A sun straight down: the path from a point to the light runs up to the box's top.
    LightSettings sun;
    sun.direction = {0, -1, 0};
    EXPECT_NEAR(lightPathInBox(box, sun, {0, 0.5f, 0}), 1.5f, 1e-5f);
    // A point light outside the box: only the part inside counts.
    LightSettings point;
    point.type = LightType::Point;
    point.position = {0, 5, 0};
    EXPECT_NEAR(lightPathInBox(box, point, {0, 0.5f, 0}), 1.5f, 1e-5f);
}

// ---- the raster march (GL, llvmpipe) ----

constexpr int kSize = 64;

// A closed room [-2, 2] x [0, 3] x [-2, 2] of black walls (they reflect nothing), so the image is
// the in-scattered light alone; `grey` makes the walls reflect instead.
Scene room(bool grey = false) {
    Scene s;
    s.name = "volumeRoom";
    MeshBuilder b(s);
    int m = b.material("wall", glm::vec3(grey ? 0.5f : 0.0f), 1.0f);
    b.box(m, {0.0f, 1.5f, 0.0f}, {2.0f, 1.5f, 2.0f}, 0.0f);
    s.finalize();
    return s;
}

FrameSettings roomFrame(glm::vec3 eye, glm::vec3 target) {
    FrameSettings fs;
    fs.camera.eye = eye;
    fs.camera.target = target;
    fs.camera.fovY = 40.0f;
    LightSettings l;
    l.type = LightType::Point;
    l.position = {0.0f, 1.5f, 0.0f};
    l.intensity = 5.0f;
    l.color = {1.0f, 0.8f, 0.6f};
    fs.lights = {l};
    fs.render.ambient = glm::vec3(0.0f);
    fs.render.specular = false;  // black walls would still reflect the light specularly
    fs.volumetric.enabled = true;
    fs.volumetric.density = 0.2f;
    fs.volumetric.samples = 400;
    fs.volumetric.resolutionScale = 1.0f;
    fs.volumetric.jitter = false;
    fs.volumetric.blur = VolumeBlur::None;
    fs.width = fs.height = kSize;
    return fs;
}

glm::vec3 pixel(const std::vector<float>& hdr, int x, int y) {
    const float* p = &hdr[(size_t(y) * kSize + size_t(x)) * 4];
    return {p[0], p[1], p[2]};
}

// The in-scattered radiance along the ray through pixel (x, y), by Simpson's rule over the part
// of the ray inside the room, from gi/volumetric/medium.h's model (no occluders in the room).
glm::dvec3 expectedInscatter(const FrameSettings& fs, const Bounds& box, int x, int y) {
    glm::mat4 inv = glm::inverse(projectionMatrix(fs.camera, 1.0f) * viewMatrix(fs.camera));
    glm::vec2 ndc = (glm::vec2(x, y) + 0.5f) / float(kSize) * 2.0f - 1.0f;
    glm::vec4 far = inv * glm::vec4(ndc, 1.0f, 1.0f);
    glm::vec3 d = glm::normalize(glm::vec3(far) / far.w - fs.camera.eye);
    Medium m = makeMedium(fs.volumetric, box);
    float t0, t1;
    if (!clipRayToBox(box, fs.camera.eye, d, 1e30f, t0, t1)) return glm::dvec3(0.0);
    const LightSettings& l = fs.lights[0];
    const int n = 4000;
    glm::dvec3 sum(0.0);
    for (int i = 0; i <= n; ++i) {
        double t = t0 + (t1 - t0) * i / n;
        glm::vec3 p = fs.camera.eye + float(t) * d;
        glm::vec3 toLight = l.position - p;
        double dist = glm::length(toLight);
        glm::vec3 travel = -toLight / float(dist);
        double f = phase(m.phase, glm::dot(travel, -d)) * m.transmittance(lightPathInBox(box, l, p)) *
                   m.transmittance(float(t - t0)) / (dist * dist);
        double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        sum += w * f * glm::dvec3(l.color * l.intensity);
    }
    return sum * (double(m.sigmaS) * double(m.intensity) * double(t1 - t0) / (3.0 * n));
}

class VolumetricGL : public test::GLTest {};

// For every phase function, the march through the room matches the integral of the model,
// looking towards the light (forward scattering for g > 0) and away from it.
TEST_F(VolumetricGL, MarchMatchesTheIntegralForEachPhaseFunction) {
    Scene scene = room();
    Renderer r;
    r.setScene(scene);
    for (const auto& [f, name] : EnumNames<PhaseFunction>::values)
        for (glm::vec3 eye : {glm::vec3(0.0f, 1.5f, 1.8f), glm::vec3(0.0f, 1.5f, -0.5f)}) {
            FrameSettings fs = roomFrame(eye, eye + glm::vec3(0.0f, 0.0f, -1.0f));
            fs.volumetric.phase = f;
            fs.volumetric.g = 0.6f;
            r.render(fs);
            std::vector<float> hdr = r.readHDR();
            for (glm::ivec2 px : {glm::ivec2(kSize / 2, kSize / 2), glm::ivec2(8, 50)}) {
                glm::dvec3 want = expectedInscatter(fs, scene.bounds, px.x, px.y);
                glm::vec3 got = pixel(hdr, px.x, px.y);
                ASSERT_GT(want.r, 1e-4) << name;
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(got[c], want[c], 0.01 * want[c] + 1e-4) << name << " eye z " << eye.z << " pixel " << px.x << "," << px.y;
            }
        }
}

// Enabled with a density of 0 adds nothing (the medium is inactive: the same pixels as disabled).
TEST_F(VolumetricGL, ZeroDensityAddsNothing) {
    Scene scene = room(true);
    Renderer r;
    r.setScene(scene);
    FrameSettings fs = roomFrame({0.0f, 1.5f, 1.8f}, {0.0f, 1.0f, 0.0f});
    fs.volumetric.enabled = false;
    r.render(fs);
    std::vector<float> off = r.readHDR();
    fs.volumetric.enabled = true;
    fs.volumetric.density = 0.0f;
    fs.volumetric.absorption = 1.0f;
    r.render(fs);
    EXPECT_EQ(r.readHDR(), off);
    fs.volumetric.density = 0.2f;
    r.render(fs);
    EXPECT_NE(r.readHDR(), off);
}

// The scene behind the medium fades by exp(-sigma_t d) along the view ray (attenuateScene), and
// not at all without it.
TEST_F(VolumetricGL, SceneFadesByTheViewTransmittance) {
    Scene scene = room(true);
    Renderer r;
    r.setScene(scene);
    FrameSettings fs = roomFrame({0.0f, 1.5f, 1.8f}, {0.0f, 1.5f, 0.0f});
    fs.volumetric.enabled = false;
    r.render(fs);
    glm::vec3 clear = pixel(r.readHDR(), kSize / 2, kSize / 2);  // the far wall at z = -2, 3.8 m away
    fs.volumetric.enabled = true;
    fs.volumetric.density = 1e-6f;  // active, but hardly any light scattered
    fs.volumetric.absorption = 0.3f;
    r.render(fs);
    glm::vec3 faded = pixel(r.readHDR(), kSize / 2, kSize / 2);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(faded[c] / clear[c], std::exp(-0.3 * 3.8), 0.01);
    fs.volumetric.attenuateScene = false;
    r.render(fs);
    glm::vec3 unfaded = pixel(r.readHDR(), kSize / 2, kSize / 2);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(unfaded[c] / clear[c], 1.0, 0.01);
    // The seed's optical thickness l is a mean free path: the same fade with l = 1 / 0.3.
    fs.volumetric.attenuateScene = true;
    fs.volumetric.attenuation = VolumeAttenuation::OpticalThickness;
    fs.volumetric.opticalThickness = 1.0f / 0.3f;
    r.render(fs);
    glm::vec3 seed = pixel(r.readHDR(), kSize / 2, kSize / 2);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(seed[c], faded[c], 0.01 * faded[c]);
}

// A shadow cuts the shaft: a spot above a slab lights the medium beside the slab, not under it;
// headless renders repeat exactly, jitter included.
TEST_F(VolumetricGL, ShadowedMediumStaysDarkAndRendersRepeat) {
    Scene scene;
    {
        scene.name = "slab";
        MeshBuilder b(scene);
        int black = b.material("black", glm::vec3(0.0f), 1.0f);
        b.box(black, {0.0f, 1.5f, 0.0f}, {2.0f, 1.5f, 2.0f}, 0.0f);
        b.box(black, {-0.6f, 2.0f, 0.0f}, {0.6f, 0.05f, 1.0f}, 0.0f);  // a slab under the left half of the spot
        scene.finalize();
    }
    Renderer r;
    r.setScene(scene);
    FrameSettings fs = roomFrame({0.0f, 1.0f, 1.9f}, {0.0f, 1.0f, 0.0f});
    fs.lights = {spot({0.0f, 2.9f, 0.0f}, {0, -1, 0}, 40.0f)};
    fs.lights[0].intensity = 10.0f;
    fs.volumetric.jitter = true;
    fs.volumetric.samples = 64;
    r.render(fs);
    std::vector<float> hdr = r.readHDR();
    // Project points below the slab (x = -0.6) and beside it (x = +0.6), at y = 1, z = 0.
    glm::mat4 viewProj = projectionMatrix(fs.camera, 1.0f) * viewMatrix(fs.camera);
    auto at = [&](glm::vec3 w) {
        glm::vec4 c = viewProj * glm::vec4(w, 1.0f);
        glm::ivec2 p = glm::clamp(glm::ivec2((glm::vec2(c) / c.w * 0.5f + 0.5f) * float(kSize)), glm::ivec2(0), glm::ivec2(kSize - 1));
        return pixel(hdr, p.x, p.y);
    };
    glm::vec3 shadowed = at({-0.6f, 1.0f, 0.0f}), lit = at({0.6f, 1.0f, 0.0f});
    EXPECT_GT(lit.r, 0.01f);
    EXPECT_LT(shadowed.r, 0.5f * lit.r);
    r.render(fs);
    EXPECT_EQ(r.readHDR(), hdr);
}

// The depth-aware blur keeps the bright shaft seen past an edge off the near surface beside it;
// the plain Gaussian spreads it there.
TEST_F(VolumetricGL, DepthAwareBlurDoesNotBleedAcrossEdges) {
    Scene scene;
    {
        scene.name = "edge";
        MeshBuilder b(scene);
        int black = b.material("black", glm::vec3(0.0f), 1.0f);
        b.box(black, {0.0f, 1.5f, 0.0f}, {2.0f, 1.5f, 2.0f}, 0.0f);
        b.quad(black, {-2.0f, 0.0f, 1.5f}, {2.0f, 0.0f, 0.0f}, {0.0f, 3.0f, 0.0f});  // near panel: the left half of the view
        scene.finalize();
    }
    Renderer r;
    r.setScene(scene);
    FrameSettings fs = roomFrame({0.0f, 1.5f, 1.95f}, {0.0f, 1.5f, 0.0f});
    fs.volumetric.resolutionScale = 0.25f;
    auto edgeBand = [&](VolumeBlur blur) {
        fs.volumetric.blur = blur;
        r.render(fs);
        std::vector<float> hdr = r.readHDR();
        // The panel's pixels 2 to 6 pixels from its edge at x = kSize / 2, against the shaft
        // seen past the edge, 2 to 6 pixels the other side.
        double band = 0, past = 0;
        for (int y = 8; y < kSize - 8; ++y)
            for (int i = 2; i < 7; ++i) {
                band += pixel(hdr, kSize / 2 - 1 - i, y).r;
                past += pixel(hdr, kSize / 2 + i, y).r;
            }
        return band / past;
    };
    double none = edgeBand(VolumeBlur::None), gaussian = edgeBand(VolumeBlur::Gaussian), aware = edgeBand(VolumeBlur::DepthAware);
    std::printf("near panel beside the edge / shaft past it: no blur %.4f, gaussian %.4f, depth-aware %.4f\n", none, gaussian, aware);
    EXPECT_GT(gaussian, 0.05);
    EXPECT_LT(aware, 0.01);
}

}  // namespace
}  // namespace gi
