#include "ui/editor.h"

#include "gi/reference/framing.h"
#include "gi/render/image_io.h"
#include "gi/scene/camera.h"
#include "gi/util/error.h"
#include "gi/util/paths.h"
#include "ui/panel_util.h"
#include "ui/settings_panel.h"
#include "ui/texture_bridge.h"

#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <type_traits>

namespace fs = std::filesystem;

namespace gi::ui {


Editor::Editor(const EditorOptions& options, GIThread& gi)
    : mPreviewer(options.view), mGI(gi), mWidth(options.width), mHeight(options.height) {
    mGI.acquire();  // the caller holds it already; members were made in it
    mLive = true;
    for (const PassPanelEntry& e : passPanels()) mPanels.emplace_back(e.section, e.create(options));
    for (const std::string& name : options.previewers) mShowPreviewer[name] = true;
    mOpenLights = options.lightsPanel;
    mScrollToLights = mOpenLights ? 10 : 0;
    fs::path defaultFile = presetDir() / "default.json";
    bool isPreset = true;
    // The default preset: default.json, else the built-in one (no files at all).
    auto loadDefault = [&] {
        if (fs::exists(defaultFile)) {
            mPreset = loadPreset(defaultFile);
            mPresetPath = defaultFile;
        } else {
            mPreset = builtinDefaultPreset();  // no files at all: default.json as compiled in
            mPresetPath.clear();
        }
        mPathField = defaultFile.string();
    };
    std::string openError;
    try {
        if (!options.preset.empty()) {
            mPreset = presetForInput(options.preset, -1);
            // A glTF input has no preset file yet: Save As suggests one named after it.
            isPreset = lowercase(options.preset.extension().string()) == ".json";
            mPresetPath = isPreset ? options.preset : fs::path();
            mPathField = (isPreset ? options.preset : presetDir() / (options.preset.stem().string() + ".json")).string();
        } else {
            loadDefault();
        }
        if (options.referenceSPP > 0) mPreset.reference.spp = options.referenceSPP;
        // A glTF file opens with its own first camera (or one framing it) and its lights.
        installScene(mPreset, !isPreset);
    } catch (const std::exception& e) {
        // A preset that does not load opens the editor anyway, on the default preset, with the
        // error shown and the path kept in the path field to fix and open again.
        openError = e.what();
        isPreset = true;
        loadDefault();
        mPathField = options.preset.string();
        if (options.referenceSPP > 0) mPreset.reference.spp = options.referenceSPP;
        installScene(mPreset, false);
    }
    if (!options.reference.empty()) {
        mReference.setView(referenceViewFromName(options.reference));
        mReference.setEnabled(true);
    }
    mGoodPreset = mPreset;
    settle(mPresetPath.empty() ? "opened " + options.preset.filename().string() : "opened " + mPresetPath.filename().string());
    mPresetError = openError;
    mScript = options.script;
    mResizeWindow = options.resizeWindow;
    mPreviewer.setFill(options.fillView);
    mLayoutFile = options.layoutFile;
    loadLayout();
    for (const std::string& name : options.previewers) mShowPreviewer[name] = true;  // the command line wins
    if (options.fillView) mPreviewer.setFill(true);
    mOutputFBO = gl::createFramebuffer();
    const GLubyte* renderer = glGetString(GL_RENDERER);
    mGLRenderer = renderer ? reinterpret_cast<const char*>(renderer) : "unknown";
    scanFiles();
}

Editor::~Editor() {
    // The frame in flight uses the renderer; every member is then deleted in the context it was made in.
    mGI.acquire();
}

void Editor::loadLayout() {
    std::error_code ec;
    if (mLayoutFile.empty() || !fs::exists(mLayoutFile, ec)) return;
    try {
        json j = json::parse(readTextFile(mLayoutFile, size_t(1) << 20));
        mLeftWidth = std::max(j.value("leftWidth", mLeftWidth), kMinColumnWidth);
        mRightWidth = std::max(j.value("rightWidth", mRightWidth), kMinColumnWidth);
        const json previewers = j.value("previewers", json::object());
        for (auto it = previewers.begin(); it != previewers.end(); ++it) mShowPreviewer[it.key()] = it.value().get<bool>();
        mPreviewer.setView(j.value("view", mPreviewer.view()));
        mPreviewer.setFill(j.value("fillView", mPreviewer.fill()));
        mPreviewDivisor = std::clamp(j.value("dragPreview", mPreviewDivisor), 1, 8);
        const json sections = j.value("sections", json::object());
        for (auto it = sections.begin(); it != sections.end(); ++it) mSectionOpen[it.key()] = it.value().get<bool>();
    } catch (const std::exception& e) {
        mPresetError = "layout " + mLayoutFile.string() + " ignored: " + e.what();
    }
}

void Editor::saveLayout() const {
    if (mLayoutFile.empty()) return;
    json previewers = json::object();
    for (const auto& [name, shown] : mShowPreviewer) previewers[name] = shown;
    json sections = json::object();
    for (const auto& [name, open] : mSectionOpen) sections[name] = open;
    json j = {{"leftWidth", mLeftWidth}, {"rightWidth", mRightWidth}, {"previewers", previewers}, {"sections", sections},
              {"view", mPreviewer.view()},  {"fillView", mPreviewer.fill()}, {"dragPreview", mPreviewDivisor}};
    std::error_code ec;
    fs::create_directories(mLayoutFile.parent_path(), ec);
    writeFileAtomic(mLayoutFile, j.dump(2) + "\n");
}

void Editor::requestScreenshot() {
    char name[64];
    std::time_t now = std::time(nullptr);
    std::strftime(name, sizeof name, "gi-workbench-%Y%m%d-%H%M%S", std::localtime(&now));
    mScreenshotRequest = fs::current_path() / name;
}

void Editor::writeScreenshot(const std::vector<uint8_t>& scene, const std::vector<uint8_t>& window, int width, int height) {
    if (!mScreenshotRequest) return;
    const std::string base = mScreenshotRequest->string();
    mScreenshotRequest.reset();
    try {
        writePNG(base + "-window.png", width, height, window);
        // The viewport's rectangle of the scene read (rows bottom first, as GL gives them).
        const int x0 = std::clamp(mViewport.x, 0, width), w = std::clamp(mViewport.width, 0, width - x0);
        const int h = std::min(mViewport.height, height);
        std::vector<uint8_t> crop(size_t(w) * size_t(h) * 4);
        for (int y = 0; y < h; ++y)
            std::copy_n(scene.begin() + (size_t(y) * size_t(width) + size_t(x0)) * 4, size_t(w) * 4, crop.begin() + size_t(y) * size_t(w) * 4);
        writePNG(base + "-viewport.png", w, h, crop);
        mPresetStatus = "screenshot " + base + "-window.png and -viewport.png";
    } catch (const std::exception& e) {
        mPresetError = std::string("screenshot: ") + e.what();
    }
}

void Editor::helpWindow() {
    if (!mShowHelp) return;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.5f), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowBgAlpha(1.0f);  // over the panels: their text must not show through
    if (ImGui::Begin("Help: shortcuts and mouse", &mShowHelp, ImGuiWindowFlags_AlwaysAutoResize)) {
        static constexpr const char* kRows[][2] = {
            {"F1", "this window"},
            {"F12", "screenshot: the window and the viewport as PNGs in the current folder"},
            {"P", "pause or resume the GI (the last image stays)"},
            {"F", "flip between A and the live image (compare A/B, once A is held)"},
            {"Ctrl+Z", "undo the last settings change (a drag, a typed value or a camera flight)"},
            {"Ctrl+Shift+Z, Ctrl+Y", "redo"},
            {"right drag in the viewport", "look around"},
            {"W A S D, Q E", "fly forward, left, back, right, down, up (hold Shift: 4x faster)"},
            {"left click in the viewport", "pick the pixel the overlays point at"},
            {"right click a value", "reset it to its default, or revert it to the file"},
            {"double click a preset", "open it"},
            {"Ctrl+click a slider", "type a value"},
            {"wheel / drag on the buffer preview", "zoom / pan"},
            {"Space (Reference in toggle view)", "hold to see the reference"},
            {"drag the split line", "move the Reference split"},
            {"drag a column's inner edge", "widen or narrow the panels (kept per user)"},
        };
        if (ImGui::BeginTable("help", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerH)) {
            for (const auto& row : kRows) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(row[0]);
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(row[1]);
            }
            ImGui::EndTable();
        }
    }
    ImGui::End();
}

