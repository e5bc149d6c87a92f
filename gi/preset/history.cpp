#include "gi/preset/history.h"

#include <map>

namespace gi {

namespace {

// The preset's keys as --list-settings names them, with their JSON text; lights and bookmarks apart.
std::map<std::string, std::string> flatten(const json& j) {
    std::map<std::string, std::string> out;
    for (auto it = j.begin(); it != j.end(); ++it) {
        if (it.key() == "lights" || it.key() == "bookmarks") continue;
        if (it->is_object())
            for (auto f = it->begin(); f != it->end(); ++f) out[it.key() + "." + f.key()] = f->dump();
        else
            out[it.key()] = it->dump();
    }
    return out;
}

void diffMaps(const std::map<std::string, std::string>& a, const std::map<std::string, std::string>& b, const std::string& prefix,
              std::vector<PresetChange>& out) {
    for (const auto& [key, value] : a) {
        auto it = b.find(key);
        if (it == b.end()) out.push_back({prefix + key, value, ""});
        else if (it->second != value) out.push_back({prefix + key, value, it->second});
    }
    for (const auto& [key, value] : b)
        if (!a.count(key)) out.push_back({prefix + key, "", value});
}

}  // namespace

std::map<std::string, std::string> flattenPreset(const Preset& p) {
    json j = presetToJson(p);
    std::map<std::string, std::string> out = flatten(j);
    if (!p.lightsFromScene)
        for (size_t i = 0; i < p.lights.size(); ++i)
            for (auto& [key, value] : flatten(j["lights"][i])) out["lights." + std::to_string(i) + "." + key] = value;
    for (size_t i = 0; i < p.bookmarks.size(); ++i)
        for (auto& [key, value] : flatten(j["bookmarks"][i])) out["bookmarks." + std::to_string(i) + "." + key] = value;
    return out;
}

std::map<std::string, std::string> lightValues(const LightSettings& light) { return flatten(toJson(light)); }

std::vector<PresetChange> presetDiff(const Preset& before, const Preset& after) {
    json a = presetToJson(before), b = presetToJson(after);
    std::vector<PresetChange> out;
    diffMaps(flatten(a), flatten(b), "", out);
    if (before.lightsFromScene != after.lightsFromScene) {
        auto text = [](const Preset& p) { return p.lightsFromScene ? std::string("the scene's") : std::to_string(p.lights.size()) + " lights"; };
        out.push_back({"lights", text(before), text(after)});
    } else if (!before.lightsFromScene) {
        size_t n = std::max(before.lights.size(), after.lights.size());
        for (size_t i = 0; i < n; ++i) {
            std::map<std::string, std::string> la, lb;
            if (i < before.lights.size()) la = flatten(a["lights"][i]);
            if (i < after.lights.size()) lb = flatten(b["lights"][i]);
            diffMaps(la, lb, "lights." + std::to_string(i) + ".", out);
        }
    }
    if (before.bookmarks.size() != after.bookmarks.size()) {
        out.push_back({"bookmarks", std::to_string(before.bookmarks.size()) + " views", std::to_string(after.bookmarks.size()) + " views"});
    } else {
        for (size_t i = 0; i < after.bookmarks.size(); ++i)
            diffMaps(flatten(a["bookmarks"][i]), flatten(b["bookmarks"][i]), "bookmarks." + std::to_string(i) + ".", out);
    }
    return out;
}

std::string describeChanges(const std::vector<PresetChange>& changes) {
    if (changes.empty()) return "no change";
    if (changes.size() == 1) {
        const PresetChange& c = changes.front();
        return c.key + " " + (c.before.empty() ? "(none)" : c.before) + " -> " + (c.after.empty() ? "(none)" : c.after);
    }
    std::string s = std::to_string(changes.size()) + " settings: ";
    for (size_t i = 0; i < changes.size() && i < 3; ++i) s += (i ? ", " : "") + changes[i].key;
    if (changes.size() > 3) s += ", ...";
    return s;
}

void PresetHistory::reset(const Preset& p, std::string label) {
    mStates.assign(1, State{p, std::move(label)});
    mIndex = 0;
}

bool PresetHistory::record(const Preset& p) {
    std::vector<PresetChange> changes = presetDiff(current(), p);
    if (changes.empty()) return false;
    mStates.resize(mIndex + 1);
    mStates.push_back(State{p, describeChanges(changes)});
    if (mStates.size() > mLimit) mStates.erase(mStates.begin());
    mIndex = mStates.size() - 1;
    return true;
}

const Preset& PresetHistory::undo() {
    if (mIndex > 0) --mIndex;
    return current();
}

const Preset& PresetHistory::redo() {
    if (mIndex + 1 < mStates.size()) ++mIndex;
    return current();
}

const Preset& PresetHistory::jump(size_t index) {
    mIndex = index < mStates.size() ? index : mStates.size() - 1;
    return current();
}

}  // namespace gi
