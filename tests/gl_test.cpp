// GL tests on the headless EGL context (Mesa llvmpipe in CI): direct light against the analytic
// radiance, shadows, shader errors and reload, determinism and the memory budget.
#include "gi/gl/buffer_texture.h"
#include "gi/gl/shader.h"
#include "gi/preset/preset.h"
#include "gi/render/renderer.h"
#include "gi/scene/mesh_builder.h"
#include "gi/util/paths.h"
#include "test_util.h"

#include <glm/gtc/constants.hpp>

#include <fstream>
#include <set>

namespace gi {
namespace {

constexpr int kSize = 128;

// A large grey floor at y = 0, optionally with a floating plate at y = plateY over [-0.5, 0.5]^2.
Scene floorScene(float albedo, bool plate, float plateY = 1.0f) {
    Scene s;
    s.name = "floor";
    MeshBuilder b(s);
    int grey = b.material("grey", glm::vec3(albedo), 1.0f);
    b.quad(grey, {-20, 0, 20}, {40, 0, 0}, {0, 0, -40});
    if (plate) b.quad(grey, {-0.5f, plateY, 0.5f}, {1, 0, 0}, {0, 0, -1});
    s.finalize();
    return s;
}

FrameSettings frame(glm::vec3 eye, glm::vec3 target, LightSettings light) {
    FrameSettings fs;
    fs.camera.eye = eye;
    fs.camera.target = target;
    fs.camera.near = 0.01f;
    fs.lights = {light};
    fs.render.ambient = glm::vec3(0.0f);
    fs.render.specular = false;
    fs.toneMap.op = ToneMapper::Linear;
    fs.width = fs.height = kSize;
    return fs;
}

// Mean HDR radiance of the 4x4 pixels at the image centre (the camera target).
glm::vec3 centreRadiance(const Renderer& r) {
    std::vector<float> px = r.readHDR();
    glm::vec3 sum(0.0f);
    for (int y = kSize / 2 - 2; y < kSize / 2 + 2; ++y)
        for (int x = kSize / 2 - 2; x < kSize / 2 + 2; ++x)
            sum += glm::vec3(px[(y * kSize + x) * 4], px[(y * kSize + x) * 4 + 1], px[(y * kSize + x) * 4 + 2]);
    return sum / 16.0f;
}

class GL : public test::GLTest {};

TEST_F(GL, ContextIsOpenGL45Core) {
    GLint major = 0, minor = 0, profile = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    EXPECT_GE(major * 10 + minor, 45);
    EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
    std::printf("renderer: %s\n", glRendererString().c_str());
}

// The grids LPV and diffusion view as buffer textures: one past this GL's limit is refused with
// the setting named, one within it passes.
TEST_F(GL, BufferTextureLimitIsCheckedNamingTheSetting) {
    GLint max = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max);
    ASSERT_GE(max, 65536) << "GL 4.5's minimum";
    EXPECT_NO_THROW(gl::requireBufferTexels(size_t(max), "lpv.gridResolution"));
    try {
        gl::requireBufferTexels(size_t(max) + 1, "lpv.gridResolution");
        FAIL() << "a view one texel past the limit was accepted";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind("lpv.gridResolution: ", 0), 0u) << e.what();
        EXPECT_NE(std::string(e.what()).find(std::to_string(max)), std::string::npos) << e.what();
    }
}

// Issue 17 item 4: with static lights the shadow maps are drawn once and kept; moving a light
// redraws them, and the kept maps give the same pixels as fresh ones. keepStaticWork off redraws
// every frame.
TEST_F(GL, StaticShadowMapsAreKeptAndRedrawnWhenALightMoves) {
    Scene scene = makeBuiltinScene("cornell");
    Preset p;
    FrameSettings fs = frameSettings(p, scene, 64, 48);
    ASSERT_FALSE(fs.lights.empty());
    ASSERT_TRUE(fs.lights[0].castShadows);
    Renderer r;
    r.setScene(scene);
    r.render(fs);
    r.render(fs);
    EXPECT_EQ(r.shadowDrawCount(), 1) << "a static light's maps are drawn once";
    std::vector<float> kept = r.readHDR();
    EXPECT_EQ(test::renderedAfresh(scene, fs)->readHDR(), kept) << "kept maps give the pixels fresh ones do";
    // A camera move keeps the maps, and the frame still matches a fresh renderer's (the G-buffer
    // once relied on the shadow pass to turn depth writes back on before its clear).
    FrameSettings turned = fs;
    turned.camera.eye += glm::vec3(0.3f, -0.2f, 0.0f);
    r.render(turned);
    EXPECT_EQ(r.shadowDrawCount(), 1) << "a camera move keeps the maps";
    EXPECT_EQ(r.readHDR(), test::renderedAfresh(scene, turned)->readHDR()) << "after a camera move";

    FrameSettings moved = fs;
    moved.lights[0].position += glm::vec3(0.2f, 0.0f, 0.0f);
    r.render(moved);
    EXPECT_EQ(r.shadowDrawCount(), 2) << "a moved light redraws them";
    EXPECT_NE(r.readHDR(), kept) << "the moved light's shadows";
    r.render(fs);
    EXPECT_EQ(r.shadowDrawCount(), 3);
    EXPECT_EQ(r.readHDR(), kept);
    fs.render.keepStaticWork = false;
    r.render(fs);
    r.render(fs);
    EXPECT_EQ(r.shadowDrawCount(), 5) << "keepStaticWork off: every frame";
}

