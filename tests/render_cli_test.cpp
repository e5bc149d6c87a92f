// gi-render end to end: every shipped preset renders, outputs and stats are complete, bad input
// gives a one-line error and a non-zero exit, and the same input gives the same pixels.
#include "gi/envmap/envmap_image.h"
#include "gi/preset/preset.h"
#include "gi/preset/reflect.h"
#include "gi/scene/scene.h"
#include "gi/render/image_io.h"
#include "gi/util/paths.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <set>

namespace gi {
namespace {

std::string render(const std::string& args) { return std::string(GI_RENDER_EXE) + " " + args; }

json readJSON(const std::filesystem::path& p) { return json::parse(readTextFile(p)); }

bool sharedScenesPresent() { return std::filesystem::exists(std::filesystem::path(GI_SHARED_DIR) / "scenes"); }

// Whether a shipped preset's files (a glTF scene, an environment map) can be found: presets made
// for ../shared's scenes and maps are skipped where ../shared is absent (built-ins never are).
bool presetFilesPresent(const std::filesystem::path& path) {
    Preset p = loadPreset(path);
    try {
        if (!isBuiltinScene(p.header.scene)) resolveAsset(p.header.scene, p.folder);
        if (p.environment.enabled) resolveEnvironmentFile(p.environment.file, p.folder);
    } catch (const Error&) {
        return false;
    }
    return true;
}

TEST(RenderCLI, EveryShippedPresetRenders) {
    for (const auto& entry : std::filesystem::directory_iterator(GI_PRESET_DIR)) {
        if (entry.path().extension() != ".json") continue;
        if (!sharedScenesPresent() && !presetFilesPresent(entry.path())) continue;
        auto out = test::tempDir() / entry.path().stem();
        auto r = test::runCommand(render(entry.path().string() + " --out " + out.string() + " --width 192 --height 128"));
        ASSERT_EQ(r.exitCode, 0) << entry.path() << "\n" << r.output;
        ImageRGBA8 img = readImage8(out / "image.png");
        EXPECT_EQ(img.width, 192);
        EXPECT_EQ(img.height, 128);
        EXPECT_TRUE(std::filesystem::exists(out / "image.exr"));
        json stats = readJSON(out / "stats.json");
        ASSERT_TRUE(stats["passes"].is_array()) << stats.dump();
        std::set<std::string> names;
        for (auto& p : stats["passes"]) {
            names.insert(p["name"].get<std::string>());
            EXPECT_TRUE(p["gpuMs"].is_number());
            EXPECT_TRUE(p["memoryBytes"].is_number());
        }
        for (const char* pass : {"shadows", "gbuffer", "ssao", "lighting", "tonemap"})
            EXPECT_TRUE(names.count(pass)) << entry.path() << " has no pass " << pass;
        // The indirect term comes from the technique's passes, or for none the environment map
        // (when enabled) or the constant fill.
        std::string technique = stats["settings"]["technique"];
        bool environment = stats["settings"].contains("environment") && stats["settings"]["environment"]["enabled"].get<bool>();
        if (technique == "none") {
            EXPECT_TRUE(names.count(environment ? "environment.shade" : "indirect")) << entry.path();
        } else if (technique == "lpv") {
            for (const char* pass : {"lpv.rsm", "lpv.inject", "lpv.geometry", "lpv.propagate", "lpv.shade"})
                EXPECT_TRUE(names.count(pass)) << entry.path() << " has no pass " << pass;
        }
        EXPECT_TRUE(stats["gpuMsTotal"].is_number());
        EXPECT_GT(stats["memoryBytes"].get<double>(), 0.0);
        EXPECT_FALSE(stats["renderer"].get<std::string>().empty());
        EXPECT_EQ(stats["settings"]["schemaVersion"], Preset::kSchemaVersion);
        // A view into the two-room scene's closed room is black in the reference: what light it
        // shows has leaked, and the image test holds it to its preset's maxLeakFraction
        // (diffusion_two_rooms: a mean of 7 of 255 once diffusion stopped lighting the shared
        // wall's foot from the lit room).
        const bool closedRoom = stats["settings"]["scene"] == "two_rooms" && stats["settings"]["camera"].value("sceneCamera", -1) == 1;
        double mean = 0;
        for (size_t i = 0; i < img.rgba.size(); i += 4) mean += img.rgba[i] + img.rgba[i + 1] + img.rgba[i + 2];
        if (!closedRoom) EXPECT_GT(mean / (img.rgba.size() / 4 * 3), 8.0) << entry.path() << " renders (nearly) black";
    }
}

TEST(RenderCLI, NoInputRendersTheBuiltInDefault) {
    auto out = test::tempDir();
    auto r = test::runCommand(render("--out " + out.string() + " --width 128 --height 128"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    auto r2 = test::runCommand(render(std::string(GI_PRESET_DIR) + "/default.json --out " + (out / "file").string() +
                                      " --width 128 --height 128"));
    ASSERT_EQ(r2.exitCode, 0) << r2.output;
    EXPECT_EQ(readImage8(out / "image.png").rgba, readImage8(out / "file" / "image.png").rgba);
}

TEST(RenderCLI, SameInputSamePixels) {
    auto out = test::tempDir();
    std::string preset = std::string(GI_PRESET_DIR) + "/basic.json";
    for (const char* d : {"a", "b"}) {
        auto r = test::runCommand(render(preset + " --out " + (out / d).string() + " --width 160 --height 120 --frames 2"));
        ASSERT_EQ(r.exitCode, 0) << r.output;
    }
    EXPECT_EQ(readImage8(out / "a" / "image.png").rgba, readImage8(out / "b" / "image.png").rgba);
}

TEST(RenderCLI, ViewsAndSetOverrides) {
    auto out = test::tempDir();
    auto r = test::runCommand(render(std::string(GI_PRESET_DIR) + "/basic.json --out " + out.string() +
                                     " --width 128 --height 96 --views --set toneMap.exposure=1.5 --set render.shadowMapSize=512"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char* v : {"final", "albedo", "normal", "depth", "roughnessMetallic", "emissive", "indirect", "shadow0"})
        EXPECT_TRUE(std::filesystem::exists(out / "views" / (std::string(v) + ".png"))) << v;
    json stats = readJSON(out / "stats.json");
    EXPECT_FLOAT_EQ(stats["settings"]["toneMap"]["exposure"].get<float>(), 1.5f);
    EXPECT_EQ(stats["settings"]["render"]["shadowMapSize"], 512);
}

TEST(RenderCLI, LPVViewsAndPointLightCube) {
    auto out = test::tempDir();
    auto r = test::runCommand(render(std::string(GI_PRESET_DIR) + "/lpv_basic.json --out " + out.string() +
                                     " --width 96 --height 64 --views --set ssao.enabled=true"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char* v : {"lpv.rsmFlux0c0", "lpv.rsmNormal0c0", "lpv.rsmPosition0c0", "lpv.volume0", "lpv.geometryRSM0",
                          "lpv.geometryGBuffer0", "ssao", "ssaoRaw"})
        EXPECT_TRUE(std::filesystem::exists(out / "views" / (std::string(v) + ".png"))) << v;
    {
        ImageRGBA8 volume = readImage8(out / "views" / "lpv.volume0.png");
        size_t lit = 0;
        for (size_t i = 0; i < volume.rgba.size(); i += 4) lit += volume.rgba[i] + volume.rgba[i + 1] + volume.rgba[i + 2] > 30;
        EXPECT_GT(lit, volume.rgba.size() / 4 / 10) << "the LPV volume slice is (nearly) black";
    }
    // A point light is injected through its cube RSM: no warning, and its six faces and their
    // cross are among the views.
    auto dir = test::tempDir();
    std::ofstream(dir / "point.json") << R"({"schemaVersion": 1, "scene": "cornell", "technique": "lpv",
        "lights": [{"type": "point", "position": [0, 1.8, 0], "intensity": 4}]})";
    auto p = test::runCommand(render((dir / "point.json").string() + " --out " + (dir / "o").string() +
                                     " --width 32 --height 32 --views --set lpv.rsmResolution=32"));
    ASSERT_EQ(p.exitCode, 0) << p.output;
    EXPECT_EQ(p.output.find("no indirect light"), std::string::npos) << p.output;
    for (int face = 0; face < 6; ++face)
        for (const char* v : {"lpv.rsmFlux0f", "lpv.rsmNormal0f", "lpv.rsmPosition0f"})
            EXPECT_TRUE(std::filesystem::exists(dir / "o" / "views" / (v + std::to_string(face) + ".png"))) << v << face;
    ImageRGBA8 cross = readImage8(dir / "o" / "views" / "lpv.rsmCube0.png");
    size_t lit = 0;
    for (size_t i = 0; i < cross.rgba.size(); i += 4) lit += cross.rgba[i] + cross.rgba[i + 1] + cross.rgba[i + 2] > 30;
    // Six of the cross's twelve cells are faces; the Cornell box fills them but for its open front.
    EXPECT_GT(lit, cross.rgba.size() / 4 / 4) << "the cube RSM cross is (nearly) black";
    // The built-in Cornell box, a closed room but for its front, gets the coarsest fitted grid,
    // and stats.json says so and why.
    json pointStats = readJSON(dir / "o" / "stats.json");
    EXPECT_EQ(pointStats["lpv"]["gridResolution"].get<double>(), 16.0) << pointStats["lpv"].dump();
    EXPECT_GT(pointStats["lpv"]["meanSurfaceGap"].get<double>(), 0.5);
    EXPECT_NE(pointStats["lpv"]["grid"].get<std::string>().find("fitted"), std::string::npos);
}

TEST(RenderCLI, GLTFInputWithItsCamera) {
    if (!sharedScenesPresent()) GTEST_SKIP() << "../shared/scenes is not beside this checkout";
    auto out = test::tempDir();
    auto file = std::filesystem::path(GI_SHARED_DIR) / "scenes" / "water_bottle" / "WaterBottle.gltf";
    auto r = test::runCommand(render(file.string() + " --out " + out.string() + " --width 128 --height 128"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    // Its glowing label is its light: no sun is invented.
    EXPECT_EQ(r.output.find("default sun"), std::string::npos) << r.output;
    auto avocado = std::filesystem::path(GI_SHARED_DIR) / "scenes" / "avocado" / "Avocado.gltf";
    auto a = test::runCommand(render(avocado.string() + " --out " + (out / "a").string() + " --width 32 --height 32"));
    ASSERT_EQ(a.exitCode, 0) << a.output;
    EXPECT_NE(a.output.find("default sun"), std::string::npos) << "a scene without lights or emitters should say so";
    auto bad = test::runCommand(render(file.string() + " --camera 3 --out " + out.string()));
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.output.find("camera.sceneCamera"), std::string::npos) << bad.output;
}

TEST(RenderCLI, ScoreWritesMetricsAndMapsAndReusesTheReference) {
    auto dir = test::tempDir();
    std::string env = "GI_CACHE_DIR=" + (dir / "cache").string() + " ";
    std::string args = std::string(GI_PRESET_DIR) + "/basic.json --width 64 --height 48 --score --spp 16 --out ";
    auto first = test::runCommand(env + render(args + (dir / "a").string()));
    ASSERT_EQ(first.exitCode, 0) << first.output;
    json a = readJSON(dir / "a" / "stats.json");
    for (const char* key : {"ssim", "score", "rmse", "psnr", "leakFraction", "leakEnergy"})
        EXPECT_TRUE(a["metrics"][key].is_number()) << key << " in " << a["metrics"].dump();
    EXPECT_GT(a["metrics"]["ssim"].get<double>(), 0.5);
    EXPECT_LE(a["metrics"]["ssim"].get<double>(), 1.0);
    EXPECT_FALSE(a["reference"]["fromCache"].get<bool>());
    EXPECT_EQ(a["reference"]["spp"], 16);
    for (const char* f : {"reference.exr", "reference.png", "ssim_map.png", "heat_map.png", "leak_map.png"})
        EXPECT_TRUE(std::filesystem::exists(dir / "a" / f)) << f;

    auto second = test::runCommand(env + render(args + (dir / "b").string()));
    ASSERT_EQ(second.exitCode, 0) << second.output;
    json b = readJSON(dir / "b" / "stats.json");
    EXPECT_TRUE(b["reference"]["fromCache"].get<bool>());
    EXPECT_TRUE(b["referenceIndirect"]["fromCache"].get<bool>());
    EXPECT_EQ(a["metrics"], b["metrics"]) << "a cached reference must score exactly like a fresh one";

    // Another tool's images can be scored too: gi-compare reads the runner's PNGs.
    auto cmp = test::runCommand(std::string(GI_COMPARE_EXE) + " " + (dir / "a" / "image.png").string() + " " +
                                (dir / "a" / "reference.png").string() + " --json");
    ASSERT_EQ(cmp.exitCode, 0) << cmp.output;
    EXPECT_NEAR(json::parse(cmp.output)["ssim"].get<double>(), a["metrics"]["ssim"].get<double>(), 0.01);

    auto onlyReference = test::runCommand(env + render(std::string(GI_PRESET_DIR) +
                                                       "/default.json --width 32 --height 24 --reference --spp 4 --out " +
                                                       (dir / "c").string()));
    ASSERT_EQ(onlyReference.exitCode, 0) << onlyReference.output;
    EXPECT_TRUE(std::filesystem::exists(dir / "c" / "reference.exr"));
    EXPECT_FALSE(readJSON(dir / "c" / "stats.json").contains("metrics"));
}

// Work estimated past render.timeBudgetSeconds is refused up front, in one line naming the key,
// the estimate and what to change, before any GL work: a prefilter of 2048^2 x 4096 samples
// (about 16 minutes on llvmpipe) and a fresh reference; a cached reference is never refused.
TEST(RenderCLI, LongWorkPastTheTimeBudgetIsRefused) {
    auto dir = test::tempDir();
    auto oneLine = [](const std::string& output) {
        std::string trimmed = output;
        while (!trimmed.empty() && trimmed.back() == '\n') trimmed.pop_back();
        return trimmed.find('\n') == std::string::npos;
    };
    auto start = std::chrono::steady_clock::now();
    auto prefilter = test::runCommand(render(std::string(GI_PRESET_DIR) + "/environment_spheres_sky.json --width 128 --height 96"
                                             " --set environment.cubeSize=2048 --set environment.samples=4096 --out " +
                                             (dir / "prefilter").string()));
    // Refused from the estimate, not after minutes of work (a generous bound, not a benchmark).
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 60.0);
    EXPECT_NE(prefilter.exitCode, 0);
    EXPECT_EQ(prefilter.output.rfind("gi-render: key 'render.timeBudgetSeconds': environment prefilter estimated at ", 0), 0u)
        << prefilter.output;
    EXPECT_NE(prefilter.output.find(" s (cubeSize 2048, samples 4096) exceeds the budget of 600 s; lower environment.samples or "
                                    "environment.cubeSize, or raise render.timeBudgetSeconds"),
              std::string::npos)
        << prefilter.output;
    EXPECT_TRUE(oneLine(prefilter.output)) << prefilter.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "prefilter" / "image.png"));

    // 64x48 at 256 spp is estimated past a 1 s budget (and takes about a second): rendered with
    // the default budget, then cached, it is not refused under the small one; 512 spp is.
    std::string env = "GI_CACHE_DIR=" + (dir / "cache").string() + " ";
    std::string args = std::string(GI_PRESET_DIR) + "/default.json --width 64 --height 48 --reference --out ";
    auto fresh = test::runCommand(env + render(args + (dir / "a").string() + " --spp 256"));
    ASSERT_EQ(fresh.exitCode, 0) << fresh.output;
    auto cached = test::runCommand(env + render(args + (dir / "b").string() + " --spp 256 --set render.timeBudgetSeconds=1"));
    ASSERT_EQ(cached.exitCode, 0) << cached.output;
    EXPECT_TRUE(readJSON(dir / "b" / "stats.json")["reference"]["fromCache"].get<bool>());
    auto refused = test::runCommand(env + render(args + (dir / "c").string() + " --spp 512 --set render.timeBudgetSeconds=1"));
    EXPECT_NE(refused.exitCode, 0);
    EXPECT_EQ(refused.output.rfind("gi-render: key 'render.timeBudgetSeconds': path-traced reference estimated at ", 0), 0u)
        << refused.output;
    EXPECT_NE(refused.output.find(" s (64x48, 512 spp) exceeds the budget of 1 s; lower reference.spp (--spp) or the image size, or "
                                  "raise render.timeBudgetSeconds"),
              std::string::npos)
        << refused.output;
    EXPECT_TRUE(oneLine(refused.output)) << refused.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "c" / "image.png")) << "refused before the raster image";
}

