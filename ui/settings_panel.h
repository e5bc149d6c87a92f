// Settings panels generated from the reflection table: drawSettings walks a settings struct's
// visit() list and draws the widget each field type calls for, so no panel holds per-field code.
#pragma once

#include "gi/preset/reflect.h"
#include "gi/preset/settings.h"

#include <map>
#include <vector>

#include <glm/vec3.hpp>
#include <imgui.h>

#include <string>

namespace gi::ui {

// The widget label "words##key" (gi::readableKey's words; the ImGui ID stays the key's).
std::string fieldLabel(const FieldMeta& m);
// A number's printf format with the field's unit after it ("%.3f m"; "%" escaped).
std::string unitFormat(const char* number, const FieldMeta& m);

// One widget per field type, labelled with the key in words; a number shows its unit in the
// widget. Each returns true when the user changed the value; the value is then already clamped
// to the field's range.
bool drawField(float& value, const FieldMeta& m);
bool drawField(int& value, const FieldMeta& m);
bool drawField(bool& value, const FieldMeta& m);
bool drawField(std::string& value, const FieldMeta& m);
bool drawField(glm::vec3& value, const FieldMeta& m);
bool drawField(std::vector<float>& value, const FieldMeta& m);

// Tooltip for the last item: description, unit, range (numbers only) and what a change costs.
void fieldTooltip(const FieldMeta& m, bool showRange);
// Tooltip for the last item, drawn disabled: description, unit and why it cannot be edited.
void readOnlyTooltip(const FieldMeta& m, const char* reason);

template <ReflectedEnum E>
bool drawField(E& value, const FieldMeta& m) {
    bool changed = false;
    bool open = ImGui::BeginCombo(fieldLabel(m).c_str(), enumName(value));
    fieldTooltip(m, false);
    if (open) {
        for (const auto& [v, name] : EnumNames<E>::values) {
            if (ImGui::Selectable(name, v == value) && v != value) {
                value = v;
                changed = true;
            }
        }
        ImGui::EndCombo();
    }
    return changed;
}

template <ChoiceString T>
bool drawField(T& value, const FieldMeta& m) {
    bool changed = false;
    bool open = ImGui::BeginCombo(fieldLabel(m).c_str(), value.name.c_str());
    fieldTooltip(m, false);
    if (open) {
        for (const std::string& name : T::choices()) {
            if (ImGui::Selectable(name.c_str(), name == value.name) && name != value.name) {
                value.name = name;
                changed = true;
            }
        }
        ImGui::EndCombo();
    }
    return changed;
}

// What drawSettings compares each field with, by full key (prefix + key, as --list-settings
// names it) to the JSON text of the value (gi/preset/history.h flattenPreset): the defaults and
// the file on disk. A value that differs gets a marker beside it, and its right-click menu resets
// it to the default or reverts it to the file. A null map draws no such marker.
struct FieldBaselines {
    std::string prefix;  // "vct.", "" for the header, "lights.0."
    const std::map<std::string, std::string>* defaults = nullptr;
    const std::map<std::string, std::string>* disk = nullptr;
    bool* developerOpen = nullptr;               // the developer node's state (drawSettings)
    std::vector<std::string>* shown = nullptr;   // receives the full key of each field drawn
};

// Markers left of the last item: a blue dot where the value differs from the default, an
// orange bar where it differs from the file on disk (an unsaved change).
void fieldMarkers(bool differsFromDefault, bool differsFromDisk);
// The right-click menu of the last item; returns the JSON text of the value chosen, or "".
std::string resetMenu(const char* id, const std::string* defaultValue, const std::string* diskValue, bool differsFromDefault,
                      bool differsFromDisk);

// Draws every field of `s` and returns the OR of the Cost bits of the fields that changed. The
// fields an artist tunes come first; those marked forDevelopers follow under a "developer" tree
// node, closed unless *developerOpen (kept by the caller; ImGui's own state when null) says
// otherwise. Its label counts them and those off their default.
template <Settings S>
uint8_t drawSettings(S& s, const FieldBaselines& baselines = {}) {
    uint8_t cost = 0;
    auto lookup = [](const std::map<std::string, std::string>* m, const std::string& key) -> const std::string* {
        if (!m) return nullptr;
        auto it = m->find(key);
        return it == m->end() ? nullptr : &it->second;
    };
    auto drawOne = [&](auto& field, const FieldMeta& m) {
        if (baselines.shown) baselines.shown->push_back(baselines.prefix + m.key);
        const char* readOnly = nullptr;
        if constexpr (HasReadOnlyFields<S>) readOnly = s.readOnly(m.key);
        if (!readOnly) {
            if (drawField(field, m)) cost |= uint8_t(m.cost);
            const std::string key = baselines.prefix + m.key;
            const std::string* def = lookup(baselines.defaults, key);
            const std::string* disk = lookup(baselines.disk, key);
            if (!def && !disk) return;
            const std::string now = gi::detail::write(field).dump();
            bool offDefault = def && *def != now, offDisk = disk && *disk != now;
            fieldMarkers(offDefault, offDisk);
            std::string chosen = resetMenu(m.key, def, disk, offDefault, offDisk);
            if (!chosen.empty() && setField(s, m.key, chosen, key)) cost |= uint8_t(m.cost);
            return;
        }
        // Shown with its value, disabled; a copy, so not even a clamp can write to it.
        auto shown = field;
        ImGui::BeginDisabled();
        drawField(shown, m);
        ImGui::EndDisabled();
        readOnlyTooltip(m, readOnly);
    };
    // Sections share key names (a light's and the camera's "color", "near"...): scope the IDs.
    ImGui::PushID(S::kSection.data(), S::kSection.data() + S::kSection.size());
    int developer = 0, developerOffDefault = 0;
    s.visit([&](auto& field, const FieldMeta& m) {
        if (!m.developer) return drawOne(field, m);
        ++developer;
        const std::string* def = lookup(baselines.defaults, baselines.prefix + m.key);
        if (def && *def != gi::detail::write(field).dump()) ++developerOffDefault;
    });
    if (developer > 0) {
        std::string label = "developer (" + std::to_string(developer) + " settings";
        if (developerOffDefault) label += ", " + std::to_string(developerOffDefault) + " not default";
        label += ")";
        if (baselines.developerOpen) ImGui::SetNextItemOpen(*baselines.developerOpen, ImGuiCond_Always);
        const bool open = ImGui::TreeNode("developer", "%s", label.c_str());
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("settings one debugs rather than tunes: biases, sample counts, budgets, test thresholds");
        if (baselines.developerOpen) *baselines.developerOpen = open;
        if (open) {
            s.visit([&](auto& field, const FieldMeta& m) {
                if (m.developer) drawOne(field, m);
            });
            ImGui::TreePop();
        }
    }
    ImGui::PopID();
    return cost;
}

}  // namespace gi::ui
