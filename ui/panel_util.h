// What every editor panel shares: the layout at first use, message colours, and small helpers.
#pragma once

#include <glm/glm.hpp>
#include <imgui.h>

#include <cstddef>
#include <string>

namespace gi::ui {

inline const ImVec4 kErrorColor{1.0f, 0.4f, 0.35f, 1.0f};
inline const ImVec4 kWarningColor{1.0f, 0.8f, 0.35f, 1.0f};
// Layout at first use: a left column for the preset, a right one for stats, the previewer and
// the reference, and the middle of the window left free for the viewport.
inline constexpr float kMargin = 8.0f, kLeftWidth = 330.0f, kRightWidth = 340.0f, kStatsHeight = 300.0f;
inline constexpr float kMaxFlyStepSeconds = 0.1f;  // the most flight one frame applies, however slow it was
inline constexpr float kMinColumnWidth = 200.0f;   // a docked column can be dragged no narrower
inline constexpr float kReferenceHeight = 205.0f;  // the Reference panel, at the bottom of the right column
inline constexpr float kLabelWidth = 135.0f;       // room for a setting's name in words beside its widget
inline constexpr float kSideWindowWidth = 250.0f;  // a pass's own window, beside the Stats window over the viewport

void wrappedText(const ImVec4& color, const std::string& text);
void hintText(const std::string& text);
std::string lowercase(std::string s);
double mebibytes(size_t bytes);
// The part of the window the scene is drawn in, between the docked panel columns, in window
// pixels from the left. It spans the window's height, so ImGui's and GL's rows agree on it.
struct ViewportRect {
    int x = 0, width = 0, height = 0;
    unsigned framebuffer = 0;  // what the viewport is drawn into: the editor's composite (Editor::compositeTexture)
    ImVec2 origin() const { return ImVec2(float(x), 0.0f); }
    ImVec2 size() const { return ImVec2(float(width), float(height)); }
    bool contains(ImVec2 p) const { return p.x >= float(x) && p.x < float(x + width) && p.y >= 0.0f && p.y < float(height); }
};
// Screen position of a world point for the overlays (in the viewport's rectangle); false behind the eye.
bool projectToScreen(const glm::mat4& viewProj, const glm::vec3& p, const ViewportRect& viewport, ImVec2& out);

}  // namespace gi::ui