std::string Editor::title() const {
    std::string file = mPresetPath.empty() ? "untitled" : mPresetPath.filename().string();
    return "GI Workbench - " + file + (mDirty ? " *" : "");
}

void Editor::frame(int width, int height, float dt, float workMs) {
    mFrameMs = mFrameMs == 0.0f ? workMs : 0.9f * mFrameMs + 0.1f * workMs;
    // Shown twice a second: a number that changed every frame would make every frame one to draw.
    if (auto now = std::chrono::steady_clock::now(); now - mFrameMsShownAt > std::chrono::milliseconds(500)) {
        mShownFrameMs = mFrameMs;
        mFrameMsShownAt = now;
    }

    CameraSettings camera = mPreset.camera;
    if (camera.sceneCamera >= 0 && camera.sceneCamera < int(mScene.cameras.size())) {
        // Flying away from one of the file's cameras starts from it and leaves it.
        takeSceneCamera(camera, mScene.cameras[camera.sceneCamera]);
        camera.sceneCamera = -1;
    }
    float radius = mScene.bounds.valid() ? 0.5f * glm::length(mScene.bounds.extent()) : 1.0f;
    // A slow frame moves the camera by at most kMaxFlyStepSeconds of flight: a tap of W during a
    // 1 s frame is not a second's flight.
    bool cameraMoved = mFlyCamera.update(camera, std::min(dt, kMaxFlyStepSeconds), radius);
    if (cameraMoved) {
        mPreset.camera = camera;
        apply(uint8_t(Cost::Uniform));
    }
    // Undo and redo, unless a text field is taking the keys (it has its own undo).
    const ImGuiIO& io = ImGui::GetIO();
    if (io.KeyCtrl && !io.WantTextInput && !ImGui::IsAnyItemActive()) {
        if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Z), true)) io.KeyShift ? redo() : undo();
        else if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Y), true)) redo();
    }

    // P pauses and resumes the GI work, unless a text field takes the keys.
    if (!io.WantTextInput && !io.KeyCtrl && ImGui::IsKeyPressed('P', false))  // GLFW_KEY_P: 1.86 indexes keys by GLFW code
        mPaused = !mPaused;

    // F1: help; F12: a screenshot of the window and of the viewport, named after the time.
    if (ImGui::IsKeyPressed(290 /* GLFW_KEY_F1 */, false)) mShowHelp = !mShowHelp;
    // F flips between A and the live image (B) once A is held.
    if (!io.WantTextInput && !io.KeyCtrl && mSnapshotA && ImGui::IsKeyPressed('F', false)) flipCompare();  // GLFW_KEY_F
    if (ImGui::IsKeyPressed(301 /* GLFW_KEY_F12 */, false)) requestScreenshot();

    mRendered.reset();
    // Between GI frames this UI frame holds the GI context: it takes the finished frame and may use
    // the renderer; otherwise the panels show what they last read of it.
    mLive = mGI.tryAcquire();
    textureBridge().setLive(mLive);
    if (mLive) collectResult();
    // The panels dock to the window's sides (drawPanels); the scene fills what lies between.
    const float minViewport = 0.25f * float(width);
    const float columns = mLeftWidth + mRightWidth;
    const float shrink = columns > float(width) - minViewport && columns > 0.0f ? std::max(float(width) - minViewport, 0.0f) / columns : 1.0f;
    mLeftWidth *= shrink;
    mRightWidth *= shrink;
    mViewport = {int(mLeftWidth), std::max(width - int(mLeftWidth) - int(mRightWidth), 1), height};
    if (width > 0 && height > 0) renderViewport(mInteracting || cameraMoved);
    drawPanels();
    recordEdit(cameraMoved);
    // A script acts from the second frame on, one action per frame, each once the GI shows what
    // the last one asked for, as a user would.
    const bool waitingForReference = mScriptNext < mScript.size() && mScript[mScriptNext] == "wait-reference" && !mReference.settled();
    const bool waitingForTune = mScriptNext < mScript.size() && mScript[mScriptNext] == "tune-wait" && mTune && !mTune->done();
    if (mFrames++ > 0 && mScriptNext < mScript.size() && giCaughtUp() && !waitingForReference && !waitingForTune) {
        runAction(mScript[mScriptNext++]);
        recordEdit(false);
    }
    // A preview renders while this interaction goes on (a script's drag lasts until its next other action).
    mInteracting = ImGui::IsAnyItemActive() || cameraMoved || mScriptDrag;
    submitIfNeeded();
}

