// The editor's undo history and the key-by-key difference of two presets. Pure logic on Presets
// (no UI), so the editor's undo, redo, history list and "differs from the file" markers are
// tested without a window.
#pragma once

#include "gi/preset/preset.h"

#include <map>
#include <string>
#include <vector>

namespace gi {

// One key whose value differs between two presets: keys as --list-settings names them
// ("vct.nudge", "scene"), lights as "lights.N.key", or "lights" when one preset names lights and
// the other takes the scene's; values as their JSON text.
struct PresetChange {
    std::string key;
    std::string before;  // "" where the key is absent (a light only one of them has)
    std::string after;
};
std::vector<PresetChange> presetDiff(const Preset& before, const Preset& after);
// Every key of the preset with its value's JSON text, as presetDiff compares them (lights as
// lights.N.key, present only when the preset names its lights).
std::map<std::string, std::string> flattenPreset(const Preset& p);
// The JSON text of a light's values, by key (no prefix).
std::map<std::string, std::string> lightValues(const LightSettings& light);
// "vct.nudge 3 -> 2" for one change, "3 settings: vct.nudge, camera.eye, ..." for more.
std::string describeChanges(const std::vector<PresetChange>& changes);

// A linear history of preset states. The editor records the preset once an edit is complete (a
// drag, a typed value, a camera flight: one step each), so undo returns to the state before it.
// Recording after an undo drops the states that redo would have reached.
class PresetHistory {
public:
    explicit PresetHistory(size_t limit = 256) : mLimit(limit < 2 ? 2 : limit) {}

    // Starts over with one state, labelled `label` (e.g. "opened default.json").
    void reset(const Preset& p, std::string label);
    // Appends p if it differs from the current state; returns whether it did.
    bool record(const Preset& p);

    bool canUndo() const { return mIndex > 0; }
    bool canRedo() const { return mIndex + 1 < mStates.size(); }
    const Preset& undo();  // the state before the current one (the current one when there is none)
    const Preset& redo();
    const Preset& jump(size_t index);  // clamped to the states there are

    const Preset& current() const { return mStates[mIndex].preset; }
    size_t index() const { return mIndex; }
    size_t size() const { return mStates.size(); }
    const std::string& label(size_t i) const { return mStates[i].label; }

private:
    struct State {
        Preset preset;
        std::string label;  // what changed to reach it
    };
    std::vector<State> mStates{State{}};
    size_t mIndex = 0;
    size_t mLimit;
};

}  // namespace gi
