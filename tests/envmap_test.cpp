// Environment lighting: loading and the latlong convention, the prefiltered chain (a constant
// map stays constant at every mip, for both lobes, and so does the irradiance cube), the
// split-sum table against a brute-force quadrature, the sky and its rotation, and errors that name
// the file.
#include "gi/envmap/environment.h"
#include "common/ggx.h"
#include "gi/render/image_io.h"
#include "gi/render/renderer.h"
#include "gi/scene/mesh_builder.h"
#include "gi/util/error.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

namespace gi {
namespace {

TEST(EnvironmentImage, LatLongConventionRoundTrips) {
    for (glm::vec3 d : {glm::vec3(0, 0, -1), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f))})
        for (float rot : {0.0f, 90.0f, -37.0f}) {
            glm::vec3 back = latLongDirection(latLongUV(d, rot), rot);
            EXPECT_NEAR(glm::length(back - d), 0.0f, 1e-5f);
        }
    // The image's centre looks along -z, +x lies at u = 0.75, the zenith at the top row.
    EXPECT_NEAR(latLongUV({0, 0, -1}, 0).x, 0.5f, 1e-6f);
    EXPECT_NEAR(latLongUV({1, 0, 0}, 0).x, 0.75f, 1e-6f);
    EXPECT_NEAR(latLongUV({0, 1, 0}, 0).y, 0.0f, 1e-6f);
    // Turning the map by +90 degrees about +y (right-handed) carries what lay along -z to -x.
    EXPECT_NEAR(glm::length(latLongUV({-1, 0, 0}, 90.0f) - latLongUV({0, 0, -1}, 0.0f)), 0.0f, 1e-5f);
}

TEST(EnvironmentImage, BuiltinsAndErrorsNameTheFile) {
    EnvironmentImage c = loadEnvironment("builtin:constant");
    EXPECT_EQ(sampleEnvironment(c, glm::normalize(glm::vec3(1, 2, 3)), 10.0f), glm::vec3(1.0f));
    EnvironmentImage sky = loadEnvironment("builtin:sky");
    EXPECT_GT(sampleEnvironment(sky, {0, 1, 0}, 0).b, sampleEnvironment(sky, {0, -1, 0}, 0).b) << "blue sky above, ground below";
    auto message = [](const std::string& file) {
        try {
            loadEnvironment(file);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(message("no_such_map.hdr").find("no_such_map.hdr"), std::string::npos);
    EXPECT_NE(message("builtin:nope").find("builtin:nope"), std::string::npos);
    EXPECT_NE(message("missing_{face}.png").find("missing_px.png"), std::string::npos);
    // A file that is not an image.
    std::filesystem::path bad = test::tempDir() / "broken.hdr";
    { std::ofstream(bad) << "#?RADIANCE\nthis is not an image\n"; }
    EXPECT_NE(message(bad.string()).find("broken.hdr"), std::string::npos);
}

// Six faces given as a pattern with {face} become the latlong: each axis direction shows its
// face's colour (GL's face order and orientation), 8-bit faces decoded from sRGB.
TEST(EnvironmentImage, SixFaceCubeMapLoads) {
    std::filesystem::path dir = test::tempDir();
    const char* names[6] = {"px", "nx", "py", "ny", "pz", "nz"};
    const glm::vec3 colours[6] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}};
    for (int f = 0; f < 6; ++f) {
        std::vector<uint8_t> px(8 * 8 * 4);
        for (size_t i = 0; i < 64; ++i)
            for (int c = 0; c < 3; ++c) px[i * 4 + size_t(c)] = uint8_t(colours[f][c] * 255.0f);
        for (size_t i = 0; i < 64; ++i) px[i * 4 + 3] = 255;
        writePNG(dir / ("sky_" + std::string(names[f]) + ".png"), 8, 8, px);
    }
    EnvironmentImage env = loadEnvironment((dir / "sky_{face}.png").string());
    EXPECT_EQ(env.width, 32);
    EXPECT_EQ(env.height, 16);
    const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int f = 0; f < 6; ++f) {
        glm::vec3 c = sampleEnvironment(env, axes[f], 0.0f);
        EXPECT_NEAR(glm::length(c - colours[f]), 0.0f, 1e-3f) << names[f];
    }
    // A face of another size is refused, naming it.
    std::vector<uint8_t> small(4 * 4 * 4, 255);
    writePNG(dir / "sky_nz.png", 4, 4, small);
    try {
        loadEnvironment((dir / "sky_{face}.png").string());
        ADD_FAILURE() << "faces of two sizes loaded";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("sky_nz.png"), std::string::npos) << e.what();
    }
}

