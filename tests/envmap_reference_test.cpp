// The path-traced reference lit by an environment map (gi/reference/path_tracer.h, the latlong
// convention of gi/envmap/envmap_image.h): a white furnace under the constant map, next-event
// estimation of the map agreeing with BSDF sampling alone and with a quadrature of the
// irradiance while cutting the noise, rotation, a near-mirror reflecting the map times Fresnel,
// the modes, the shadow rays counted, determinism, nothing changed without the map, and the
// cache key.
//
// Most cases look at one sphere of radius 1 at the origin, alone in the scene: it is convex, so
// every ray that leaves it escapes, and a pixel holds the map's light after exactly one bounce.
#include "gi/envmap/envmap_image.h"
#include "gi/reference/path_tracer.h"
#include "gi/reference/reference_cache.h"
#include "gi/scene/camera.h"
#include "gi/scene/mesh_builder.h"
#include "gi/util/error.h"
#include "test_util.h"

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace gi {
namespace {

constexpr double kPi = glm::pi<double>();

Scene sphereScene(glm::vec3 color, float roughness = 1.0f, float metallic = 0.0f, bool floor = false) {
    Scene s;
    MeshBuilder b(s);
    int m = b.material("sphere", color, roughness);
    s.materials[m].metallic = metallic;
    b.sphere(m, glm::vec3(0.0f), 1.0f, 96, 48);
    if (floor) {
        int f = b.material("floor", glm::vec3(0.5f), 1.0f);
        b.quad(f, {-4, -1, 4}, {8, 0, 0}, {0, 0, -8});
    }
    s.finalize();
    return s;
}

// Looks at the origin from `eye`, lit by `file` alone (no punctual lights), diffuse only.
FrameSettings envFrame(glm::vec3 eye, const std::string& file, int size = 24, float fovY = 40.0f) {
    FrameSettings fs;
    fs.camera.eye = eye;
    fs.camera.target = glm::vec3(0.0f);
    fs.camera.fovY = fovY;
    fs.camera.near = 0.01f;
    fs.render.specular = false;
    fs.lights.clear();
    fs.environment.enabled = true;
    fs.environment.file = file;
    fs.width = fs.height = size;
    return fs;
}

glm::vec3 pixel(const ImageRGB& img, int x, int y) {
    const float* p = &img.rgb[(size_t(y) * img.width + x) * 3];
    return {p[0], p[1], p[2]};
}

double lum(glm::dvec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// The direction of the ray through (x + jx, y + jy), made as the tracer makes it.
glm::vec3 rayDirection(const FrameSettings& fs, float x, float y) {
    const glm::mat4 invViewProj =
        glm::inverse(projectionMatrix(fs.camera, float(fs.width) / float(fs.height)) * viewMatrix(fs.camera));
    glm::vec2 ndc(2.0f * x / float(fs.width) - 1.0f, 1.0f - 2.0f * y / float(fs.height));
    glm::vec4 pn = invViewProj * glm::vec4(ndc, -1.0f, 1.0f), pf = invViewProj * glm::vec4(ndc, 1.0f, 1.0f);
    return glm::normalize(glm::vec3(pf) / pf.w - glm::vec3(pn) / pn.w);
}

// Pixels wholly on the unit sphere at the origin (its mesh lies within 0.1 % of the radius)
// and pixels wholly off it, by the angles of the pixel's centre and corner rays to its centre.
enum class Cover { Sphere, Background, Edge };
std::vector<Cover> coverage(const FrameSettings& fs) {
    const glm::vec3 toCentre = glm::normalize(-fs.camera.eye);
    const double dist = glm::length(fs.camera.eye);
    const double outer = std::asin(1.0 / dist), inner = std::asin(0.99 / dist);
    auto angle = [&](glm::vec3 d) { return std::acos(std::clamp(double(glm::dot(d, toCentre)), -1.0, 1.0)); };
    std::vector<Cover> cover(size_t(fs.width) * fs.height);
    for (int y = 0; y < fs.height; ++y)
        for (int x = 0; x < fs.width; ++x) {
            glm::vec3 c = rayDirection(fs, x + 0.5f, y + 0.5f);
            double spread = 0.0;
            for (int k = 0; k < 4; ++k)
                spread = std::max(spread, double(std::acos(std::min(1.0f, glm::dot(c, rayDirection(fs, float(x + (k & 1)), float(y + (k >> 1))))))));
            double a = angle(c);
            cover[size_t(y) * fs.width + x] = a + spread < inner ? Cover::Sphere : a - spread > outer ? Cover::Background : Cover::Edge;
        }
    return cover;
}

// Where a ray from `eye` along d meets the analytic unit sphere (false if it misses).
bool hitUnitSphere(glm::dvec3 eye, glm::dvec3 d, glm::dvec3& p) {
    double b = glm::dot(eye, d), c = glm::dot(eye, eye) - 1.0, disc = b * b - c;
    if (disc < 0.0) return false;
    p = eye + (-b - std::sqrt(disc)) * d;
    return true;
}

// Irradiance at a surface of normal n under the map (rotation 0), by the midpoint rule over a
// latlong grid of the map's own resolution times `refine`: the quadrature the tracer must agree with.
double irradiance(const EnvironmentImage& env, glm::dvec3 n, int refine = 2) {
    const int W = env.width * refine, H = env.height * refine;
    double E = 0.0;
    for (int y = 0; y < H; ++y) {
        double v = (y + 0.5) / H, dOmega = 2.0 * kPi * kPi * std::sin(kPi * v) / (double(W) * H);
        for (int x = 0; x < W; ++x) {
            glm::vec3 d = latLongDirection({float((x + 0.5) / W), float(v)}, 0.0f);
            double cosTheta = glm::dot(glm::dvec3(d), n);
            if (cosTheta > 0.0) E += lum(glm::dvec3(sampleEnvironment(env, d, 0.0f))) * cosTheta * dOmega;
        }
    }
    return E;
}

// A diffuse sphere of albedo 0.8 under the constant map of radiance 1 reflects 0.8 everywhere
// (it cannot see itself); the background is the map (1) with the skybox and black without.
// The estimator's noise per sample was measured at about 0.21 (MIS of the map's near-uniform
// density and cosine sampling), so at 512 spp a pixel's standard deviation is about 0.0094:
// 0.05 per pixel is over 5 sigma, and the mean over ~190 pixels is good to 0.1 % plus the
// mesh's loss at the horizon (directions above the shading normal's horizon but below the
// face's; measured -0.08 %).
TEST(EnvmapReference, Furnace) {
    Scene scene = sphereScene(glm::vec3(0.8f));
    PathTracer pt(scene);
    ReferenceSettings rs;
    rs.spp = 512;
    for (bool skybox : {true, false}) {
        FrameSettings fs = envFrame({0, 0, 4}, "builtin:constant");
        fs.environment.skybox = skybox;
        ImageRGB img = pt.render(fs, rs);
        std::vector<Cover> cover = coverage(fs);
        double sum = 0.0, sum2 = 0.0, worst = 0.0;
        int onSphere = 0, background = 0;
        for (int y = 0; y < fs.height; ++y)
            for (int x = 0; x < fs.width; ++x) {
                glm::vec3 c = pixel(img, x, y);
                Cover k = cover[size_t(y) * fs.width + x];
                if (k == Cover::Background) {
                    ++background;
                    EXPECT_EQ(c, glm::vec3(skybox ? 1.0f : 0.0f)) << x << ", " << y;
                } else if (k == Cover::Sphere) {
                    ++onSphere;
                    for (int i = 0; i < 3; ++i) {
                        sum += c[i] / 3.0;
                        sum2 += c[i] * c[i] / 3.0;
                        worst = std::max(worst, std::abs(double(c[i]) - 0.8));
                    }
                    EXPECT_NEAR(c.r, 0.8f, 0.05f) << x << ", " << y;
                    EXPECT_NEAR(c.g, c.r, 1e-6f);
                }
            }
        double mean = sum / onSphere, sd = std::sqrt(std::max(0.0, sum2 / onSphere - mean * mean));
        std::printf("skybox %d: %d sphere pixels mean %.5f (sd %.4f, worst %.4f), %d background pixels\n", skybox, onSphere,
                    mean, sd, worst, background);
        ASSERT_GT(onSphere, 100);
        ASSERT_GT(background, 100);
        EXPECT_NEAR(mean, 0.8, 0.004);
    }
}

struct Estimate {
    double mean = 0.0, stdError = 0.0;  // over the seeds
    double pixelVariance = 0.0;         // per sphere pixel across seeds, averaged
    double centre = 0.0, centreError = 0.0;
};

// `seeds` independent renders: the sphere pixels' mean luminance and its standard error from
// the seeds' spread, the mean per-pixel variance, and the same for the centre pixel.
Estimate estimate(PathTracer& pt, const FrameSettings& fs, int spp, int seeds) {
    std::vector<Cover> cover = coverage(fs);
    std::vector<double> means, centres;
    std::vector<double> s1(cover.size(), 0.0), s2(cover.size(), 0.0);
    for (int seed = 1; seed <= seeds; ++seed) {
        ReferenceSettings rs;
        rs.spp = spp;
        rs.seed = seed;
        ImageRGB img = pt.render(fs, rs);
        double sum = 0.0;
        int n = 0;
        for (size_t i = 0; i < cover.size(); ++i) {
            double l = lum(glm::dvec3(pixel(img, int(i % fs.width), int(i / fs.width))));
            s1[i] += l;
            s2[i] += l * l;
            if (cover[i] == Cover::Sphere) sum += l, ++n;
        }
        means.push_back(n > 0 ? sum / n : 0.0);
        centres.push_back(lum(glm::dvec3(pixel(img, fs.width / 2, fs.height / 2))));
    }
    auto meanAndError = [](const std::vector<double>& v, double& mean, double& error) {
        mean = 0.0;
        for (double x : v) mean += x / double(v.size());
        double var = 0.0;
        for (double x : v) var += (x - mean) * (x - mean) / double(v.size() - 1);
        error = std::sqrt(var / double(v.size()));
    };
    Estimate e;
    meanAndError(means, e.mean, e.stdError);
    meanAndError(centres, e.centre, e.centreError);
    int n = 0;
    for (size_t i = 0; i < cover.size(); ++i)
        if (cover[i] == Cover::Sphere) {
            double m = s1[i] / seeds;
            e.pixelVariance += (s2[i] / seeds - m * m) * seeds / (seeds - 1.0);
            ++n;
        }
    if (n > 0) e.pixelVariance /= n;
    return e;
}

// Under builtin:sky (a 3 degree sun 40 times brighter than the sky) the diffuse sphere's mean
// with next-event estimation of the map equals BSDF sampling alone (the tracer with its
// sampling switched off), within 4 standard errors of the difference (from 8 seeds each), and
// the centre pixel equals albedo / pi x the irradiance by quadrature over its footprint. Next
// event estimation cuts the per-pixel variance at equal spp several times over: BSDF sampling
// finds the sun about once in 500 samples.
TEST(EnvmapReference, ImportanceSamplingIsUnbiasedAndLowersVariance) {
    Scene scene = sphereScene(glm::vec3(0.8f));
    // From the sun's side, so the lit cap and the terminator are in view.
    const glm::vec3 eye = 4.0f * glm::normalize(glm::vec3(1.0f, 0.6f, 0.3f));
    FrameSettings fs = envFrame(eye, "builtin:sky", 25, 35.0f);
    PathTracer withNEE(scene), bsdfOnly(scene);
    bsdfOnly.setEnvironmentSampling(false);
    const int spp = 256, seeds = 8;
    Estimate a = estimate(withNEE, fs, spp, seeds), b = estimate(bsdfOnly, fs, spp, seeds);
    double tolerance = 4.0 * std::hypot(a.stdError, b.stdError);
    std::printf("sphere mean: NEE %.5f +- %.5f, BSDF only %.5f +- %.5f (difference %+.2f%%, tolerance %.2f%%)\n", a.mean,
                a.stdError, b.mean, b.stdError, 100.0 * (a.mean - b.mean) / b.mean, 100.0 * tolerance / b.mean);
    std::printf("per-pixel variance at %d spp: NEE %.3g, BSDF only %.3g (ratio %.3f)\n", spp, a.pixelVariance,
                b.pixelVariance, a.pixelVariance / b.pixelVariance);
    EXPECT_NEAR(a.mean, b.mean, tolerance);
    EXPECT_LT(tolerance, 0.03 * b.mean);  // the comparison is tight enough to mean something
    EXPECT_LT(a.pixelVariance, 0.25 * b.pixelVariance);

    // The centre pixel against the quadrature: a one-pixel frame whose footprint is the centre
    // pixel's, traced at 8 x 4096 spp (standard error about 0.2 %), and albedo / pi x the
    // irradiance over a 4 x 4 grid of rays in it on the analytic sphere, 0.5 % more for the
    // mesh (faceted positions, the horizon cut).
    FrameSettings one = fs;
    one.width = one.height = 1;
    one.camera.fovY = glm::degrees(2.0f * std::atan(std::tan(glm::radians(fs.camera.fovY) / 2.0f) / float(fs.height)));
    Estimate c = estimate(withNEE, one, 4096, seeds);
    EnvironmentImage env = loadEnvironment("builtin:sky");
    double expected = 0.0;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            glm::dvec3 d(rayDirection(one, (i + 0.5f) / 4.0f, (j + 0.5f) / 4.0f)), p;
            ASSERT_TRUE(hitUnitSphere(glm::dvec3(eye), d, p));
            expected += 0.8 / kPi * irradiance(env, glm::normalize(p)) / 16.0;
        }
    double centreTolerance = 5.0 * c.centreError + 0.005 * expected;
    std::printf("centre pixel: NEE %.5f +- %.5f, quadrature %.5f (%+.2f%%, tolerance %.2f%%)\n", c.centre, c.centreError, expected,
                100.0 * (c.centre - expected) / expected, 100.0 * centreTolerance / expected);
    EXPECT_NEAR(c.centre, expected, centreTolerance);
}

// A map that is plainly not symmetric: red, green, blue and white quarters in u, the upper
// half three times brighter, written to an EXR.
std::string quarterMap() {
    ImageRGB map;
    map.width = 64;
    map.height = 32;
    const glm::vec3 quarters[4] = {{3.0f, 0.3f, 0.3f}, {0.3f, 3.0f, 0.3f}, {0.3f, 0.3f, 3.0f}, {1.0f, 1.0f, 1.0f}};
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x) {
            glm::vec3 c = quarters[x / 16] * (y < 16 ? 1.0f : 0.3f);
            map.rgb.insert(map.rgb.end(), {c.r, c.g, c.b});
        }
    auto file = test::tempDir() / "quarters.exr";
    writeEXR(file, map);
    return file.string();
}

// Turning the map by 90 degrees about +y is turning the world: the view from the eye turned by
// the same angle (rotateY: (x, y, z) -> (z, y, -x)) sees the same sky behind the sphere (the
// same rays, up to rounding) and the same mean colour on it (lit through next-event estimation
// and BSDF sampling, both of which must turn), while the turned view of the unturned map, or
// of the map turned the other way, does not. The sphere's mean is good to about 0.25 % (measured
// over seeds at this spp: the map's sharp edges make the noise heavy-tailed).
TEST(EnvmapReference, RotationTurnsTheWorld) {
    Scene scene = sphereScene(glm::vec3(0.8f));
    PathTracer pt(scene);
    ReferenceSettings rs;
    rs.spp = 1024;
    const std::string map = quarterMap();
    const glm::vec3 eye = 4.0f * glm::normalize(glm::vec3(1.0f, 0.6f, 0.3f)), turned(eye.z, eye.y, -eye.x);
    struct Look {
        glm::dvec3 sphere{0.0};
        std::vector<glm::vec3> sky;
    };
    auto look = [&](glm::vec3 from, float rotation) {
        FrameSettings fs = envFrame(from, map);
        fs.environment.rotation = rotation;
        ImageRGB img = pt.render(fs, rs);
        std::vector<Cover> cover = coverage(fs);
        Look l;
        int n = 0;
        for (size_t i = 0; i < cover.size(); ++i) {
            glm::vec3 c = pixel(img, int(i % fs.width), int(i / fs.width));
            if (cover[i] == Cover::Sphere) l.sphere += glm::dvec3(c), ++n;
            if (cover[i] == Cover::Background) l.sky.push_back(c);
        }
        l.sphere /= double(n);
        return l;
    };
    Look original = look(eye, 0.0f);
    auto compare = [&](const char* name, float rotation, double& sphereDiff, double& skyDiff) {
        Look l = look(turned, rotation);
        sphereDiff = skyDiff = 0.0;
        for (int c = 0; c < 3; ++c) sphereDiff = std::max(sphereDiff, std::abs(l.sphere[c] / original.sphere[c] - 1.0));
        for (size_t i = 0; i < l.sky.size(); ++i)
            for (int c = 0; c < 3; ++c) skyDiff = std::max(skyDiff, double(std::abs(l.sky[i][c] - original.sky[i][c])));
        std::printf("%-24s sphere mean (%.4f %.4f %.4f) vs (%.4f %.4f %.4f): %.2f%%; sky differs by up to %.4f\n", name,
                    l.sphere.r, l.sphere.g, l.sphere.b, original.sphere.r, original.sphere.g, original.sphere.b,
                    100.0 * sphereDiff, skyDiff);
    };
    double sphereDiff, skyDiff;
    compare("map turned 90", 90.0f, sphereDiff, skyDiff);
    EXPECT_LT(sphereDiff, 0.01);
    EXPECT_LT(skyDiff, 1e-3);
    compare("map not turned", 0.0f, sphereDiff, skyDiff);
    EXPECT_GT(sphereDiff, 0.2);
    EXPECT_GT(skyDiff, 0.5);
    compare("map turned -90", -90.0f, sphereDiff, skyDiff);
    EXPECT_GT(sphereDiff, 0.2);
    EXPECT_GT(skyDiff, 0.5);
}

// A metal sphere of roughness 0.05 (GGX alpha 0.0025) is nearly a mirror: the centre pixel
// sees the map in the mirror direction times Schlick's F (F0 = the base colour, at near-normal
// incidence), averaged here over a 4 x 4 grid of rays in the pixel on the analytic sphere. The
// sky there is a smooth gradient; 3 % covers the lobe's spread, the mesh and the noise.
TEST(EnvmapReference, GlossyMetalReflectsTheMap) {
    const glm::vec3 base(0.9f, 0.6f, 0.3f);
    Scene scene = sphereScene(base, 0.05f, 1.0f);
    const glm::vec3 eye(0.0f, 2.0f, 4.0f);
    FrameSettings fs = envFrame(eye, "builtin:sky", 31, 30.0f);
    fs.render.specular = true;
    ReferenceSettings rs;
    rs.spp = 64;
    ImageRGB img = PathTracer(scene).render(fs, rs);
    EnvironmentImage env = loadEnvironment("builtin:sky");
    glm::dvec3 expected(0.0);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            glm::dvec3 d(rayDirection(fs, fs.width / 2 + (i + 0.5f) / 4.0f, fs.height / 2 + (j + 0.5f) / 4.0f)), p;
            ASSERT_TRUE(hitUnitSphere(glm::dvec3(eye), d, p));
            glm::dvec3 n = glm::normalize(p), r = glm::reflect(d, n);
            double NoV = glm::dot(n, -d), k = std::pow(1.0 - NoV, 5.0);
            glm::dvec3 F = glm::dvec3(base) + (1.0 - glm::dvec3(base)) * k;
            expected += F * glm::dvec3(sampleEnvironment(env, glm::vec3(r), 0.0f)) / 16.0;
        }
    glm::dvec3 traced(pixel(img, fs.width / 2, fs.height / 2));
    std::printf("centre pixel (%.4f %.4f %.4f), expected (%.4f %.4f %.4f)\n", traced.r, traced.g, traced.b, expected.r, expected.g,
                expected.b);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(traced[c], expected[c], 0.03 * expected[c]) << "channel " << c;
    // The colour is the metal's: without F (white) the red to blue ratio would be the sky's.
    EXPECT_GT(traced.r / traced.b, 2.0 * double(sampleEnvironment(env, glm::normalize(eye), 0.0f).r /
                                                sampleEnvironment(env, glm::normalize(eye), 0.0f).b));
}

