#include "ui/settings_panel.h"

#include "gi/preset/reflect.h"

#include <glm/common.hpp>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdio>

namespace gi::ui {

namespace {

// ImGui clamps drags to [lo, hi]; an unbounded end becomes a huge finite one it can handle.
float lowEnd(const FieldMeta& m) { return std::isfinite(m.min) ? float(m.min) : -FLT_MAX / 2; }
float highEnd(const FieldMeta& m) { return std::isfinite(m.max) ? float(m.max) : FLT_MAX / 2; }
double span(const FieldMeta& m) { return m.max - m.min; }  // inf when unbounded

// Drag speed per pixel: the field's own step, else a fraction of a small range, else relative
// to the value so a 0.05 m near plane and a 2048 MiB budget both drag sensibly.
float dragSpeed(const FieldMeta& m, float value) {
    if (m.step > 0) return float(m.step);
    if (span(m) <= 100) return float(span(m) / 200);
    return 0.005f * std::max(1.0f, std::abs(value));
}

bool isColor(const FieldMeta& m) {
    std::string key = m.key;
    std::transform(key.begin(), key.end(), key.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return key.find("color") != std::string::npos || key.find("colour") != std::string::npos ||
           key.find("ambient") != std::string::npos;
}

constexpr ImGuiSliderFlags kDragFlags = ImGuiSliderFlags_AlwaysClamp | ImGuiSliderFlags_NoRoundToFormat;

}  // namespace

void fieldMarkers(bool differsFromDefault, bool differsFromDisk) {
    if (!differsFromDefault && !differsFromDisk) return;
    ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
    ImDrawList* draw = ImGui::GetWindowDrawList();
    // In the window's left padding, which the content clip rectangle leaves out.
    ImVec2 wp = ImGui::GetWindowPos();
    draw->PushClipRect(wp, ImVec2(wp.x + ImGui::GetWindowWidth(), wp.y + ImGui::GetWindowHeight()), false);
    float y = 0.5f * (lo.y + hi.y);
    if (differsFromDefault) draw->AddCircleFilled(ImVec2(lo.x - 5.0f, y), 3.0f, IM_COL32(90, 160, 255, 255));
    if (differsFromDisk) draw->AddRectFilled(ImVec2(lo.x - 1.5f, lo.y), ImVec2(lo.x + 0.5f, hi.y), IM_COL32(255, 150, 40, 255));
    draw->PopClipRect();
    if (ImGui::IsItemHovered() && ImGui::GetIO().KeyAlt)
        ImGui::SetTooltip("%s%s%s", differsFromDefault ? "differs from the default" : "", differsFromDefault && differsFromDisk ? "; " : "",
                          differsFromDisk ? "not saved: differs from the file" : "");
}

std::string resetMenu(const char* id, const std::string* defaultValue, const std::string* diskValue, bool differsFromDefault,
                      bool differsFromDisk) {
    std::string chosen;
    if (!ImGui::BeginPopupContextItem(id)) return chosen;
    if (defaultValue && ImGui::MenuItem("Reset to default", defaultValue->c_str(), false, differsFromDefault)) chosen = *defaultValue;
    if (diskValue && ImGui::MenuItem("Revert to the file", diskValue->c_str(), false, differsFromDisk)) chosen = *diskValue;
    ImGui::EndPopup();
    return chosen;
}

void fieldTooltip(const FieldMeta& m, bool showRange) {
    if (!ImGui::IsItemHovered()) return;
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30);
    ImGui::TextUnformatted(m.description);
    if (*m.unit) ImGui::Text("unit: %s", m.unit);
    if (showRange) ImGui::Text("range: %s", detail::rangeText(m).c_str());
    ImGui::Text("change: %s", costName(m.cost));
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
}

void readOnlyTooltip(const FieldMeta& m, const char* reason) {
    if (!ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) return;
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30);
    ImGui::TextUnformatted(m.description);
    if (*m.unit) ImGui::Text("unit: %s", m.unit);
    ImGui::Text("read-only: %s", reason);
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
}

