// SSAO: the kernel and noise tile (CPU), and GL tests on G-buffers the Renderer draws: flat
// ground is unoccluded, a crease is darker than open floor, radius and strength switch the
// effect off, disabled fills ones, two runs give the same pixels, and radius and bias follow the
// scene's size (the same scene 100x larger gives the same AO at the default settings).
#include "gi/preset/preset.h"
#include "gi/render/renderer.h"
#include "gi/scene/mesh_builder.h"
#include "gi/ssao/ssao.h"
#include "test_util.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

namespace gi {
namespace {

constexpr int kSize = 128;
// The built-in Cornell box's diagonal: the fixtures below run the pass directly with settings
// meaning what they did in metres there (the defaults are 0.5 m and 0.025 m).
const float kCornellDiagonal = std::sqrt(12.0f);

// A large floor at y = 0, optionally with a wall at z = -1 facing +z: the crease runs along x.
Scene floorScene(bool wall) {
    Scene s;
    s.name = "ssaoFloor";
    MeshBuilder b(s);
    int grey = b.material("grey", glm::vec3(0.5f), 1.0f);
    b.quad(grey, {-20, 0, 20}, {40, 0, 0}, {0, 0, -21});
    if (wall) b.quad(grey, {-20, 0, -1}, {40, 0, 0}, {0, 10, 0});
    s.finalize();
    return s;
}

FrameSettings frame(glm::vec3 eye, glm::vec3 target, glm::vec3 up = {0, 1, 0}) {
    FrameSettings fs;
    fs.camera.eye = eye;
    fs.camera.target = target;
    fs.camera.up = up;
    fs.camera.near = 0.05f;
    fs.camera.far = 100.0f;
    fs.lights.clear();
    fs.width = fs.height = kSize;
    return fs;
}

GLuint viewTexture(const Renderer& r, const std::string& name) {
    for (const DebugView& v : r.debugViews())
        if (v.name == name) return v.texture;
    ADD_FAILURE() << "renderer has no view " << name;
    return 0;
}

// Draws the scene's G-buffer and runs SSAO on it; keeps both alive for read-back.
struct Fixture {
    Renderer renderer;
    SSAO ssao;
    FrameSettings fs;

    Fixture(const Scene& scene, const FrameSettings& frameSettings) : fs(frameSettings) {
        renderer.setScene(scene);
        renderer.render(fs);
    }
    glm::mat4 view() const { return viewMatrix(fs.camera); }
    glm::mat4 proj() const { return projectionMatrix(fs.camera, float(fs.width) / float(fs.height)); }

    std::vector<float> run(const SSAOSettings& s) {
        gl::GpuTimer timer;
        timer.beginFrame();
        ssao.execute(s, viewTexture(renderer, "depth"), viewTexture(renderer, "normal"), fs.width, fs.height, view(),
                     proj(), kCornellDiagonal, timer);
        timer.endFrame();
        timer.resolve(true);
        std::vector<float> ao(size_t(fs.width) * fs.height);
        glGetTextureImage(ssao.aoTexture(), 0, GL_RED, GL_FLOAT, GLsizei(ao.size() * sizeof(float)), ao.data());
        return ao;
    }