// The modes split the map's light by bounces: for the sphere alone everything arrives after
// one bounce or none, so direct is full, pixel for pixel (the same random numbers) and indirect
// is black, sky included; over a floor, direct + indirect = full in the mean (1 %, ~4 sigma).
TEST(EnvmapReference, ModesSplitByBounces) {
    ReferenceSettings rs;
    rs.spp = 16;
    FrameSettings fs = envFrame({0, 1, 4}, "builtin:sky");
    {
        PathTracer pt(sphereScene(glm::vec3(0.8f)));
        ImageRGB full = pt.render(fs, rs);
        rs.mode = ReferenceMode::Direct;
        ImageRGB direct = pt.render(fs, rs);
        rs.mode = ReferenceMode::Indirect;
        ImageRGB indirect = pt.render(fs, rs);
        EXPECT_EQ(full.rgb, direct.rgb);
        EXPECT_EQ(*std::max_element(indirect.rgb.begin(), indirect.rgb.end()), 0.0f);
    }
    PathTracer pt(sphereScene(glm::vec3(0.8f), 1.0f, 0.0f, true));
    auto mean = [&](ReferenceMode mode) {
        rs.mode = mode;
        rs.spp = 256;
        ImageRGB img = pt.render(fs, rs);
        double s = 0.0;
        for (float v : img.rgb) s += v;
        return s / double(img.rgb.size());
    };
    double full = mean(ReferenceMode::Full), direct = mean(ReferenceMode::Direct), indirect = mean(ReferenceMode::Indirect);
    std::printf("over a floor: full %.5f, direct %.5f + indirect %.5f = %.5f\n", full, direct, indirect, direct + indirect);
    EXPECT_GT(indirect, 0.02 * full);
    EXPECT_NEAR(direct + indirect, full, 0.01 * full);
}

