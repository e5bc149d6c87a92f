#include "gi/preset/preset.h"

#include "gi/scene/emitters.h"

#include "gi/envmap/envmap_image.h"

#include "gi/scene/camera.h"
#include "gi/scene/scene.h"
#include "gi/util/paths.h"

namespace gi {

namespace {

template <Settings S>
std::string sectionPrefix() {
    return S::kSection.empty() ? std::string() : std::string(S::kSection) + ".";
}

std::vector<std::string> topLevelKeys() {
    std::vector<std::string> keys = fieldKeys<PresetHeader>("");
    keys.insert(keys.end(), {"schemaVersion", "lights", "bookmarks"});
    Preset p;
    p.forEachSection([&](auto& s) { keys.emplace_back(std::decay_t<decltype(s)>::kSection); });
    return keys;
}

// The JSON values of a settings struct's fields, in the table's order.
template <Settings S>
std::vector<json> fieldValues(const S& s) {
    std::vector<json> v;
    const_cast<S&>(s).visit([&](auto& field, const FieldMeta&) { v.push_back(detail::write(field)); });
    return v;
}

// The fields of `s` whose value differs from `base` (fieldValues of the defaults), in the table's order.
template <Settings S>
nlohmann::ordered_json changedFields(const S& s, const std::vector<json>& base) {
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    size_t i = 0;
    const_cast<S&>(s).visit([&](auto& field, const FieldMeta& m) {
        json v = detail::write(field);
        if (i >= base.size() || v != base[i]) j[m.key] = nlohmann::ordered_json::parse(v.dump());
        ++i;
    });
    return j;
}

}  // namespace

nlohmann::ordered_json presetToSavedJson(const Preset& p) {
    const Preset defaults;
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    j["schemaVersion"] = Preset::kSchemaVersion;
    const nlohmann::ordered_json header = changedFields(p.header, fieldValues(defaults.header));
    for (auto it = header.begin(); it != header.end(); ++it) j[it.key()] = it.value();
    std::vector<std::vector<json>> sections;
    const_cast<Preset&>(defaults).forEachSection([&](auto& s) { sections.push_back(fieldValues(s)); });
    size_t i = 0;
    const_cast<Preset&>(p).forEachSection([&](auto& s) {
        nlohmann::ordered_json changed = changedFields(s, sections[i++]);
        if (!changed.empty()) j[std::string(std::decay_t<decltype(s)>::kSection)] = changed;
    });
    if (!p.lightsFromScene) {
        const std::vector<json> light = fieldValues(LightSettings{});
        nlohmann::ordered_json lights = nlohmann::ordered_json::array();
        for (const auto& l : p.lights) lights.push_back(changedFields(l, light));
        j["lights"] = lights;
    }
    if (!p.bookmarks.empty()) {
        nlohmann::ordered_json bookmarks = nlohmann::ordered_json::array();
        for (const auto& b : p.bookmarks) bookmarks.push_back(nlohmann::ordered_json::parse(toJson(b).dump()));
        j["bookmarks"] = bookmarks;
    }
    return j;
}

json presetToJson(const Preset& p) {
    json j = toJson(p.header);
    j["schemaVersion"] = Preset::kSchemaVersion;
    Preset& mp = const_cast<Preset&>(p);
    mp.forEachSection([&](auto& s) { j[std::string(std::decay_t<decltype(s)>::kSection)] = toJson(s); });
    if (!p.lightsFromScene) {
        json lights = json::array();
        for (const auto& l : p.lights) lights.push_back(toJson(l));
        j["lights"] = lights;
    }
    if (!p.bookmarks.empty()) {
        json bookmarks = json::array();
        for (const auto& b : p.bookmarks) bookmarks.push_back(toJson(b));
        j["bookmarks"] = bookmarks;
    }
    return j;
}

Preset presetFromJson(const json& j, const std::string& context) {
    if (!j.is_object()) throw Error(context + ": a preset must be a JSON object");
    auto version = j.find("schemaVersion");
    if (version == j.end()) throw Error(context + ": key 'schemaVersion' is missing");
    if (!version->is_number_integer())
        throw Error(context + ": key 'schemaVersion': expected an integer, got " + version->type_name());
    int v = version->get<int>();
    if (v > Preset::kSchemaVersion)
        throw Error(context + ": key 'schemaVersion': " + std::to_string(v) +
                    " is newer than this build understands (" + std::to_string(Preset::kSchemaVersion) + ")");
    if (v < 1) throw Error(context + ": key 'schemaVersion': " + std::to_string(v) + " is not a valid version");
    // Migrations from older versions. 1 -> 2: ssao.radius and ssao.bias changed from metres to
    // fractions of the scene's diagonal. Converting needs the scene's size, which the preset
    // alone does not give, so a version-1 preset that sets them is refused with the conversion
    // rather than read in the new unit; one that does not set them means the same in both.
    if (v < 2) {
        auto ssao = j.find("ssao");
        if (ssao != j.end() && ssao->is_object())
            for (const char* key : {"radius", "bias"})
                if (ssao->contains(key))
                    throw Error(detail::where(context, std::string("ssao.") + key) +
                                ": schemaVersion " + std::to_string(v) +
                                " gives it in metres; since schemaVersion 2 it is a fraction of the scene bounds' diagonal "
                                "(the built-in Cornell box's is 3.46 m, so 0.5 m there is 0.144): divide by the scene's "
                                "diagonal and set schemaVersion to 2");
    }

    std::vector<std::string> keys = topLevelKeys();
    json header = json::object();
    for (auto it = j.begin(); it != j.end(); ++it) {
        bool known = false;
        for (auto& k : keys) known |= (k == it.key());
        if (!known)
            throw Error(detail::where(context, it.key()) + ": unknown key (did you mean '" +
                        detail::nearest(it.key(), keys) + "'?)");
    }
    for (auto& k : fieldKeys<PresetHeader>(""))
        if (j.contains(k)) header[k] = j[k];

    Preset p;
    fromJson(p.header, header, context, "");
    p.forEachSection([&](auto& s) {
        using S = std::decay_t<decltype(s)>;
        auto it = j.find(std::string(S::kSection));
        if (it != j.end()) fromJson(s, *it, context, sectionPrefix<S>());
    });
    if (auto it = j.find("lights"); it != j.end()) {
        if (!it->is_array()) throw Error(detail::where(context, "lights") + ": expected an array of lights");
        if (it->size() > 64) throw Error(detail::where(context, "lights") + ": more than 64 lights");
        p.lightsFromScene = false;
        for (size_t i = 0; i < it->size(); ++i) {
            LightSettings l;
            fromJson(l, (*it)[i], context, "lights." + std::to_string(i) + ".");
            p.lights.push_back(l);
        }
    }
    if (auto it = j.find("bookmarks"); it != j.end()) {
        if (!it->is_array()) throw Error(detail::where(context, "bookmarks") + ": expected an array of views");
        if (it->size() > 256) throw Error(detail::where(context, "bookmarks") + ": more than 256 views");
        for (size_t i = 0; i < it->size(); ++i) {
            CameraBookmark b;
            fromJson(b, (*it)[i], context, "bookmarks." + std::to_string(i) + ".");
            p.bookmarks.push_back(b);
        }
    }
    return p;
}

Preset presetFromText(const std::string& text, const std::string& context) {
    json j;
    try {
        j = json::parse(text);
    } catch (const json::parse_error& e) {
        throw Error(context + ": invalid JSON at byte " + std::to_string(e.byte));
    } catch (const json::exception& e) {
        // Not only syntax: a number past the range of a double (1e400) is out_of_range.406.
        std::string what = e.what();
        for (auto& c : what)
            if (c == '\n') c = ' ';
        throw Error(context + ": invalid JSON: " + what);
    }
    return presetFromJson(j, context);
}

Preset loadPreset(const std::filesystem::path& path) {
    Preset p = presetFromText(readTextFile(path, kMaxPresetBytes), path.string());
    p.folder = path.parent_path();
    return p;
}

void savePreset(const Preset& p, const std::filesystem::path& path) {
    writeFileAtomic(path, presetToSavedJson(p).dump(2) + "\n");
}

void applySetting(Preset& p, const std::string& assignment) {
    auto eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0)
        throw Error("--set '" + assignment + "': expected key=value");
    std::string key = assignment.substr(0, eq);
    std::string value = assignment.substr(eq + 1);

