// Emissive surfaces as area lights: grouping at load, the frame's light list (no invented sun
// where the author put emitters), the exact irradiance of a polygon against its closed form, the
// raster's area light against the same, and switching an emitter off in the raster and the
// reference alike.
#include "common/light.h"
#include "gi/preset/preset.h"
#include "gi/reference/path_tracer.h"
#include "gi/render/renderer.h"
#include "gi/scene/emitters.h"
#include "gi/scene/mesh_builder.h"
#include "gi/util/error.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace gi {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The form factor from a point to a parallel a x b rectangle at height h whose corner is right
// above it (the classic closed form, e.g. Howell's catalogue, configuration B-3).
double cornerFormFactor(double a, double b, double h) {
    double A = a / h, B = b / h;
    double sa = std::sqrt(1.0 + A * A), sb = std::sqrt(1.0 + B * B);
    return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2.0 * kPi);
}

// A unit square at height h emitting downwards (front -y), as two front-wound triangles.
struct Square {
    glm::vec3 p[4];
};
Square square(float h) { return {{{-0.5f, h, -0.5f}, {0.5f, h, -0.5f}, {0.5f, h, 0.5f}, {-0.5f, h, 0.5f}}}; }

// Irradiance at P (normal N) from the square of unit radiance through the shared light model.
double squareIrradiance(const Square& s, glm::vec3 P, glm::vec3 N, bool doubleSided = false) {
    // (p1 - p0) x (p2 - p0) = (1,0,0) x (1,0,1) = (0,-1,0): the front faces down.
    return light::triangleIrradiance(s.p[0], s.p[1], s.p[2], P, N, doubleSided) +
           light::triangleIrradiance(s.p[0], s.p[2], s.p[3], P, N, doubleSided);
}

TEST(AreaLight, PolygonIrradianceMatchesTheClosedFormAtTheCentreAndACorner) {
    const float h = 0.5f;
    Square s = square(h);
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    double centre = squareIrradiance(s, {0.0f, 0.0f, 0.0f}, up);
    double centreExact = kPi * 4.0 * cornerFormFactor(0.5, 0.5, h);
    double corner = squareIrradiance(s, {0.5f, 0.0f, 0.5f}, up);
    double cornerExact = kPi * cornerFormFactor(1.0, 1.0, h);
    std::printf("centre %.6f exact %.6f, corner %.6f exact %.6f\n", centre, centreExact, corner, cornerExact);
    EXPECT_NEAR(centre, centreExact, 0.02 * centreExact);
    EXPECT_NEAR(corner, cornerExact, 0.02 * cornerExact);
    // Single-sided: nothing behind it; double-sided: the mirror image.
    EXPECT_EQ(squareIrradiance(s, {0.0f, 2.0f * h, 0.0f}, -up), 0.0);
    EXPECT_NEAR(squareIrradiance(s, {0.0f, 2.0f * h, 0.0f}, -up, true), centreExact, 0.02 * centreExact);
    // A point on the light's own plane sees it edge-on: nothing (the edge formula alone would
    // count the whole hemisphere inside it).
    EXPECT_EQ(squareIrradiance(s, {0.1f, h, 0.1f}, -up, true), 0.0);
    EXPECT_EQ(squareIrradiance(s, {0.1f, h + 1e-5f, 0.1f}, up, true), 0.0);
}

TEST(AreaLight, PolygonIrradianceClipsAtTheHorizon) {
    // A receiver tilted 60 degrees, so part of the square lies below its horizon: against a
    // numerical integral of L cos(receiver)+ cos(emitter) / d^2 over the square's area.
    Square s = square(0.5f);
    const glm::vec3 P(0.3f, 0.0f, 0.1f);
    const glm::vec3 N = glm::normalize(glm::vec3(std::sin(1.047f), std::cos(1.047f), 0.0f));
    const int n = 600;
    double numeric = 0.0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            glm::dvec3 q(-0.5 + (i + 0.5) / n, 0.5, -0.5 + (j + 0.5) / n);
            glm::dvec3 d = q - glm::dvec3(P);
            double d2 = glm::dot(d, d);
            glm::dvec3 w = d / std::sqrt(d2);
            double cosR = std::max(glm::dot(w, glm::dvec3(N)), 0.0);
            double cosE = w.y;  // the emitter faces -y: cos at the emitter is the direction's y
            numeric += cosR * cosE / d2 / (double(n) * n);
        }
    double exact = squareIrradiance(s, P, N);
    std::printf("tilted: polygon %.6f numeric %.6f\n", exact, numeric);
    EXPECT_NEAR(exact, numeric, 0.01 * numeric);
    EXPECT_LT(exact, squareIrradiance(s, P, {0.0f, 1.0f, 0.0f}));
}

