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
        // On failure the renderer keeps its old programs; the log says why. A frame in flight finishes first.
        mGI.acquire();
        mShaderLog = mRenderer.reloadShaders(log) ? std::string() : log;
        ++mLiveGeneration;
        if (mShaderLog.empty()) mPresetStatus = "shaders reloaded";
    }
    ImGui::BeginDisabled(!mHistory.canUndo());
    if (ImGui::Button("Undo")) undo();
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::BeginDisabled(!mHistory.canRedo());
    if (ImGui::Button("Redo")) redo();
    ImGui::EndDisabled();
    ImGui::SameLine();
    if (ImGui::Button("Reset settings")) resetAll();
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("every section's settings to their defaults; the scene, technique, camera and lights stay (undo brings them back)");
    hintText("Ctrl+Z undo, Ctrl+Shift+Z redo; right-click a value to reset it (blue dot: not the default, orange bar: not saved)");
    if (ImGui::TreeNode("history", "history (%zu of %zu)", mHistory.index() + 1, mHistory.size())) {
        historyPanel();
        ImGui::TreePop();
    }
    if (!mPresetError.empty()) wrappedText(kErrorColor, mPresetError);
    else if (!mConfirmOverwrite.empty()) wrappedText(kWarningColor, mPresetStatus);
    else if (!mPresetStatus.empty()) hintText(mPresetStatus);
    if (!mShaderLog.empty()) wrappedText(kErrorColor, mShaderLog);
}

void Editor::historyPanel() {
    // Newest first; clicking a state goes back (or forward) to it, as that many undos would.
    if (!ImGui::BeginListBox("##history", ImVec2(-FLT_MIN, 6.25f * ImGui::GetTextLineHeightWithSpacing()))) return;
    for (size_t k = mHistory.size(); k-- > 0;) {
        ImGui::PushID(int(k));
        bool here = k == mHistory.index();
        if (ImGui::Selectable(mHistory.label(k).c_str(), here) && !here) restore(mHistory.jump(k));
        if (k > mHistory.index() && ImGui::IsItemHovered()) ImGui::SetTooltip("undone: click to redo up to here");
        ImGui::PopID();
    }
    ImGui::EndListBox();
}

}  // namespace gi::ui
