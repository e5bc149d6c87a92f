#include "ui/editor.h"

#include "common/shared.h"
#include "gi/envmap/environment.h"
#include "gi/lpv/lpv.h"
#include "gi/scene/camera.h"

#include "gi/util/error.h"
#include "gi/util/paths.h"
#include "gi/volumetric/phase_plot.h"
#include "ui/settings_panel.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <imgui.h>
#include <imgui_internal.h>  // ButtonEx, for a Load button that fires on press
#include <imgui_stdlib.h>

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <cmath>
#include <cstdio>
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
constexpr float kPhaseWidth = 250.0f;  // the Phase function window, beside the Stats window over the viewport

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

// Screen position of a world point for the overlays; false behind the eye.
bool projectToScreen(const glm::mat4& viewProj, const glm::vec3& p, ImVec2 display, ImVec2& out) {
    glm::vec4 c = viewProj * glm::vec4(p, 1.0f);
    if (c.w <= 1e-4f) return false;
    out = ImVec2((c.x / c.w * 0.5f + 0.5f) * display.x, (0.5f - c.y / c.w * 0.5f) * display.y);
    return true;
}


}  // namespace

Editor::Editor(const EditorOptions& options) : mPreviewer(options.view), mWidth(options.width), mHeight(options.height) {
    if (!options.voxelView.empty()) {
        bool known = false;
        std::string names;
        for (const auto& [value, name] : EnumNames<VoxelViewSource>::values) {
            names += std::string(names.empty() ? "" : ", ") + name;
            if (options.voxelView == name) {
                mVoxelParams.source = value;
                known = true;
            }
        }
        if (!known) throw Error("unknown voxel view '" + options.voxelView + "' (valid: " + names + ")");
        mVoxelDisplay = options.voxelWindow ? VoxelDisplay::Window : VoxelDisplay::Viewport;
    }
    mShowCones = options.coneOverlay;
    mShowPhase = options.phasePlot;
    mOpenMips = options.roughnessMips;
    mScrollToMips = mOpenMips ? 10 : 0;
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
        takeSceneCamera(camera, mScene.cameras[camera.sceneCamera]);
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
    Scene scene = loadScene(p.header.scene, p.folder, p.render.memoryBudgetMB);
    if (resetView) {
        p.camera = scene.cameras.empty() ? frameBounds(scene.bounds) : scene.cameras.front();
        p.camera.sceneCamera = -1;
        p.lightsFromScene = true;
        p.lights.clear();
    }
    // Refuse a scene past the memory budget before uploading it (a prefilter past the time
    // budget is refused by the frame, so the preset still opens and its settings can be lowered).
    Renderer::checkMemoryBudget(frameSettings(p, scene, mWidth, mHeight), GPUScene::estimateBytes(scene));
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
        if (mVoxelDisplay == VoxelDisplay::Viewport && fs.technique == "vct") {
            std::vector<VoxelGridView> grids = voxelGrids(fs);
            mVoxelView.render(grids, voxelParams(fs, grids, float(width) / float(height)), 0, width, height);
        }
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
    if (!mShowCascades || mPreset.header.technique != "lpv" || !mScene.bounds.valid() || mWidth <= 0) return;
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

std::vector<VoxelGridView> Editor::voxelGrids(const FrameSettings& fs) const {
    return gi::voxelGrids(mRenderer.debugViews(), fs, mScene.bounds);
}

VoxelViewParams Editor::voxelParams(const FrameSettings& fs, const std::vector<VoxelGridView>& grids, float aspect) const {
    VoxelViewParams params = mVoxelParams;
    params.viewProj = projectionMatrix(fs.camera, aspect) * viewMatrix(fs.camera);
    if (mVoxelAutoLevel) params.level = finestLevelHolding(grids, fs.camera.target);
    return params;
}

void Editor::readConePick() {
    if (!mShowCones || mPreset.header.technique != "vct" || mRenderer.width() <= 0) return;
    if (!mPickPending && mPickGeneration == mSceneGeneration) return;
    mPickPending = false;
    mPickGeneration = mSceneGeneration;
    // The point stays where it was picked while the camera moves, so its cones can be seen from the side.
    glm::ivec2 size(mRenderer.width(), mRenderer.height());
    mPick.pixel = glm::clamp(glm::ivec2(mPickUV * glm::vec2(size)), glm::ivec2(0), size - 1);
    FrameSettings fs = frameSettings(mPreset, mScene, size.x, size.y);
    mPick.valid = pickSurface(mRenderer, fs.camera, mPick.pixel, mPick.surface);
}

void Editor::drawConeOverlay() {
    if (!mShowCones || mPreset.header.technique != "vct" || !mPick.valid || !mScene.bounds.valid() || mWidth <= 0)
        return;
    FrameSettings fs = frameSettings(mPreset, mScene, mWidth, mHeight);
    glm::mat4 viewProj = projectionMatrix(fs.camera, float(mWidth) / float(mHeight)) * viewMatrix(fs.camera);
    std::vector<VoxelBox> boxes = vctLevels(fs.vct, mScene.bounds.min, mScene.bounds.max, fs.camera.eye);
    float voxel = boxes.front().cellSize;
    const SurfacePick& p = mPick.surface;
    std::vector<ConeGlyph> glyphs = vctConeGlyphs(fs.vct, p.position, p.normal, fs.camera.eye, p.roughness, voxel);
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    for (const GlyphLine& l : coneGlyphLines(glyphs, mConeLength * voxel)) {
        glm::vec4 c = glm::clamp(l.colour, 0.0f, 1.0f) * 255.0f;
        ImU32 colour = IM_COL32(int(c.r), int(c.g), int(c.b), int(c.a));
        ImVec2 sa, sb;
        if (!projectToScreen(viewProj, l.a, display, sa) || !projectToScreen(viewProj, l.b, display, sb)) continue;
        if (l.a == l.b)
            draw->AddCircleFilled(sa, 0.5f * l.width, colour);
        else
            draw->AddLine(sa, sb, colour, l.width);
    }
}

void Editor::vctPanel() {
    ImGui::Separator();
    ImGui::TextUnformatted("previewers");
    int display = int(mVoxelDisplay);
    ImGui::Combo("voxel view", &display, "off\0in the viewport\0in a window\0");
    mVoxelDisplay = VoxelDisplay(display);
    if (mVoxelDisplay != VoxelDisplay::Off) {
        int source = int(mVoxelParams.source);
        ImGui::Combo("voxels show", &source, "albedo\0normal\0emission\0radiance\0");
        mVoxelParams.source = VoxelViewSource(source);
        const VCTSettings& s = mPreset.vct;
        int levels = s.mode == VCTMode::Dense ? 1 : s.levelCount;
        if (levels > 1) {
            ImGui::Checkbox("auto level", &mVoxelAutoLevel);
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("the finest level that holds the camera's target");
            ImGui::SameLine();
            if (mVoxelAutoLevel) ImGui::BeginDisabled();
            ImGui::SliderInt("voxel level", &mVoxelParams.level, 0, levels - 1);
            if (mVoxelAutoLevel) ImGui::EndDisabled();
        }
        mVoxelParams.level = std::clamp(mVoxelParams.level, 0, levels - 1);
        if (mVoxelParams.source == VoxelViewSource::Radiance) {
            ImGui::SliderInt("voxel mip", &mVoxelParams.mip, 0, vctMipCount(s.gridResolution) - 1);
            ImGui::SliderFloat("solid from", &mVoxelParams.opacityThreshold, 0.01f, 1.0f, "opacity %.2f");
        }
        if (mVoxelParams.source == VoxelViewSource::Radiance || mVoxelParams.source == VoxelViewSource::Emission)
            ImGui::SliderFloat("voxel exposure", &mVoxelParams.exposure, -10.0f, 10.0f, "%.1f EV");
        ImGui::Checkbox("voxel edges", &mVoxelParams.edges);
    }
    ImGui::Checkbox("cone set at picked pixel", &mShowCones);
    if (mShowCones) {
        ImGui::SliderFloat("cone length", &mConeLength, 1.0f, 64.0f, "%.0f voxels");
        if (ImGui::Button("Centre pixel")) {
            mPickUV = glm::vec2(0.5f);
            mPickPending = true;
        }
        ImGui::SameLine();
        hintText("left click the viewport to pick");
        if (mPick.valid)
            ImGui::TextDisabled("pixel (%d, %d): n (%.2f, %.2f, %.2f), roughness %.2f", mPick.pixel.x, mPick.pixel.y,
                                mPick.surface.normal.x, mPick.surface.normal.y, mPick.surface.normal.z,
                                mPick.surface.roughness);
        else
            ImGui::TextDisabled("pixel (%d, %d): no surface", mPick.pixel.x, mPick.pixel.y);
    }
}

void Editor::voxelWindow() {
    if (mVoxelDisplay != VoxelDisplay::Window || mPreset.header.technique != "vct" || mWidth <= 0) return;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(kLeftWidth + 2 * kMargin, display.y - 300.0f - kMargin), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(400.0f, 300.0f), ImGuiCond_FirstUseEver);
    bool open = true;
    if (ImGui::Begin("Voxel view", &open, ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse)) {
        ImVec2 avail = ImGui::GetContentRegionAvail();
        int w = std::max(int(avail.x), 16), h = std::max(int(avail.y), 16);
        if (!mVoxelImage || mVoxelImage.width() != w || mVoxelImage.height() != h) {
            mVoxelImage = gl::Texture::create2D(GL_RGBA8, w, h);
            if (!mVoxelFBO) mVoxelFBO = gl::createFramebuffer();
            glNamedFramebufferTexture(mVoxelFBO.id(), GL_COLOR_ATTACHMENT0, mVoxelImage.id(), 0);
        }
        FrameSettings fs = frameSettings(mPreset, mScene, mWidth, mHeight);
        std::vector<VoxelGridView> grids = voxelGrids(fs);
        mVoxelView.render(grids, voxelParams(fs, grids, float(w) / float(h)), mVoxelFBO.id(), w, h);
        ImGui::Image(ImTextureID(intptr_t(mVoxelImage.id())), ImVec2(float(w), float(h)), ImVec2(0, 1), ImVec2(1, 0));
    }
    ImGui::End();
    if (!open) mVoxelDisplay = VoxelDisplay::Off;
}

