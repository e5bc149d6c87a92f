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

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstring>
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

// A Radiance header of the given size (`-Y height +X width`) and then `body` bytes.
void writeRadiance(const std::filesystem::path& path, const std::string& size, const std::string& body = {}) {
    std::ofstream f(path, std::ios::binary);
    f << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" << size << "\n" << body;
}

// The message loading `file` fails with ("" when it loads); a crash fails the whole test binary.
std::string loadError(const std::string& file, size_t budgetBytes = kDefaultEnvironmentBudgetBytes) {
    try {
        loadEnvironment(file, {}, budgetBytes);
    } catch (const Error& e) {
        return e.what();
    }
    return {};
}

#define EXPECT_ERROR_NAMES(message, file, problem)                                                          \
    do {                                                                                                   \
        std::string m_ = (message);                                                                        \
        EXPECT_NE(m_.find(file), std::string::npos) << "the file is not named: " << m_;                   \
        EXPECT_NE(m_.find(problem), std::string::npos) << "'" << (problem) << "' is not said: " << m_;     \
        EXPECT_EQ(m_.find('\n'), std::string::npos) << "not one line: " << m_;                            \
    } while (0)

// Bad map files are refused with one line naming the file and what is wrong, from the header,
// before any pixel buffer exists (so a header claiming 10^12 pixels costs nothing).
TEST(EnvironmentImage, BadFilesAreRefusedFromTheirHeader) {
    std::filesystem::path dir = test::tempDir();
    std::filesystem::create_directories(dir / "folder.hdr");
    EXPECT_ERROR_NAMES(loadError((dir / "folder.hdr").string()), "folder.hdr", "is a folder");
    { std::ofstream(dir / "empty.hdr"); }
    EXPECT_ERROR_NAMES(loadError((dir / "empty.hdr").string()), "empty.hdr", "empty file");
    { std::ofstream(dir / "notes.exr") << "these are notes, not pixels\n"; }
    EXPECT_ERROR_NAMES(loadError((dir / "notes.exr").string()), "notes.exr", "cannot read environment map");
    // Absurd sizes: past the largest texture, and within it but past the memory budget.
    writeRadiance(dir / "huge.hdr", "-Y 1000000 +X 1000000", "abcd");
    EXPECT_ERROR_NAMES(loadError((dir / "huge.hdr").string()), "huge.hdr", "1000000x1000000 is larger than 16384 px per side");
    writeRadiance(dir / "big.hdr", "-Y 16000 +X 16000", "abcd");
    EXPECT_ERROR_NAMES(loadError((dir / "big.hdr").string()), "big.hdr", "key 'render.memoryBudgetMB'");
    writeRadiance(dir / "modest.hdr", "-Y 512 +X 1024", "abcd");
    EXPECT_ERROR_NAMES(loadError((dir / "modest.hdr").string(), size_t(1) << 20), "modest.hdr",
                       "needs 12 MiB, past the budget of 1 MiB (key 'render.memoryBudgetMB')");
    // No pixels: zero or negative sizes, and a latlong one pixel wide.
    writeRadiance(dir / "zero.hdr", "-Y 0 +X 0");
    EXPECT_ERROR_NAMES(loadError((dir / "zero.hdr").string()), "zero.hdr", "no pixels");
    writeRadiance(dir / "negative.hdr", "-Y -5 +X 10");
    EXPECT_ERROR_NAMES(loadError((dir / "negative.hdr").string()), "negative.hdr", "no pixels");
    writeRadiance(dir / "thin.hdr", "-Y 4 +X 1", std::string(16, char(128)));
    EXPECT_ERROR_NAMES(loadError((dir / "thin.hdr").string()), "thin.hdr", "1 px wide");
    // Truncated: a 16x8 flat (unencoded) RGBE file with 3 of its 8 rows, and an RLE one cut in its
    // first row's header; with all 8 rows it loads.
    std::string row(16 * 4, char(0));
    for (size_t i = 0; i < row.size(); i += 4) row[i] = row[i + 1] = row[i + 2] = char(128), row[i + 3] = char(129);  // 1.0
    writeRadiance(dir / "truncated.hdr", "-Y 8 +X 16", row + row + row);
    EXPECT_ERROR_NAMES(loadError((dir / "truncated.hdr").string()), "truncated.hdr", "cannot decode environment map");
    writeRadiance(dir / "truncated_rle.hdr", "-Y 8 +X 64", std::string("\x02\x02\x00\x40\xc0", 5));
    EXPECT_ERROR_NAMES(loadError((dir / "truncated_rle.hdr").string()), "truncated_rle.hdr", "cannot decode environment map");
    writeRadiance(dir / "whole.hdr", "-Y 8 +X 16", row + row + row + row + row + row + row + row);
    EnvironmentImage whole = loadEnvironment((dir / "whole.hdr").string());
    EXPECT_EQ(whole.width, 16);
    EXPECT_EQ(whole.height, 8);
    EXPECT_NEAR(whole.texel(3, 5).g, 1.0f, 1e-6f);
}

