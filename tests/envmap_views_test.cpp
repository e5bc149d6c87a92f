// Views of the prefiltered environment (the Roughness mips panel and `gi-render --views`): the
// latlong view of mip 0 shows the map where gi/envmap/envmap_image.h's convention puts it (the
// zenith row blue, the ground row dark, pixel for pixel against sampleEnvironment), a rough mip
// is smoother than mip 0, the cross puts +y above +z, and the runner writes every mip.
#include "common/shared.h"
#include "gi/envmap/environment.h"
#include "gi/render/image_io.h"
#include "gi/render/renderer.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace gi {
namespace {

constexpr int kW = 128, kH = 64;

class EnvironmentViews : public test::GLTest {};

// The built-in sky prefiltered into a 128^2 chain: 8 mips of the seed's 11 levels.
EnvironmentSettings skySettings() {
    EnvironmentSettings s;
    s.enabled = true;
    s.file = "builtin:sky";
    s.cubeSize = 128;
    s.samples = 32;
    return s;
}

DebugView mipView(const Environment& env, int mode, int level) {
    DebugView v;
    v.name = "environment.mip" + std::to_string(level);
    v.texture = env.prefiltered();
    v.target = GL_TEXTURE_CUBE_MAP;
    v.mode = mode;
    v.width = kW;
    v.height = kH;
    v.level = level;
    return v;
}

// Pixel (x, y) of a renderViewImage result, y counted from the top row.
glm::ivec3 pixel(const std::vector<uint8_t>& img, int width, int height, int x, int yTop) {
    const uint8_t* p = &img[(size_t(height - 1 - yTop) * size_t(width) + size_t(x)) * 4];
    return {p[0], p[1], p[2]};
}

// As shaders/common/color.glsl's linearToSRGB, to 8 bits.
glm::ivec3 srgb8(glm::vec3 c) {
    glm::ivec3 out;
    for (int k = 0; k < 3; ++k) {
        float x = std::clamp(c[k], 0.0f, 1.0f);
        float e = x < 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
        out[k] = int(std::lround(e * 255.0f));
    }
    return out;
}

// What a blur lowers, on the luma of an 8-bit latlong image, each row weighed by its solid angle
// (sin theta: the rows near the poles are stretched): the variance of the pixels, and the mean
// squared difference of neighbouring pixels (right and down).
struct Spread {
    double variance = 0.0, gradient = 0.0;
};
Spread spread(const std::vector<uint8_t>& img, int width, int height) {
    auto luma = [&](int x, int y) {
        glm::ivec3 p = pixel(img, width, height, x, y);
        return 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b;
    };
    double sum = 0.0, sq = 0.0, grad = 0.0, weight = 0.0, gradWeight = 0.0;
    for (int y = 0; y < height; ++y) {
        double w = std::sin((y + 0.5) / height * 3.14159265358979);
        for (int x = 0; x < width; ++x) {
            double l = luma(x, y);
            sum += w * l;
            sq += w * l * l;
            weight += w;
            if (x + 1 < width && y + 1 < height) {
                double dx = luma(x + 1, y) - l, dy = luma(x, y + 1) - l;
                grad += w * (dx * dx + dy * dy);
                gradWeight += w;
            }
        }
    }
    double mean = sum / weight;
    return {sq / weight - mean * mean, grad / gradWeight};
}

TEST_F(EnvironmentViews, LatLongOfMipZeroIsTheMap) {
    Renderer renderer;
    Environment env;
    gl::GpuTimer timer;
    timer.beginFrame();
    env.prepare(skySettings(), timer);
    timer.endFrame();
    ASSERT_TRUE(env.ready());
    ASSERT_EQ(env.mips().size(), 8u);
    std::vector<uint8_t> img = renderer.renderViewImage(mipView(env, shared::kViewCubeLatLong, 0), kW, kH);
    const EnvironmentImage& sky = env.image();
    // Rows near the zenith, in the sky, and in the ground, away from the horizon's step and the
    // sun (at u = 0.62, 30 degrees up).
    for (int y : {1, 4, 12, 44, 56, 62})
        for (int x : {3, 30, 64, 100, 125}) {
            glm::vec3 dir = latLongDirection({(float(x) + 0.5f) / kW, (float(y) + 0.5f) / kH}, 0.0f);
            glm::ivec3 expected = srgb8(sampleEnvironment(sky, dir, 0.0f));
            glm::ivec3 got = pixel(img, kW, kH, x, y);
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], expected[k], 6) << "pixel (" << x << ", " << y << ") channel " << k;
        }
    glm::ivec3 zenith = pixel(img, kW, kH, kW / 2, 0), ground = pixel(img, kW, kH, kW / 2, kH - 1);
    EXPECT_GT(zenith.b, zenith.r + 60) << "the top row is the blue zenith";
    EXPECT_LT(std::max({ground.r, ground.g, ground.b}), 130) << "the bottom row is the dark ground";
    EXPECT_GT(zenith.b, ground.b + 80);
    // The cross's top cell is +y (blue), its bottom cell -y (ground): the cell above +z.
    std::vector<uint8_t> cross = renderer.renderViewImage(mipView(env, shared::kViewCubeCross, 0), 128, 96);
    glm::ivec3 top = pixel(cross, 128, 96, 48, 16), bottom = pixel(cross, 128, 96, 48, 80);
    EXPECT_GT(top.b, top.r + 60) << "+y above +z";
    EXPECT_LT(bottom.b, 130) << "-y below +z";
}