void Editor::volumetricPanel() {
    const VolumetricSettings& v = mPreset.volumetric;
    if (v.enabled && v.density <= 0.0f)
        wrappedText(kWarningColor, "density is 0: the medium scatters nothing, so volumetric lighting adds nothing");
    ImGui::Checkbox("phase function window", &mShowPhase);
}

uint8_t Editor::roughnessMipsPanel() {
    if (mOpenMips) ImGui::SetNextItemOpen(true, ImGuiCond_Once);
    bool open = ImGui::TreeNodeEx("Roughness mips", ImGuiTreeNodeFlags_Framed);
    if (mScrollToMips > 0) {
        // Started with --mips-panel: keep the panel at the top of the window until the layout settles.
        ImGui::SetScrollHereY(0.0f);
        --mScrollToMips;
    }
    if (!open) return 0;
    EnvironmentSettings& s = mPreset.environment;
    const Environment* envPass = mRenderer.activePass<Environment>();
    GI_ASSERT(envPass, "the environment is an effect: the renderer always holds it");
    const Environment& env = *envPass;
    // The change tag comes from the settings table, as for every other edit.
    Cost tableCost = Cost::Reallocate;
    s.visit([&](auto&, const FieldMeta& m) {
        if (std::string_view(m.key) == "mipRoughness") tableCost = m.cost;
    });
    uint8_t cost = 0;

    if (!s.enabled) {
        hintText("environment lighting is off (environment.enabled): no mip chain is built; the table below is what one would hold");
    } else if (!env.ready()) {
        wrappedText(kErrorColor, "the environment map did not load" + (mFrameError.empty() ? std::string(" (see the message above)")
                                                                                          : ": " + mFrameError));
    } else if (!mFrameError.empty() && lowercase(mFrameError).find("environment") != std::string::npos) {
        wrappedText(kErrorColor, "the last change failed, the chain shown is the previous one: " + mFrameError);
    }

    // How many mips the cube can hold, and the mip each entry feeds (-1: skipped), by the rule
    // the prefilter uses (Environment::chainMipOfEntry).
    EnvironmentSettings full = s;
    full.mipRoughness.assign(32, 0.0f);
    const int fit = Environment::chainMipCount(full);
    std::vector<float>& table = s.mipRoughness;
    auto mipOf = [&](int entry) { return Environment::chainMipOfEntry(s, entry); };
    const bool cone = s.distribution == PrefilterDistribution::BeckmannCone;
    const std::vector<Environment::MipInfo> built = env.ready() ? env.mips() : std::vector<Environment::MipInfo>{};
    const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerH | ImGuiTableFlags_SizingStretchProp;
    if (ImGui::BeginTable("mips", 6, flags)) {
        ImGui::TableSetupColumn("mip", ImGuiTableColumnFlags_WidthFixed);
        ImGui::TableSetupColumn("roughness", ImGuiTableColumnFlags_WidthStretch, 2.2f);
        ImGui::TableSetupColumn("face", ImGuiTableColumnFlags_WidthStretch, 1.0f);
        ImGui::TableSetupColumn("spp", ImGuiTableColumnFlags_WidthStretch, 1.0f);
        ImGui::TableSetupColumn("disk", ImGuiTableColumnFlags_WidthStretch, 1.0f);
        ImGui::TableSetupColumn("ms", ImGuiTableColumnFlags_WidthStretch, 1.1f);
        static const char* const tips[6] = {"the mip the entry feeds (click: preview it)",
                                            "perceptual roughness (settings: environment.mipRoughness)",
                                            "texels per cube face",
                                            "prefilter samples per texel (copy: roughness 0 copies the source)",
                                            "beckmannCone: the sampling disk's radius, tan theta (seed 004 Fig. 3.24)",
                                            "prefilter time of the mip (CPU clock around the finished dispatch)"};
        ImGui::TableNextRow(ImGuiTableRowFlags_Headers);
        for (int c = 0; c < 6; ++c) {
            ImGui::TableSetColumnIndex(c);
            ImGui::TableHeader(ImGui::TableGetColumnName(c));
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tips[c]);
        }
        for (size_t e = 0; e < table.size(); ++e) {
            const int mip = mipOf(int(e));
            ImGui::PushID(int(e));
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            if (mip >= 0) {
                char label[16];
                std::snprintf(label, sizeof label, "%d", mip);
                if (ImGui::Selectable(label, mMipSelected == mip)) mMipSelected = mip;
            } else {
                ImGui::TextDisabled("-");
                if (ImGui::IsItemHovered()) ImGui::SetTooltip("entry %zu is skipped: the cube has %d mips", e, fit);
            }
            ImGui::TableNextColumn();
            // Dragging one entry past a neighbour pushes the neighbour along: the table stays
            // non-decreasing, as shading's piecewise linear lookup needs.
            float r = table[e];
            ImGui::SetNextItemWidth(-FLT_MIN);
            if (ImGui::DragFloat("##roughness", &r, 0.005f, 0.0f, 1.0f, "%.3f", ImGuiSliderFlags_AlwaysClamp)) {
                table[e] = r;
                for (size_t j = 0; j < e; ++j) table[j] = std::min(table[j], r);
                for (size_t j = e + 1; j < table.size(); ++j) table[j] = std::max(table[j], r);
                cost |= uint8_t(tableCost);
            }
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("perceptual roughness of entry %zu (dragging past a neighbour moves it too)", e);
            const bool used = mip >= 0;
            auto cell = [](const char* fmt, auto value, bool show) {
                ImGui::TableNextColumn();
                if (show) ImGui::Text(fmt, value);
                else ImGui::TextDisabled("-");
            };
            cell("%d", used ? std::max(s.cubeSize >> mip, 1) : 0, used);
            if (used && table[e] <= 0.0f) {
                ImGui::TableNextColumn();
                ImGui::TextDisabled("copy");
            } else {
                cell("%d", s.samples, used);
            }
            cell("%.2f", Environment::beckmannDiskRadius(table[e]), used && cone);
            const bool timed = used && size_t(mip) < built.size();
            cell("%.1f", timed ? built[size_t(mip)].ms : 0.0, timed);
            ImGui::PopID();
        }
        ImGui::EndTable();
    }
    if (int(table.size()) > fit) {
        const int first = fit - 1, last = int(table.size()) - 2;
        std::string skipped = first == last ? "entry " + std::to_string(first) + " is"
                                            : "entries " + std::to_string(first) + ".." + std::to_string(last) + " are";
        hintText("a " + std::to_string(s.cubeSize) + "^2 cube has " + std::to_string(fit) + " mips: " + skipped +
                 " skipped and the last entry goes on the last mip");
    }
    const bool canAdd = int(table.size()) < fit;
    if (!canAdd) ImGui::BeginDisabled();
    if (ImGui::Button("Add mip")) {
        // Continues the last step, so the table stays non-decreasing and ends at most at 1.
        float last = table.back(), step = table.size() > 1 ? last - table[table.size() - 2] : 0.1f;
        table.push_back(std::min(1.0f, last + std::max(step, 0.0f)));
        cost |= uint8_t(tableCost);
    }
    if (!canAdd) ImGui::EndDisabled();
    ImGui::SameLine();
    const bool canRemove = table.size() > 1;
    if (!canRemove) ImGui::BeginDisabled();
    if (ImGui::Button("Remove last")) {
        table.pop_back();
        cost |= uint8_t(tableCost);
    }
    if (!canRemove) ImGui::EndDisabled();
    ImGui::SameLine();
    if (ImGui::Button("Seed defaults")) {
        table = EnvironmentSettings{}.mipRoughness;
        cost |= uint8_t(tableCost);
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("the seed's 11 levels (seed 004, Fig. 3.24)");
    if (env.ready()) {
        double total = env.loadMs();
        for (const Environment::MipInfo& info : built) total += info.ms;
        char line[128];
        std::snprintf(line, sizeof line, "%zu mips (%s): load %.1f ms, with the prefilter %.1f ms", built.size(),
                      enumName(s.distribution), env.loadMs(), total);
        hintText(line);
    }

    // The selected mip of the built chain, through the renderer's view pass.
    if (s.enabled && env.ready() && !built.empty()) {
        ImGui::Separator();
        mMipSelected = std::clamp(mMipSelected, 0, int(built.size()) - 1);
        if (ImGui::RadioButton("cross", !mMipLatLong)) mMipLatLong = false;
        ImGui::SameLine();
        if (ImGui::RadioButton("latlong", mMipLatLong)) mMipLatLong = true;
        ImGui::SliderInt("preview mip", &mMipSelected, 0, int(built.size()) - 1);
        ImGui::SliderFloat("mip exposure", &mMipExposure, -10.0f, 10.0f, "%.1f EV");
        const float width = std::max(std::floor(ImGui::GetContentRegionAvail().x), 64.0f);
        const int w = int(width), h = mMipLatLong ? w / 2 : w * 3 / 4;
        if (!mMipImage || mMipImage.width() != w || mMipImage.height() != h) {
            mMipImage = gl::Texture::create2D(GL_RGBA8, w, h);
            if (!mMipFBO) mMipFBO = gl::createFramebuffer();
            glNamedFramebufferTexture(mMipFBO.id(), GL_COLOR_ATTACHMENT0, mMipImage.id(), 0);
        }
        DebugView view;
        view.name = "environment.mip" + std::to_string(mMipSelected);
        view.texture = env.prefiltered();
        view.target = GL_TEXTURE_CUBE_MAP;
        view.mode = mMipLatLong ? shared::kViewCubeLatLong : shared::kViewCubeCross;
        view.width = w;
        view.height = h;
        view.level = mMipSelected;
        Renderer::ViewParams params;
        params.exposure = mMipExposure;
        glBindFramebuffer(GL_FRAMEBUFFER, mMipFBO.id());
        glViewport(0, 0, w, h);
        mRenderer.drawView(view, params);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        ImGui::Image(ImTextureID(intptr_t(mMipImage.id())), ImVec2(float(w), float(h)), ImVec2(0, 1), ImVec2(1, 0));
        const Environment::MipInfo& info = built[size_t(mMipSelected)];
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip(mMipLatLong ? "latlong: the centre looks along -z, +x at three quarters, the zenith at the top"
                                          : "cross: -x +z +x -z in the middle row, +y above +z, -y below");
        ImGui::TextDisabled("mip %d: roughness %.3f, %d^2 a face", mMipSelected, info.roughness, info.size);
    }
    ImGui::TreePop();
    return cost;
}