class EnvironmentGL : public test::GLTest {};

// Reads mip `level` of a cube map as RGBA floats.
std::vector<float> readCube(GLuint tex, int level, int size) {
    std::vector<float> px(size_t(size) * size * 6 * 4);
    glGetTextureImage(tex, level, GL_RGBA, GL_FLOAT, GLsizei(px.size() * sizeof(float)), px.data());
    return px;
}

// Prefiltering a constant environment returns the constant at every mip, for GGX and for the
// seed's Beckmann cone, and the irradiance cube holds E / pi = the constant.
TEST_F(EnvironmentGL, ConstantEnvironmentStaysConstantAtEveryMip) {
    for (PrefilterDistribution dist : {PrefilterDistribution::GGX, PrefilterDistribution::BeckmannCone}) {
        Environment env;
        EnvironmentSettings s;
        s.enabled = true;
        s.file = "builtin:constant";
        s.cubeSize = 32;
        s.samples = 32;
        s.distribution = dist;
        gl::GpuTimer timer;
        timer.beginFrame();
        env.prepare(s, timer);
        timer.endFrame();
        ASSERT_TRUE(env.ready());
        ASSERT_EQ(env.mips().size(), 6u) << "32^2 halves 5 times: 6 of the 11 table entries";
        for (size_t m = 0; m < env.mips().size(); ++m) {
            int size = env.mips()[m].size;
            EXPECT_EQ(size, 32 >> m);
            std::vector<float> px = readCube(env.prefiltered(), int(m), size);
            float worst = 0.0f;
            for (size_t i = 0; i < px.size(); i += 4)
                for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(px[i + size_t(c)] - 1.0f));
            EXPECT_LT(worst, 2e-3f) << enumName(dist) << " mip " << m << " roughness " << env.mips()[m].roughness;
        }
        std::vector<float> irr = readCube(env.irradiance(), 0, 32);
        for (size_t i = 0; i < irr.size(); i += 4) ASSERT_NEAR(irr[i], 1.0f, 2e-3f);
    }
}

// The split-sum table is the integral it stands for: (A, B) at a few (N.V, roughness) match a
// brute-force quadrature over the hemisphere of the same GGX D and visibility (common/ggx.h,
// shared with the direct light and the path tracer), and a smooth mirror at normal incidence
// reflects everything (A + B = 1). Karis's analytic fit is no oracle: it reads 0.90 where the
// integral is 1.00 (roughness 0.17, N.V 0.97).
TEST_F(EnvironmentGL, SplitSumTableIsTheIntegral) {
    Environment env;
    const int n = 128;
    std::vector<float> lut(size_t(n) * n * 2);
    glGetTextureImage(env.brdfLUT(), 0, GL_RG, GL_FLOAT, GLsizei(lut.size() * sizeof(float)), lut.data());
    auto table = [&](int x, int y) { return glm::vec2(lut[(size_t(y) * n + x) * 2], lut[(size_t(y) * n + x) * 2 + 1]); };
    auto quadrature = [](float NoV, float roughness) {
        float a = std::max(roughness * roughness, 0.002f);
        glm::vec3 V(std::sqrt(1.0f - NoV * NoV), 0.0f, NoV);
        const int nt = 1200, np = 2400;
        double A = 0, B = 0;
        for (int i = 0; i < nt; ++i) {
            double theta = (i + 0.5) / nt * 0.5 * 3.14159265358979;
            double dTheta = 0.5 * 3.14159265358979 / nt;
            for (int j = 0; j < np; ++j) {
                double phi = (j + 0.5) / np * 2.0 * 3.14159265358979, dPhi = 2.0 * 3.14159265358979 / np;
                glm::vec3 L(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)));
                glm::vec3 H = glm::normalize(V + L);
                float NoL = L.z, VoH = std::max(glm::dot(V, H), 0.0f);
                double f = double(ggx::D_GGX(H.z, a)) * ggx::V_SmithGGXCorrelated(NoV, NoL, a) * NoL;
                double Fc = std::pow(1.0 - VoH, 5.0);
                double dw = std::sin(theta) * dTheta * dPhi;
                A += f * (1.0 - Fc) * dw;
                B += f * Fc * dw;
            }
        }
        return glm::vec2(float(A), float(B));
    };
    for (glm::ivec2 xy : {glm::ivec2(20, 50), glm::ivec2(64, 64), glm::ivec2(120, 40), glm::ivec2(100, 127), glm::ivec2(10, 110)}) {
        float NoV = (float(xy.x) + 0.5f) / n, roughness = (float(xy.y) + 0.5f) / n;
        glm::vec2 want = quadrature(NoV, roughness), got = table(xy.x, xy.y);
        EXPECT_NEAR(got.x, want.x, 0.01f) << "N.V " << NoV << " roughness " << roughness;
        EXPECT_NEAR(got.y, want.y, 0.01f) << "N.V " << NoV << " roughness " << roughness;
    }
    glm::vec2 mirror = table(n - 1, 0);
    EXPECT_NEAR(mirror.x + mirror.y, 1.0f, 0.02f);
}

