// The scene panel: the header's scene field (a built-in name or a glTF path) and the glTF files
// of the asset search path; picking one reloads the scene.
#include "ui/editor.h"

#include "ui/panel_util.h"
#include "ui/settings_panel.h"

#include <imgui.h>
#include <imgui_internal.h>  // ButtonEx, for a Load button that fires on press
#include <cfloat>

namespace fs = std::filesystem;

namespace gi::ui {

uint8_t Editor::scenePanel() {
    // The header's scene field takes any built-in name or glTF path; its ReloadScene cost loads it.
    uint8_t cost = drawSettings(mPreset.header);
    // Fires on press, in the same frame as the path field's end-of-edit, so one load serves both.
    if (ImGui::ButtonEx("Load", ImVec2(0, 0), ImGuiButtonFlags_PressedOnClick)) cost |= uint8_t(Cost::ReloadScene);
    ImGui::SameLine();
    if (ImGui::Button("Rescan")) scanFiles();
    if (!mSceneError.empty()) wrappedText(kErrorColor, mSceneError);

    if (ImGui::BeginListBox("##scenes", ImVec2(-FLT_MIN, 5.25f * ImGui::GetTextLineHeightWithSpacing()))) {
        auto entry = [&](const std::string& name, const std::string& label) {
            if (ImGui::Selectable(label.c_str(), name == mLoadedScene)) {
                mPreset.header.scene = name;
                cost |= uint8_t(Cost::ReloadScene);
            }
        };
        for (const std::string& name : builtinSceneNames()) entry(name, name + " (built-in)");
        for (const std::string& file : mSceneFiles) entry(file, file);
        ImGui::EndListBox();
    }
    ImGui::TextDisabled("%s: %zu triangles, %zu materials, %zu lights", mScene.name.c_str(), mScene.triangleCount(),
                        mScene.materials.size(), mScene.lights.size());
    for (const std::string& w : mScene.warnings) wrappedText(kWarningColor, w);
    return cost;
}

}  // namespace gi::ui
