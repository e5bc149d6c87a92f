// The presets panel: open, save, save as (atomic), the presets folder, and shader reloads that
// keep the last good programs.
#include "ui/editor.h"

#include "ui/panel_util.h"
#include "ui/settings_panel.h"

#include <imgui.h>
#include <imgui_stdlib.h>

namespace fs = std::filesystem;

namespace gi::ui {

void Editor::presetsPanel() {
    ImGui::Text("file: %s%s", mPresetPath.empty() ? "(not saved)" : mPresetPath.filename().c_str(), mDirty ? " (modified)" : "");
    ImGui::InputText("path", &mPathField);
    if (ImGui::BeginListBox("##presets", ImVec2(-FLT_MIN, 3.25f * ImGui::GetTextLineHeightWithSpacing()))) {
        for (const fs::path& file : mPresetFiles) {
            if (ImGui::Selectable(file.filename().c_str(), fs::path(mPathField) == file, ImGuiSelectableFlags_AllowDoubleClick)) {
                mPathField = file.string();
                if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) openPreset(file);
            }
        }
        ImGui::EndListBox();
    }
    if (ImGui::Button("Open")) openPreset(mPathField);
    ImGui::SameLine();
    if (ImGui::Button("Save")) savePresetAs(mPresetPath.empty() ? fs::path(mPathField) : mPresetPath);
    ImGui::SameLine();
    if (ImGui::Button("Save As")) savePresetAs(mPathField);
    ImGui::SameLine();
    if (ImGui::Button("Reload shaders")) {
        std::string log;
        // On failure the renderer keeps its old programs; the log says why.
        mShaderLog = mRenderer.reloadShaders(log) ? std::string() : log;
        ++mLiveGeneration;
        if (mShaderLog.empty()) mPresetStatus = "shaders reloaded";
    }
    if (!mPresetError.empty()) wrappedText(kErrorColor, mPresetError);
    else if (!mConfirmOverwrite.empty()) wrappedText(kWarningColor, mPresetStatus);
    else if (!mPresetStatus.empty()) hintText(mPresetStatus);
    if (!mShaderLog.empty()) wrappedText(kErrorColor, mShaderLog);
}

}  // namespace gi::ui
