// Preset files: the shipped presets, validation messages, --set, schema version, atomic saves.
#include "gi/preset/preset.h"
#include "gi/scene/scene.h"
#include "gi/util/paths.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <fstream>
#include <set>

namespace gi {
namespace {

std::string errorOf(const json& j) {
    try {
        presetFromJson(j, "p.json");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(Preset, ShippedPresetsLoad) {
    int count = 0;
    for (const auto& entry : std::filesystem::directory_iterator(GI_PRESET_DIR)) {
        if (entry.path().extension() != ".json") continue;
        EXPECT_NO_THROW(loadPreset(entry.path())) << entry.path();
        ++count;
    }
    EXPECT_GE(count, 3);
}

TEST(Preset, BuiltInDefaultIsTheDefaultFile) {
    // gi-render without input and the editor without files use the compiled-in default.json.
    Preset file = loadPreset(std::filesystem::path(GI_PRESET_DIR) / "default.json");
    Preset builtin = builtinDefaultPreset();
    EXPECT_EQ(presetToJson(builtin), presetToJson(file));
    EXPECT_EQ(builtin.header.scene, "cornell");
    EXPECT_TRUE(isBuiltinScene(builtin.header.scene)) << "the default must need no files";
}

TEST(Preset, SaveLoadRoundTripIsAtomic) {
    auto dir = test::tempDir();
    Preset p;
    p.header.scene = "basic";
    p.camera.fovY = 55.0f;
    p.lightsFromScene = false;
    LightSettings l;
    l.type = LightType::Spot;
    l.outerConeDeg = 35.0f;
    p.lights.push_back(l);
    auto path = dir / "p.json";
    {
        std::ofstream(path) << "previous";
    }
    savePreset(p, path);
    Preset back = loadPreset(path);
    EXPECT_EQ(presetToJson(back), presetToJson(p));
    int files = 0;
    for (auto& e : std::filesystem::directory_iterator(dir)) files += e.is_regular_file();
    EXPECT_EQ(files, 1) << "a temporary file was left behind";
    EXPECT_THROW(savePreset(p, dir / "missing" / "p.json"), Error);
    EXPECT_EQ(presetToJson(loadPreset(path)), presetToJson(p)) << "a failed save touched another file";
}

// A saved file is what a person would write: only the keys that differ from the defaults, in
// the settings table's order, floats as typed (3.4, not 3.4000000953674316), and it reads back
// to the same preset.
TEST(Preset, SavedFileHoldsOnlyChangedKeysInTableOrder) {
    auto dir = test::tempDir();
    Preset p;
    p.header.scene = "basic";
    p.camera.eye = {0.2f, 1.5f, 3.4f};  // the default eye is (0, 1, 3.4)
    p.camera.fovY = 55.0f;
    p.vct.nudge = 2.3f;
    p.vct.gridResolution = 32;  // declared before nudge in the table
    auto path = dir / "p.json";
    savePreset(p, path);
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    json j = json::parse(text);
    std::set<std::string> top;
    for (auto it = j.begin(); it != j.end(); ++it) top.insert(it.key());
    EXPECT_EQ(top, (std::set<std::string>{"schemaVersion", "scene", "camera", "vct"})) << text;
    EXPECT_EQ(j["camera"].size(), 2u) << text;
    EXPECT_EQ(j["vct"].size(), 2u) << text;
    EXPECT_NE(text.find("3.4\n"), std::string::npos) << "float noise: " << text;
    EXPECT_NE(text.find("\"nudge\": 2.3\n"), std::string::npos) << text;
    EXPECT_LT(text.find("gridResolution"), text.find("nudge")) << "not in the table's order: " << text;
    EXPECT_LT(text.find("\"scene\""), text.find("\"camera\"")) << text;
    EXPECT_EQ(presetToJson(loadPreset(path)), presetToJson(p));

    // Every shipped preset survives a save and a reload unchanged, and no saved file is larger
    // than the shipped one by more than formatting.
    for (const auto& entry : std::filesystem::directory_iterator(GI_PRESET_DIR)) {
        if (entry.path().extension() != ".json") continue;
        Preset shipped = loadPreset(entry.path());
        savePreset(shipped, dir / "again.json");
        Preset back = loadPreset(dir / "again.json");
        back.folder = shipped.folder;
        EXPECT_EQ(presetToJson(back), presetToJson(shipped)) << entry.path();
        EXPECT_EQ(presetToSavedJson(back), presetToSavedJson(shipped)) << entry.path();
    }
}

TEST(Preset, MessagesNameTheKey) {
    json base = presetToJson(Preset{});
    auto with = [&](const std::function<void(json&)>& f) {
        json j = base;
        f(j);
        return errorOf(j);
    };
    EXPECT_NE(with([](json& j) { j["render"]["shadowMapSize"] = 100000; }).find("key 'render.shadowMapSize': 100000 is out of range [64, 8192]"),
              std::string::npos);
    EXPECT_NE(with([](json& j) { j["render"]["shadowMapSise"] = 1; }).find("did you mean 'render.shadowMapSize'"), std::string::npos);
    EXPECT_NE(with([](json& j) { j["camra"] = json::object(); }).find("did you mean 'camera'"), std::string::npos);
    EXPECT_NE(with([](json& j) { j["camera"]["fovY"] = "wide"; }).find("key 'camera.fovY': expected a number, got string"),
              std::string::npos);
    EXPECT_NE(with([](json& j) { j["technique"] = "magic"; }).find("unknown value 'magic' (valid: none, lpv, vct, diffusion)"), std::string::npos);
    EXPECT_NE(with([](json& j) { j["lights"] = json::array({{{"type", "laser"}}}); }).find("key 'lights.0.type'"),
              std::string::npos);
    EXPECT_NE(with([](json& j) { j["lights"] = 3; }).find("key 'lights'"), std::string::npos);
    EXPECT_NE(with([](json& j) { j["camera"]["eye"] = json::array({1, 2}); }).find("key 'camera.eye'"), std::string::npos);
    EXPECT_NE(with([](json& j) { j.erase("schemaVersion"); }).find("'schemaVersion' is missing"), std::string::npos);
    EXPECT_NE(with([](json& j) { j["schemaVersion"] = 99; }).find("newer than this build"), std::string::npos);
    EXPECT_NE(errorOf(json::array()).find("must be a JSON object"), std::string::npos);
}

TEST(Preset, SchemaVersion1SSAOLengthsInMetresAreRefusedWithTheConversion) {
    // Version 2 made ssao.radius and ssao.bias fractions of the scene's diagonal. A version-1
    // preset that sets them meant metres: it is refused naming the key and the conversion, never
    // read in the new unit. One that leaves them out means the same in both versions.
    json v1 = {{"schemaVersion", 1}, {"scene", "cornell"}, {"ssao", {{"enabled", true}}}};
    Preset p = presetFromJson(v1, "old.json");
    EXPECT_TRUE(p.ssao.enabled);
    EXPECT_EQ(p.ssao.radius, SSAOSettings{}.radius);
    for (const char* key : {"radius", "bias"}) {
        json j = v1;
        j["ssao"][key] = 0.02;
        std::string msg = errorOf(j);
        EXPECT_NE(msg.find(std::string("p.json: key 'ssao.") + key + "': schemaVersion 1 gives it in metres"), std::string::npos) << msg;
        EXPECT_NE(msg.find("fraction of the scene bounds' diagonal"), std::string::npos) << msg;
        EXPECT_NE(msg.find("set schemaVersion to 2"), std::string::npos) << msg;
        j["schemaVersion"] = 2;
        Preset now = presetFromJson(j, "new.json");
        EXPECT_FLOAT_EQ(std::string(key) == "radius" ? now.ssao.radius : now.ssao.bias, 0.02f);
    }
    // Saved presets carry the version whose units they use.
    EXPECT_EQ(presetToJson(p)["schemaVersion"], 2);
    EXPECT_EQ(Preset::kSchemaVersion, 2);
}

TEST(Preset, BrokenFilesGiveOneLineErrors) {
    auto dir = test::tempDir();
    auto write = [&](const char* name, const char* text) {
        std::ofstream(dir / name) << text;
        return dir / name;
    };
    for (auto path : {write("trunc.json", "{\"schemaVersion\": 1, \"scene\": "), write("empty.json", ""),
                      write("garbage.json", "\x01\x02\xff"), dir / "missing.json"}) {
        try {
            loadPreset(path);
            ADD_FAILURE() << path << " loaded";
        } catch (const Error& e) {
            std::string msg = e.what();
            EXPECT_NE(msg.find(path.filename().string()), std::string::npos) << msg;
            EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        }
    }
}

TEST(Preset, ApplySetting) {
    Preset p;
    applySetting(p, "render.shadowMapSize=512");
    EXPECT_EQ(p.render.shadowMapSize, 512);
    applySetting(p, "camera.eye=[1,2,3]");
    EXPECT_EQ(p.camera.eye, glm::vec3(1, 2, 3));
    applySetting(p, "toneMap.op=reinhard");
    EXPECT_EQ(p.toneMap.op, ToneMapper::Reinhard);
    applySetting(p, "scene=basic");
    EXPECT_EQ(p.header.scene, "basic");
    EXPECT_THROW(applySetting(p, "render.shadowMapSize=-4"), Error);
    EXPECT_THROW(applySetting(p, "render.shadowMapSize"), Error);
    try {
        applySetting(p, "render.shadowmapsize=4");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("did you mean 'render.shadowMapSize'"), std::string::npos) << e.what();
    }
    EXPECT_THROW(applySetting(p, "lights.0.intensity=2"), Error);  // lights come from the scene
    p.lightsFromScene = false;
    p.lights.resize(1);
    applySetting(p, "lights.0.intensity=2");
    EXPECT_FLOAT_EQ(p.lights[0].intensity, 2.0f);
    EXPECT_THROW(applySetting(p, "lights.3.intensity=2"), Error);
    EXPECT_THROW(applySetting(p, "lights.x.intensity=2"), Error);
}

TEST(Preset, ListSettingsCoversEveryKeyOnce) {
    auto list = listSettings();
    std::set<std::string> keys;
    for (auto& s : list) {
        EXPECT_TRUE(keys.insert(s.key).second) << "duplicate " << s.key;
        EXPECT_FALSE(s.description.empty()) << s.key;
        json j = settingInfoToJson(s);
        EXPECT_TRUE(j.contains("default")) << s.key;
    }
    for (auto k : {"scene", "technique", "camera.fovY", "render.shadowMapSize", "toneMap.exposure", "lights.N.type"})
        EXPECT_TRUE(keys.count(k)) << k;
}

TEST(Preset, SceneCameraBringsItsClipPlanes) {
    // A scene in millimetres: the file's camera (or the one framing the bounds) sets near and far;
    // the preset's default far plane of 100 would clip everything away.
    Scene scene;
    CameraSettings fileCamera;
    fileCamera.eye = {0.0f, 0.0f, 2500.0f};
    fileCamera.target = {0.0f, 0.0f, 0.0f};
    fileCamera.near = 12.5f;
    fileCamera.far = 7500.0f;
    scene.cameras.push_back(fileCamera);
    Preset p;
    p.camera.sceneCamera = 0;
    FrameSettings fs = frameSettings(p, scene, 16, 16);
    EXPECT_EQ(fs.camera.near, 12.5f);
    EXPECT_EQ(fs.camera.far, 7500.0f);
    EXPECT_EQ(fs.camera.eye, fileCamera.eye);
    p.camera.sceneCamera = -1;
    EXPECT_EQ(frameSettings(p, scene, 16, 16).camera.far, Preset{}.camera.far);
}

TEST(Preset, AssetSearchPathOrder) {
    auto dir = test::tempDir();
    std::ofstream(dir / "a.gltf") << "{}";
    EXPECT_EQ(resolveAsset("a.gltf", dir), dir / "a.gltf");
    setenv("GI_ASSET_PATH", dir.c_str(), 1);
    EXPECT_EQ(resolveAsset("a.gltf"), dir / "a.gltf");
    unsetenv("GI_ASSET_PATH");
    try {
        resolveAsset("nope/missing.gltf", dir);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("GI_ASSET_PATH"), std::string::npos);
    }
}

TEST(Preset, BookmarksRoundTripAndBadOnesNameTheirKey) {
    Preset p;
    CameraBookmark wide;
    wide.name = "wide";
    wide.eye = {1.0f, 2.0f, 3.0f};
    wide.fovY = 55.0f;
    p.bookmarks.push_back(wide);
    const std::string saved = presetToSavedJson(p).dump();
    Preset back = presetFromText(saved, "saved");
    ASSERT_EQ(back.bookmarks.size(), 1u);
    EXPECT_EQ(back.bookmarks[0].name, "wide");
    EXPECT_EQ(back.bookmarks[0].eye, wide.eye);
    EXPECT_EQ(back.bookmarks[0].fovY, 55.0f);
    // No views: no "bookmarks" key at all.
    EXPECT_EQ(presetToSavedJson(Preset{}).dump().find("bookmarks"), std::string::npos);
    try {
        presetFromText(R"({"schemaVersion": 2, "bookmarks": [{"name": "a", "fovY": 500}]})", "views.json");
        FAIL() << "an out-of-range fovY was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("bookmarks.0.fovY"), std::string::npos) << e.what();
    }
    EXPECT_THROW(presetFromText(R"({"schemaVersion": 2, "bookmarks": {"name": "a"}})", "views.json"), Error);
}

}  // namespace
}  // namespace gi