    if (setField(p.header, key, value, key)) return;
    bool done = false;
    p.forEachSection([&](auto& s) {
        using S = std::decay_t<decltype(s)>;
        std::string prefix = sectionPrefix<S>();
        if (!done && key.rfind(prefix, 0) == 0) done = setField(s, key.substr(prefix.size()), value, key);
    });
    if (done) return;
    if (key.rfind("lights.", 0) == 0) {
        std::string rest = key.substr(7);
        auto dot = rest.find('.');
        if (dot == std::string::npos) throw Error("--set: key '" + key + "': expected lights.N.key");
        size_t index = 0;
        try {
            index = std::stoul(rest.substr(0, dot));
        } catch (...) {
            throw Error("--set: key '" + key + "': expected a light index after 'lights.'");
        }
        if (p.lightsFromScene)
            throw Error("--set: key '" + key + "': this preset takes its lights from the scene; "
                        "set them in the preset's \"lights\" list first");
        if (index >= p.lights.size())
            throw Error("--set: key '" + key + "': light " + std::to_string(index) + " does not exist (the preset has " +
                        std::to_string(p.lights.size()) + ")");
        if (setField(p.lights[index], rest.substr(dot + 1), value, key)) return;
        throw Error("--set: key '" + key + "': unknown key (did you mean 'lights." + std::to_string(index) + "." +
                    detail::nearest(rest.substr(dot + 1), fieldKeys<LightSettings>("")) + "'?)");
    }
    std::vector<std::string> all;
    for (auto& s : listSettings()) all.push_back(s.key);
    throw Error("--set: key '" + key + "': unknown key (did you mean '" + detail::nearest(key, all) + "'?)");
}