// Cluster culling (render.cullClusters, GPUScene::drawIf): a row of spheres (2304 triangles, nine
// clusters each) of which the camera sees the middle, lit by a spot light and a point light whose
// cube faces each see part of the row. The frame must be the same pixels as without culling, with
// fewer triangles drawn in the G-buffer and in the shadow maps.
TEST_F(GL, CulledClustersLeaveThePixelsAsTheyWere) {
    Scene scene;
    MeshBuilder b(scene);
    int grey = b.material("grey", glm::vec3(0.6f), 0.7f);
    b.quad(grey, {-24, 0, 4}, {48, 0, 0}, {0, 0, -8});
    for (int i = -5; i <= 5; ++i) b.sphere(grey, {4.0f * float(i), 1.0f, 0.0f}, 1.0f);
    scene.finalize();
    ASSERT_GT(scene.draws[1].indexCount / 3, 2 * GPUScene::kClusterTriangles) << "a sphere spans several clusters";
    Preset p;
    FrameSettings fs = frameSettings(p, scene, 96, 64);
    fs.camera.eye = {0.5f, 2.0f, 7.0f};
    fs.camera.target = {0.5f, 1.0f, 0.0f};
    fs.camera.fovY = 40.0f;
    LightSettings spot;
    spot.type = LightType::Spot;
    spot.position = {0.0f, 6.0f, 3.0f};
    spot.direction = glm::normalize(glm::vec3(0.0f, -1.0f, -0.5f));
    spot.outerConeDeg = 40.0f;
    spot.innerConeDeg = 30.0f;
    spot.intensity = 30.0f;
    LightSettings point;
    point.type = LightType::Point;
    point.position = {2.0f, 2.5f, 2.0f};
    point.intensity = 10.0f;
    fs.lights = {spot, point};
    auto render = [&](bool cull, uint64_t& gbuffer, uint64_t& shadows) {
        FrameSettings f = fs;
        f.render.cullClusters = cull;
        Renderer r;
        r.setScene(scene);
        r.render(f);
        r.resolveTimings();
        for (const PassStats& s : r.passStats()) {
            if (s.name == "gbuffer") gbuffer = s.triangles;
            if (s.name == "shadows") shadows = s.triangles;
        }
        return r.readHDR();
    };
    uint64_t gAll = 0, sAll = 0, gCulled = 0, sCulled = 0;
    std::vector<float> all = render(false, gAll, sAll);
    std::vector<float> culled = render(true, gCulled, sCulled);
    std::printf("triangles drawn, without and with culling: gbuffer %llu, %llu; shadows %llu, %llu\n", (unsigned long long)gAll,
                (unsigned long long)gCulled, (unsigned long long)sAll, (unsigned long long)sCulled);
    EXPECT_EQ(culled, all) << "culling changed pixels";
    int lit = 0;
    for (size_t i = 0; i < all.size(); i += 4) lit += all[i] > 0.01f;
    EXPECT_GT(lit, int(all.size() / 4) / 2) << "too little of the frame is lit to compare";
    const uint64_t triangles = scene.triangleCount();
    EXPECT_EQ(gAll, 2 * triangles) << "without culling: the depth pass and the G-buffer pass draw every triangle";
    EXPECT_EQ(sAll, 7 * triangles) << "without culling: the spot's map and the point light's six faces";
    EXPECT_LT(gCulled, gAll / 2) << "the camera sees three of the eleven spheres";
    EXPECT_LT(sCulled, sAll / 2) << "each cube face sees part of the row";
    // LPV's RSMs (the spot's map and the point light's cube) are culled alike. LPV's injection
    // sums floats with atomics in whatever order the threads run, so two runs of the same RSMs
    // may differ in the last bits, and the RGBA16F frame then by one step of fp16 (this comparison
    // failed once, exact, under a loaded suite): each value within 2^-10 of itself.
    fs.technique = "lpv";
    fs.lpv.gridResolution = 32;
    uint64_t unused = 0;
    std::vector<float> lpvAll = render(false, unused, unused);
    std::vector<float> lpvCulled = render(true, unused, unused);
    ASSERT_EQ(lpvCulled.size(), lpvAll.size());
    double worst = 0.0;
    for (size_t i = 0; i < lpvAll.size(); ++i)
        worst = std::max(worst, std::abs(double(lpvCulled[i]) - lpvAll[i]) / std::max(std::abs(double(lpvAll[i])), 1e-3));
    std::printf("LPV with and without culling: largest relative difference %.2e\n", worst);
    EXPECT_LE(worst, 1.0 / 1024.0) << "culling changed LPV's pixels";
    EXPECT_NE(lpvAll, all) << "LPV added no light";
}

