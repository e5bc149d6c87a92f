#include "ui/panel_util.h"

#include <algorithm>
#include <cctype>

namespace gi::ui {

void wrappedText(const ImVec4& color, const std::string& text) {
    ImGui::PushStyleColor(ImGuiCol_Text, color);
    ImGui::TextWrapped("%s", text.c_str());
    ImGui::PopStyleColor();
}

void hintText(const std::string& text) { wrappedText(ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled), text); }

std::string lowercase(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

double mebibytes(size_t bytes) { return double(bytes) / (1024.0 * 1024.0); }

bool projectToScreen(const glm::mat4& viewProj, const glm::vec3& p, const ViewportRect& viewport, ImVec2& out) {
    glm::vec4 c = viewProj * glm::vec4(p, 1.0f);
    if (c.w <= 1e-4f) return false;
    out = ImVec2(float(viewport.x) + (c.x / c.w * 0.5f + 0.5f) * float(viewport.width), (0.5f - c.y / c.w * 0.5f) * float(viewport.height));
    return true;
}

}  // namespace gi::ui
