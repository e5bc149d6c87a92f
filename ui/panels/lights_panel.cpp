// The lights panel (the preset's own lights or the scene's) and the camera's tools beside its
// generated fields.
#include "ui/editor.h"

#include "gi/preset/history.h"
#include "gi/reference/framing.h"
#include "gi/scene/camera.h"
#include "gi/scene/emitters.h"

#include "ui/panel_util.h"
#include "ui/settings_panel.h"

#include <imgui.h>

#include <cstdio>

namespace fs = std::filesystem;

namespace gi::ui {

uint8_t Editor::cameraTools() {
    uint8_t cost = 0;
    if (ImGui::Button("Frame scene") && mScene.bounds.valid()) {
        // The view a file without a camera starts from (from inside when the scene is a room);
        // traced once per scene.
        if (!mFramedView) mFramedView = mScene.framedCamera ? mScene.cameras[0] : frameScene(mScene, PathTracer(mScene)).camera;
        const CameraSettings& framed = *mFramedView;
        mPreset.camera.eye = framed.eye;
        mPreset.camera.target = framed.target;
        mPreset.camera.near = framed.near;
        mPreset.camera.far = framed.far;
        mPreset.camera.sceneCamera = -1;
        cost |= uint8_t(Cost::Uniform);
    }
    hintText("viewport: right drag to look, WASD/QE to move, Shift: faster");

    // The file's cameras by name.
    if (!mScene.cameras.empty()) {
        std::string current = "jump to a file camera";
        if (ImGui::BeginCombo("file cameras", current.c_str())) {
            for (size_t i = 0; i < mScene.cameras.size(); ++i)
                if (ImGui::Selectable((std::to_string(i) + ": " + mScene.cameraName(i)).c_str())) takeFileCamera(i);
            ImGui::EndCombo();
        }
    }
    // Views saved in the preset.
    ImGui::TextUnformatted("views (saved in the preset)");
    int removed = -1;
    for (size_t i = 0; i < mPreset.bookmarks.size(); ++i) {
        ImGui::PushID(int(i));
        if (ImGui::SmallButton("x")) removed = int(i);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("remove this view");
        ImGui::SameLine();
        if (ImGui::Selectable(mPreset.bookmarks[i].name.c_str())) jumpTo(mPreset.bookmarks[i]);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("jump to this view");
        ImGui::PopID();
    }
    if (removed >= 0) {
        mPreset.bookmarks.erase(mPreset.bookmarks.begin() + removed);
        apply(uint8_t(Cost::Uniform));
    }
    if (mBookmarkName.empty()) mBookmarkName = "view " + std::to_string(mPreset.bookmarks.size() + 1);
    char name[64];
    std::snprintf(name, sizeof name, "%s", mBookmarkName.c_str());
    if (ImGui::InputText("##viewName", name, sizeof name)) mBookmarkName = name;
    ImGui::SameLine();
    if (ImGui::Button("Add view")) {
        addBookmark(mBookmarkName);
        mBookmarkName.clear();
    }
    return cost;
}

void Editor::addBookmark(const std::string& name) {
    CameraBookmark b;
    b.name = name.empty() ? "view " + std::to_string(mPreset.bookmarks.size() + 1) : name;
    b.eye = mPreset.camera.eye;
    b.target = mPreset.camera.target;
    b.fovY = mPreset.camera.fovY;
    mPreset.bookmarks.push_back(b);
    apply(uint8_t(Cost::Uniform));
}

void Editor::jumpTo(const CameraBookmark& view) {
    mPreset.camera.eye = view.eye;
    mPreset.camera.target = view.target;
    mPreset.camera.fovY = view.fovY;
    mPreset.camera.sceneCamera = -1;
    apply(uint8_t(Cost::Uniform));
}

void Editor::takeFileCamera(size_t index) {
    GI_ASSERT(index < mScene.cameras.size(), "a file camera the scene has");
    takeSceneCamera(mPreset.camera, mScene.cameras[index]);
    mPreset.camera.sceneCamera = -1;
    apply(uint8_t(Cost::Uniform));
}

uint8_t Editor::lightsPanel() {
    // Scene lights are shown as they are; the first edit copies them into the preset.
    std::vector<LightSettings> lights = mPreset.lightsFromScene ? sceneLights(mScene) : mPreset.lights;
    if (usesDefaultSun(mPreset, mScene))
        hintText("no lights and nothing emissive in the scene: lit by a default sun until you add a light");
    uint8_t cost = 0;
    if (mPreset.lightsFromScene) {
        hintText("the scene's own lights (an edit copies them into the preset)");
    } else if (ImGui::Button("Use the scene's lights")) {
        mPreset.lightsFromScene = true;
        mPreset.lights.clear();
        return uint8_t(Cost::Reallocate);
    }
    int removed = -1;
    for (size_t i = 0; i < lights.size(); ++i) {
        ImGui::PushID(int(i));
        const LightSettings& l = lights[i];
        bool area = l.type == LightType::Area && l.emitter >= 0 && l.emitter < int(mScene.emitters.size());
        std::string title = "light " + std::to_string(i) + ": " + enumName(l.type);
        if (area) {
            const Emitter& e = mScene.emitters[size_t(l.emitter)];
            char buf[160];
            std::snprintf(buf, sizeof buf, " '%s' (%zu triangles, %.3g m2)", e.name.c_str(), e.triangles.size(), double(e.area));
            title += buf;
        }
        if (!l.enabled) title += " (off)";
        // The place the frame gives it, whatever the preset holds (the fields are read-only).
        if (area) lights[i] = placeAreaLight(lights[i], mScene.emitters[size_t(l.emitter)]);
        if (mOpenLights) ImGui::SetNextItemOpen(true, ImGuiCond_Once);
        if (ImGui::TreeNodeEx("light", area ? 0 : ImGuiTreeNodeFlags_DefaultOpen, "%s", title.c_str())) {
            static const std::map<std::string, std::string> defaults = lightValues(LightSettings{});
            std::map<std::string, std::string> disk;
            bool onDisk = !mPresetPath.empty() && !mDiskPreset.lightsFromScene && i < mDiskPreset.lights.size();
            if (onDisk) disk = lightValues(mDiskPreset.lights[i]);
            cost |= drawSettings(lights[i], FieldBaselines{"", &defaults, onDisk ? &disk : nullptr});
            if (ImGui::SmallButton("Remove light")) removed = int(i);
            ImGui::TreePop();
        }
        ImGui::PopID();
    }
    if (removed >= 0) {
        lights.erase(lights.begin() + removed);
        cost |= uint8_t(Cost::Reallocate);
    }
    if (ImGui::Button("Add light")) {
        lights.emplace_back();
        cost |= uint8_t(Cost::Reallocate);
    }
    if (cost) {
        mPreset.lights = std::move(lights);
        mPreset.lightsFromScene = false;
    }
    return cost;
}

}  // namespace gi::ui