// Each next-event estimate that lies above the surface casts one shadow ray. Under the constant
// map the sampled direction is uniform over the sphere of directions, so about half of them do.
// The paths are otherwise the same rays as with BSDF sampling alone (camera ray, one bounce
// that escapes), and those are the camera rays plus the sphere hits.
TEST(EnvmapReference, ShadowRaysAreCounted) {
    Scene scene = sphereScene(glm::vec3(0.8f));
    FrameSettings fs = envFrame({0, 0, 4}, "builtin:constant");
    ReferenceSettings rs;
    rs.spp = 512;
    PathTracer withNEE(scene), bsdfOnly(scene);
    bsdfOnly.setEnvironmentSampling(false);
    withNEE.render(fs, rs);
    bsdfOnly.render(fs, rs);
    const double cameraRays = double(fs.width) * fs.height * rs.spp;
    const double sphereHits = double(bsdfOnly.raysTraced()) - cameraRays;
    const double perHit = (double(withNEE.raysTraced()) - double(bsdfOnly.raysTraced())) / sphereHits;
    std::printf("%.0f sphere hits, %.4f shadow rays each\n", sphereHits, perHit);
    EXPECT_GT(sphereHits, 0.1 * cameraRays);
    EXPECT_GT(perHit, 0.47);  // ~120000 hits: the binomial noise is 0.0015
    EXPECT_LT(perHit, 0.515);
}