TEST_F(GL, LambertPlaneMatchesAnalyticRadiance) {
    const float albedo = 0.5f;
    Renderer r;
    r.setScene(floorScene(albedo, false));
    const glm::vec3 target(0.3f, 0.0f, -0.2f);
    const glm::vec3 eye(1.0f, 3.0f, 2.0f);

    // Directional: L = albedo / pi * E * cos(theta).
    LightSettings sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(0.4f, -1.0f, 0.3f));
    sun.intensity = 2.0f;
    r.render(frame(eye, target, sun));
    float expected = albedo / glm::pi<float>() * sun.intensity * -sun.direction.y;
    EXPECT_NEAR(centreRadiance(r).x, expected, 0.01f * expected);
    EXPECT_NEAR(centreRadiance(r).z, expected, 0.01f * expected);

    // Point: L = albedo / pi * I * cos(theta) / d^2.
    LightSettings point;
    point.type = LightType::Point;
    point.position = {-0.5f, 1.5f, 0.4f};
    point.intensity = 5.0f;
    r.render(frame(eye, target, point));
    glm::vec3 toLight = point.position - target;
    float d = glm::length(toLight);
    expected = albedo / glm::pi<float>() * point.intensity * (toLight.y / d) / (d * d);
    EXPECT_NEAR(centreRadiance(r).y, expected, 0.01f * expected);

    // Spot, target inside the inner cone: same as a point light.
    LightSettings spot = point;
    spot.type = LightType::Spot;
    spot.direction = glm::normalize(target - spot.position);
    spot.innerConeDeg = 20.0f;
    spot.outerConeDeg = 30.0f;
    r.render(frame(eye, target, spot));
    EXPECT_NEAR(centreRadiance(r).y, expected, 0.01f * expected);
    // Outside the outer cone: dark.
    spot.direction = glm::normalize(glm::vec3(1, -0.2f, 0));
    r.render(frame(eye, target, spot));
    EXPECT_LT(centreRadiance(r).y, 1e-4f);
}

TEST_F(GL, ShadowedPointIsDarkForEveryLightType) {
    Renderer r;
    r.setScene(floorScene(0.5f, true, 1.0f));
    // The camera looks from the side, under the plate, at the floor point below it.
    const glm::vec3 eye(3.0f, 0.4f, 0.3f);
    LightSettings lights[3];
    lights[0].type = LightType::Directional;
    lights[0].direction = {0.0f, -1.0f, 0.0f};
    lights[1].type = LightType::Point;
    lights[1].position = {0.0f, 3.0f, 0.0f};
    lights[1].intensity = 30.0f;
    lights[2].type = LightType::Spot;
    lights[2].position = {0.0f, 3.0f, 0.0f};
    lights[2].direction = {0.0f, -1.0f, 0.0f};
    lights[2].intensity = 30.0f;
    lights[2].outerConeDeg = 60.0f;
    lights[2].innerConeDeg = 50.0f;
    for (const LightSettings& l : lights) {
        r.render(frame(eye, {0.0f, 0.0f, 0.0f}, l));
        float shadowed = centreRadiance(r).x;
        r.render(frame(eye, {1.2f, 0.0f, 0.0f}, l));  // beside the plate's shadow
        float lit = centreRadiance(r).x;
        EXPECT_GT(lit, 0.2f) << "light type " << int(l.type);
        EXPECT_LT(shadowed, 0.01f * lit) << "light type " << int(l.type);
        // Without shadows the same point is lit.
        LightSettings noShadow = l;
        noShadow.castShadows = false;
        r.render(frame(eye, {0.0f, 0.0f, 0.0f}, noShadow));
        EXPECT_GT(centreRadiance(r).x, 0.5f * lit) << "light type " << int(l.type);
    }
}