void Editor::collectResult() {
    if (!mResult) return;
    GIResult r = std::move(*mResult);
    mResult.reset();
    if (r.error.empty()) {
        mRenderMs = r.frame.ms;
        mRenderSize = {r.frame.width, r.frame.height};
        mRendered = r.frame;
        mRenderedKey = r.key;
        mGoodPreset = r.preset;
    } else {
        // Keep the last picture and go back to the settings that made it. The message stays
        // until dismissed, since the restored settings render fine on the next frame.
        mFrameError = r.error + " (previous settings restored)";
        mFailedKey = r.key;
        mRenderedKey.clear();
        mPreset = mGoodPreset;
        ++mLiveGeneration;
    }
    ++mOutputGeneration;
    mPassStats = mRenderer.passStats();
    mPassReports = mRenderer.passReports(frameSettings(mGoodPreset, mScene, mRenderSize.x, mRenderSize.y));
    mMemoryBytes = mRenderer.memoryBytes();
    mPickPending = true;  // the focus pixel's surface, of the new frame
}

void Editor::submitIfNeeded() {
    if (!mGI.held()) return;  // the GI thread is rendering
    const int width = mWidth, height = mHeight;
    const int divisor = mInteracting ? std::max(mPreviewDivisor, 1) : 1;
    const int w = std::max(width / divisor, 1), h = std::max(height / divisor, 1);
    mWantKey = liveKey(w, h);
    if (mPaused || width <= 0 || height <= 0 || mWantKey == mRenderedKey || mWantKey == mFailedKey) {
        mGI.release();
        return;
    }
    FrameSettings fs;
    try {
        fs = frameSettings(mPreset, mScene, w, h);
    } catch (const std::exception& e) {
        mFrameError = e.what();
        mFailedKey = mWantKey;
        mGI.release();
        return;
    }
    mGI.submit([this, fs = std::move(fs), key = mWantKey, preset = mPreset, w, h, started = mFrames] {
        GIResult r{key, preset, {0.0f, w, h, started}, {}};
        auto start = std::chrono::steady_clock::now();
        try {
            mRenderer.render(fs);
            mRenderer.resolveTimings();  // the pass timers of this frame, for the Stats panel
        } catch (const std::exception& e) {
            r.error = e.what();
        }
        r.frame.ms = std::chrono::duration<float, std::milli>(std::chrono::steady_clock::now() - start).count();
        mResult = std::move(r);
    });
}

void Editor::recordEdit(bool cameraMoved) {
    if (!mEditPending || ImGui::IsAnyItemActive() || cameraMoved) return;
    mEditPending = false;
    mHistory.record(mPreset);
    mDirty = !presetDiff(mDiskPreset, mPreset).empty();
}

void Editor::restore(const Preset& target) {
    Preset p = target;
    if (p.header.scene != mLoadedScene || p.folder != mPreset.folder) {
        try {
            installScene(p, false);  // the state's own camera and lights, not the scene's
        } catch (const std::exception& e) {
            mSceneError = e.what();
            return;
        }
    }
    mPreset = mGoodPreset = p;
    mSceneError.clear();
    mFrameError.clear();
    ++mLiveGeneration;
    mDirty = !presetDiff(mDiskPreset, mPreset).empty();
}

void Editor::undo() {
    if (mHistory.canUndo()) restore(mHistory.undo());
}

void Editor::redo() {
    if (mHistory.canRedo()) restore(mHistory.redo());
}

void Editor::resetKey(const std::string& key) {
    auto defaults = flattenPreset(Preset{});
    auto it = defaults.find(key);
    if (it == defaults.end()) throw Error("reset: key '" + key + "' is not a setting");
    applySetting(mPreset, key + "=" + it->second);
    apply(key == "scene" ? uint8_t(Cost::ReloadScene) : uint8_t(Cost::Uniform));
}