// Long work says how far it is on stderr even when stderr is no terminal (here a pipe): the
// reference a line per pass (at most about one a second) and its last, the prefilter once it
// has run a second; a prefilter over in a moment stays quiet.
TEST(RenderCLI, ProgressLinesWhenStderrIsNotATerminal) {
    auto dir = test::tempDir();
    std::string env = "GI_CACHE_DIR=" + (dir / "cache").string() + " ";
    auto reference = test::runCommand(env + render(std::string(GI_PRESET_DIR) + "/default.json --width 32 --height 24 --reference "
                                                   "--spp 8 --out " + (dir / "a").string()));
    ASSERT_EQ(reference.exitCode, 0) << reference.output;
    EXPECT_NE(reference.output.find("gi-render: reference: 1 / 8 spp, "), std::string::npos) << reference.output;
    EXPECT_NE(reference.output.find("gi-render: reference: 8 / 8 spp, "), std::string::npos) << reference.output;
    EXPECT_EQ(reference.output.find('\r'), std::string::npos) << "no carriage returns into a pipe";

    // Whether the prefilter speaks depends on how long it took here (stats.json's per-mip times):
    // 128^2 at 2048 samples takes 2 to 4 s on llvmpipe, 32^2 at 8 a few ms.
    std::string sky = std::string(GI_PRESET_DIR) + "/environment_spheres_sky.json --width 64 --height 48 --out ";
    auto prefilterMs = [&](const std::filesystem::path& out) {
        json stats = readJSON(out / "stats.json");
        double ms = 0.0;
        for (const json& m : stats["environment"]["mips"]) ms += m["ms"].get<double>();
        return ms;
    };
    for (const auto& [name, sets] : {std::pair<std::string, std::string>{"quick", "cubeSize=32 --set environment.samples=8"},
                                     {"slow", "cubeSize=128 --set environment.samples=2048"}}) {
        auto r = test::runCommand(render(sky + (dir / name).string() + " --set environment." + sets));
        ASSERT_EQ(r.exitCode, 0) << r.output;
        double ms = prefilterMs(dir / name);
        if (ms > 1200.0) {
            EXPECT_NE(r.output.find(name == "slow" ? "gi-render: environment prefilter: 8 / 8 mips, " : "gi-render: environment prefilter: "),
                      std::string::npos)
                << name << "\n" << r.output;
        } else if (ms < 800.0) {
            EXPECT_EQ(r.output.find("environment prefilter"), std::string::npos) << name << "\n" << r.output;
        }
    }
}