// A convex box cannot shadow itself, so with the sun's shadow map it must look as it does without
// one. It did not when a file's camera had a tiny near plane far from a model in millimetres
// (2CylinderEngine: near 0.05, the model 1.6 m away): a conventional depth buffer was too coarse
// to put the surfaces where the shadow map drew them, and the sun speckled them. The raster now
// moves the near plane up to the scene (rasterCamera). The sun comes from near the camera, so no
// face in view is at a grazing angle to it (such a face shadows itself through the filter's outer
// taps, a separate matter: see the closing note of 2026-12-05).
TEST_F(GL, ConvexBoxFarFromATinyNearPlaneIsNotSelfShadowed) {
    Scene scene = test::box({0.0f, 200.0f, 0.0f}, {200.0f, 150.0f, 250.0f}, 45.0f, 0.6f);
    Renderer r;
    r.setScene(scene);
    LightSettings sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(-0.45f, -0.7f, -0.6f));
    sun.intensity = 3.0f;
    const glm::vec3 target(0.0f, 200.0f, 0.0f);
    FrameSettings fs = frame(target + glm::normalize(glm::vec3(0.62f, 0.47f, 0.62f)) * 1400.0f, target, sun);
    fs.camera.near = 0.05f;
    fs.camera.far = 1e6f;
    r.render(fs);
    std::vector<float> shadowed = r.readHDR();
    fs.lights[0].castShadows = false;
    r.render(fs);
    std::vector<float> unshadowed = r.readHDR();
    int lit = 0, speckled = 0;
    for (size_t i = 0; i < shadowed.size(); i += 4) {
        float u = unshadowed[i + 1];
        if (u <= 0.01f) continue;  // the background and the faces turned from the sun
        ++lit;
        if (shadowed[i + 1] < 0.98f * u) ++speckled;
    }
    EXPECT_GT(lit, kSize * kSize / 5) << "the box's sunlit faces fill too little of the frame to tell";
    EXPECT_LT(speckled, lit / 200) << speckled << " of " << lit << " sunlit pixels shadowed by their own surface";
}

TEST_F(GL, AmbientAndEmissiveComposite) {
    Scene s;
    MeshBuilder b(s);
    int m = b.material("m", glm::vec3(0.4f), 1.0f);
    b.quad(m, {-20, 0, 20}, {40, 0, 0}, {0, 0, -40});
    s.materials[m].emissive = {0.25f, 0.0f, 0.0f};
    s.finalize();
    Renderer r;
    r.setScene(s);
    FrameSettings fs = frame({0, 2, 2}, {0, 0, 0}, LightSettings{});
    fs.lights = sceneLights(s);  // the emission is the quad's area light's (it lights nothing else)
    ASSERT_EQ(fs.lights.size(), 1u);
    fs.render.ambient = {0.5f, 0.5f, 0.5f};
    r.render(fs);
    glm::vec3 c = centreRadiance(r);
    EXPECT_NEAR(c.x, 0.25f + 0.4f * 0.5f, 1e-3f);
    EXPECT_NEAR(c.y, 0.4f * 0.5f, 1e-3f);
}

TEST_F(GL, RendersAreDeterministic) {
    Preset p;
    Scene scene = loadScene(p.header.scene);
    FrameSettings fs = frameSettings(p, scene, kSize, kSize);
    std::vector<uint8_t> images[2];
    for (auto& img : images) {
        Renderer r;
        r.setScene(scene);
        r.render(fs);
        img = r.readLDR();
    }
    EXPECT_EQ(images[0], images[1]);
    size_t nonBlack = 0;
    for (size_t i = 0; i < images[0].size(); i += 4) nonBlack += images[0][i] + images[0][i + 1] + images[0][i + 2] > 30;
    EXPECT_GT(nonBlack, images[0].size() / 4 / 2) << "the default preset renders mostly black";
}