    // The pixel a world point lands on (bottom row first, as GL reads back).
    glm::ivec2 pixelOf(glm::vec3 p) const {
        glm::vec4 clip = proj() * view() * glm::vec4(p, 1.0f);
        glm::vec2 uv = glm::vec2(clip) / clip.w * 0.5f + 0.5f;
        return glm::ivec2(uv * glm::vec2(fs.width, fs.height));
    }
};

// Mean of the (2h) x (2h) pixels around `c`.
float meanAround(const std::vector<float>& ao, glm::ivec2 c, int h = 2) {
    float sum = 0.0f;
    for (int y = c.y - h; y < c.y + h; ++y)
        for (int x = c.x - h; x < c.x + h; ++x) sum += ao[size_t(y) * kSize + x];
    return sum / float(4 * h * h);
}

TEST(SSAOKernel, HemisphereDenserNearOriginAndDeterministic) {
    for (int count : {4, 16, 64}) {
        std::vector<glm::vec3> k = ssaoKernel(count);
        ASSERT_EQ(k.size(), size_t(count));
        EXPECT_EQ(k, ssaoKernel(count));
        for (const glm::vec3& p : k) {
            EXPECT_GE(p.z, 0.0f);
            EXPECT_LE(glm::length(p), 1.0f);
        }
    }
    // The accelerating scale: the first quarter of 64 samples lies well inside the last quarter.
    std::vector<glm::vec3> k = ssaoKernel(64);
    float first = 0.0f, last = 0.0f;
    for (int i = 0; i < 16; ++i) {
        first += glm::length(k[i]);
        last += glm::length(k[48 + i]);
    }
    EXPECT_LT(first, 0.3f * last);
}

TEST(SSAOKernel, NoiseTileIsSixteenStratifiedRotations) {
    std::array<glm::vec2, 16> n = ssaoNoise();
    EXPECT_EQ(n, ssaoNoise());
    std::array<int, 16> perSector{};
    for (const glm::vec2& r : n) {
        EXPECT_NEAR(glm::length(r), 1.0f, 1e-5f);
        float a = std::atan2(r.y, r.x);
        if (a < 0.0f) a += glm::two_pi<float>();
        ++perSector[std::min(int(a / glm::two_pi<float>() * 16.0f), 15)];
    }
    for (int c : perSector) EXPECT_EQ(c, 1);
}

class SSAOTest : public test::GLTest {};

TEST_F(SSAOTest, FlatFloorSeenFromAboveIsUnoccluded) {
    Fixture f(floorScene(false), frame({0, 3, 0}, {0, 0, 0}, {0, 0, -1}));
    SSAOSettings s;
    s.enabled = true;
    std::vector<float> ao = f.run(s);
    EXPECT_GE(meanAround(ao, {kSize / 2, kSize / 2}, 8), 0.97f);
    EXPECT_GE(*std::min_element(ao.begin(), ao.end()), 0.9f);
}

TEST_F(SSAOTest, FlatFloorSeenObliquelyIsUnoccluded) {
    // 35 degrees above the ground: the half-pixel depth slope stays under the default bias.
    Fixture f(floorScene(false), frame({0, 1.4f, 2.0f}, {0, 0, 0}));
    SSAOSettings s;
    s.enabled = true;
    std::vector<float> ao = f.run(s);
    EXPECT_GE(meanAround(ao, {kSize / 2, kSize / 2}, 8), 0.97f);
}

TEST_F(SSAOTest, CreaseIsDarkerThanOpenFloor) {
    Fixture f(floorScene(true), frame({0, 1.3f, 1.8f}, {0, 0.4f, -0.5f}));
    SSAOSettings s;
    s.enabled = true;
    std::vector<float> ao = f.run(s);
    glm::ivec2 nearCrease = f.pixelOf({0, 0, -0.95f});
    glm::ivec2 farFloor = f.pixelOf({0, 0, 0.0f});  // twice the radius from the wall
    glm::ivec2 wall = f.pixelOf({0, 0.9f, -1.0f});  // high on the wall, far from the floor
    ASSERT_GT(nearCrease.y, 4);
    ASSERT_LT(wall.y, kSize - 4);
    ASSERT_GT(farFloor.y, 4);
    float crease = meanAround(ao, nearCrease);
    float open = meanAround(ao, farFloor);
    EXPECT_LT(crease, open - 0.1f) << "crease " << crease << ", open floor " << open;
    EXPECT_GE(open, 0.95f);
    EXPECT_GE(meanAround(ao, wall), 0.95f);
}

TEST_F(SSAOTest, TinyRadiusOrZeroStrengthGivesOne) {
    Fixture f(floorScene(true), frame({0, 1.3f, 1.8f}, {0, 0.4f, -0.5f}));
    SSAOSettings s;
    s.enabled = true;
    s.radius = 0.001f;  // 3.5 mm, under the 25 mm bias: nothing can count as occluded
    std::vector<float> ao = f.run(s);
    EXPECT_GE(*std::min_element(ao.begin(), ao.end()), 0.99f);

    s = SSAOSettings{};
    s.enabled = true;
    s.strength = 0.0f;
    ao = f.run(s);
    EXPECT_EQ(*std::min_element(ao.begin(), ao.end()), 1.0f);
}

TEST_F(SSAOTest, ViewsShowGreyAndDisabledFillsOnes) {
    Fixture f(floorScene(true), frame({0, 1.3f, 1.8f}, {0, 0.4f, -0.5f}));
    SSAOSettings s;
    s.enabled = true;
    std::vector<float> before = f.run(s);

    EXPECT_EQ(f.ssao.memoryBytes(), SSAO::estimateBytes(kSize, kSize));
    std::vector<DebugView> views = f.ssao.debugViews();
    ASSERT_EQ(views.size(), 2u);
    EXPECT_EQ(views[0].name, "ssaoRaw");
    EXPECT_EQ(views[1].name, "ssao");
    EXPECT_EQ(views[1].texture, f.ssao.aoTexture());
    // The previewer shows the one-channel AO as grey, crease included, not as red.
    std::vector<uint8_t> px = f.renderer.renderViewImage(views[1], kSize, kSize);
    int darkest = 255;
    for (size_t i = 0; i < px.size(); i += 4) {
        ASSERT_EQ(px[i], px[i + 1]);
        ASSERT_EQ(px[i], px[i + 2]);
        darkest = std::min<int>(darkest, px[i]);
    }
    EXPECT_LT(darkest, 230);

    s.enabled = false;
    std::vector<float> ao = f.run(s);
    EXPECT_EQ(*std::min_element(ao.begin(), ao.end()), 1.0f);
    std::string log;
    EXPECT_TRUE(f.ssao.reloadShaders(log)) << log;
    // A reloaded program gets its kernel and noise again.
    s.enabled = true;
    EXPECT_EQ(f.run(s), before);
}

TEST_F(SSAOTest, TwoRunsGiveTheSamePixels) {
    Fixture f(floorScene(true), frame({0, 1.3f, 1.8f}, {0, 0.4f, -0.5f}));
    SSAOSettings s;
    s.enabled = true;
    s.sampleCount = 32;
    std::vector<float> first = f.run(s);
    // A second instance builds its kernel and noise afresh from the same seed.
    auto other = std::make_unique<SSAO>();
    gl::GpuTimer timer;
    timer.beginFrame();
    other->execute(s, viewTexture(f.renderer, "depth"), viewTexture(f.renderer, "normal"), kSize, kSize, f.view(),
                   f.proj(), kCornellDiagonal, timer);
    timer.endFrame();
    std::vector<float> second(first.size());
    glGetTextureImage(other->aoTexture(), 0, GL_RED, GL_FLOAT, GLsizei(second.size() * sizeof(float)), second.data());
    EXPECT_EQ(first, second);
    EXPECT_EQ(first, f.run(s));
}

// The AO the renderer computes for a whole frame (the "ssao" view), at the default settings.
std::vector<float> frameAO(const Scene& scene, const FrameSettings& fs) {
    Renderer renderer;
    renderer.setScene(scene);
    renderer.render(fs);
    std::vector<float> ao(size_t(fs.width) * fs.height);
    glGetTextureImage(viewTexture(renderer, "ssao"), 0, GL_RED, GL_FLOAT, GLsizei(ao.size() * sizeof(float)), ao.data());
    return ao;
}

TEST_F(SSAOTest, SameSceneAHundredTimesLargerGivesTheSameAO) {
    // The built-in Cornell box in metres and in centimetres (every position, the camera and the
    // light times 100): radius and bias are fractions of the scene's diagonal, so the defaults
    // give the same AO. In metres they would reach 1/100 as far in the larger one.
    Scene metres = makeBuiltinScene("cornell");
    Scene centimetres = metres;
    const float k = 100.0f;
    for (Vertex& v : centimetres.vertices) v.position *= k;
    centimetres.bounds.min *= k;
    centimetres.bounds.max *= k;
    for (LightSettings& l : centimetres.lights) l.position *= k;
    EXPECT_NEAR(ssaoSceneDiagonal(metres.bounds), kCornellDiagonal, 1e-4f);
    EXPECT_NEAR(ssaoSceneDiagonal(centimetres.bounds), k * kCornellDiagonal, 1e-2f);

    Preset p;
    p.header.scene = "cornell";
    p.lightsFromScene = true;
    FrameSettings fs = frameSettings(p, metres, kSize, kSize);
    fs.ssao.enabled = true;
    FrameSettings large = frameSettings(p, centimetres, kSize, kSize);
    large.ssao.enabled = true;
    large.camera.eye *= k;
    large.camera.target *= k;
    large.camera.near *= k;
    large.camera.far *= k;

    std::vector<float> a = frameAO(metres, fs);
    std::vector<float> b = frameAO(centimetres, large);
    // Not trivially equal: the box's creases are occluded.
    float darkest = *std::min_element(a.begin(), a.end());
    EXPECT_LT(darkest, 0.7f);
    double sum = 0.0;
    float worst = 0.0f;
    for (size_t i = 0; i < a.size(); ++i) {
        float d = std::abs(a[i] - b[i]);
        sum += d;
        worst = std::max(worst, d);
    }
    double mean = sum / double(a.size());
    std::printf("darkest %.3f, mean |difference| %.5f, largest %.4f\n", darkest, mean, worst);
    EXPECT_LT(mean, 0.002);
    EXPECT_LT(worst, 0.02f);
}

}  // namespace
}  // namespace gi
