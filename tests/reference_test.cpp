// Proof of the path-traced reference: white furnace, direct light against the raster pipeline
// and the analytic value, error falling as 1/sqrt(spp), agreement in mean brightness with the
// raster direct light on the built-in scenes, determinism.
#include "gi/preset/preset.h"
#include "gi/reference/path_tracer.h"
#include "gi/reference/reference_cache.h"
#include "gi/render/renderer.h"
#include "gi/scene/mesh_builder.h"
#include "test_util.h"

#include <glm/gtc/constants.hpp>

namespace gi {
namespace {

double meanLuminance(const std::vector<float>& rgb, size_t stride) {
    double sum = 0;
    size_t n = rgb.size() / stride;
    for (size_t i = 0; i < n; ++i) sum += 0.2126 * rgb[i * stride] + 0.7152 * rgb[i * stride + 1] + 0.0722 * rgb[i * stride + 2];
    return sum / double(n);
}

// A closed sphere seen from inside: normals point inwards so its emission faces the camera.
Scene furnace(float albedo, glm::vec3 emission) {
    Scene s;
    MeshBuilder b(s);
    int m = b.material("furnace", glm::vec3(albedo), 1.0f);
    b.sphere(m, glm::vec3(0.0f), 1.0f, 96, 48);
    for (auto& v : s.vertices) v.normal = -v.normal;
    s.materials[m].emissive = emission;
    s.finalize();
    return s;
}

// The furnace's emission lights it as the scene's area lights, as frameSettings would list them.
FrameSettings furnaceFrame(int size, const Scene& scene) {
    FrameSettings fs;
    fs.lights = sceneLights(scene);
    fs.camera.eye = {0.0f, 0.0f, 0.3f};
    fs.camera.target = {0.0f, 0.1f, -1.0f};
    fs.camera.near = 0.01f;
    fs.camera.fovY = 90.0f;
    fs.render.specular = false;
    fs.width = fs.height = size;
    return fs;
}

TEST(Reference, WhiteFurnace) {
    const glm::vec3 e(0.5f, 0.5f, 0.5f);
    for (float albedo : {0.5f, 0.8f}) {
        Scene scene = furnace(albedo, e);
        PathTracer pt(scene);
        ReferenceSettings rs;
        rs.spp = 64;
        rs.maxBounces = 64;
        ImageRGB img = pt.render(furnaceFrame(32, scene), rs);
        double expected = 0.5 / (1.0 - albedo);
        double mean = meanLuminance(img.rgb, 3);
        std::printf("furnace albedo %.1f: %.5f expected %.5f (error %.3f%%)\n", albedo, mean, expected,
                    100.0 * std::abs(mean - expected) / expected);
        EXPECT_NEAR(mean, expected, 0.01 * expected) << "albedo " << albedo;
    }
}

class ReferenceGL : public test::GLTest {};

Scene floorScene(float albedo) {
    Scene s;
    MeshBuilder b(s);
    int grey = b.material("grey", glm::vec3(albedo), 1.0f);
    b.quad(grey, {-20, 0, 20}, {40, 0, 0}, {0, 0, -40});
    s.finalize();
    return s;
}

TEST_F(ReferenceGL, DirectModeMatchesRasterAndAnalyticOnLambertPlane) {
    const float albedo = 0.5f;
    Scene scene = floorScene(albedo);
    FrameSettings fs;
    fs.camera.eye = {1.0f, 3.0f, 2.0f};
    fs.camera.target = {0.3f, 0.0f, -0.2f};
    fs.render.ambient = glm::vec3(0.0f);
    fs.render.specular = false;
    fs.toneMap.op = ToneMapper::Linear;
    fs.width = fs.height = 64;
    LightSettings sun;
    sun.direction = glm::normalize(glm::vec3(0.4f, -1.0f, 0.3f));
    sun.intensity = 2.0f;
    LightSettings point;
    point.type = LightType::Point;
    point.position = {-0.5f, 1.5f, 0.4f};
    point.intensity = 5.0f;
    Renderer raster;
    raster.setScene(scene);
    PathTracer pt(scene);
    ReferenceSettings rs;
    rs.mode = ReferenceMode::Direct;
    rs.spp = 4;
    for (const LightSettings& l : {sun, point}) {
        fs.lights = {l};
        raster.render(fs);
        std::vector<float> hdr = raster.readHDR();
        ImageRGB ref = pt.render(fs, rs);
        // The camera target sits on the corner of the four centre pixels: average them, so the
        // gradient across a pixel cancels. The raster image is bottom row first, the reference top.
        int c = fs.width / 2;
        float rasterValue = 0.0f, refValue = 0.0f;
        for (int y = c - 1; y <= c; ++y)
            for (int x = c - 1; x <= c; ++x) {
                rasterValue += 0.25f * hdr[(size_t(y) * fs.width + x) * 4];
                refValue += 0.25f * ref.rgb[(size_t(fs.height - 1 - y) * fs.width + x) * 3];
            }
        glm::vec3 toLight = l.type == LightType::Point ? l.position - fs.camera.target : -l.direction;
        float d = glm::length(toLight);
        float E = l.type == LightType::Point ? l.intensity * (toLight.y / d) / (d * d) : l.intensity * (toLight.y / d);
        float analytic = albedo / glm::pi<float>() * E;
        EXPECT_NEAR(refValue, analytic, 0.01f * analytic);
        EXPECT_NEAR(refValue, rasterValue, 0.01f * analytic);
        // And over the whole image: mean brightness within 1 %.
        double rasterMean = meanLuminance(hdr, 4), refMean = meanLuminance(ref.rgb, 3);
        EXPECT_NEAR(refMean, rasterMean, 0.01 * rasterMean);
    }
}

TEST(Reference, ErrorFallsAsInverseSqrtOfSamples) {
    Scene scene = makeBuiltinScene("cornell");
    Preset p;
    FrameSettings fs = frameSettings(p, scene, 24, 24);
    PathTracer pt(scene);
    ReferenceSettings truth;
    truth.spp = 2048;
    truth.seed = 1000;
    ImageRGB ref = pt.render(fs, truth);
    double previous = 0;
    for (int spp : {16, 64, 256}) {
        // Average the error over seeds so the ratio is not at the mercy of one draw.
        double err = 0;
        for (int seed = 1; seed <= 3; ++seed) {
            ReferenceSettings rs;
            rs.spp = spp;
            rs.seed = seed;
            ImageRGB img = pt.render(fs, rs);
            double se = 0;
            for (size_t i = 0; i < img.rgb.size(); ++i) se += double(img.rgb[i] - ref.rgb[i]) * (img.rgb[i] - ref.rgb[i]);
            err += std::sqrt(se / img.rgb.size()) / 3.0;
        }
        std::printf("spp %4d: rmse %.5f%s\n", spp, err,
                    previous > 0 ? (" (ratio to previous " + std::to_string(previous / err) + ", ideal 2)").c_str() : "");
        if (previous > 0) {
            EXPECT_GT(previous / err, 1.6) << spp;
            EXPECT_LT(previous / err, 2.5) << spp;
        }
        previous = err;
    }
}

TEST_F(ReferenceGL, MeanBrightnessAgreesWithRasterDirectOnBuiltInScenes) {
    for (const char* name : {"cornell", "basic"}) {
        Scene scene = makeBuiltinScene(name);
        Preset p;
        p.header.scene = name;
        p.render.ambient = glm::vec3(0.0f);
        p.render.pcfRadius = 0.0f;
        if (std::string(name) == "basic") p.camera = scene.cameras[0];
        FrameSettings fs = frameSettings(p, scene, 96, 64);
        Renderer raster;
        raster.setScene(scene);
        raster.render(fs);
        PathTracer pt(scene);
        ReferenceSettings rs;
        rs.mode = ReferenceMode::Direct;
        rs.spp = 64;
        ImageRGB ref = pt.render(fs, rs);
        double rasterMean = meanLuminance(raster.readHDR(), 4), refMean = meanLuminance(ref.rgb, 3);
        std::printf("%s: raster direct %.5f, reference direct %.5f (%.2f%%)\n", name, rasterMean, refMean,
                    100.0 * (rasterMean - refMean) / refMean);
        EXPECT_NEAR(rasterMean, refMean, 0.03 * refMean) << name;
    }
}

TEST(Reference, DeterministicWhateverThePassSplit) {
    Scene scene = makeBuiltinScene("cornell");
    FrameSettings fs = frameSettings(Preset{}, scene, 16, 16);
    PathTracer pt(scene);
    ReferenceSettings rs;
    rs.spp = 8;
    std::vector<double> a, b;
    pt.trace(fs, rs, 0, 8, a);
    pt.trace(fs, rs, 0, 3, b);
    pt.trace(fs, rs, 3, 5, b);
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-9 * std::max(1.0, std::abs(a[i])));
    EXPECT_GT(pt.raysTraced(), 16u * 16u * 16u);
}

// Light transport does not depend on the units: the lamp-lit Cornell box (its quad the only
// light, whose radiance has no length in it) and its camera scaled to 1/100 (a 2 cm box) and to
// 100x give the image of the original. The surface offset of secondary rays once had a floor of
// 1e-4 world units, a sizeable step in a 2 cm room: the small box came out 17 % darker.
TEST(Reference, TheImageIsTheSameAtAnyScale) {
    auto mean = [](float scale) {
        Scene scene = test::scaledBuiltinScene("cornell_lamp", scale);
        FrameSettings fs = frameSettings(Preset{}, scene, 24, 24);
        test::scaleCamera(fs.camera, scale);
        ReferenceSettings rs;
        rs.spp = 64;
        return meanLuminance(PathTracer(scene).render(fs, rs).rgb, 3);
    };
    const double original = mean(1.0f);
    EXPECT_GT(original, 0.01);
    for (float scale : {0.01f, 100.0f}) EXPECT_NEAR(mean(scale) / original, 1.0, 0.01) << "scale " << scale;
}

// The same room 5 km from the origin (camera and lights moved with it) gives the same picture.
// Two things lost precision out there: the offset that lifts shadow and bounce rays off their
// surface, 1e-4 of the largest coordinate (half a metre; the mean came out at 0.937 of the
// room at the origin), and the camera rays, whose directions came from a matrix holding the
// eye's translation (0.994: the picture shifted by a fraction of a pixel). The renders are
// deterministic (per-pixel seeds), so the two differ by path noise alone: 1.0005 at 256 spp.
TEST(Reference, TheImageIsTheSameFarFromTheOrigin) {
    auto mean = [](glm::vec3 offset) {
        Scene scene = makeBuiltinScene("cornell_lamp");
        for (Vertex& v : scene.vertices) v.position += offset;
        for (LightSettings& l : scene.lights) l.position += offset;
        scene.finalize();
        FrameSettings fs = frameSettings(Preset{}, scene, 24, 24);
        fs.camera.eye += offset;
        fs.camera.target += offset;
        ReferenceSettings rs;
        rs.spp = 256;
        return meanLuminance(PathTracer(scene).render(fs, rs).rgb, 3);
    };
    const double original = mean(glm::vec3(0.0f));
    EXPECT_GT(original, 0.01);
    EXPECT_NEAR(mean(glm::vec3(5000.0f, 0.0f, -3000.0f)) / original, 1.0, 0.003);
}

TEST(Reference, CacheKeyCoversWhatDeterminesTheImage) {
    Scene scene = makeBuiltinScene("cornell");
    FrameSettings fs = frameSettings(Preset{}, scene, 16, 16);
    ReferenceSettings rs;
    uint64_t key = referenceKey(scene, fs, rs);
    EXPECT_EQ(key, referenceKey(makeBuiltinScene("cornell"), fs, rs));
    FrameSettings moved = fs;
    moved.camera.eye.x += 0.01f;
    EXPECT_NE(key, referenceKey(scene, moved, rs));
    FrameSettings dimmer = fs;
    dimmer.lights[0].intensity *= 0.5f;
    EXPECT_NE(key, referenceKey(scene, dimmer, rs));
    FrameSettings bigger = fs;
    bigger.width = 32;
    EXPECT_NE(key, referenceKey(scene, bigger, rs));
    ReferenceSettings more = rs;
    more.spp = 512;
    EXPECT_NE(key, referenceKey(scene, fs, more));
    Scene recoloured = scene;
    recoloured.materials[1].baseColor.r = 0.5f;
    EXPECT_NE(key, referenceKey(recoloured, fs, rs));
    // Tone mapping and shadow-map settings do not change the reference.
    FrameSettings toned = fs;
    toned.toneMap.exposure = 2.0f;
    toned.render.shadowMapSize = 256;
    EXPECT_EQ(key, referenceKey(scene, toned, rs));
}

// A 16x12 Cornell box at 4 spp whose references go to a fresh cache folder: GI_CACHE_DIR
// names it until the test unsets it.
struct CacheCase {
    std::filesystem::path dir;
    Scene scene;
    FrameSettings fs;
    ReferenceSettings rs;
};
CacheCase tinyCornellInFreshCache() {
    CacheCase c{test::tempDir(), makeBuiltinScene("cornell"), {}, {}};
    setenv("GI_CACHE_DIR", c.dir.c_str(), 1);
    c.fs = frameSettings(Preset{}, c.scene, 16, 12);
    c.rs.spp = 4;
    return c;
}

TEST(Reference, CacheStoresAndReloadsExactly) {
    auto [dir, scene, fs, rs] = tinyCornellInFreshCache();
    CachedReference first = cachedReference(scene, fs, rs);
    CachedReference second = cachedReference(scene, fs, rs);
    unsetenv("GI_CACHE_DIR");
    EXPECT_FALSE(first.fromCache);
    EXPECT_TRUE(second.fromCache);
    EXPECT_EQ(first.file.parent_path(), dir);
    EXPECT_EQ(first.image.rgb, second.image.rgb);
}

// A fresh reference estimated past render.timeBudgetSeconds is refused before it starts, with
// one line naming the key, the estimate and the settings; a cached one costs nothing and is
// never refused (the budget is not part of the key).
TEST(Reference, TimeBudgetRefusesFreshReferencesNotCachedOnes) {
    auto [dir, scene, fs, rs] = tinyCornellInFreshCache();
    EXPECT_FALSE(referenceCached(scene, fs, rs));
    CachedReference first = cachedReference(scene, fs, rs);
    EXPECT_TRUE(referenceCached(scene, fs, rs));
    fs.render.timeBudgetSeconds = 1e-9f;
    CachedReference again = cachedReference(scene, fs, rs);
    EXPECT_TRUE(again.fromCache);
    rs.spp = 8;
    try {
        cachedReference(scene, fs, rs);
        ADD_FAILURE() << "a fresh reference past the time budget was rendered";
    } catch (const Error& e) {
        std::string m = e.what();
        EXPECT_EQ(m.rfind("key 'render.timeBudgetSeconds': path-traced reference estimated at ", 0), 0u) << m;
        EXPECT_NE(m.find(" s (16x12, 8 spp) exceeds the budget of 0 s; lower reference.spp (--spp) or the image size, or raise "
                         "render.timeBudgetSeconds"),
                  std::string::npos)
            << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
    unsetenv("GI_CACHE_DIR");
    EXPECT_FALSE(referenceCached(scene, fs, rs));
    // The estimate grows with pixels and samples; the shipped defaults (640x360, 256 spp) fit the
    // default budget, 1920x1080 at 65536 spp is far past it.
    FrameSettings big = fs;
    big.width = 1920;
    big.height = 1080;
    rs.spp = 65536;
    EXPECT_GT(estimateReferenceSeconds(big, rs), 100.0 * RenderSettings{}.timeBudgetSeconds);
    FrameSettings usual = fs;
    usual.width = 640;
    usual.height = 360;
    EXPECT_LT(estimateReferenceSeconds(usual, ReferenceSettings{}), 0.5 * RenderSettings{}.timeBudgetSeconds);
    EXPECT_NO_THROW(checkReferenceTimeBudget(big, rs, 0)) << "no fresh reference, nothing to refuse";
}

// A render reports after each pass (passes double: progress comes early), up to the total.
TEST(Reference, ProgressAfterEachPassUpToTheTotal) {
    Scene scene = makeBuiltinScene("cornell");
    FrameSettings fs = frameSettings(Preset{}, scene, 8, 6);
    ReferenceSettings rs;
    rs.spp = 20;
    std::vector<int> done;
    PathTracer pt(scene);
    ImageRGB img = pt.render(fs, rs, [&](int d, int total) {
        EXPECT_EQ(total, 20);
        done.push_back(d);
        return true;
    });
    EXPECT_EQ(done, (std::vector<int>{1, 3, 7, 15, 20}));
    EXPECT_EQ(img.width, 8);
}

TEST(Reference, AlphaMaskedSheetCastsNoShadowWhereCutOut) {
    // A plate whose texture is fully transparent must not shadow the floor.
    Scene s;
    MeshBuilder b(s);
    Texture hole;
    hole.width = hole.height = 2;
    hole.rgba.assign(16, 0);
    s.textures.push_back(hole);
    int floor = b.material("floor", glm::vec3(0.5f), 1.0f);
    int plate = b.material("plate", glm::vec3(0.5f), 1.0f, 0);
    s.materials[plate].alphaMode = AlphaMode::Mask;
    b.quad(floor, {-20, 0, 20}, {40, 0, 0}, {0, 0, -40});
    b.quad(plate, {-2, 1, 2}, {4, 0, 0}, {0, 0, -4});
    s.finalize();
    FrameSettings fs;
    fs.camera.eye = {3.0f, 0.4f, 0.3f};
    fs.camera.target = {0.0f, 0.0f, 0.0f};
    fs.render.specular = false;
    fs.width = fs.height = 8;
    LightSettings sun;
    sun.direction = {0.0f, -1.0f, 0.0f};
    fs.lights = {sun};
    ReferenceSettings rs;
    rs.mode = ReferenceMode::Direct;
    rs.spp = 1;
    float expected = 0.5f / glm::pi<float>() * sun.intensity;
    ImageRGB open = PathTracer(s).render(fs, rs);
    EXPECT_NEAR(open.rgb[(4 * 8 + 4) * 3], expected, 1e-3f);
    s.materials[plate].alphaMode = AlphaMode::Opaque;
    ImageRGB closed = PathTracer(s).render(fs, rs);
    EXPECT_LT(closed.rgb[(4 * 8 + 4) * 3], 1e-4f);
}

}  // namespace
}  // namespace gi