Scene emitterScene(glm::vec3 emission = glm::vec3(1.0f)) {
    Scene s;
    s.name = "emitter";
    MeshBuilder b(s);
    int grey = b.material("grey", glm::vec3(0.5f), 1.0f);
    int lamp = b.material("lamp", glm::vec3(0.0f), 1.0f);
    b.quad(grey, {-20, 0, 20}, {40, 0, 0}, {0, 0, -40});
    b.quad(lamp, {-0.5f, 0.5f, -0.5f}, {1, 0, 0}, {0, 0, 1});  // normal -y
    s.materials[size_t(lamp)].emissive = emission;
    s.finalize();
    return s;
}

TEST(AreaLight, EmissiveTrianglesGroupIntoEmittersFacingTheirNormals) {
    Scene s = emitterScene();
    ASSERT_EQ(s.emitters.size(), 1u);
    const Emitter& e = s.emitters[0];
    EXPECT_EQ(e.name, "lamp");
    EXPECT_EQ(e.triangles.size(), 2u);
    EXPECT_NEAR(e.area, 1.0f, 1e-5f);
    EXPECT_NEAR(e.normal.y, -1.0f, 1e-5f);
    EXPECT_NEAR(e.centroid.y, 0.5f, 1e-5f);
    for (size_t t = 0; t < e.triangles.size(); ++t) {
        glm::vec3 front = glm::cross(e.corners[3 * t + 1] - e.corners[3 * t], e.corners[3 * t + 2] - e.corners[3 * t]);
        EXPECT_LT(front.y, 0.0f) << "triangle " << t << " must be wound to face its normal";
    }
    int emissive = 0;
    for (int k : s.triangleEmitter) emissive += k == 0;
    EXPECT_EQ(emissive, 2);

    // Two lamps apart are two lights; a large sheet is split into parts of at most the limit.
    Scene two;
    MeshBuilder b(two);
    int lamp = b.material("lamp", glm::vec3(0.0f));
    b.quad(lamp, {-3, 1, 0}, {1, 0, 0}, {0, 0, 1});
    b.quad(lamp, {3, 1, 0}, {1, 0, 0}, {0, 0, 1});
    for (int i = 0; i < 20; ++i) b.quad(lamp, {float(i), 5, 0}, {1, 0, 0}, {0, 0, 1});  // 40 connected triangles
    two.materials[size_t(lamp)].emissive = glm::vec3(2.0f);
    two.finalize();
    ASSERT_GE(two.emitters.size(), 2u + 3u);
    size_t total = 0;
    for (const Emitter& em : two.emitters) {
        EXPECT_LE(em.triangles.size(), size_t(kMaxEmitterTriangles));
        total += em.triangles.size();
    }
    EXPECT_EQ(total, 44u);
}