TEST_F(GL, EveryPassIsTimedAndReportsMemory) {
    Preset p;
    Scene scene = loadScene("basic");
    Renderer r;
    r.setScene(scene);
    r.render(frameSettings(p, scene, kSize, kSize));
    r.timer().resolve(true);
    std::vector<std::string> names;
    double total = 0.0;
    size_t gbuffer = 0, lighting = 0;
    for (const auto& s : r.passStats()) {
        names.push_back(s.name);
        total += s.gpuMs;
        if (s.name == "gbuffer") gbuffer = s.memoryBytes;
        if (s.name == "lighting") lighting = s.memoryBytes;
    }
    EXPECT_EQ(names, (std::vector<std::string>{"shadows", "gbuffer", "indirect", "ssao", "lighting", "tonemap"}));
    EXPECT_GT(total, 0.0) << "a frame that took no time was not timed";
    // The G-buffer's five targets (RGBA8, RGBA16F, RGBA8, RGBA16F, depth 32F with stencil 8,
    // which takes 8 bytes) and the HDR image.
    EXPECT_EQ(gbuffer, size_t(kSize) * kSize * (4 + 8 + 4 + 8 + 8));
    EXPECT_EQ(lighting, size_t(kSize) * kSize * 8);
    EXPECT_GT(r.memoryBytes(), size_t(kSize) * kSize * 40);
    // Views of buffers that hold a picture show one: more than one colour, not all black.
    for (const auto& v : r.debugViews()) {
        if (v.name != "final" && v.name != "albedo" && v.name != "normal" && v.name != "depth" && v.name != "hdr") continue;
        auto img = r.renderViewImage(v, 64, 64);
        std::set<uint32_t> colours;
        for (size_t i = 0; i < img.size(); i += 4) colours.insert(uint32_t(img[i]) << 16 | uint32_t(img[i + 1]) << 8 | img[i + 2]);
        EXPECT_GT(colours.size(), 4u) << v.name << " shows a flat image";
    }
}

TEST_F(GL, MemoryBudgetRefusesHugeSettingsBeforeAllocating) {
    FrameSettings fs;
    fs.lights.resize(2);
    fs.lights[1].type = LightType::Point;
    fs.render.shadowMapSize = 8192;  // a cube of 8192^2 x 6 x 4 bytes = 1.5 GiB
    fs.render.memoryBudgetMB = 512;
    try {
        Renderer::checkBudget(fs, 0);
        FAIL() << "not refused";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("render.memoryBudgetMB"), std::string::npos) << e.what();
    }
    fs.render.shadowMapSize = 1024;
    EXPECT_NO_THROW(Renderer::checkBudget(fs, 0));
    fs.width = -3;
    EXPECT_THROW(Renderer::checkBudget(fs, 0), Error);
}

class Shaders : public test::GLTest {
protected:
    std::filesystem::path mDir;
    void SetUp() override {
        test::GLTest::SetUp();
        mDir = test::tempDir();
        std::filesystem::create_directories(mDir / "common");
        std::filesystem::copy(std::filesystem::path(GI_SHADER_DIR) / "common" / "fullscreen.vert", mDir / "common");
        setenv("GI_SHADER_DIR", mDir.c_str(), 1);
    }
    void TearDown() override {
        unsetenv("GI_SHADER_DIR");
        test::GLTest::TearDown();
    }
    void write(const std::string& name, const std::string& text) { std::ofstream(mDir / name) << text; }
};

TEST_F(Shaders, CompileErrorNamesFileAndLine) {
    write("inc.glsl", "float helper() { return 1.0; }\n");
    write("bad.frag", "#include \"inc.glsl\"\nout vec4 o;\nvoid main() {\n  o = vec4(undefinedThing);\n}\n");
    try {
        gl::Program p("bad", {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "bad.frag"}});
        FAIL() << "compiled";
    } catch (const Error& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find("bad.frag:4"), std::string::npos) << msg;
    }
    write("errinc.glsl", "\nfloat broken( { }\n");
    write("inc2.frag", "#include \"errinc.glsl\"\nout vec4 o;\nvoid main() { o = vec4(1.0); }\n");
    try {
        gl::Program p("inc2", {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "inc2.frag"}});
        FAIL() << "compiled";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("errinc.glsl:2"), std::string::npos) << e.what();
    }
}

TEST_F(Shaders, FailedReloadKeepsTheLastGoodProgram) {
    write("p.frag", "out vec4 o;\nvoid main() { o = vec4(1.0); }\n");
    gl::Program p("p", {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "p.frag"}});
    GLuint before = p.id();
    ASSERT_NE(before, 0u);
    write("p.frag", "out vec4 o;\nvoid main() { o = vec4(1.0) }\n");
    EXPECT_FALSE(p.reload());
    EXPECT_EQ(p.id(), before);
    EXPECT_NE(p.log().find("p.frag:2"), std::string::npos) << p.log();
    GLint linked = 0;
    glGetProgramiv(p.id(), GL_LINK_STATUS, &linked);
    EXPECT_TRUE(linked);
    write("p.frag", "out vec4 o;\nvoid main() { o = vec4(0.5); }\n");
    EXPECT_TRUE(p.reload());
    EXPECT_TRUE(p.log().empty());
}

}  // namespace
}  // namespace gi
