// Settings panels generated from the reflection table: drawSettings walks a settings struct's
// visit() list and draws the widget each field type calls for, so no panel holds per-field code.
#pragma once

#include "gi/preset/settings.h"

#include <vector>

#include <glm/vec3.hpp>
#include <imgui.h>

#include <string>

namespace gi::ui {

// One widget per field type, labelled with the key. Each returns true when the user changed the
// value; the value is then already clamped to the field's range.
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
    bool open = ImGui::BeginCombo(m.key, enumName(value));
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
    bool open = ImGui::BeginCombo(m.key, value.name.c_str());
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

// Draws every field of `s` and returns the OR of the Cost bits of the fields that changed.
template <Settings S>
uint8_t drawSettings(S& s) {
    uint8_t cost = 0;
    // Sections share key names (a light's and the camera's "color", "near"...): scope the IDs.
    ImGui::PushID(S::kSection.data(), S::kSection.data() + S::kSection.size());
    s.visit([&](auto& field, const FieldMeta& m) {
        const char* readOnly = nullptr;
        if constexpr (HasReadOnlyFields<S>) readOnly = s.readOnly(m.key);
        if (!readOnly) {
            if (drawField(field, m)) cost |= uint8_t(m.cost);
            return;
        }
        // Shown with its value, disabled; a copy, so not even a clamp can write to it.
        auto shown = field;
        ImGui::BeginDisabled();
        drawField(shown, m);
        ImGui::EndDisabled();
        readOnlyTooltip(m, readOnly);
    });
    ImGui::PopID();
    return cost;
}

}  // namespace gi::ui