// The same settings give the same pixels, in one tracer (the map cached) or a fresh one, and
// passes sum to the whole; another seed or rotation changes them.
TEST(EnvmapReference, Deterministic) {
    Scene scene = sphereScene(glm::vec3(0.7f, 0.5f, 0.3f), 0.3f, 0.5f, true);
    FrameSettings fs = envFrame({1, 1, 4}, "builtin:sky", 16);
    fs.render.specular = true;
    fs.environment.rotation = 30.0f;
    fs.environment.intensity = 1.5f;
    ReferenceSettings rs;
    rs.spp = 8;
    PathTracer pt(scene);
    ImageRGB a = pt.render(fs, rs), b = pt.render(fs, rs), c = PathTracer(scene).render(fs, rs);
    EXPECT_EQ(a.rgb, b.rgb);
    EXPECT_EQ(a.rgb, c.rgb);
    std::vector<double> whole, split;
    pt.trace(fs, rs, 0, 8, whole);
    pt.trace(fs, rs, 0, 3, split);
    pt.trace(fs, rs, 3, 5, split);
    for (size_t i = 0; i < whole.size(); ++i) EXPECT_NEAR(whole[i], split[i], 1e-9 * std::max(1.0, std::abs(whole[i])));
    rs.seed = 2;
    EXPECT_NE(a.rgb, pt.render(fs, rs).rgb);
    rs.seed = 1;
    fs.environment.rotation = 31.0f;
    EXPECT_NE(a.rgb, pt.render(fs, rs).rgb);
}