// EXR: a data window far past the file's end, or a huge one the file seems to hold, is refused;
// a cut file too; more than four channels load as RGB from the first three.
TEST(EnvironmentImage, BadEXRFilesAreRefused) {
    std::filesystem::path dir = test::tempDir();
    auto writeEXRChannels = [&](const std::filesystem::path& path, int channels) {
        OIIO::ImageSpec spec(4, 2, channels, OIIO::TypeDesc::FLOAT);
        std::vector<float> px(size_t(4 * 2 * channels));
        for (size_t i = 0; i < px.size(); ++i) px[i] = float(i % size_t(channels) + 1);  // channel c holds c + 1
        auto out = OIIO::ImageOutput::create(path.string());
        ASSERT_TRUE(out && out->open(path.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, px.data()) && out->close());
    };
    writeEXRChannels(dir / "five.exr", 5);
    EnvironmentImage five = loadEnvironment((dir / "five.exr").string());
    EXPECT_EQ(five.texel(1, 1), glm::vec3(1, 2, 3));
    writeEXRChannels(dir / "grey.exr", 2);
    EXPECT_EQ(loadEnvironment((dir / "grey.exr").string()).texel(0, 0), glm::vec3(1, 1, 1)) << "grey + alpha repeats grey";

    writeEXRChannels(dir / "small.exr", 3);
    std::string bytes;
    {
        std::ifstream in(dir / "small.exr", std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    // The header's dataWindow attribute: name, type, size 16, then xMin yMin xMax yMax.
    size_t at = bytes.find(std::string("dataWindow\0box2i\0", 17));
    ASSERT_NE(at, std::string::npos);
    at += 17 + 4;
    auto withWindow = [&](int32_t xMax, int32_t yMax, size_t padding) {
        std::string b = bytes;
        std::memcpy(&b[at + 8], &xMax, 4);
        std::memcpy(&b[at + 12], &yMax, 4);
        return b + std::string(padding, '\0');
    };
    std::ofstream(dir / "window_past_end.exr", std::ios::binary) << withWindow(999999, 999999, 0);
    EXPECT_ERROR_NAMES(loadError((dir / "window_past_end.exr").string()), "window_past_end.exr", "cannot read environment map");
    // With room for the line offset table, OpenEXR opens it as 16000x16000: 6 GB to decode.
    std::ofstream(dir / "window_huge.exr", std::ios::binary) << withWindow(15999, 15999, 16000 * 8);
    EXPECT_ERROR_NAMES(loadError((dir / "window_huge.exr").string()), "window_huge.exr", "key 'render.memoryBudgetMB'");
    std::ofstream(dir / "cut.exr", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    std::string cut = loadError((dir / "cut.exr").string());
    EXPECT_ERROR_NAMES(cut, "cut.exr", "environment map");
}

// Cube faces are checked from their headers, all six before any is decoded.
// A PNG whose ancillary chunk states 2 GB: libpng would allocate that in OpenImageIO's open()
// (gi-fuzz found it through a glTF texture); the layout is checked first.
TEST(EnvironmentImage, PNGChunkPastTheEndIsRefusedBeforeLibpng) {
    auto dir = test::tempDir();
    // A PNG signature, a 4x2 IHDR, then a tEXt chunk stating 0x7F000000 bytes in a 52-byte file.
    std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R', 0, 0, 0, 4, 0, 0, 0, 2,
                                8, 2, 0, 0, 0, 0, 0, 0, 0, 0x7F, 0, 0, 0, 't', 'E', 'X', 't', 'a', 'b', 'c', 'd', 'e', 'f', 'g', 'h', 'i', 'j', 'k'};
    std::ofstream(dir / "chunk.png", std::ios::binary).write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
    EXPECT_ERROR_NAMES(loadError((dir / "chunk.png").string()), "chunk.png",
                       "environment map is damaged: PNG chunk 'tEXt' at byte 33 states 2130706432 bytes, past the end of the image (52 bytes)");
}

TEST(EnvironmentImage, BadCubeFacesAreRefused) {
    std::filesystem::path dir = test::tempDir();
    std::string row(8 * 4, char(0));
    for (size_t i = 0; i < row.size(); i += 4) row[i] = row[i + 1] = row[i + 2] = char(128), row[i + 3] = char(129);
    std::string face;
    for (int y = 0; y < 8; ++y) face += row;
    for (const char* f : {"px", "nx", "py", "ny", "pz", "nz"}) writeRadiance(dir / ("cube_" + std::string(f) + ".hdr"), "-Y 8 +X 8", face);
    EXPECT_EQ(loadEnvironment((dir / "cube_{face}.hdr").string()).width, 32);
    const std::string pattern = (dir / "cube_{face}.hdr").string();
    writeRadiance(dir / "cube_py.hdr", "-Y 8 +X 16", face + face);
    EXPECT_ERROR_NAMES(loadError(pattern), "cube_py.hdr", "square and of one size (px is 8x8, this face 16x8)");
    writeRadiance(dir / "cube_py.hdr", "-Y 4 +X 4", face);
    EXPECT_ERROR_NAMES(loadError(pattern), "cube_py.hdr", "square and of one size");
    writeRadiance(dir / "cube_py.hdr", "-Y 8 +X 8", face);
    for (const char* f : {"px", "nx", "py", "ny", "pz", "nz"}) writeRadiance(dir / ("cube_" + std::string(f) + ".hdr"), "-Y 9000 +X 9000");
    EXPECT_ERROR_NAMES(loadError(pattern), "cube_px.hdr", "larger than 16384 px per side");
    for (const char* f : {"px", "nx", "py", "ny", "pz", "nz"}) writeRadiance(dir / ("cube_" + std::string(f) + ".hdr"), "-Y 4000 +X 4000");
    EXPECT_ERROR_NAMES(loadError(pattern), "cube_{face}.hdr", "key 'render.memoryBudgetMB'");
    std::filesystem::remove(dir / "cube_nz.hdr");
    std::filesystem::create_directories(dir / "cube_nz.hdr");
    EXPECT_ERROR_NAMES(loadError(pattern), "cube_nz.hdr", "is a folder");
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

// The prefilter's time is estimated from its settings alone: the defaults take well under a
// second, cubeSize 2048 with 4096 samples is refused past the default budget, naming the key,
// the estimate, the settings and the budget; Renderer::checkBudget (gi-render and the editor
// call it before any GL allocation) refuses it too.
TEST(EnvironmentBudget, PrefilterPastTheTimeBudgetIsRefused) {
    EnvironmentSettings s;
    s.enabled = true;
    EXPECT_LT(Environment::estimateSeconds(s), 1.0);
    EXPECT_NO_THROW(Environment::checkTimeBudget(s, RenderSettings{}.timeBudgetSeconds));
    // Only mips of roughness above 0 are sampled: 256^2's chain samples mips 1 to 8.
    EXPECT_DOUBLE_EQ(Environment::estimateSamples(s), 6.0 * 64.0 * (128 * 128 + 64 * 64 + 32 * 32 + 16 * 16 + 8 * 8 + 4 * 4 + 2 * 2 + 1));
    s.cubeSize = 2048;
    s.samples = 4096;
    EXPECT_GT(Environment::estimateSeconds(s), 600.0);
    FrameSettings fs;
    fs.environment = s;
    try {
        Renderer::checkBudget(fs, 0);
        ADD_FAILURE() << "a prefilter of 2048^2 x 4096 samples was not refused";
    } catch (const Error& e) {
        std::string m = e.what();
        EXPECT_EQ(m.rfind("key 'render.timeBudgetSeconds': environment prefilter estimated at ", 0), 0u) << m;
        EXPECT_NE(m.find(" s (cubeSize 2048, samples 4096) exceeds the budget of 600 s; lower environment.samples or "
                         "environment.cubeSize, or raise render.timeBudgetSeconds"),
                  std::string::npos)
            << m;
    }
    fs.render.timeBudgetSeconds = 1e6f;
    EXPECT_NO_THROW(Renderer::checkBudget(fs, 0));
    fs.environment.enabled = false;
    fs.render.timeBudgetSeconds = 1.0f;
    EXPECT_NO_THROW(Renderer::checkBudget(fs, 0)) << "a disabled environment costs nothing";
}

TEST(Progress, LinesSayDoneTotalElapsedAndTimeLeft) {
    ProgressUpdate u;
    u.task = "reference";
    u.done = 64;
    u.total = 1024;
    u.unit = "spp";
    u.fraction = 64.0 / 1024.0;
    u.seconds = 12.3;
    EXPECT_EQ(formatProgress(u), "reference: 64 / 1024 spp, 12.3 s, ~3 min left");
    u.done = u.total;
    u.fraction = 1.0;
    u.detail = "all";
    EXPECT_EQ(formatProgress(u), "reference: 1024 / 1024 spp (all), 12.3 s");
}

// prepare() reports its progress to the sink, mip by mip, and refuses (before allocating) a
// prefilter past render.timeBudgetSeconds or a map past render.memoryBudgetMB.
TEST_F(EnvironmentGL, PrepareReportsProgressAndKeepsToTheBudgets) {
    EnvironmentSettings s;
    s.enabled = true;
    s.file = "builtin:constant";
    s.cubeSize = 64;
    s.samples = 8;
    gl::GpuTimer timer;
    std::vector<ProgressUpdate> heard;
    {
        Environment env;
        timer.beginFrame();
        env.prepare(s, timer, RenderSettings{}, [&](const ProgressUpdate& u) { heard.push_back(u); });
        timer.endFrame();
        ASSERT_TRUE(env.ready());
        ASSERT_FALSE(heard.empty());
        EXPECT_EQ(heard.back().task, "environment prefilter");
        EXPECT_EQ(heard.back().done, double(env.mips().size()));
        EXPECT_EQ(heard.back().total, double(env.mips().size()));
        EXPECT_DOUBLE_EQ(heard.back().fraction, 1.0);
        for (size_t i = 1; i < heard.size(); ++i) EXPECT_GE(heard[i].fraction, heard[i - 1].fraction);
    }
    {
        Environment env;
        RenderSettings render;
        render.timeBudgetSeconds = 1e-6f;
        timer.beginFrame();
        try {
            env.prepare(s, timer, render);
            ADD_FAILURE() << "a prefilter past the time budget ran";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("render.timeBudgetSeconds"), std::string::npos) << e.what();
        }
        timer.endFrame();
        EXPECT_FALSE(env.ready());
    }
    {
        std::filesystem::path file = test::tempDir() / "small.hdr";
        writeRadiance(file, "-Y 8 +X 16", std::string(16 * 8 * 4, char(128)));
        s.file = file.string();
        Environment env;
        RenderSettings render;
        render.memoryBudgetMB = 0.001f;  // 1 KiB; decoding 16x8 takes 3 KiB
        timer.beginFrame();
        try {
            env.prepare(s, timer, render);
            ADD_FAILURE() << "a map past the memory budget loaded";
        } catch (const Error& e) {
            EXPECT_ERROR_NAMES(std::string(e.what()), "small.hdr", "render.memoryBudgetMB");
        }
        timer.endFrame();
        EXPECT_FALSE(env.ready());
    }
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

// A technique that does not gather the environment says so; technique none, which does, and an
// environment switched off or scaled to nothing say nothing.
TEST(Environment, TechniquesThatDoNotGatherItSaySo) {
    FrameSettings fs;
    fs.environment.enabled = true;
    ASSERT_TRUE(findPass("vct") && findPass("vct")->gathersSky) << "VCT's cones read the sky";
    for (const PassInfo& p : passRegistry()) {
        if (p.role != PassRole::Technique) continue;
        fs.technique = std::string(p.name);
        bool noted = EnvironmentSettings::notes(fs).find("technique " + fs.technique) != std::string::npos;
        EXPECT_EQ(noted, !p.gathersSky) << p.name;
    }
    fs.technique = "none";
    EXPECT_EQ(EnvironmentSettings::notes(fs), "");
    fs.technique = "vct";
    fs.environment.intensity = 0.0f;
    EXPECT_EQ(EnvironmentSettings::notes(fs), "");
    fs.environment.intensity = 1.0f;
    fs.environment.enabled = false;
    EXPECT_EQ(EnvironmentSettings::notes(fs), "");
}

}  // namespace
}  // namespace gi
