// The pass registry: derived from the section list, it names every pass once, and every
// registered technique renders end to end with its passes in stats.json under the names it reports.
#include "gi/preset/preset.h"
#include "gi/preset/reflect.h"
#include "gi/render/pass.h"
#include "gi/util/paths.h"
#include "gi/vct/vct.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace gi {
namespace {

TEST(PassRegistry, FollowsTheSectionList) {
    // Every section that declares a pass is registered, in the list's order, once.
    std::vector<std::string> sections;
    FrameSections().forEachSection([&](const auto& s) {
        using S = std::decay_t<decltype(s)>;
        if constexpr (PassSettings<S>) sections.emplace_back(S::kSection);
    });
    std::vector<std::string> registered;
    for (const PassInfo& p : passRegistry()) registered.emplace_back(p.name);
    EXPECT_EQ(registered, sections);
    // The order is the stages' order: the sky (environment) lies behind the medium (volumetric).
    auto at = [&](const char* name) { return std::find(registered.begin(), registered.end(), name) - registered.begin(); };
    for (const char* name : {"lpv", "vct", "ssao", "environment", "volumetric"}) EXPECT_LT(size_t(at(name)), registered.size()) << name;
    EXPECT_LT(at("environment"), at("volumetric"));

    // The technique key's choices are "none" and the technique passes, nothing else.
    std::vector<std::string> techniques{"none"};
    for (const PassInfo& p : passRegistry())
        if (p.role == PassRole::Technique) techniques.emplace_back(p.name);
    EXPECT_EQ(TechniqueChoice::choices(), techniques);
    ASSERT_NE(findPass("vct"), nullptr);
    EXPECT_EQ(findPass("vct")->name, "vct");
    EXPECT_EQ(findPass("none"), nullptr);
    EXPECT_EQ(findPass("render"), nullptr) << "render is a section without a pass";

    // A technique is active when chosen, an effect always.
    FrameSettings fs;
    fs.technique = "lpv";
    EXPECT_TRUE(passActive(*findPass("lpv"), fs));
    EXPECT_FALSE(passActive(*findPass("vct"), fs));
    EXPECT_TRUE(passActive(*findPass("ssao"), fs));
}

TEST(PassRegistry, TechniqueKeyAcceptsRegisteredNamesOnly) {
    Preset p;
    applySetting(p, "technique=vct");
    EXPECT_EQ(p.header.technique.name, "vct");
    try {
        applySetting(p, "technique=lvp");
        FAIL() << "an unknown technique was accepted";
    } catch (const Error& e) {
        std::string valid;
        for (const std::string& n : TechniqueChoice::choices()) valid += (valid.empty() ? "" : ", ") + n;
        EXPECT_NE(std::string(e.what()).find("(valid: " + valid + ")"), std::string::npos) << e.what();
        EXPECT_NE(valid.find("none, lpv, vct"), std::string::npos) << valid;
    }
    EXPECT_EQ(p.header.technique.name, "vct");
    EXPECT_EQ(presetToJson(p)["technique"], "vct");
}

TEST(PassRegistry, EstimatesAddUpOverTheActivePasses) {
    FrameSettings fs;
    fs.width = 64;
    fs.height = 48;
    for (const std::string& technique : TechniqueChoice::choices()) {
        fs.technique = technique;
        size_t sum = 0;
        for (const PassInfo& p : passRegistry())
            if (passActive(p, fs)) sum += p.estimateBytes(fs);
        size_t none = 0;
        FrameSettings plain = fs;
        plain.technique = "none";
        for (const PassInfo& p : passRegistry())
            if (passActive(p, plain)) none += p.estimateBytes(plain);
        EXPECT_EQ(Renderer::estimateFrameBytes(fs) - Renderer::estimateFrameBytes(plain), sum - none) << technique;
    }
    for (const char* technique : {"lpv", "vct"}) EXPECT_GT(findPass(technique)->estimateBytes(fs), 0u) << technique;
}

class PassRegistryGL : public test::GLTest {};

// Every registered technique, with every effect on, renders through gi-render; each active pass's
// reported names are timer rows of stats.json, and nothing else is.
TEST_F(PassRegistryGL, EveryTechniqueRendersWithItsPassesInStats) {
    const std::vector<std::string> frame{"shadows", "gbuffer", "lighting", "tonemap"};
    for (const std::string& technique : TechniqueChoice::choices()) {
        for (bool effects : {false, true}) {
            std::string name = technique + (effects ? "_effects" : "");
            std::vector<std::string> sets{"technique=" + technique, "lpv.gridResolution=16", "lpv.rsmResolution=64",
                                          "vct.gridResolution=32"};
            if (effects)
                sets.insert(sets.end(), {"ssao.enabled=true", "volumetric.enabled=true", "volumetric.density=0.2",
                                         "environment.enabled=true", "environment.file=builtin:sky", "environment.cubeSize=32",
                                         "environment.samples=8"});
            else
                sets.insert(sets.end(), {"ssao.enabled=false", "volumetric.enabled=false", "environment.enabled=false"});
            std::string command = std::string(GI_RENDER_EXE) + " --width 96 --height 64";
            Preset preset = builtinDefaultPreset();
            for (const std::string& s : sets) {
                command += " --set " + s;
                applySetting(preset, s);
            }
            std::filesystem::path out = test::tempDir() / name;
            auto r = test::runCommand(command + " --out " + out.string());
            ASSERT_EQ(r.exitCode, 0) << name << "\n" << r.output;
            std::set<std::string> rows;
            json stats = json::parse(readTextFile(out / "stats.json"));
            for (const json& p : stats["passes"]) rows.insert(p["name"].get<std::string>());

            Scene scene = loadScene(preset.header.scene);
            FrameSettings fs = frameSettings(preset, scene, 96, 64);
            std::set<std::string> expected(frame.begin(), frame.end());
            for (const PassInfo& info : passRegistry()) {
                if (!passActive(info, fs)) continue;
                for (const std::string& n : info.create()->passNames(fs)) {
                    EXPECT_TRUE(rows.count(n)) << name << ": " << info.name << " reports pass " << n << ", not in stats.json";
                    expected.insert(n);
                }
            }
            // Technique none fills the ambient term itself unless the environment lit it.
            if (technique == "none" && !fs.environment.enabled) expected.insert("indirect");
            EXPECT_EQ(rows, expected) << name;
        }
    }
}

// The cost tags decide what a pass rebuilds: a Uniform change rebuilds nothing, a Reallocate
// change rebuilds what it tags, and an unchanged frame rebuilds nothing.
// A preset with `technique` and the environment on, both at small sizes (a 16^2 cube, 4 samples).
Preset smallPreset(const char* technique) {
    Preset p;
    p.header.technique.name = technique;
    p.lpv.gridResolution = 16;
    p.vct.gridResolution = 32;
    p.environment.enabled = true;
    p.environment.file = "builtin:sky";
    p.environment.cubeSize = 16;
    p.environment.samples = 4;
    return p;
}

TEST_F(PassRegistryGL, CostTagsDecideWhatIsRebuilt) {
    Scene scene = loadScene("cornell");
    Preset p = smallPreset("vct");
    Renderer r;
    r.setScene(scene);
    auto frame = [&](const Preset& preset) {
        r.render(frameSettings(preset, scene, 48, 32));
        r.timer().resolve(true);
        bool prefiltered = false;
        for (const PassStats& s : r.passStats()) prefiltered |= s.name == "environment.prefilter";
        return prefiltered;
    };
    auto voxelizations = [&] { return dynamic_cast<const VCT*>(r.technique())->voxelizationCount(); };
    EXPECT_TRUE(frame(p)) << "the first frame builds the maps";
    int first = voxelizations();
    EXPECT_GT(first, 0);
    EXPECT_FALSE(frame(p)) << "an unchanged frame rebuilt the maps";
    EXPECT_EQ(voxelizations(), first);

    p.environment.intensity = 2.0f;  // Uniform
    p.vct.nudge = 1.0f;              // Uniform
    EXPECT_FALSE(frame(p)) << "a uniform change rebuilt the maps";
    EXPECT_EQ(voxelizations(), first) << "a uniform change revoxelized";

    p.environment.samples = 8;  // Reallocate: the maps are built from it
    EXPECT_TRUE(frame(p));
    EXPECT_EQ(voxelizations(), first) << "another section's change revoxelized";

    p.vct.gridResolution = 48;  // Reallocate: new grids, voxelized afresh
    EXPECT_FALSE(frame(p));
    EXPECT_GT(voxelizations(), first);
    EXPECT_EQ(dynamic_cast<const VCT*>(r.technique())->resolution(), 48);
}

// Every active pass's previewers draw something: images with more than a flat colour, overlays
// lines inside the frame (the cone set needs a surface at the focus).
TEST_F(PassRegistryGL, PreviewersDrawWhatTheyName) {
    Scene scene = loadScene("cornell");
    std::set<std::string> seen;
    for (const char* technique : {"lpv", "vct"}) {
        Preset p = smallPreset(technique);
        p.volumetric.enabled = true;
        p.volumetric.density = 0.2f;
        Renderer r;
        r.setScene(scene);
        FrameSettings fs = frameSettings(p, scene, 64, 48);
        r.render(fs);
        PreviewContext ctx = r.previewContext(fs, glm::ivec2(32, 24));
        ASSERT_TRUE(ctx.focus) << "the centre of the Cornell box is a surface";
        for (const Previewer& pv : r.previewers(fs)) {
            seen.insert(pv.name);
            ASSERT_NE(bool(pv.image), bool(pv.overlay)) << pv.name << ": exactly one of image and overlay";
            if (pv.image) {
                PreviewImage img = pv.image(ctx);
                ASSERT_GT(img.width, 0) << pv.name;
                ASSERT_EQ(img.rgba.size(), size_t(img.width) * size_t(img.height) * 4) << pv.name;
                std::set<uint32_t> colours;
                for (size_t i = 0; i < img.rgba.size(); i += 4)
                    colours.insert(uint32_t(img.rgba[i]) << 16 | uint32_t(img.rgba[i + 1]) << 8 | img.rgba[i + 2]);
                EXPECT_GT(colours.size(), 4u) << pv.name << " draws a flat image";
            } else {
                std::vector<GlyphLine> lines = pv.overlay(ctx);
                EXPECT_FALSE(lines.empty()) << pv.name;
                int inside = 0;
                for (const GlyphLine& l : lines) {
                    glm::vec4 c = ctx.viewProj * glm::vec4(l.a, 1.0f);
                    inside += c.w > 0.0f && std::abs(c.x) <= c.w * 1.01f && std::abs(c.y) <= c.w * 1.01f;
                }
                EXPECT_GT(inside, 0) << pv.name << " draws nothing in view";
            }
        }
    }
    for (const char* name : {"lpv.cascades", "vct.voxels", "vct.voxels.radiance", "vct.cones", "volumetric.phase", "environment.mips",
                             "environment.mip0"})
        EXPECT_TRUE(seen.count(name)) << name;
}

}  // namespace
}  // namespace gi