// The sky shows the map where no surface is, turns with `rotation`, and scales with intensity;
// disabled, the background is black.
TEST_F(EnvironmentGL, SkyShowsTheMapAndTurnsWithRotation) {
    Scene scene;
    {
        scene.name = "empty";
        MeshBuilder b(scene);
        int m = b.material("grey", glm::vec3(0.5f), 1.0f);
        b.sphere(m, {0.0f, 0.0f, -50.0f}, 0.01f);  // something to have bounds
        scene.finalize();
    }
    Renderer r;
    r.setScene(scene);
    FrameSettings fs;
    // Looking 40 degrees up, away from the horizon's steep gradient (the cube is coarser than the map).
    const glm::vec3 view = glm::normalize(glm::vec3(0.0f, std::sin(glm::radians(40.0f)), -std::cos(glm::radians(40.0f))));
    fs.camera.eye = {0, 0, 0};
    fs.camera.target = view;
    fs.lights.clear();
    fs.width = fs.height = 32;
    fs.environment.enabled = true;
    fs.environment.file = "builtin:sky";
    fs.environment.cubeSize = 64;
    fs.environment.samples = 8;
    auto centre = [&]() {
        r.render(fs);
        std::vector<float> hdr = r.readHDR();
        const float* p = &hdr[(size_t(16) * 32 + 16) * 4];
        return glm::vec3(p[0], p[1], p[2]);
    };
    EnvironmentImage sky = loadEnvironment("builtin:sky");
    glm::vec3 expected = sampleEnvironment(sky, view, 0.0f);
    glm::vec3 seen = centre();
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(seen[c], expected[c], 0.05f * expected[c] + 0.01f);
    fs.environment.intensity = 2.0f;
    glm::vec3 brighter = centre();
    EXPECT_NEAR(brighter.b, 2.0f * seen.b, 0.02f * seen.b + 0.01f);
    fs.environment.intensity = 1.0f;
    fs.environment.rotation = 180.0f;  // the centre now sees what lay behind the camera
    glm::vec3 turned = centre();
    glm::vec3 behind = sampleEnvironment(sky, {-view.x, view.y, -view.z}, 0.0f);
    EXPECT_NEAR(turned.r, behind.r, 0.05f * behind.r + 0.01f);
    fs.environment.enabled = false;
    EXPECT_EQ(centre(), glm::vec3(0.0f));
}

// A bad file is a one-line error naming it, raised by render (gi-render and the editor show it).
TEST_F(EnvironmentGL, MissingMapFailsWithItsName) {
    Scene scene = makeBuiltinScene("spheres");
    Renderer r;
    r.setScene(scene);
    FrameSettings fs;
    fs.width = fs.height = 16;
    fs.environment.enabled = true;
    fs.environment.file = "/nowhere/sky.exr";
    try {
        r.render(fs);
        FAIL() << "rendered with a missing map";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("/nowhere/sky.exr"), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace gi