void Editor::phaseWindow() {
    const VolumetricSettings& v = mPreset.volumetric;
    // Switching volumetric lighting on shows its phase function.
    if (v.enabled && !mVolumetricWasOn) mShowPhase = true;
    mVolumetricWasOn = v.enabled;
    if (!mShowPhase) return;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(display.x - kRightWidth - kPhaseWidth - 2 * kMargin, kMargin), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(kPhaseWidth, 0.0f), ImGuiCond_FirstUseEver);
    if (ImGui::Begin("Phase function", &mShowPhase, ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse)) {
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
        if (ImGui::RadioButton("linear", !mPhaseLog)) mPhaseLog = false;
        ImGui::SameLine();
        if (ImGui::RadioButton("log", mPhaseLog)) mPhaseLog = true;
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("radius 1 + log10(p / peak) / 3: three decades below the peak");
        ImGui::SameLine();
        ImGui::Checkbox("others", &mPhaseOthers);
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
        if (mPhaseOthers)
            for (const auto& [f, name] : EnumNames<PhaseFunction>::values)
                if (f != p.function) {
                    PhaseParams other = p;
                    other.function = f;
                    polyline(phaseLobe(other, mPhaseLog, 180), IM_COL32(200, 200, 210, 60), 1.0f);
                }
        // The fill as a fan from the centre: the lobe is star-shaped about it (one radius per
        // angle) but not convex (Rayleigh), and this ImGui has no concave fill.
        std::vector<glm::vec2> lobe = phaseLobe(p, mPhaseLog, 360);
        const ImU32 fill = colour(kPhasePlotLobe, 0.16f);
        const ImVec2 white = ImGui::GetFontTexUvWhitePixel();
        draw->PrimReserve(int(lobe.size()) * 3, int(lobe.size()) * 3);
        for (size_t i = 0; i < lobe.size(); ++i) {
            draw->PrimVtx(c, white, fill);
            draw->PrimVtx(screen(lobe[i]), white, fill);
            draw->PrimVtx(screen(lobe[(i + 1) % lobe.size()]), white, fill);
        }
        const PhasePlotScale scale = phasePlotScale(p, mPhaseLog);
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

void Editor::drawPanels() {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    uint8_t cost = 0;
    drawCascadeOverlay();
    const ImGuiIO& io = ImGui::GetIO();
    // A left click on the viewport (not on a panel) picks the pixel whose cone set is drawn.
    if (mShowCones && mPreset.header.technique == "vct" && !io.WantCaptureMouse &&
        ImGui::IsMouseClicked(ImGuiMouseButton_Left) && display.x > 0.0f && display.y > 0.0f) {
        mPickUV = glm::vec2(io.MousePos.x / display.x, 1.0f - io.MousePos.y / display.y);
        mPickPending = true;
    }
    readConePick();
    drawConeOverlay();

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
            // The active technique's settings are what is being tuned: open them too.
            bool open = S::kSection == "render" || S::kSection == "toneMap" ||
                        (S::kSection == "vct" && mPreset.header.technique == "vct") ||
                        (S::kSection == "environment" && mOpenMips);
            if (!ImGui::CollapsingHeader(S::kSection.data(), open ? ImGuiTreeNodeFlags_DefaultOpen : 0)) return;
            cost |= drawSettings(section);
            if constexpr (std::is_same_v<S, CameraSettings>) cost |= cameraTools();
            if constexpr (std::is_same_v<S, LPVSettings>) {
                ImGui::Checkbox("show cascades in the viewport", &mShowCascades);
                std::string note = lpvIgnoredLights(mPreset.lightsFromScene ? mScene.lights : mPreset.lights);
                if (!note.empty()) wrappedText(kWarningColor, note);
            }
            if constexpr (std::is_same_v<S, VCTSettings>) vctPanel();
            if constexpr (std::is_same_v<S, VolumetricSettings>) volumetricPanel();
            if constexpr (std::is_same_v<S, EnvironmentSettings>) cost |= roughnessMipsPanel();
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

    voxelWindow();
    phaseWindow();
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
