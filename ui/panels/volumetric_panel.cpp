// Volumetric lighting's panel: a note when the medium scatters nothing, and the Phase function
// window (the lobe as a polar plot, linear or log, the other functions faintly, the value under
// the mouse), opened whenever volumetric lighting is switched on.
#include "gi/volumetric/phase.h"
#include "gi/volumetric/phase_plot.h"
#include "ui/editor.h"
#include "ui/panel_util.h"
#include "ui/pass_panel.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace gi::ui {

namespace {

class VolumetricPanel final : public PassPanel {
public:
    explicit VolumetricPanel(const EditorOptions& options) : mShow(options.phasePlot) {}

    uint8_t drawSection(PanelContext& ctx) override {
        const VolumetricSettings& v = ctx.preset.volumetric;
        if (v.enabled && v.density <= 0.0f)
            wrappedText(kWarningColor, "density is 0: the medium scatters nothing, so volumetric lighting adds nothing");
        ImGui::Checkbox("phase function window", &mShow);
        return 0;
    }

    void drawWindows(PanelContext& ctx) override;

private:
    bool mShow = false;
    bool mLog = false;      // the plot's radius on the log scale of gi/volumetric/phase_plot.h
    bool mOthers = true;    // the other five functions as faint curves
};

void VolumetricPanel::drawWindows(PanelContext& ctx) {
    const VolumetricSettings& v = ctx.preset.volumetric;
    if (!mShow) return;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(display.x - kRightWidth - kSideWindowWidth - 2 * kMargin, kMargin), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(kSideWindowWidth, 0.0f), ImGuiCond_FirstUseEver);
    if (ImGui::Begin("Phase function", &mShow, ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse)) {
        const PhaseParams p = phaseParams(v);
        ImGui::TextUnformatted(phaseFunctionLabel(p.function));
        ImGui::SameLine();
        if (p.function == PhaseFunction::HenyeyGreenstein)
            ImGui::TextDisabled("g = %.2f", p.g);
        else if (p.function == PhaseFunction::Schlick && v.schlickFromG)
            ImGui::TextDisabled("k = %.3f (from g = %.2f)", p.k, p.g);
        else if (p.function == PhaseFunction::Schlick)
            ImGui::TextDisabled("k = %.3f", p.k);
        else
            ImGui::TextDisabled("(no parameter)");
        if (ImGui::RadioButton("linear", !mLog)) mLog = false;
        ImGui::SameLine();
        if (ImGui::RadioButton("log", mLog)) mLog = true;
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("radius 1 + log10(p / peak) / 3: three decades below the peak");
        ImGui::SameLine();
        ImGui::Checkbox("others", &mOthers);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("the other five functions (same g), each scaled to its own peak");

        // The plot: light travels along +x (the arrow); forward scattering is to the right.
        float side = std::max(ImGui::GetContentRegionAvail().x, 64.0f);
        ImVec2 corner = ImGui::GetCursorScreenPos();
        ImGui::InvisibleButton("##lobe", ImVec2(side, side));
        const bool hovered = ImGui::IsItemHovered();
        PhasePlotLayout layout = phasePlotLayout(int(side));
        const ImVec2 c(corner.x + layout.centre.x, corner.y + layout.centre.y);
        const float R = layout.radius;
        auto screen = [&](const glm::vec2& q) { return ImVec2(c.x + R * q.x, c.y - R * q.y); };
        auto colour = [](const glm::vec3& rgb, float a) {
            return ImGui::ColorConvertFloat4ToU32(ImVec4(rgb.r, rgb.g, rgb.b, a));
        };
        ImDrawList* draw = ImGui::GetWindowDrawList();
        draw->AddRectFilled(corner, ImVec2(corner.x + side, corner.y + side), colour(kPhasePlotBackground, 1.0f), 3.0f);
        const ImU32 grid = IM_COL32(66, 66, 74, 255), axis = IM_COL32(128, 128, 138, 255);
        draw->AddCircle(c, 0.5f * R, grid, 64, 1.0f);
        draw->AddCircle(c, R, grid, 96, 1.0f);
        const float tip = 1.2f * R, head = 0.05f * side;
        draw->AddLine(ImVec2(c.x - tip, c.y), ImVec2(c.x + tip - 0.5f * head, c.y), axis, 1.0f);
        draw->AddTriangleFilled(ImVec2(c.x + tip, c.y), ImVec2(c.x + tip - head, c.y - 0.45f * head),
                                ImVec2(c.x + tip - head, c.y + 0.45f * head), axis);
        auto polyline = [&](const std::vector<glm::vec2>& lobe, ImU32 col, float thickness) {
            std::vector<ImVec2> points(lobe.size());
            for (size_t i = 0; i < lobe.size(); ++i) points[i] = screen(lobe[i]);
            draw->AddPolyline(points.data(), int(points.size()), col, ImDrawFlags_Closed, thickness);
        };
        if (mOthers)
            for (const auto& [f, name] : EnumNames<PhaseFunction>::values)
                if (f != p.function) {
                    PhaseParams other = p;
                    other.function = f;
                    polyline(phaseLobe(other, mLog, 180), IM_COL32(200, 200, 210, 60), 1.0f);
                }
        // The fill as a fan from the centre: the lobe is star-shaped about it (one radius per
        // angle) but not convex (Rayleigh), and this ImGui has no concave fill.
        std::vector<glm::vec2> lobe = phaseLobe(p, mLog, 360);
        const ImU32 fill = colour(kPhasePlotLobe, 0.16f);
        const ImVec2 white = ImGui::GetFontTexUvWhitePixel();
        draw->PrimReserve(int(lobe.size()) * 3, int(lobe.size()) * 3);
        for (size_t i = 0; i < lobe.size(); ++i) {
            draw->PrimVtx(c, white, fill);
            draw->PrimVtx(screen(lobe[i]), white, fill);
            draw->PrimVtx(screen(lobe[(i + 1) % lobe.size()]), white, fill);
        }
        const PhasePlotScale scale = phasePlotScale(p, mLog);
        const double isotropic = 1.0 / (4.0 * glm::pi<double>());
        if (float r = scale.radius(isotropic); r > 0.0f) draw->AddCircle(c, r * R, colour(kPhasePlotIsotropic, 0.9f), 96, 1.0f);
        polyline(lobe, colour(kPhasePlotLobe, 1.0f), 2.0f);
        if (hovered) {
            // The value in the direction under the mouse.
            ImVec2 m = ImGui::GetIO().MousePos;
            double theta = std::atan2(-(m.y - c.y), m.x - c.x);
            double value = phase(p, std::cos(theta));
            glm::vec2 q = scale.radius(value) * glm::vec2(float(std::cos(theta)), float(std::sin(theta)));
            draw->AddLine(c, screen(q), IM_COL32(255, 255, 255, 160), 1.0f);
            draw->AddCircleFilled(screen(q), 3.0f, IM_COL32(255, 255, 255, 220));
            ImGui::SetTooltip("theta %.0f deg: p = %.4g /sr (%.2f x isotropic)", std::abs(glm::degrees(theta)), value,
                              value / isotropic);
        }
        ImGui::TextColored(ImVec4(kPhasePlotIsotropic.r, kPhasePlotIsotropic.g, kPhasePlotIsotropic.b, 1.0f), "isotropic");
        ImGui::SameLine();
        ImGui::TextDisabled("= 1/(4 pi) = %.4f /sr", isotropic);
        const double forward = phase(p, 1.0), side90 = phase(p, 0.0), backward = phase(p, -1.0);
        ImGui::Text("p(0) forward    %.4g /sr", forward);
        ImGui::Text("p(90)           %.4g /sr", side90);
        ImGui::Text("p(180) backward %.4g /sr", backward);
        ImGui::TextDisabled("forward : backward = %.3g : 1", forward / backward);
        if (!v.enabled) hintText("volumetric lighting is off (volumetric.enabled)");
        else if (v.density <= 0.0f) hintText("density is 0: nothing scatters");
    }
    ImGui::End();
}

}  // namespace

std::unique_ptr<PassPanel> makeVolumetricPanel(const EditorOptions& options) { return std::make_unique<VolumetricPanel>(options); }

}  // namespace gi::ui