// With the environment off its settings change nothing: the same pixels and rays as a frame
// that never had them, here with a sun and a point light; a map scaled to zero is no map.
TEST(EnvmapReference, DisabledChangesNothing) {
    Scene scene = sphereScene(glm::vec3(0.6f), 0.4f, 0.0f, true);
    FrameSettings plain = envFrame({1, 1, 4}, "builtin:sky", 16);
    plain.environment = EnvironmentSettings{};
    plain.render.specular = true;
    LightSettings sun;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    LightSettings point;
    point.type = LightType::Point;
    point.position = {1.5f, 1.0f, 1.0f};
    point.intensity = 4.0f;
    plain.lights = {sun, point};
    ReferenceSettings rs;
    rs.spp = 8;
    PathTracer reference(scene);
    ImageRGB expected = reference.render(plain, rs);
    FrameSettings off = plain;
    off.environment.file = "builtin:constant";
    off.environment.intensity = 5.0f;
    off.environment.rotation = 45.0f;
    PathTracer pt(scene);
    EXPECT_EQ(pt.render(off, rs).rgb, expected.rgb);
    EXPECT_EQ(pt.raysTraced(), reference.raysTraced());
    FrameSettings zero = off;
    zero.environment.enabled = true;
    zero.environment.intensity = 0.0f;
    EXPECT_EQ(pt.render(zero, rs).rgb, expected.rgb);
    // And the map, on, does change the image (so the comparisons above can fail).
    zero.environment.intensity = 1.0f;
    EXPECT_NE(pt.render(zero, rs).rgb, expected.rgb);
}