TEST(AreaLight, EmittersLightTheFrameAndNoSunIsInvented) {
    Scene s = emitterScene();
    Preset p;
    p.lightsFromScene = true;
    EXPECT_FALSE(usesDefaultSun(p, s));
    std::vector<LightSettings> lights = frameLights(p, s);
    ASSERT_EQ(lights.size(), 1u);
    EXPECT_EQ(lights[0].type, LightType::Area);
    EXPECT_EQ(lights[0].emitter, 0);
    EXPECT_NEAR(lights[0].position.y, 0.5f, 1e-5f);

    // Neither punctual lights nor emitters: the default sun, and the caller can say so.
    Scene dark = emitterScene(glm::vec3(0.0f));
    EXPECT_TRUE(dark.emitters.empty());
    EXPECT_TRUE(usesDefaultSun(p, dark));
    ASSERT_EQ(frameLights(p, dark).size(), 1u);
    EXPECT_EQ(frameLights(p, dark)[0].type, LightType::Directional);

    // A preset with its own lights still gets the emitters it does not name; one it switches
    // off is left out; an emitter that does not exist is an error naming the key.
    Preset own;
    own.lightsFromScene = false;
    own.lights = {LightSettings{}};
    EXPECT_EQ(frameLights(own, s).size(), 2u);
    LightSettings off;
    off.type = LightType::Area;
    off.emitter = 0;
    off.enabled = false;
    own.lights.push_back(off);
    EXPECT_EQ(frameLights(own, s).size(), 1u);
    own.lights.back().emitter = 3;
    try {
        frameLights(own, s);
        ADD_FAILURE() << "an emitter past the end must be refused";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("lights.1.emitter"), std::string::npos) << e.what();
    }
}

TEST(AreaLight, PlacedFieldsAreReadOnlyInTheSettingsTable) {
    // The editor draws a field disabled where the settings say it is derived: an area light's
    // position and direction (placeAreaLight overwrites them every frame), nothing of a spot's.
    // Walking visit() checks the names match the table's keys.
    auto readOnlyKeys = [](const LightSettings& l) {
        std::vector<std::string> keys;
        LightSettings copy = l;
        copy.visit([&](auto&, const FieldMeta& m) {
            if (l.readOnly(m.key)) keys.push_back(m.key);
        });
        return keys;
    };
    static_assert(HasReadOnlyFields<LightSettings>);
    LightSettings area;
    area.type = LightType::Area;
    area.emitter = 0;
    EXPECT_EQ(readOnlyKeys(area), (std::vector<std::string>{"position", "direction"}));
    LightSettings spot;
    spot.type = LightType::Spot;
    EXPECT_TRUE(readOnlyKeys(spot).empty());
    EXPECT_NE(std::string(area.readOnly("position")).find("emissive surface"), std::string::npos);
}

class AreaLightGL : public test::GLTest {};

constexpr int kSize = 128;

glm::vec3 centre(const Renderer& r) {
    std::vector<float> px = r.readHDR();
    glm::vec3 sum(0.0f);
    for (int y = kSize / 2 - 1; y < kSize / 2 + 1; ++y)
        for (int x = kSize / 2 - 1; x < kSize / 2 + 1; ++x)
            sum += glm::vec3(px[(y * kSize + x) * 4], px[(y * kSize + x) * 4 + 1], px[(y * kSize + x) * 4 + 2]);
    return sum / 4.0f;
}

// Looking straight down from just under the lamp at floor point `at`.
FrameSettings downAt(const Scene& s, glm::vec3 at) {
    Preset p;
    p.lightsFromScene = true;
    FrameSettings fs = frameSettings(p, s, kSize, kSize);
    fs.camera.eye = at + glm::vec3(0.0f, 0.45f, 0.0f);
    fs.camera.target = at;
    fs.camera.up = {0.0f, 0.0f, -1.0f};
    fs.camera.fovY = 10.0f;
    fs.camera.near = 0.01f;
    fs.render.ambient = glm::vec3(0.0f);
    fs.render.specular = false;
    fs.toneMap.op = ToneMapper::Linear;
    return fs;
}

TEST_F(AreaLightGL, TheRasterMatchesTheClosedFormWithItsShadowMapOn) {
    Scene s = emitterScene();
    Renderer r;
    r.setScene(s);
    // Radiance of the grey (0.5) Lambertian floor: 0.5 / pi x E.
    struct Case {
        glm::vec3 at;
        double E;
    } cases[] = {{{0.0f, 0.0f, 0.0f}, kPi * 4.0 * cornerFormFactor(0.5, 0.5, 0.5)},
                 {{0.5f, 0.0f, 0.5f}, kPi * cornerFormFactor(1.0, 1.0, 0.5)}};
    for (const Case& c : cases) {
        FrameSettings fs = downAt(s, c.at);
        ASSERT_TRUE(fs.lights.at(0).castShadows);
        r.render(fs);
        double got = centre(r).x, want = 0.5 / kPi * c.E;
        std::printf("floor at (%.1f, %.1f): %.5f closed form %.5f\n", c.at.x, c.at.z, got, want);
        EXPECT_NEAR(got, want, 0.02 * want);
    }
}