std::vector<SettingInfo> listSettings() {
    std::vector<SettingInfo> out;
    describe<PresetHeader>(out, "");
    Preset p;
    p.forEachSection([&](auto& s) {
        using S = std::decay_t<decltype(s)>;
        describe<S>(out, sectionPrefix<S>());
    });
    describe<LightSettings>(out, "lights.N.");
    return out;
}

json settingInfoToJson(const SettingInfo& s) {
    json j = {{"key", s.key},        {"type", s.type}, {"description", s.description},
              {"unit", s.unit},      {"cost", s.cost}, {"default", s.defaultValue}};
    if (std::isfinite(s.min)) j["min"] = s.min;
    if (std::isfinite(s.max)) j["max"] = s.max;
    if (!s.choices.empty()) j["choices"] = s.choices;
    if (s.developer) j["developer"] = true;
    return j;
}

Preset presetForInput(const std::filesystem::path& input, int sceneCamera) {
    std::string ext = input.extension().string();
    for (auto& c : ext) c = char(std::tolower(c));
    if (ext == ".gltf" || ext == ".glb") {
        Preset p;
        p.header.scene = std::filesystem::absolute(input).string();
        // The file's first camera (loadScene adds one framing the scene when it has none).
        p.camera.sceneCamera = std::max(sceneCamera, 0);
        p.lightsFromScene = true;
        return p;
    }
    if (ext != ".json") throw Error(input.string() + ": expected a preset (.json) or a glTF file (.gltf, .glb)");
    Preset p = loadPreset(input);
    if (sceneCamera >= 0) p.camera.sceneCamera = sceneCamera;
    return p;
}

bool usesDefaultSun(const Preset& p, const Scene& scene) {
    return p.lightsFromScene && scene.lights.empty() && scene.emitters.empty();
}

std::vector<LightSettings> frameLights(const Preset& p, const Scene& scene) {
    if (usesDefaultSun(p, scene)) {
        // A file with no lights and nothing emissive would render black but for the ambient
        // term: light it with a sun (gi-render and the editor say so).
        LightSettings sun;
        sun.direction = {-0.4f, -0.8f, -0.45f};
        return {sun};
    }
    std::vector<LightSettings> listed = p.lightsFromScene ? sceneLights(scene) : p.lights;
    // The scene's emitters light it whatever the preset lists: those it does not name join with
    // their defaults.
    std::vector<bool> named(scene.emitters.size(), false);
    for (size_t i = 0; i < listed.size(); ++i) {
        if (listed[i].type != LightType::Area) continue;
        int e = listed[i].emitter;
        if (e < 0 || e >= int(scene.emitters.size()))
            throw Error("key 'lights." + std::to_string(i) + ".emitter': emitter " + std::to_string(e) +
                        " does not exist (scene '" + scene.name + "' has " + std::to_string(scene.emitters.size()) +
                        " emissive surfaces)");
        named[size_t(e)] = true;
    }
    for (const LightSettings& l : sceneLights(scene))
        if (l.type == LightType::Area && !named[size_t(l.emitter)]) listed.push_back(l);
    std::vector<LightSettings> lights;
    for (LightSettings l : listed) {
        if (!l.enabled) continue;
        lights.push_back(l.type == LightType::Area ? placeAreaLight(l, scene.emitters[size_t(l.emitter)]) : l);
    }
    return lights;
}

FrameSettings frameSettings(const Preset& p, const Scene& scene, int width, int height) {
    FrameSettings fs;
    fs.camera = p.camera;
    if (p.camera.sceneCamera >= 0) {
        if (p.camera.sceneCamera >= int(scene.cameras.size()))
            throw Error("key 'camera.sceneCamera': camera " + std::to_string(p.camera.sceneCamera) + " does not exist (scene '" +
                        scene.name + "' has " + std::to_string(scene.cameras.size()) + ")");
        takeSceneCamera(fs.camera, scene.cameras[p.camera.sceneCamera]);
    }
    fs.lights = frameLights(p, scene);
    static_cast<FrameSections&>(fs) = p;
    fs.technique = p.header.technique.name;
    // Found once here, so the raster and the path tracer load the same file whatever the folder.
    // A name not found stays as it is: loading it then fails with the error naming it.
    if (fs.environment.enabled) {
        try {
            fs.environment.file = resolveEnvironmentFile(p.environment.file, p.folder);
        } catch (const Error&) {
        }
    }
    fs.width = width;
    fs.height = height;
    return fs;
}

}  // namespace gi