std::string fieldLabel(const FieldMeta& m) { return readableKey(m.key) + "##" + m.key; }

std::string unitFormat(const char* number, const FieldMeta& m) {
    std::string format = number;
    if (!*m.unit) return format;
    format += ' ';
    for (const char* u = m.unit; *u; ++u) format += *u == '%' ? std::string("%%") : std::string(1, *u);
    return format;
}

bool drawField(float& value, const FieldMeta& m) {
    float v = value;
    bool changed;
    const std::string label = fieldLabel(m);
    if (m.step == 0 && span(m) <= 100)
        changed = ImGui::SliderFloat(label.c_str(), &v, lowEnd(m), highEnd(m), unitFormat("%.3f", m).c_str(), kDragFlags);
    else
        changed = ImGui::DragFloat(label.c_str(), &v, dragSpeed(m, v), lowEnd(m), highEnd(m), unitFormat("%.4g", m).c_str(), kDragFlags);
    fieldTooltip(m, true);
    if (!changed) return false;
    value = std::clamp(v, lowEnd(m), highEnd(m));
    return true;
}

bool drawField(int& value, const FieldMeta& m) {
    int lo = std::isfinite(m.min) ? int(m.min) : INT_MIN / 2;
    int hi = std::isfinite(m.max) ? int(m.max) : INT_MAX / 2;
    float speed = m.step > 0 ? float(m.step) : std::max(0.2f, 0.005f * float(std::abs(value)));
    int v = value;
    bool changed = ImGui::DragInt(fieldLabel(m).c_str(), &v, speed, lo, hi, unitFormat("%d", m).c_str(), ImGuiSliderFlags_AlwaysClamp);
    fieldTooltip(m, true);
    if (!changed) return false;
    value = std::clamp(v, lo, hi);
    return true;
}

bool drawField(bool& value, const FieldMeta& m) {
    bool changed = ImGui::Checkbox(fieldLabel(m).c_str(), &value);
    fieldTooltip(m, false);
    return changed;
}

bool drawField(std::string& value, const FieldMeta& m) {
    ImGui::InputText(fieldLabel(m).c_str(), &value);
    fieldTooltip(m, false);
    // Report the edit once it is complete (Enter or focus lost), not on every keystroke: a
    // half-typed scene path must not trigger a reload.
    return ImGui::IsItemDeactivatedAfterEdit();
}

bool drawField(glm::vec3& value, const FieldMeta& m) {
    glm::vec3 v = value;
    bool changed;
    if (isColor(m))
        changed = ImGui::ColorEdit3(fieldLabel(m).c_str(), &v.x, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR);
    else
        changed = ImGui::DragFloat3(fieldLabel(m).c_str(), &v.x, dragSpeed(m, std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)})),
                                    lowEnd(m), highEnd(m), unitFormat("%.3f", m).c_str(), kDragFlags);
    fieldTooltip(m, true);
    if (!changed) return false;
    value = glm::clamp(v, glm::vec3(lowEnd(m)), glm::vec3(highEnd(m)));
    return true;
}

bool drawField(std::vector<float>& value, const FieldMeta& m) {
    // A tree node of one drag per entry; entries are not added or removed here (a panel that
    // owns the list, e.g. the roughness mips, does that).
    bool changed = false;
    bool open = ImGui::TreeNode(m.key, "%s (%zu)", readableKey(m.key).c_str(), value.size());
    fieldTooltip(m, true);
    if (!open) return false;
    for (size_t i = 0; i < value.size(); ++i) {
        ImGui::PushID(int(i));
        float v = value[i];
        char label[32];
        std::snprintf(label, sizeof label, "[%zu]", i);
        if (ImGui::DragFloat(label, &v, dragSpeed(m, std::abs(v)), lowEnd(m), highEnd(m), "%.3f", kDragFlags)) {
            value[i] = std::clamp(v, float(lowEnd(m)), float(highEnd(m)));
            changed = true;
        }
        ImGui::PopID();
    }
    ImGui::TreePop();
    return changed;
}

}  // namespace gi::ui
