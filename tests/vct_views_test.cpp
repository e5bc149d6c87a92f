// VCT previewers: the voxel view shows a known voxel at the pixel it projects to and background
// where the ray meets nothing (dense and clipmap grids, the latter with a toroidal offset), and
// the cone glyphs follow trace.glsl's tangent frame and trace.comp's specular cone.
#include "gi/render/renderer.h"
#include "gi/scene/camera.h"
#include "gi/scene/mesh_builder.h"
#include "gi/vct/vct_views.h"
#include "test_util.h"

#include <algorithm>

namespace gi {
namespace {

constexpr int kSize = 128;

// A grey floor over [-2, 2]^2 at y = 0 and a red box of half size 0.75 on it, at the origin.
Scene boxScene() {
    Scene s;
    s.name = "redBox";
    MeshBuilder b(s);
    int grey = b.material("grey", glm::vec3(0.5f), 1.0f);
    int red = b.material("red", glm::vec3(0.8f, 0.05f, 0.05f), 1.0f);
    b.quad(grey, {-2, 0, 2}, {4, 0, 0}, {0, 0, -4});
    b.box(red, {0.0f, 0.75f, 0.0f}, glm::vec3(0.75f), 0.0f);
    s.finalize();
    return s;
}

FrameSettings boxFrame(VCTMode mode) {
    FrameSettings fs;
    fs.camera.eye = {0.0f, 0.75f, 5.0f};
    fs.camera.target = {0.0f, 0.75f, 0.0f};
    fs.camera.near = 0.05f;
    LightSettings sun;
    sun.direction = {0.2f, -0.8f, -0.6f};  // lights the box's top and front
    fs.lights = {sun};
    fs.technique = "vct";
    fs.vct.gridResolution = 32;
    fs.vct.mode = mode;
    fs.vct.levelCount = 2;
    // Clipmap: the finest level spans the camera +- 5.5, which holds the box, and sits off the
    // lattice origin, so the toroidal offset is not zero. Its voxels (11/32) do not divide the
    // box's size, so conservative voxelization does not grow the box by a whole voxel.
    if (mode != VCTMode::Dense) fs.vct.levelExtent = 11.0f;
    fs.width = fs.height = kSize;
    return fs;
}

struct Pixel {
    int r, g, b;
};

Pixel pixelAt(const std::vector<uint8_t>& img, const glm::mat4& viewProj, const glm::vec3& world) {
    glm::vec4 c = viewProj * glm::vec4(world, 1.0f);
    int x = std::clamp(int((c.x / c.w * 0.5f + 0.5f) * kSize), 0, kSize - 1);
    int y = std::clamp(int((c.y / c.w * 0.5f + 0.5f) * kSize), 0, kSize - 1);  // bottom row first
    const uint8_t* p = &img[(size_t(y) * kSize + size_t(x)) * 4];
    return {p[0], p[1], p[2]};
}

class VCTViews : public test::GLTest, public ::testing::WithParamInterface<VCTMode> {};
class VCTPick : public test::GLTest {};

TEST_P(VCTViews, VoxelViewShowsTheBoxAndBackground) {
    Scene scene = boxScene();
    FrameSettings fs = boxFrame(GetParam());
    Renderer renderer;
    renderer.setScene(scene);
    renderer.render(fs);

    std::vector<VoxelGridView> grids = voxelGrids(renderer.debugViews(), fs, scene.bounds);
    ASSERT_EQ(grids.size(), GetParam() == VCTMode::Dense ? 1u : 2u);
    if (GetParam() == VCTMode::Clipmap) {
        EXPECT_NE(grids[0].wrap, glm::ivec3(0));
    }

    VoxelView view;
    VoxelViewParams params;
    params.viewProj = projectionMatrix(fs.camera, 1.0f) * viewMatrix(fs.camera);
    params.background = glm::vec3(0.0f, 0.0f, 1.0f);
    std::vector<uint8_t> img = view.renderImage(grids, params, kSize, kSize);

    // The box's front face: red voxels.
    Pixel box = pixelAt(img, params.viewProj, {0.0f, 0.75f, 0.75f});
    EXPECT_GT(box.r, 120);
    EXPECT_LT(box.g, box.r / 2);
    EXPECT_LT(box.b, box.r / 2);
    // The floor beside it: grey voxels.
    Pixel floor = pixelAt(img, params.viewProj, {1.4f, 0.0f, 1.2f});
    EXPECT_GT(floor.r, 100);
    EXPECT_NEAR(floor.r, floor.g, 6);
    EXPECT_NEAR(floor.r, floor.b, 6);
    // Above the box the ray crosses empty voxels and leaves the grid: background.
    Pixel empty = pixelAt(img, params.viewProj, {0.0f, 3.0f, -2.0f});
    EXPECT_EQ(empty.r, 0);
    EXPECT_EQ(empty.g, 0);
    EXPECT_EQ(empty.b, 255);

    // Radiance: the lit front face is solid and red, the empty space still background.
    params.source = VoxelViewSource::Radiance;
    img = view.renderImage(grids, params, kSize, kSize);
    Pixel lit = pixelAt(img, params.viewProj, {0.0f, 0.75f, 0.75f});
    EXPECT_GT(lit.r, 40);
    EXPECT_LT(lit.g, lit.r / 2);
    EXPECT_LT(lit.b, lit.r / 2);
    EXPECT_EQ(pixelAt(img, params.viewProj, {0.0f, 3.0f, -2.0f}).b, 255);
}

INSTANTIATE_TEST_SUITE_P(Modes, VCTViews, ::testing::Values(VCTMode::Dense, VCTMode::Clipmap),
                         [](const auto& info) { return std::string(enumName(info.param)); });

// The surface under a pixel is the one the camera sees there: the red box's front face (z = 0.75,
// normal +z, the material's roughness 1) at the centre, nothing in the sky.
TEST_F(VCTPick, PickSurfaceReconstructsTheGBufferPoint) {
    Scene scene = boxScene();
    FrameSettings fs = boxFrame(VCTMode::Dense);
    Renderer renderer;
    renderer.setScene(scene);
    renderer.render(fs);
    SurfacePick pick;
    ASSERT_TRUE(renderer.pickSurface({kSize / 2, kSize / 2}, pick));
    EXPECT_NEAR(pick.position.x, 0.0f, 0.03f);
    EXPECT_NEAR(pick.position.y, 0.75f, 0.03f);
    EXPECT_NEAR(pick.position.z, 0.75f, 0.01f);
    EXPECT_GT(pick.normal.z, 0.99f);
    EXPECT_NEAR(pick.roughness, 1.0f, 0.01f);
    EXPECT_FALSE(renderer.pickSurface({kSize / 2, kSize - 1}, pick)) << "the top row sees the sky";
}

// Glyph strokes land where their world points project: a stroke across the image colours the
// pixels under it, a dot a small disc, and pixels away from both stay as they were.
TEST(VCTConeGlyphs, StrokesAreDrawnWhereTheyProject) {
    const int w = 64, h = 48;
    std::vector<uint8_t> img(size_t(w) * h * 4, 0);
    glm::mat4 identity(1.0f);  // world x, y in [-1, 1] are the image
    std::vector<GlyphLine> lines = {{{-0.5f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f, 1.0f}, 2.0f},
                                    {{0.0f, 0.5f, 0.0f}, {0.0f, 0.5f, 0.0f}, {0.0f, 1.0f, 0.0f, 1.0f}, 6.0f}};
    drawGlyphLines(img, w, h, identity, lines);
    auto at = [&](int x, int y) { return &img[(size_t(y) * w + x) * 4]; };
    // The line at y = h / 2 from x = w / 4 to 3 w / 4.
    EXPECT_EQ(at(w / 2, h / 2)[0], 255);
    EXPECT_EQ(at(w / 4 + 2, h / 2)[0], 255);
    EXPECT_EQ(at(w / 8, h / 2)[0], 0) << "beyond the line's end";
    EXPECT_EQ(at(w / 2, h / 2 + 4)[0], 0) << "off the line's width";
    // The dot at (w / 2, 3 h / 4): green inside its radius of 3 pixels, untouched outside.
    EXPECT_EQ(at(w / 2, 3 * h / 4)[1], 255);
    EXPECT_EQ(at(w / 2 + 5, 3 * h / 4)[1], 0);
    // Half-transparent strokes blend.
    std::vector<uint8_t> grey(size_t(w) * h * 4, 100);
    drawGlyphLines(grey, w, h, identity, {{{-1.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f, 0.5f}, 3.0f}});
    EXPECT_NEAR(int(grey[(size_t(h / 2) * w + w / 2) * 4]), 178, 1);  // 100 + (255 - 100) / 2
    // A stroke behind the camera (w <= 0) is skipped, not drawn mirrored.
    glm::mat4 flip(1.0f);
    flip[3][3] = -1.0f;
    std::vector<uint8_t> clean(size_t(w) * h * 4, 0);
    drawGlyphLines(clean, w, h, flip, lines);
    EXPECT_EQ(std::count(clean.begin(), clean.end(), uint8_t(0)), std::ptrdiff_t(clean.size()));
}

// The glyph strokes: per cone an axis, a 32-segment aperture circle and two silhouettes, a start
// dot where the nudge lies within the drawn length, and the apex's two dots.
TEST(VCTConeGlyphs, StrokesPerCone) {
    VCTSettings s;
    s.coneSet = ConeSetKind::Six;
    s.specularCone = false;
    s.nudge = 1.0f;
    std::vector<ConeGlyph> glyphs = vctConeGlyphs(s, glm::vec3(0.0f), {0.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 5.0f}, 0.5f, 0.1f);
    ASSERT_EQ(glyphs.size(), 6u);
    std::vector<GlyphLine> lines = coneGlyphLines(glyphs, 1.2f);
    EXPECT_EQ(lines.size(), 6u * (1 + 1 + 32 + 2) + 2);
    // The aperture circle of the first cone (along the normal) has radius length * tan(30 deg).
    const GlyphLine& rim = lines[2];
    EXPECT_NEAR(glm::length(rim.a - glm::vec3(0.0f, 1.2f, 0.0f)), 1.2f * std::tan(glm::radians(30.0f)), 1e-4f);
}

TEST(VCTConeGlyphs, TangentFrameIsOrthonormalAroundTheNormal) {
    for (glm::vec3 n : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(0, 1, 0), glm::normalize(glm::vec3(0.3f, -0.5f, -0.8f)),
                        glm::normalize(glm::vec3(-0.7f, 0.2f, 0.1f))}) {
        glm::mat3 f = vctTangentFrame(n);
        for (int i = 0; i < 3; ++i) {
            EXPECT_NEAR(glm::length(f[i]), 1.0f, 1e-5f);
            for (int j = i + 1; j < 3; ++j) EXPECT_NEAR(glm::dot(f[i], f[j]), 0.0f, 1e-5f);
        }
        EXPECT_NEAR(glm::length(f[2] - n), 0.0f, 1e-6f);
        EXPECT_GT(glm::dot(glm::cross(f[0], f[1]), n), 0.0f);  // right-handed
    }
}

TEST(VCTConeGlyphs, DiffuseSetInTheHemisphereAndSpecularAlongTheReflection) {
    VCTSettings s;
    s.coneSet = ConeSetKind::Nine;
    s.nudge = 2.0f;
    glm::vec3 p(1, 2, 3), n = glm::normalize(glm::vec3(0.2f, 1.0f, -0.3f)), eye(4, 6, 8);
    std::vector<ConeGlyph> g = vctConeGlyphs(s, p, n, eye, 0.5f, 0.1f);
    ASSERT_EQ(g.size(), 10u);
    float weights = 0.0f;
    for (size_t i = 0; i < 9; ++i) {
        EXPECT_FALSE(g[i].specular);
        EXPECT_GT(glm::dot(g[i].direction, n), 0.5f);  // nine: at most 54.7 degrees off the normal
        EXPECT_NEAR(g[i].tanHalf, std::tan(glm::radians(30.0f)), 1e-5f);
        EXPECT_GE(g[i].start, 2.0f * 0.1f * 1.7320508f - 1e-5f);
        weights += g[i].weight;
    }
    EXPECT_NEAR(weights, 1.0f, 1e-5f);
    // The first cone of the nine is along the normal.
    EXPECT_NEAR(glm::length(g[0].direction - n), 0.0f, 1e-5f);
    const ConeGlyph& spec = g[9];
    EXPECT_TRUE(spec.specular);
    glm::vec3 v = glm::normalize(eye - p);
    EXPECT_NEAR(glm::dot(spec.direction, n), glm::dot(v, n), 1e-5f);  // mirror angle
    EXPECT_NEAR(glm::dot(glm::cross(v, n), spec.direction), 0.0f, 1e-5f);  // in the plane of v and n
    EXPECT_NEAR(spec.tanHalf, std::tan(0.5f * glm::radians(0.5f * (1.0f + 80.0f))), 1e-5f);
    s.specularCone = false;
    EXPECT_EQ(vctConeGlyphs(s, p, n, eye, 0.5f, 0.1f).size(), 9u);
}

}  // namespace
}  // namespace gi