TEST_F(EnvironmentViews, RougherMipIsSmoother) {
    Renderer renderer;
    Environment env;
    gl::GpuTimer timer;
    timer.beginFrame();
    env.prepare(skySettings(), timer);
    timer.endFrame();
    ASSERT_TRUE(env.ready());
    const size_t last = env.mips().size() - 1;
    ASSERT_EQ(env.mips()[5].roughness, 0.3f);
    ASSERT_EQ(env.mips()[last].roughness, 1.0f) << "the table's last entry goes on the last mip";
    auto at = [&](size_t m) { return spread(renderer.renderViewImage(mipView(env, shared::kViewCubeLatLong, int(m)), kW, kH), kW, kH); };
    Spread sharp = at(0), medium = at(5), rough = at(last);
    // Measured on llvmpipe: variance 1526, 1210, 142; neighbour difference 224, 145, 20. The
    // sky-ground split keeps most of the variance until the lobe spans the hemisphere.
    EXPECT_LT(medium.variance, 0.9 * sharp.variance);
    EXPECT_LT(medium.gradient, 0.75 * sharp.gradient);
    EXPECT_LT(rough.variance, 0.2 * sharp.variance);
    EXPECT_LT(rough.gradient, 0.2 * sharp.gradient);
    EXPECT_LT(rough.variance, medium.variance);
}

// gi-render --views writes each mip as a 256 x 128 latlong and all of them on one sheet.
TEST(EnvironmentViewsCLI, RunnerWritesEveryMip) {
    auto out = test::tempDir();
    std::string cmd = std::string(GI_RENDER_EXE) + " " + std::string(GI_PRESET_DIR) +
                      "/environment_spheres.json --set environment.file=builtin:sky --set environment.cubeSize=32"
                      " --set environment.samples=16 --width 64 --height 48 --views --out " + out.string();
    auto r = test::runCommand(cmd);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    // 32^2 halves five times: 6 mips of the 11 table entries.
    for (int m = 0; m < 6; ++m) {
        std::filesystem::path file = out / "views" / ("environment.mip" + std::to_string(m) + ".png");
        ASSERT_TRUE(std::filesystem::exists(file)) << file;
        ImageRGBA8 img = readImage8(file);
        EXPECT_EQ(img.width, 256);
        EXPECT_EQ(img.height, 128);
        // Top row first here: the sky above, the ground below.
        const uint8_t* top = &img.rgba[(size_t(0) * 256 + 128) * 4];
        const uint8_t* bottom = &img.rgba[(size_t(127) * 256 + 128) * 4];
        EXPECT_GT(top[2], bottom[2]) << "mip " << m;
    }
    EXPECT_FALSE(std::filesystem::exists(out / "views" / "environment.mip6.png"));
    ImageRGBA8 sheet = readImage8(out / "views" / "environment.mips.png");
    EXPECT_EQ(sheet.width, 4 * 256 + 3 * 4);
    EXPECT_EQ(sheet.height, 2 * 128 + 4);
}

}  // namespace
}  // namespace gi
