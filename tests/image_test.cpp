// Preset image tests, driven by tests/image_tests.json: each case names a preset, its size, the
// reference's samples per pixel and optional `set` overrides; the bounds come from the preset's
// own "quality" section (minSSIM, maxLeakFraction), so a preset states what it must reach.
// References are cached (GI_CACHE_DIR, set by ctest to the build tree).
#include "gi/metrics/metrics.h"
#include "gi/preset/preset.h"
#include "gi/reference/reference_cache.h"
#include "gi/render/renderer.h"
#include "gi/util/paths.h"
#include "test_util.h"

namespace gi {
namespace {

struct ImageCase {
    std::string preset;
    int width = 128, height = 96, spp = 256;
    std::vector<std::string> sets;
    bool needsSharedScenes = false;
};

std::vector<ImageCase> loadCases() {
    std::vector<ImageCase> cases;
    json j = json::parse(readTextFile(std::filesystem::path(GI_SOURCE_DIR) / "tests" / "image_tests.json"));
    for (const json& c : j) {
        ImageCase ic;
        ic.preset = c.at("preset").get<std::string>();
        ic.width = c.value("width", ic.width);
        ic.height = c.value("height", ic.height);
        ic.spp = c.value("spp", ic.spp);
        ic.sets = c.value("set", std::vector<std::string>{});
        ic.needsSharedScenes = c.value("needsSharedScenes", false);
        cases.push_back(ic);
    }
    return cases;
}

void PrintTo(const ImageCase& c, std::ostream* os) { *os << c.preset << " " << c.width << "x" << c.height << " " << c.spp << " spp"; }

class ImageTest : public test::GLTest, public ::testing::WithParamInterface<ImageCase> {};

TEST_P(ImageTest, MeetsThePresetsBoundsAgainstTheReference) {
    const ImageCase& c = GetParam();
    if (c.needsSharedScenes && !std::filesystem::exists(std::filesystem::path(GI_SHARED_DIR) / "scenes"))
        GTEST_SKIP() << "../shared/scenes is not beside this checkout";
    Preset preset = loadPreset(std::filesystem::path(GI_PRESET_DIR) / c.preset);
    for (const auto& s : c.sets) applySetting(preset, s);
    preset.reference.spp = c.spp;
    ASSERT_GT(preset.quality.minSSIM, 0.0f) << c.preset << " states no quality.minSSIM";

    Scene scene = loadScene(preset.header.scene, preset.folder);
    FrameSettings fs = frameSettings(preset, scene, c.width, c.height);
    Renderer renderer;
    renderer.setScene(scene);
    renderer.render(fs);
    ImageRGB image = imageFromGL(c.width, c.height, renderer.readHDR());
    ImageRGB indirect = imageFromGL(c.width, c.height, renderer.readIndirectRadiance());

    CachedReference full = cachedReference(scene, fs, preset.reference);
    ReferenceSettings indirectSettings = preset.reference;
    indirectSettings.mode = ReferenceMode::Indirect;
    CachedReference indirectRef = cachedReference(scene, fs, indirectSettings);
    Metrics m = scoreRender({&image, &full.image, &indirect, &indirectRef.image, fs.toneMap});
    std::printf("%s %dx%d, %d spp (reference %s, %.1f s): ssim %.4f (bound %.4f), score %.3g, rmse %.4f, psnr %.2f dB, "
                "leak %.4f (bound %.4f), leak energy %.4f\n",
                c.preset.c_str(), c.width, c.height, c.spp, full.fromCache ? "cached" : "rendered", full.seconds, m.ssim,
                preset.quality.minSSIM, m.score, m.rmse, m.psnr, m.leakFraction, preset.quality.maxLeakFraction,
                m.leakEnergy);
    EXPECT_GE(m.ssim, preset.quality.minSSIM);
    EXPECT_LE(m.leakFraction, preset.quality.maxLeakFraction);
    std::printf("brightness %.3f of the reference (bound: within %.2f)\n", m.brightness, preset.quality.maxBrightnessError);
    EXPECT_LE(std::abs(m.brightness - 1.0), preset.quality.maxBrightnessError);
    if (preset.quality.minSSIMLinear > 0.0f) {
        double linear = compareImages(image, full.image).ssim;
        std::printf("ssim without tone mapping %.4f (bound %.4f)\n", linear, preset.quality.minSSIMLinear);
        EXPECT_GE(linear, preset.quality.minSSIMLinear);
    }
}

INSTANTIATE_TEST_SUITE_P(Presets, ImageTest, ::testing::ValuesIn(loadCases()), [](const auto& info) {
    std::string name = std::filesystem::path(info.param.preset).stem().string();
    for (auto& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
    return name;
});

}  // namespace
}  // namespace gi