void Editor::resetSection(const std::string& name) {
    bool found = false;
    Preset defaults;
    mPreset.forEachSection([&](auto& section) {
        using S = std::decay_t<decltype(section)>;
        defaults.forEachSection([&](auto& d) {
            if constexpr (std::is_same_v<std::decay_t<decltype(d)>, S>)
                if (S::kSection == name) {
                    section = d;
                    found = true;
                }
        });
    });
    if (!found) throw Error("reset: '" + name + "' is not a settings section");
    apply(uint8_t(Cost::Uniform));
}

void Editor::resetAll() {
    Preset defaults;
    CameraSettings camera = mPreset.camera;
    Preset p = defaults;
    p.header = mPreset.header;
    p.camera = camera;
    p.lightsFromScene = mPreset.lightsFromScene;
    p.lights = mPreset.lights;
    p.folder = mPreset.folder;
    mPreset = p;
    apply(uint8_t(Cost::Uniform));
}

void Editor::settle(const std::string& label) {
    mDiskPreset = mPreset;
    mHistory.reset(mPreset, label);
    mEditPending = false;
    mDirty = false;
    mPresetError.clear();
    mSceneError.clear();
    mFrameError.clear();
}

void Editor::runAction(const std::string& action) {
    auto space = action.find(' ');
    std::string verb = action.substr(0, space), arg = space == std::string::npos ? "" : action.substr(space + 1);
    mScriptDrag = false;  // a drag lasts from its first drag action to the next other action
    if (verb == "set" || verb == "drag") {
        applySetting(mPreset, arg);
        apply(arg.rfind("scene=", 0) == 0 ? uint8_t(Cost::ReloadScene) : uint8_t(Cost::Uniform));
        mScriptDrag = verb == "drag";
    } else if (verb == "resize") {
        int w = 0, h = 0;
        if (std::sscanf(arg.c_str(), "%dx%d", &w, &h) != 2 || w < 64 || h < 64 || !mResizeWindow)
            throw Error("script: resize takes WIDTHxHEIGHT, each at least 64: '" + arg + "'");
        mResizeWindow(w, h);
    } else if (verb == "bookmark") {
        addBookmark(arg);
    } else if (verb == "goto") {
        auto it = std::find_if(mPreset.bookmarks.begin(), mPreset.bookmarks.end(), [&](const CameraBookmark& b) { return b.name == arg; });
        if (it == mPreset.bookmarks.end()) throw Error("script: no view named '" + arg + "'");
        jumpTo(*it);
    } else if (verb == "camera") {
        int i = std::atoi(arg.c_str());
        if (i < 0 || i >= int(mScene.cameras.size())) throw Error("script: the scene has no camera " + arg);
        takeFileCamera(size_t(i));
    } else if (verb == "screenshot") {
        if (arg.empty()) throw Error("script: screenshot takes a path (PATH-window.png and PATH-viewport.png are written)");
        mScreenshotRequest = fs::path(arg);
    } else if (verb == "hold") {
        mHoldRequested = true;
    } else if (verb == "compare") {
        if (!mSnapshotA) throw Error("script: compare needs A held first (hold)");
        if (arg == "live" || arg == "b") mCompareView = CompareView::Live;
        else if (arg == "a") mCompareView = CompareView::A;
        else if (arg == "split") mCompareView = CompareView::Split;
        else throw Error("script: compare takes live, a or split: '" + arg + "'");
    } else if (verb == "diff-file") {
        diffWithFile(arg);
    } else if (verb == "tune") {
        // tune TECHNIQUE BUDGET_MS RENDERS [WxH]: start the auto-tune; tune-wait runs once it ends.
        char technique[64] = {0};
        double budget = 0.0;
        int renders = 0, w = mTuneRequest.width, h = mTuneRequest.height;
        int n = std::sscanf(arg.c_str(), "%63s %lf %d %dx%d", technique, &budget, &renders, &w, &h);
        if (n < 3 || budget <= 0.0 || renders < 1) throw Error("script: tune takes TECHNIQUE BUDGET_MS RENDERS [WxH]: '" + arg + "'");
        mTuneRequest.technique = technique;
        mTuneRequest.budgetMs = budget;
        mTuneRequest.renders = size_t(renders);
        mTuneRequest.width = w;
        mTuneRequest.height = h;
        mSectionForce["auto-tune"] = true;
        startTune();
    } else if (verb == "matrix-load") {
        loadMatrix(arg);
        mSectionForce["compare A/B"] = true;
    } else if (verb == "matrix-pick") {
        size_t a = 0, b = 0;
        if (std::sscanf(arg.c_str(), "%zu %zu", &a, &b) != 2 || a >= mMatrixCells.size() || b >= mMatrixCells.size())
            throw Error("script: matrix-pick takes two cell indices below " + std::to_string(mMatrixCells.size()) + ": '" + arg + "'");
        mMatrixPick = {a, b};
    } else if (verb == "matrix-view") {
        if (arg != "side" && arg != "split") throw Error("script: matrix-view takes side or split: '" + arg + "'");
        mMatrixView = arg == "side" ? 0 : 1;
    } else if (verb == "tune-wait") {
        // Runs once the search has ended (see frame()).
    } else if (verb == "tune-cancel") {
        if (mTune) mTune->cancel();
    } else if (verb == "tune-apply") {
        applyTune();
    } else if (verb == "help") {
        mShowHelp = !mShowHelp;
    } else if (verb == "wait" || verb == "wait-reference") {  // wait-reference ran once the reference settled
        // Nothing: a frame as a user who is looking at the picture.
    } else if (verb == "pause" || verb == "resume") {
        mPaused = verb == "pause";
    } else if (verb == "undo") {
        undo();
    } else if (verb == "redo") {
        redo();
    } else if (verb == "reset") {
        resetKey(arg);
    } else if (verb == "reset-section") {
        resetSection(arg);
    } else if (verb == "reset-all") {
        resetAll();
    } else if (verb == "save") {
        savePresetAs(mPresetPath.empty() ? fs::path(mPathField) : mPresetPath);
    } else if (verb == "save-as") {
        savePresetAs(arg);
    } else if (verb == "open") {
        openPreset(arg);
    } else if (verb == "section") {
        // section NAME open|closed; NAME/developer is a section's developer node.
        size_t space = arg.rfind(' ');
        std::string name = arg.substr(0, space), how = space == std::string::npos ? "" : arg.substr(space + 1);
        if (space == std::string::npos || (how != "open" && how != "closed"))
            throw Error("script: section takes a name and open or closed (e.g. 'section vct/developer open')");
        if (name.find('/') != std::string::npos)
            mSectionOpen[name] = how == "open";
        else
            mSectionForce[name] = how == "open";
    } else {
        throw Error("script: unknown action '" + action + "'");
    }
}

