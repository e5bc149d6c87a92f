// The stats panel: per-pass GPU time and memory of the last frame, and the budget.
#include "ui/editor.h"

#include "ui/panel_util.h"
#include "ui/settings_panel.h"

#include <imgui.h>
#include <algorithm>

namespace fs = std::filesystem;

namespace gi::ui {

void Editor::statsPanel() {
    ImGui::TextWrapped("%s", mGLRenderer.c_str());
    ImGui::Text("UI %.1f ms a frame, viewport %dx%d", mShownFrameMs, mWidth, mHeight);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("the UI's work per frame; while the GI renders and nothing happens the UI waits for input, so the GI gets the cores");
    // The GI renders only when its image would change: say what the picture on screen is.
    const char* state = mPaused ? "paused" : giSettled() ? "up to date" : mGI.busy() ? "rendering" : mRenderSize != glm::ivec2(mWidth, mHeight) ? "preview" : "waiting";
    ImGui::Text("GI %.1f ms at %dx%d, %s", mRenderMs, mRenderSize.x, mRenderSize.y, state);
    if (ImGui::SmallButton("Help (F1)")) mShowHelp = !mShowHelp;
    ImGui::SameLine();
    if (ImGui::SmallButton("Screenshot (F12)")) requestScreenshot();
    ImGui::Checkbox("pause GI (P)", &mPaused);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("stop rendering; the last image stays and settings can still be edited");
    ImGui::SameLine();
    static const int kDivisors[] = {1, 2, 4, 8};
    int choice = int(std::find(std::begin(kDivisors), std::end(kDivisors), mPreviewDivisor) - std::begin(kDivisors));
    ImGui::SetNextItemWidth(70.0f);
    if (ImGui::Combo("drag preview", &choice, "off\0" "1/2\0" "1/4\0" "1/8\0") && choice >= 0 && choice < 4)
        mPreviewDivisor = kDivisors[choice];
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("while a value is dragged or the camera flies, the GI renders at this fraction of the width and height;\n"
                          "the full frame follows when you let go");
    size_t passBytes = 0;
    if (ImGui::BeginTable("passes", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerH)) {
        ImGui::TableSetupColumn("pass");
        ImGui::TableSetupColumn("GPU ms");
        ImGui::TableSetupColumn("MiB");
        ImGui::TableHeadersRow();
        double totalMs = 0.0;
        auto row = [](const char* name, double ms, size_t bytes) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(name);
            ImGui::TableNextColumn();
            ImGui::Text("%.2f", ms);
            ImGui::TableNextColumn();
            ImGui::Text("%.1f", mebibytes(bytes));
        };
        for (const PassStats& p : mPassStats) {
            row(p.name.c_str(), p.gpuMs, p.memoryBytes);
            totalMs += p.gpuMs;
            passBytes += p.memoryBytes;
        }
        row("total", totalMs, passBytes);
        ImGui::EndTable();
    }
    size_t total = mMemoryBytes;
    ImGui::Text("GPU memory %.1f MiB (scene %.1f MiB)", mebibytes(total), mebibytes(total - std::min(total, passBytes)));
    ImGui::Text("budget %.0f MiB", double(mPreset.render.memoryBudgetMB));
}

}  // namespace gi::ui