TEST_F(AreaLightGL, AnEmitterSwitchedOffGoesDarkInTheRasterAndTheReference) {
    Scene s = emitterScene();
    Preset p;
    p.lightsFromScene = false;
    LightSettings lamp = sceneLights(s).at(0);
    lamp.intensity = 2.0f;
    p.lights = {lamp};
    // Seen from below, the lamp glows at twice its emission in both renderers.
    auto look = [&](const Preset& preset) {
        FrameSettings fs = frameSettings(preset, s, 32, 32);
        fs.camera.eye = {0.0f, 0.05f, 0.0f};
        fs.camera.target = {0.0f, 1.0f, 0.0f};
        fs.camera.up = {0.0f, 0.0f, -1.0f};
        fs.camera.fovY = 20.0f;
        fs.camera.near = 0.01f;
        fs.toneMap.op = ToneMapper::Linear;
        return fs;
    };
    Renderer r;
    r.setScene(s);
    PathTracer pt(s);
    ReferenceSettings rs;
    rs.spp = 4;
    rs.mode = ReferenceMode::Direct;
    FrameSettings on = look(p);
    r.render(on);
    EXPECT_NEAR(r.readHDR()[(16 * 32 + 16) * 4], 2.0f, 1e-3f);
    EXPECT_NEAR(pt.render(on, rs).rgb[(16 * 32 + 16) * 3], 2.0f, 1e-3f);
    p.lights[0].enabled = false;
    FrameSettings off = look(p);
    EXPECT_TRUE(off.lights.empty());
    r.render(off);
    EXPECT_EQ(r.readHDR()[(16 * 32 + 16) * 4], 0.0f);
    EXPECT_EQ(pt.render(off, rs).rgb[(16 * 32 + 16) * 3], 0.0f);
}

TEST_F(AreaLightGL, TheBuiltinLampCornellIsLitByItsQuadAlone) {
    // cornell_lamp (CI's quad-lit case, no ../shared needed): one emissive quad under the
    // ceiling, no punctual light, so its presets get the one area light and no default sun.
    Scene s = makeBuiltinScene("cornell_lamp");
    EXPECT_TRUE(s.lights.empty());
    ASSERT_EQ(s.emitters.size(), 1u);
    EXPECT_EQ(s.emitters[0].name, "lamp");
    EXPECT_NEAR(s.emitters[0].area, 0.47f * 0.38f, 1e-4f);
    EXPECT_NEAR(s.emitters[0].normal.y, -1.0f, 1e-5f);
    Preset p = loadPreset(std::filesystem::path(GI_PRESET_DIR) / "cornell_lamp.json");
    EXPECT_EQ(p.header.scene, "cornell_lamp");
    EXPECT_FALSE(usesDefaultSun(p, s));
    FrameSettings fs = frameSettings(p, s, 16, 12);
    ASSERT_EQ(fs.lights.size(), 1u);
    EXPECT_EQ(fs.lights[0].type, LightType::Area);

    // The reference sees the lamp and nothing else: with it switched off the image is black.
    PathTracer pt(s);
    ReferenceSettings rs;
    rs.spp = 2;
    auto total = [](const ImageRGB& img) {
        double sum = 0.0;
        for (float v : img.rgb) sum += v;
        return sum;
    };
    EXPECT_GT(total(pt.render(fs, rs)), 1.0);
    p.lightsFromScene = false;
    p.lights = {sceneLights(s).at(0)};
    p.lights[0].enabled = false;
    FrameSettings off = frameSettings(p, s, 16, 12);
    EXPECT_TRUE(off.lights.empty());
    EXPECT_FALSE(usesDefaultSun(p, s));
    EXPECT_EQ(total(pt.render(off, rs)), 0.0);
}

}  // namespace
}  // namespace gi
