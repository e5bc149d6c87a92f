#include "ui/editor.h"

#include "gi/lpv/lpv.h"

#include "gi/util/paths.h"
#include "ui/settings_panel.h"

#include <glm/geometric.hpp>
#include <imgui.h>
#include <imgui_internal.h>  // ButtonEx, for a Load button that fires on press
#include <imgui_stdlib.h>

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <type_traits>

namespace fs = std::filesystem;

namespace gi::ui {

namespace {

const ImVec4 kErrorColor{1.0f, 0.4f, 0.35f, 1.0f};
const ImVec4 kWarningColor{1.0f, 0.8f, 0.35f, 1.0f};
// Layout at first use: a left column for the preset, a right one for stats, the previewer and
// the reference, and the middle of the window left free for the viewport.
constexpr float kMargin = 8.0f, kLeftWidth = 330.0f, kRightWidth = 340.0f, kStatsHeight = 240.0f;
constexpr float kReferenceHeight = 205.0f;  // the Reference panel, at the bottom of the right column
constexpr float kLabelWidth = 110.0f;  // room for the longest settings key beside its widget

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

}  // namespace

Editor::Editor(const EditorOptions& options) : mPreviewer(options.view), mWidth(options.width), mHeight(options.height) {
    fs::path defaultFile = presetDir() / "default.json";
    bool isPreset = true;
    if (!options.preset.empty()) {
        mPreset = presetForInput(options.preset, -1);
        // A glTF input has no preset file yet: Save As suggests one named after it.
        isPreset = lowercase(options.preset.extension().string()) == ".json";
        mPresetPath = isPreset ? options.preset : fs::path();
        mPathField = (isPreset ? options.preset : presetDir() / (options.preset.stem().string() + ".json")).string();
    } else {
        if (fs::exists(defaultFile)) {
            mPreset = loadPreset(defaultFile);
            mPresetPath = defaultFile;
        } else {
            mPreset = builtinDefaultPreset();  // no files at all: default.json as compiled in
        }
        mPathField = defaultFile.string();
    }
    if (options.referenceSPP > 0) mPreset.reference.spp = options.referenceSPP;
    if (!options.reference.empty()) {
        mReference.setView(referenceViewFromName(options.reference));
        mReference.setEnabled(true);
    }
    // A glTF file opens with its own first camera (or one framing it) and its lights.
    installScene(mPreset, !isPreset);
    mGoodPreset = mPreset;
    mOutputFBO = gl::createFramebuffer();
    const GLubyte* renderer = glGetString(GL_RENDERER);
    mGLRenderer = renderer ? reinterpret_cast<const char*>(renderer) : "unknown";
    scanFiles();
}

std::string Editor::title() const {
    std::string file = mPresetPath.empty() ? "untitled" : mPresetPath.filename().string();
    return "GI Workbench - " + file + (mDirty ? " *" : "");
}

void Editor::frame(int width, int height, float dt) {
    mFrameMs = mFrameMs == 0.0f ? dt * 1000.0f : 0.9f * mFrameMs + 0.1f * dt * 1000.0f;

    CameraSettings camera = mPreset.camera;
    if (camera.sceneCamera >= 0 && camera.sceneCamera < int(mScene.cameras.size())) {
        // Flying away from one of the file's cameras starts from it and leaves it.
        const CameraSettings& c = mScene.cameras[camera.sceneCamera];
        camera.eye = c.eye;
        camera.target = c.target;
        camera.up = c.up;
        camera.fovY = c.fovY;
        camera.sceneCamera = -1;
    }
    float radius = mScene.bounds.valid() ? 0.5f * glm::length(mScene.bounds.extent()) : 1.0f;
    if (mFlyCamera.update(camera, dt, radius)) {
        mPreset.camera = camera;
        apply(uint8_t(Cost::Uniform));
    }

    if (width > 0 && height > 0) renderViewport(width, height);
    drawPanels();
}

void Editor::apply(uint8_t cost) {
    if (!cost) return;
    mDirty = true;
    ++mLiveGeneration;
    if (cost & uint8_t(Cost::ReloadScene)) {
        Preset p = mPreset;
        try {
            installScene(p, true);
            mPreset = mGoodPreset = p;
            mSceneError.clear();
        } catch (const std::exception& e) {
            mSceneError = e.what();
            mPreset.header.scene = mLoadedScene;
        }
    }
    // Uniform, Reallocate and Recompile need nothing here: the renderer compares each frame's
    // FrameSettings with what it holds and reallocates its targets and shadow maps itself.
}

void Editor::installScene(Preset& p, bool resetView) {
    Scene scene = loadScene(p.header.scene, p.folder);
    if (resetView) {
        p.camera = scene.cameras.empty() ? frameBounds(scene.bounds) : scene.cameras.front();
        p.camera.sceneCamera = -1;
        p.lightsFromScene = true;
        p.lights.clear();
    }
    // Refuse a scene past the memory budget before uploading it.
    Renderer::checkBudget(frameSettings(p, scene, mWidth, mHeight), scene);
    mRenderer.setScene(scene);
    mScene = std::move(scene);
    mLoadedScene = p.header.scene;
    ++mSceneGeneration;
    ++mLiveGeneration;
}

void Editor::renderViewport(int width, int height) {
    mWidth = width;
    mHeight = height;
    FrameSettings fs;
    try {
        fs = frameSettings(mPreset, mScene, width, height);
        mRenderer.render(fs);
        mGoodPreset = mPreset;
    } catch (const std::exception& e) {
        // Keep the last picture and go back to the settings that made it. The message stays
        // until dismissed, since the restored settings render fine on the next frame.
        mFrameError = std::string(e.what()) + " (previous settings restored)";
        mPreset = mGoodPreset;
        fs = frameSettings(mPreset, mScene, width, height);
        ++mLiveGeneration;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
    glClearColor(0.08f, 0.08f, 0.09f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    if (mRenderer.width() > 0) {
        // Attached every frame: a resized output texture may reuse the old one's name.
        glNamedFramebufferTexture(mOutputFBO.id(), GL_COLOR_ATTACHMENT0, mRenderer.outputTexture(), 0);
        glBlitNamedFramebuffer(mOutputFBO.id(), 0, 0, 0, mRenderer.width(), mRenderer.height(), 0, 0, width, height,
                               GL_COLOR_BUFFER_BIT, GL_LINEAR);
        mReference.update(mScene, mSceneGeneration, mLiveGeneration, fs, mPreset.reference, mRenderer);
        mReference.drawViewport(width, height);
    }
}

void Editor::openPreset(const fs::path& path) {
    try {
        Preset p = loadPreset(path);
        installScene(p, false);
        mPreset = mGoodPreset = p;
        mPresetPath = path;
        mPathField = path.string();
        mDirty = false;
        mPresetError.clear();
        mSceneError.clear();
        mFrameError.clear();
        mPresetStatus = "opened " + path.string();
    } catch (const std::exception& e) {
        mPresetError = e.what();
    }
}

void Editor::savePresetAs(const fs::path& path) {
    // Never replace another file silently: the first press warns, the second writes.
    if (path != mPresetPath && fs::exists(path) && mConfirmOverwrite != path) {
        mConfirmOverwrite = path;
        mPresetError.clear();
        mPresetStatus = path.filename().string() + " exists: press again to replace it";
        return;
    }
    mConfirmOverwrite.clear();
    try {
        savePreset(mPreset, path);  // atomic: the old file stays whole until the new one is complete
        mPresetPath = path;
        mPathField = path.string();
        mDirty = false;
        mPresetError.clear();
        mPresetStatus = "saved " + path.string();
        scanFiles();
    } catch (const std::exception& e) {
        mPresetError = e.what();
    }
}

void Editor::scanFiles() {
    mSceneFiles.clear();
    for (const fs::path& root : assetSearchPath(mPreset.folder)) {
        std::error_code ec;
        fs::recursive_directory_iterator it(root, fs::directory_options::skip_permission_denied, ec), end;
        for (; !ec && it != end; it.increment(ec)) {
            // Two levels below each root: enough for scenes/Sponza/glTF/Sponza.gltf.
            if (it.depth() >= 2 && it->is_directory(ec)) it.disable_recursion_pending();
            std::string ext = lowercase(it->path().extension().string());
            if (ext == ".gltf" || ext == ".glb") mSceneFiles.push_back(it->path().lexically_relative(root).generic_string());
        }
    }
    std::sort(mSceneFiles.begin(), mSceneFiles.end());
    mSceneFiles.erase(std::unique(mSceneFiles.begin(), mSceneFiles.end()), mSceneFiles.end());

    mPresetFiles.clear();
    std::error_code ec;
    for (fs::directory_iterator it(presetDir(), ec), end; !ec && it != end; it.increment(ec))
        if (it->path().extension() == ".json") mPresetFiles.push_back(it->path());
    std::sort(mPresetFiles.begin(), mPresetFiles.end());
}

void Editor::drawCascadeOverlay() {
    if (!mShowCascades || mPreset.header.technique != TechniqueKind::LPV || !mScene.bounds.valid() || mWidth <= 0) return;
    FrameSettings fs = frameSettings(mPreset, mScene, mWidth, mHeight);
    glm::mat4 viewProj = projectionMatrix(fs.camera, float(mWidth) / float(mHeight)) * viewMatrix(fs.camera);
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const ImU32 colours[4] = {IM_COL32(255, 220, 60, 200), IM_COL32(80, 220, 255, 200), IM_COL32(255, 110, 200, 200),
                              IM_COL32(150, 255, 120, 200)};
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    std::vector<CascadeBox> boxes = lpvCascades(fs.lpv, mScene.bounds.min, mScene.bounds.max, fs.camera.eye);
    for (size_t k = 0; k < boxes.size(); ++k) {
        glm::vec4 clip[8];
        for (int i = 0; i < 8; ++i)
            clip[i] = viewProj * glm::vec4(boxes[k].min + boxes[k].extent * glm::vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1), 1.0f);
        for (int a = 0; a < 8; ++a)
            for (int bit = 1; bit < 8; bit <<= 1) {
                int b = a | bit;
                if (b == a || clip[a].w <= 1e-4f || clip[b].w <= 1e-4f) continue;  // an edge behind the eye is skipped
                auto screen = [&](const glm::vec4& c) {
                    return ImVec2((c.x / c.w * 0.5f + 0.5f) * display.x, (0.5f - c.y / c.w * 0.5f) * display.y);
                };
                draw->AddLine(screen(clip[a]), screen(clip[b]), colours[k % 4], 1.5f);
            }
    }
}

void Editor::drawPanels() {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    uint8_t cost = 0;
    drawCascadeOverlay();

    ImGui::SetNextWindowPos(ImVec2(kMargin, kMargin), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(kLeftWidth, display.y - 2 * kMargin), ImGuiCond_FirstUseEver);
    if (ImGui::Begin("GI Workbench")) {
        ImGui::PushItemWidth(-kLabelWidth);
        if (!mFrameError.empty()) {
            wrappedText(kErrorColor, mFrameError);
            if (ImGui::SmallButton("Dismiss")) mFrameError.clear();
            ImGui::Separator();
        }
        if (ImGui::CollapsingHeader("scene", ImGuiTreeNodeFlags_DefaultOpen)) cost |= scenePanel();
        if (ImGui::CollapsingHeader("presets", ImGuiTreeNodeFlags_DefaultOpen)) presetsPanel();
        if (ImGui::CollapsingHeader("lights")) cost |= lightsPanel();
        // Every fixed section the preset has, so a new technique's settings appear by themselves.
        mPreset.forEachSection([&](auto& section) {
            using S = std::decay_t<decltype(section)>;
            bool open = S::kSection == "render" || S::kSection == "toneMap";
            if (!ImGui::CollapsingHeader(S::kSection.data(), open ? ImGuiTreeNodeFlags_DefaultOpen : 0)) return;
            cost |= drawSettings(section);
            if constexpr (std::is_same_v<S, CameraSettings>) cost |= cameraTools();
            if constexpr (std::is_same_v<S, LPVSettings>) {
                ImGui::Checkbox("show cascades in the viewport", &mShowCascades);
                std::string note = lpvIgnoredLights(mPreset.lightsFromScene ? mScene.lights : mPreset.lights);
                if (!note.empty()) wrappedText(kWarningColor, note);
            }
        });
        ImGui::PopItemWidth();
    }
    ImGui::End();

    float rightX = display.x - kRightWidth - kMargin;
    ImGui::SetNextWindowPos(ImVec2(rightX, kMargin), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(kRightWidth, kStatsHeight), ImGuiCond_FirstUseEver);
    if (ImGui::Begin("Stats")) statsPanel();
    ImGui::End();

    float previewerHeight = display.y - kStatsHeight - kReferenceHeight - 4 * kMargin;
    ImGui::SetNextWindowPos(ImVec2(rightX, kStatsHeight + 2 * kMargin), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(kRightWidth, previewerHeight), ImGuiCond_FirstUseEver);
    // The wheel zooms the image, so it must not scroll the window.
    if (ImGui::Begin("Buffer previewer", nullptr, ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse)) {
        ImGui::PushItemWidth(-kLabelWidth * 0.6f);
        mPreviewer.draw(mRenderer);
        ImGui::PopItemWidth();
    }
    ImGui::End();

    ImGui::SetNextWindowPos(ImVec2(rightX, display.y - kReferenceHeight - kMargin), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(kRightWidth, kReferenceHeight), ImGuiCond_FirstUseEver);
    if (ImGui::Begin("Reference")) {
        ImGui::PushItemWidth(-kLabelWidth * 0.6f);
        mReference.draw();
        ImGui::PopItemWidth();
    }
    ImGui::End();

    apply(cost);
}

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

uint8_t Editor::cameraTools() {
    uint8_t cost = 0;
    if (ImGui::Button("Frame scene") && mScene.bounds.valid()) {
        CameraSettings framed = frameBounds(mScene.bounds);
        mPreset.camera.eye = framed.eye;
        mPreset.camera.target = framed.target;
        mPreset.camera.near = framed.near;
        mPreset.camera.far = framed.far;
        mPreset.camera.sceneCamera = -1;
        cost |= uint8_t(Cost::Uniform);
    }
    hintText("viewport: right drag to look, WASD/QE to move, Shift: faster");
    return cost;
}

uint8_t Editor::lightsPanel() {
    // Scene lights are shown as they are; the first edit copies them into the preset.
    std::vector<LightSettings> lights = mPreset.lightsFromScene ? mScene.lights : mPreset.lights;
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
        if (ImGui::TreeNodeEx("light", ImGuiTreeNodeFlags_DefaultOpen, "light %zu: %s", i, enumName(lights[i].type))) {
            cost |= drawSettings(lights[i]);
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

void Editor::statsPanel() {
    ImGui::TextWrapped("%s", mGLRenderer.c_str());
    ImGui::Text("frame %.1f ms (%.1f fps), %dx%d", mFrameMs, mFrameMs > 0 ? 1000.0f / mFrameMs : 0.0f, mWidth, mHeight);
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
        for (const PassStats& p : mRenderer.passStats()) {
            row(p.name.c_str(), p.gpuMs, p.memoryBytes);
            totalMs += p.gpuMs;
            passBytes += p.memoryBytes;
        }
        row("total", totalMs, passBytes);
        ImGui::EndTable();
    }
    size_t total = mRenderer.memoryBytes();
    ImGui::Text("GPU memory %.1f MiB (scene %.1f MiB)", mebibytes(total), mebibytes(total - std::min(total, passBytes)));
    ImGui::Text("budget %.0f MiB", double(mPreset.render.memoryBudgetMB));
}

}  // namespace gi::ui