// The cache key has the environment only when it is on: its settings, and the map's pixels, so
// a map rewritten under the same name keys a new reference. A missing map does not stop the
// key; rendering it is an error naming it.
TEST(EnvmapReference, CacheKeyHasTheEnvironmentWhenEnabled) {
    Scene scene = sphereScene(glm::vec3(0.8f));
    FrameSettings fs = envFrame({0, 0, 4}, "builtin:sky", 16);
    fs.environment.enabled = false;
    ReferenceSettings rs;
    uint64_t key = referenceKey(scene, fs, rs);
    FrameSettings disabled = fs;
    disabled.environment.intensity = 3.0f;
    disabled.environment.file = "builtin:constant";
    EXPECT_EQ(key, referenceKey(scene, disabled, rs));
    FrameSettings enabled = fs;
    enabled.environment.enabled = true;
    uint64_t enabledKey = referenceKey(scene, enabled, rs);
    EXPECT_NE(key, enabledKey);
    FrameSettings brighter = enabled;
    brighter.environment.intensity = 2.0f;
    EXPECT_NE(enabledKey, referenceKey(scene, brighter, rs));

    auto file = test::tempDir() / "sky.exr";
    ImageRGB map;
    map.width = 8;
    map.height = 4;
    map.rgb.assign(8 * 4 * 3, 0.5f);
    writeEXR(file, map);
    enabled.environment.file = file.string();
    uint64_t before = referenceKey(scene, enabled, rs);
    map.rgb[5] = 2.0f;
    writeEXR(file, map);
    EXPECT_NE(before, referenceKey(scene, enabled, rs));

    enabled.environment.file = (file.parent_path() / "missing.exr").string();
    auto expectNamesFile = [&](auto&& f) {
        try {
            f();
            ADD_FAILURE() << "no error for a missing map";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("missing.exr"), std::string::npos) << e.what();
        }
    };
    EXPECT_NO_THROW(referenceKey(scene, enabled, rs));  // the editor keys every frame; the render reports it
    expectNamesFile([&] { PathTracer(scene).render(enabled, rs); });
    setenv("GI_CACHE_DIR", file.parent_path().c_str(), 1);
    expectNamesFile([&] { cachedReference(scene, enabled, rs); });
    unsetenv("GI_CACHE_DIR");
}

}  // namespace
}  // namespace gi