json Editor::state() const {
    json history = json::array();
    for (size_t i = 0; i < mHistory.size(); ++i) history.push_back(mHistory.label(i));
    json errors = json::array();
    for (const std::string* e : {&mPresetError, &mSceneError, &mFrameError})
        if (!e->empty()) errors.push_back(*e);
    return {{"title", title()},
            {"file", mPresetPath.string()},
            {"dirty", mDirty},
            {"errors", errors},
            {"status", mPresetStatus},
            {"pathField", mPathField},
            {"history", history},
            {"historyIndex", mHistory.index()},
            {"paused", mPaused},
            {"window", {int(ImGui::GetIO().DisplaySize.x), int(ImGui::GetIO().DisplaySize.y)}},
            {"leftColumnWidth", int(mLeftWidth)},
            {"rightColumnX", int(mRightColumnX)},
            {"viewport", {mViewport.x, mViewport.width, mViewport.height}},
            {"giSettled", giSettled()},
            {"compare", compareState()},
            {"tune", tuneState()},
            {"matrix", matrixState()},
            {"openSections", openSections()},
            {"fieldsShown", mFieldsShown},
            {"preset", json::parse(presetToSavedJson(mPreset).dump())}};
}

void Editor::apply(uint8_t cost) {
    if (!cost) return;
    mEditPending = true;
    ++mLiveGeneration;
    if (cost & uint8_t(Cost::ReloadScene)) {
        Preset p = mPreset;
        try {
            installScene(p, true);
            mPreset = mGoodPreset = p;
            mSceneError.clear();
            mFrameError.clear();
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
    frameCameraless(scene);  // a file with no camera: a view from inside when it is a room
    mFramedView.reset();
    if (resetView) {
        p.camera = scene.cameras.empty() ? frameBounds(scene.bounds) : scene.cameras.front();
        p.camera.sceneCamera = -1;
        p.lightsFromScene = true;
        p.lights.clear();
    }
    // Refuse a scene past the memory budget before uploading it (a prefilter past the time
    // budget is refused by the frame, so the preset still opens and its settings can be lowered).
    Renderer::checkMemoryBudget(frameSettings(p, scene, mWidth, mHeight), GPUScene::estimateBytes(scene));
    mGI.acquire();  // a frame in flight finishes first; the rest of this UI frame holds the context
    mRenderer.setScene(scene);
    mScene = std::move(scene);
    mLoadedScene = p.header.scene;
    ++mSceneGeneration;
    ++mLiveGeneration;
}

std::string Editor::liveKey(int width, int height) const {
    return std::to_string(mLiveGeneration) + " " + std::to_string(mSceneGeneration) + " " + std::to_string(width) + "x" +
           std::to_string(height) + " " + (mPreset.lightsFromScene ? "scene lights " : "") + mPreset.folder.string() + " " +
           presetToJson(mPreset).dump();
}

void Editor::renderViewport(bool interacting) {
    const int width = mViewport.width, height = mViewport.height;
    mWidth = width;
    mHeight = height;
    FrameSettings fs;
    try {
        // The panels and the reference see the full-size frame, whatever size the preview renders at.
        fs = frameSettings(mPreset, mScene, width, height);
    } catch (const std::exception& e) {
        mFrameError = std::string(e.what()) + " (previous settings restored)";
        mPreset = mGoodPreset;
        fs = frameSettings(mPreset, mScene, width, height);
        ++mLiveGeneration;
    }
    mLiveKey = liveKey(width, height);
    const bool giIdle = !mRendered && mLive && mRenderedKey == mLiveKey && !interacting;
    if (mLive) {
        // The window's background, in the GI context: its size, cleared, the GI image scaled into
        // the viewport, then what may cover it there.
        const ImVec2 window = ImGui::GetIO().DisplaySize;
        const int cw = std::max(int(window.x), 1), ch = std::max(int(window.y), 1);
        if (!mComposite || mComposite.width() != cw || mComposite.height() != ch) {
            mComposite = gl::Texture::create2D(GL_RGBA8, cw, ch);
            if (!mCompositeFBO) mCompositeFBO = gl::createFramebuffer();
            glNamedFramebufferTexture(mCompositeFBO.id(), GL_COLOR_ATTACHMENT0, mComposite.id(), 0);
        }
        if (mHoldRequested && mRenderedKey == mLiveKey && mRenderer.width() > 0) {
            holdSnapshot();
            mHoldRequested = false;
        }
        // The reference takes every core while the GI has nothing to render.
        if (mRenderer.width() > 0)
            mReference.update(mScene, mSceneGeneration, mLiveGeneration, fs, mPreset.reference, mRenderer, giIdle);
        // Composed (and read back for the window) when the GI image or the layout changed, or on
        // every frame while something else is drawn over the image.
        bool overlaid = mPreviewer.fill() || mReference.enabled() || comparing();
        for (auto& [section, p] : mPanels) overlaid |= p->drawsViewport(fs);
        const std::string composeKey = std::to_string(mOutputGeneration) + " " + std::to_string(cw) + "x" + std::to_string(ch) + " " +
                                       std::to_string(mViewport.x) + " " + std::to_string(width) + "x" + std::to_string(height);
        if (overlaid || composeKey != mComposedKey) {
            mComposedKey = overlaid ? std::string() : composeKey;
            ViewportRect target = mViewport;
            target.framebuffer = mCompositeFBO.id();
            glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
            glViewport(0, 0, cw, ch);
            glClearColor(0.08f, 0.08f, 0.09f, 1.0f);
            glClear(GL_COLOR_BUFFER_BIT);
            if (mRenderer.width() > 0) {
                // Attached every frame: a resized output texture may reuse the old one's name.
                glNamedFramebufferTexture(mOutputFBO.id(), GL_COLOR_ATTACHMENT0, mRenderer.outputTexture(), 0);
                glBlitNamedFramebuffer(mOutputFBO.id(), target.framebuffer, 0, 0, mRenderer.width(), mRenderer.height(), mViewport.x, 0,
                                       mViewport.x + width, height, GL_COLOR_BUFFER_BIT, GL_LINEAR);
                mPreviewer.drawViewport(&mRenderer, target);
                PanelContext ctx = panelContext();
                for (auto& [section, p] : mPanels) p->drawViewport(ctx, fs, target);
            }
            glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
            drawComparison(target, true);
            glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
            mReference.drawViewport(target, true);
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            textureBridge().id(mComposite);  // read back for the window
        }
    } else {
        // The composite stands; what is drawn with the panels (labels, a readout) still follows the mouse.
        mPreviewer.drawViewport(nullptr, mViewport);
        drawComparison(mViewport, false);
        mReference.drawViewport(mViewport, false);
    }
}

void Editor::openPreset(const fs::path& path) {
    try {
        Preset p = loadPreset(path);
        installScene(p, false);
        mPreset = mGoodPreset = p;
        mPresetPath = path;
        mPathField = path.string();
        settle("opened " + path.filename().string());
        mPresetStatus = "opened " + path.string();
    } catch (const std::exception& e) {
        mPresetError = e.what();
    }
}

namespace {
// A file in the presets folder the project ships (presetDir()).
bool isShippedPreset(const fs::path& path) {
    std::error_code ec;
    return fs::exists(path, ec) && fs::equivalent(path.parent_path().empty() ? fs::path(".") : path.parent_path(), presetDir(), ec);
}
}  // namespace

void Editor::savePresetAs(const fs::path& path) {
    // Never replace another file silently, nor a shipped preset: the first press warns, the second writes.
    bool shipped = isShippedPreset(path);
    if (((path != mPresetPath && fs::exists(path)) || shipped) && mConfirmOverwrite != path) {
        mConfirmOverwrite = path;
        mPresetError.clear();
        mPresetStatus = shipped ? path.filename().string() + " is a shipped preset: press Save again to change it, or Save As another file"
                                : path.filename().string() + " exists: press again to replace it";
        return;
    }
    mConfirmOverwrite.clear();
    try {
        savePreset(mPreset, path);  // atomic: the old file stays whole until the new one is complete
        mPresetPath = path;
        mPathField = path.string();
        mDiskPreset = mPreset;
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

void Editor::drawPanels() {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    uint8_t cost = 0;
    const ImGuiIO& io = ImGui::GetIO();
    // A left click on the viewport (not on a panel) picks the focus pixel the overlays point at.
    if (!io.WantCaptureMouse && ImGui::IsMouseClicked(ImGuiMouseButton_Left) && mViewport.contains(io.MousePos)) {
        mPickUV = glm::vec2((io.MousePos.x - float(mViewport.x)) / float(mViewport.width), 1.0f - io.MousePos.y / float(mViewport.height));
        mPickPending = true;
    }
    const FrameSettings frame = frameSettings(mPreset, mScene, std::max(mWidth, 1), std::max(mHeight, 1));
    if (mLive) {
        readFocus();
        mPreviewers = mRenderer.previewers(frame);
    }
    const std::vector<Previewer>& previewers = mPreviewers;
    drawOverlays(frame, previewers);
    PanelContext ctx = panelContext();

    // The columns: docked to the window's sides at its full height; their widths follow a drag of
    // their inner edge, and the viewport takes the rest (mViewport, in frame()).
    const float maxColumn = std::max(0.4f * display.x, kMinColumnWidth);
    ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(mLeftWidth, display.y), ImGuiCond_Always);
    ImGui::SetNextWindowSizeConstraints(ImVec2(kMinColumnWidth, display.y), ImVec2(maxColumn, display.y));
    const ImGuiWindowFlags docked = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse;
    bool leftOpen = ImGui::Begin("GI Workbench", nullptr, docked);
    mLeftWidth = ImGui::GetWindowWidth();
    mFieldsShown.clear();
    if (leftOpen) {
        ImGui::PushItemWidth(-kLabelWidth);
        if (!mFrameError.empty()) {
            wrappedText(kErrorColor, mFrameError);
            if (ImGui::SmallButton("Dismiss")) mFrameError.clear();
            ImGui::Separator();
        }
        if (section("scene", true)) cost |= scenePanel();
        if (section("presets", true)) presetsPanel();
        if (section("compare A/B", bool(mSnapshotA))) comparePanel();
        if (section("auto-tune", bool(mTune))) tunePanel();
        bool lightsOpen = section("lights", false, mOpenLights);
        if (mScrollToLights > 0) {
            ImGui::SetScrollHereY(0.0f);
            --mScrollToLights;
        }
        if (lightsOpen) cost |= lightsPanel();
        // Every fixed section the preset has, so a new technique's settings appear by themselves.
        static const std::map<std::string, std::string> defaults = flattenPreset(Preset{});
        const std::map<std::string, std::string> disk = flattenPreset(mDiskPreset), current = flattenPreset(mPreset);
        mPreset.forEachSection([&](auto& section) {
            using S = std::decay_t<decltype(section)>;
            // The active technique's settings are what is being tuned: open them too.
            PassPanel* own = panel(S::kSection);
            bool open = S::kSection == "render" || S::kSection == "toneMap" || mPreset.header.technique == S::kSection ||
                        (own && own->openAtStart());
            if (!this->section(S::kSection.data(), open)) return;
            const std::string prefix = std::string(S::kSection) + ".";
            bool offDefault = false;
            for (auto it = defaults.lower_bound(prefix); !offDefault && it != defaults.end() && it->first.rfind(prefix, 0) == 0; ++it) {
                auto now = current.find(it->first);
                offDefault = now != current.end() && now->second != it->second;
            }
            if (offDefault) {
                ImGui::PushID(S::kSection.data());
                if (ImGui::SmallButton("Reset section")) resetSection(std::string(S::kSection));
                ImGui::PopID();
                if (ImGui::IsItemHovered()) ImGui::SetTooltip("every %s setting to its default (undo brings them back)", S::kSection.data());
            }
            // The developer settings sit in a node of their own, closed unless the layout says.
            bool& developerOpen = mSectionOpen[std::string(S::kSection) + "/developer"];
            cost |= drawSettings(section, FieldBaselines{prefix, &defaults, mPresetPath.empty() ? nullptr : &disk,
                                                         &developerOpen, &mFieldsShown});
            if constexpr (std::is_same_v<S, CameraSettings>) cost |= cameraTools();
            passExtras(S::kSection, frame, previewers);
            if (own) cost |= own->drawSection(ctx);
        });
        ImGui::PopItemWidth();
    }
    ImGui::End();

    // The right column: Stats, the buffer previewer and the Reference panel, stacked; a drag of any
    // one's inner edge sets the column's width.
    const float rightX = display.x - mRightWidth;
    float rightWidth = mRightWidth;
    auto column = [&](const char* name, float y, float height, ImGuiWindowFlags flags, auto&& body) {
        ImGui::SetNextWindowPos(ImVec2(rightX, y), ImGuiCond_Always);
        ImGui::SetNextWindowSize(ImVec2(mRightWidth, height), ImGuiCond_Always);
        ImGui::SetNextWindowSizeConstraints(ImVec2(kMinColumnWidth, height), ImVec2(maxColumn, height));
        if (ImGui::Begin(name, nullptr, docked | flags)) body();
        if (ImGui::GetWindowWidth() != mRightWidth) rightWidth = ImGui::GetWindowWidth();
        mRightColumnX = ImGui::GetWindowPos().x;
        ImGui::End();
    };
    // In a short window Stats and Reference give up height (they scroll), so the previewer keeps
    // at least a third of the column.
    const float statsHeight = std::min(kStatsHeight, std::floor(0.36f * display.y));
    const float referenceHeight = std::min(kReferenceHeight, std::floor(0.3f * display.y));
    column("Stats", 0.0f, statsHeight, 0, [&] { statsPanel(); });
    // The wheel zooms the image, so it must not scroll the window.
    column("Buffer previewer", statsHeight, std::max(display.y - statsHeight - referenceHeight, 64.0f),
           ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse, [&] {
               ImGui::PushItemWidth(-kLabelWidth * 0.6f);
               mPreviewer.draw(mLive ? &mRenderer : nullptr);
               ImGui::PopItemWidth();
           });
    column("Reference", display.y - referenceHeight, referenceHeight, 0, [&] {
        ImGui::PushItemWidth(-kLabelWidth * 0.6f);
        mReference.draw();
        ImGui::PopItemWidth();
    });
    mRightWidth = rightWidth;

    for (auto& [section, p] : mPanels) p->drawWindows(ctx);
    previewerWindows(frame, previewers);
    helpWindow();
    apply(cost);
}

bool Editor::section(const char* name, bool defaultOpen, bool forceOpen) {
    // The user's layout decides at the first appearance; --lights-panel and the like open theirs.
    if (auto it = mSectionOpen.find(name); it != mSectionOpen.end()) ImGui::SetNextItemOpen(it->second, ImGuiCond_Once);
    if (forceOpen) ImGui::SetNextItemOpen(true, ImGuiCond_Once);
    if (auto it = mSectionForce.find(name); it != mSectionForce.end()) {  // the script's `section`
        ImGui::SetNextItemOpen(it->second, ImGuiCond_Always);
        mSectionForce.erase(it);
    }
    const bool open = ImGui::CollapsingHeader(name, defaultOpen ? ImGuiTreeNodeFlags_DefaultOpen : 0);
    mSectionOpen[name] = open;
    return open;
}

PanelContext Editor::panelContext() { return {mPreset, mScene, mLive ? &mRenderer : nullptr, mFrameError, mWidth, mHeight}; }

PassPanel* Editor::panel(std::string_view section) const {
    for (const auto& [s, p] : mPanels)
        if (s == section) return p.get();
    return nullptr;
}

void Editor::passExtras(std::string_view section, const FrameSettings& fs, const std::vector<Previewer>& previewers) {
    const PassInfo* info = findPass(section);
    if (!info || !passActive(*info, fs)) return;
    if (info->notes)
        if (std::string note = info->notes(fs); !note.empty()) wrappedText(kWarningColor, note);
    for (const auto& [name, report] : mPassReports)
        if (name == section)
            for (const auto& [key, text] : report.texts) ImGui::TextWrapped("%s: %s", key.c_str(), text.c_str());
    // The pass's previewers are named after its section.
    const std::string prefix = std::string(section) + ".";
    bool any = false;
    for (const Previewer& p : previewers) {
        if (p.name.rfind(prefix, 0) != 0) continue;
        if (!any) {
            ImGui::Separator();
            ImGui::TextUnformatted("previewers");
            any = true;
        }
        auto [it, added] = mShowPreviewer.try_emplace(p.name, false);
        ImGui::Checkbox((p.name + (p.overlay ? " (over the viewport)" : " (window)")).c_str(), &it->second);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", p.description.c_str());
    }
    if (!any) return;
    ImGui::SliderFloat("overlay size", &mOverlayScale, 0.1f, 5.0f, "%.2fx");
    if (ImGui::Button("Centre pixel")) {
        mPickUV = glm::vec2(0.5f);
        mPickPending = true;
    }
    ImGui::SameLine();
    hintText("left click the viewport to pick");
    if (mFocus)
        ImGui::TextDisabled("pixel (%d, %d): n (%.2f, %.2f, %.2f), roughness %.2f", mFocusPixel.x, mFocusPixel.y, mFocus->normal.x,
                            mFocus->normal.y, mFocus->normal.z, mFocus->roughness);
    else
        ImGui::TextDisabled("pixel (%d, %d): no surface", mFocusPixel.x, mFocusPixel.y);
}

void Editor::readFocus() {
    if (mRenderer.width() <= 0) return;
    if (!mPickPending && mPickGeneration == mSceneGeneration) return;
    mPickPending = false;
    mPickGeneration = mSceneGeneration;
    // The point stays where it was picked while the camera moves, so what points at it can be seen from the side.
    glm::ivec2 size(mRenderer.width(), mRenderer.height());
    mFocusPixel = glm::clamp(glm::ivec2(mPickUV * glm::vec2(size)), glm::ivec2(0), size - 1);
    SurfacePick pick;
    mFocus.reset();
    if (mRenderer.pickSurface(mFocusPixel, pick)) mFocus = pick;
}

void Editor::drawOverlays(const FrameSettings& fs, const std::vector<Previewer>& previewers) {
    if (mWidth <= 0) return;
    if (mLive) {
        // The lines are made while the context is held and drawn on every frame, with the
        // projection of the image they belong to.
        mOverlayLines.clear();
        if (mRenderer.width() <= 0) return;
        // The focus is read once per pick (readFocus), not every frame.
        PreviewContext ctx = mRenderer.previewContext(fs, std::nullopt);
        ctx.focus = mFocus;
        ctx.overlayScale = mOverlayScale;
        mOverlayViewProj = ctx.viewProj;
        for (const Previewer& p : previewers) {
            if (!p.overlay) continue;
            auto it = mShowPreviewer.find(p.name);
            if (it == mShowPreviewer.end() || !it->second) continue;
            std::vector<GlyphLine> lines = p.overlay(ctx);
            mOverlayLines.insert(mOverlayLines.end(), lines.begin(), lines.end());
        }
    }
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    for (const GlyphLine& l : mOverlayLines) {
        glm::vec4 c = glm::clamp(l.colour, 0.0f, 1.0f) * 255.0f;
        ImU32 colour = IM_COL32(int(c.r), int(c.g), int(c.b), int(c.a));
        ImVec2 sa, sb;
        if (!projectToScreen(mOverlayViewProj, l.a, mViewport, sa) || !projectToScreen(mOverlayViewProj, l.b, mViewport, sb)) continue;
        if (l.a == l.b)
            draw->AddCircleFilled(sa, 0.5f * l.width, colour);
        else
            draw->AddLine(sa, sb, colour, l.width);
    }
}

void Editor::previewerWindows(const FrameSettings& fs, const std::vector<Previewer>& previewers) {
    float y = kMargin;
    for (const Previewer& p : previewers) {
        if (!p.image) continue;
        auto shown = mShowPreviewer.find(p.name);
        if (shown == mShowPreviewer.end() || !shown->second) continue;
        const ImVec2 display = ImGui::GetIO().DisplaySize;
        ImGui::SetNextWindowPos(ImVec2(display.x - kRightWidth - kSideWindowWidth - 2 * kMargin, y), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowSize(ImVec2(kSideWindowWidth, 0.0f), ImGuiCond_FirstUseEver);
        y += 40.0f;
        if (ImGui::Begin(p.name.c_str(), &shown->second)) {
            PreviewWindow& w = mPreviewWindows[p.name];
            // Made again when the live image changes; a previewer may render views or read the
            // G-buffer, so only while the GI context is held.
            if (mLive && (w.generation != mLiveGeneration || !w.image)) {
                PreviewImage img = p.image(mRenderer.previewContext(fs, mFocusPixel));
                w.generation = mLiveGeneration;
                if (img.width > 0) {
                    w.image = gl::Texture::create2D(GL_RGBA8, img.width, img.height);
                    glTextureSubImage2D(w.image.id(), 0, 0, 0, img.width, img.height, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
                } else {
                    w.image = gl::Texture();
                }
            }
            if (w.image) {
                float width = std::max(ImGui::GetContentRegionAvail().x, 64.0f);
                float height = width * float(w.image.height()) / float(w.image.width());
                giImage(w.image, ImVec2(width, height));
            } else {
                hintText("nothing to show this frame");
            }
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", p.description.c_str());
        }
        ImGui::End();
    }
}

}  // namespace gi::ui