TEST(RenderCLI, ListSettings) {
    auto r = test::runCommand(render("--list-settings --json"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    json list = json::parse(r.output);
    ASSERT_TRUE(list.is_array());
    bool found = false;
    for (auto& s : list) {
        EXPECT_TRUE(s.contains("key") && s.contains("type") && s.contains("default") && s.contains("description"));
        found |= s["key"] == "render.shadowMapSize" && s["min"] == 64 && s["max"] == 8192;
    }
    EXPECT_TRUE(found);
    auto text = test::runCommand(render("--list-settings"));
    EXPECT_EQ(text.exitCode, 0);
    EXPECT_NE(text.output.find("toneMap.op"), std::string::npos);
}

TEST(RenderCLI, BadInputGivesOneLineErrorAndNonZeroExit) {
    auto dir = test::tempDir();
    std::ofstream(dir / "broken.json") << "{\"schemaVersion\": 1, \"render\": {\"shadowMapSize\": 99999}}";
    std::ofstream(dir / "typo.json") << "{\"schemaVersion\": 1, \"camera\": {\"fov\": 30}}";
    std::ofstream(dir / "bad.gltf") << "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": 7}";
    std::ofstream(dir / "notjson.json") << "{ nope";
    std::ofstream(dir / "missing_scene.json") << "{\"schemaVersion\": 1, \"scene\": \"nowhere/none.gltf\"}";
    struct Case {
        std::string args, expect;
    };
    std::string out = " --out " + (dir / "out").string();
    std::vector<Case> cases = {
        {(dir / "broken.json").string() + out, "render.shadowMapSize"},
        {(dir / "typo.json").string() + out, "did you mean 'camera.fovY'"},
        {(dir / "bad.gltf").string() + out, "bad.gltf"},
        {(dir / "notjson.json").string() + out, "invalid JSON"},
        {(dir / "missing_scene.json").string() + out, "nowhere/none.gltf"},
        {(dir / "nothere.json").string() + out, "nothere.json"},
        {"--set render.shadowMapSize=-1" + out, "render.shadowMapSize"},
        {"--set render.shadowMapSize=8192 --set render.memoryBudgetMB=64" + out, "render.memoryBudgetMB"},
        {"--set lights.0.intensity=1" + out, "lights.0.intensity"},
        {"--width -5" + out, "width"},
        {"--width 100000" + out, "width"},
        {std::string(GI_PRESET_DIR) + "/default.json", "--out"},
    };
    for (const auto& c : cases) {
        auto r = test::runCommand(render(c.args));
        EXPECT_NE(r.exitCode, 0) << c.args;
        EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << "\n" << r.output;
        std::string trimmed = r.output;
        while (!trimmed.empty() && trimmed.back() == '\n') trimmed.pop_back();
        EXPECT_EQ(trimmed.find('\n'), std::string::npos) << "not one line: " << r.output;
    }
}

}  // namespace
}  // namespace gi
