// A preset: schema version, scene, technique, camera, lights and every settings section.
// Loading validates everything and names the offending key; saving is atomic.
#pragma once

#include "gi/preset/reflect.h"
#include "gi/reference/reference_settings.h"
#include "gi/render/render_settings.h"
#include "gi/scene/scene_settings.h"

#include <filesystem>
#include <vector>

namespace gi {

// The top-level keys of a preset.
struct PresetHeader {
    static constexpr std::string_view kSection = "";
    std::string scene = "cornell";           // built-in scene name or glTF path (search path applies)
    TechniqueChoice technique;               // which technique fills the indirect term ("none" or a registered one)

    template <class V>
    void visit(V&& v) {
        v(scene, {"scene", "Built-in scene (cornell, basic) or a glTF file path", "", 0, 0, Cost::ReloadScene});
        v(technique, {"technique", "Technique that computes indirect light", "", 0, 0, Cost::Reallocate});
    }
};

// What a preset promises when its image is scored against the path-traced reference
// (tests/image_tests.json renders each listed preset and checks these bounds).
struct QualitySettings {
    static constexpr std::string_view kSection = "quality";
    float minSSIM = 0.0f;           // the SSIM the render must reach against the full reference
    float maxLeakFraction = 1.0f;   // the largest fraction of leak pixels allowed
    float maxBrightnessError = 100.0f;  // the largest |mean luminance / the reference's - 1| allowed
    float minSSIMLinear = 0.0f;     // SSIM of the images as 8-bit sRGB without tone mapping (gi-compare's); 0: unchecked

    template <class V>
    void visit(V&& v) {
        v(minSSIM, forDevelopers({"minSSIM", "SSIM the preset must reach against the path-traced reference (tests check it)", "", -1, 1}));
        v(maxLeakFraction, forDevelopers({"maxLeakFraction", "Largest fraction of pixels allowed to leak light", "", 0, 1}));
        v(maxBrightnessError, forDevelopers({"maxBrightnessError", "Largest relative error of the mean brightness against the reference", "", 0, 100}));
        v(minSSIMLinear, forDevelopers({"minSSIMLinear", "SSIM the preset must reach on 8-bit sRGB without tone mapping (as gi-compare scores; 0: unchecked)", "", 0, 1}));
    }
};

// The frame's sections (render, toneMap and every pass's, gi/render/render_settings.h) come
// from FrameSections, so a new technique's section is a preset section with no edit here.
struct Preset : FrameSections {
    // 2: ssao.radius and ssao.bias are fractions of the scene's diagonal (metres in 1).
    static constexpr int kSchemaVersion = 2;
    PresetHeader header;
    CameraSettings camera;
    std::vector<LightSettings> lights;  // used when lightsFromScene is false
    bool lightsFromScene = true;        // no "lights" key: take the scene's own lights
    std::vector<CameraBookmark> bookmarks;  // named views ("bookmarks"; written only when there are some)
    ReferenceSettings reference;
    QualitySettings quality;
    std::filesystem::path folder;       // folder of the file it came from (asset search path)

    // Every fixed settings section, for code that treats them alike.
    template <class F>
    void forEachSection(F&& f) {
        f(camera);
        FrameSections::forEachSection(f);
        f(reference);
        f(quality);
    }
};

// presets/default.json, compiled in: what gi-render without input and the editor without files use.
Preset builtinDefaultPreset();

// Every key of every section (what stats.json and the reference cache record).
json presetToJson(const Preset& p);
// What a saved preset file holds: schemaVersion, then only the keys whose value differs from
// the defaults, in the settings table's order (header, then each section; a section with no
// change is left out; lights, when the preset names them, each with its changed keys). Floats
// are written as the shortest text that reads back to the same value. Loading it gives `p` back.
nlohmann::ordered_json presetToSavedJson(const Preset& p);
// `context` names the source in error messages (usually the file path).
Preset presetFromJson(const json& j, const std::string& context);
// A preset from its JSON text; invalid JSON is an error naming the byte.
Preset presetFromText(const std::string& text, const std::string& context);
// Presets are small: a larger file is refused before it is read.
constexpr size_t kMaxPresetBytes = size_t(16) << 20;
Preset loadPreset(const std::filesystem::path& path);
void savePreset(const Preset& p, const std::filesystem::path& path);

// Applies "key=value" (keys as in --list-settings; lights as lights.N.key). Throws gi::Error.
void applySetting(Preset& p, const std::string& assignment);

// Every settings key with type, range, default and description.
std::vector<SettingInfo> listSettings();
json settingInfoToJson(const SettingInfo& s);

struct Scene;

// A preset for any runner input: a preset file as it is, or a glTF file rendered with its own
// cameras (`sceneCamera`; -1 takes the first, or one framing the scene when it has none) and lights.
// Throws gi::Error.
Preset presetForInput(const std::filesystem::path& input, int sceneCamera);
// True when the frame is lit by the invented default sun: the preset takes the scene's lights and
// the scene has neither punctual lights nor emissive surfaces.
bool usesDefaultSun(const Preset& p, const Scene& scene);
// The frame's lights: the preset's, or the scene's (sceneLights) when it lists none; the scene's
// emitters that the preset does not name join as area lights; lights switched off are left out;
// the default sun only when usesDefaultSun. Throws gi::Error naming an emitter that does not exist.
std::vector<LightSettings> frameLights(const Preset& p, const Scene& scene);
// Resolves the preset against a loaded scene: frameLights, and the file's camera when
// camera.sceneCamera is set. Throws gi::Error for a camera index past the end.
FrameSettings frameSettings(const Preset& p, const Scene& scene, int width, int height);

}  // namespace gi
