// The editor: the preset being tuned, its scene and the renderer, and the panels that edit them.
// The renderer's frames run on the GI thread (ui/gi_thread.h) whenever what they would draw has
// changed; each UI frame draws the panels over the last finished image, so the UI stays at display
// rate however slow the GI is. Panels edit the preset through the settings reflection
// (drawSettings) and report the OR of the Cost bits of what changed; Editor::apply is the one
// place that acts on those bits.
#pragma once

#include "gi/gl/handle.h"
#include "gi/preset/history.h"
#include "gi/preset/preset.h"
#include "gi/render/renderer.h"
#include "gi/scene/scene.h"
#include "ui/tune_job.h"

#include <array>
#include "ui/buffer_previewer.h"
#include "ui/fly_camera.h"
#include "ui/gi_thread.h"
#include "ui/panel_util.h"
#include "ui/pass_panel.h"
#include "ui/reference_panel.h"

#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace gi::ui {

struct EditorOptions {
    std::filesystem::path preset;  // preset or glTF file; empty: presetDir()/default.json, else the built-in default
    std::string view = "final";    // the buffer previewer's first view
    int width = 1280;              // first frame size, for the memory estimate before the scene is uploaded
    int height = 720;
    std::string reference;         // non-empty: the Reference panel starts on, in this view (live, split, ...)
    int referenceSPP = 0;          // > 0: overrides the preset's reference.spp
    std::string voxelView;         // VCT: albedo, normal or radiance shows that voxel view in the viewport
    bool voxelWindow = false;      // the voxel view in its own window instead of the viewport
    std::vector<std::string> previewers;  // previewers (gi-render --views names, or overlays: vct.cones, lpv.cascades) shown from the start
    bool phasePlot = false;        // the Phase function window open from the start (it also opens when volumetric is on)
    bool roughnessMips = false;    // the environment section's Roughness mips panel open, and scrolled to, from the start
    bool lightsPanel = false;      // the lights section open with every light expanded, and scrolled to, from the start
    // Actions run one per frame after the first frame, as a user would do them (Editor::runAction):
    // tests drive the editor with these under Xvfb.
    std::vector<std::string> script;
    bool fillView = false;         // the buffer previewer's view fills the viewport from the start
    // The user's layout (column widths, the previewers shown, the buffer view and whether it fills
    // the viewport, the drag preview): read at start and written by saveLayout(); empty: none.
    std::filesystem::path layoutFile;
    std::function<void(int, int)> resizeWindow;  // the script's resize action (the window is the caller's)
};

class Editor {
public:
    // Loads the preset and its scene and builds the renderer. Needs `gi` held by this thread (its
    // context current); every GL object the editor makes lives there. Throws gi::Error for a bad
    // preset, scene or shader.
    Editor(const EditorOptions& options, GIThread& gi);
    ~Editor();  // waits for the GI frame in flight
    Editor(const Editor&) = delete;
    Editor& operator=(const Editor&) = delete;

    // One UI frame (width x height, the window's framebuffer), called with the window's context
    // current and left so: camera input and the panels; when the GI thread is idle, the finished
    // frame is taken, the viewport composed (compositeTexture) and the next frame started if the
    // settings, camera, scene or size changed. `dt` is the previous frame's duration in seconds,
    // `workMs` its time less any wait for input (what the Stats panel shows).
    void frame(int width, int height, float dt, float workMs);
    // The window's background as last composed (the GI image in the viewport, a fill view or the
    // reference over it), made in the GI context and finished: the caller copies it into the back
    // buffer (Window::drawBackground) before the panels are drawn. Its size lags a resize until
    // the GI thread is next idle.
    const gl::Texture& composite() const { return mComposite; }

    // The window title: the preset file, starred when it has unsaved changes.
    std::string title() const;

    // The Reference panel's job has finished its samples and its metrics are of the final image
    // (or it failed): what a screenshot with a reference waits for.
    bool referenceSettled() const { return mReference.settled(); }
    std::string referenceError() const { return mReference.error(); }
    std::string referenceSummary() const { return mReference.summary(); }

    // One scripted action, through the same functions the panels and shortcuts call:
    //   set KEY=VALUE | drag KEY=VALUE | undo | redo | reset KEY | reset-section NAME | reset-all | save | save-as PATH |
    //   open PATH | pause | resume | wait | resize WIDTHxHEIGHT | bookmark NAME | goto NAME | camera N |
    //   screenshot PATH (PATH-window.png and PATH-viewport.png) | help | hold (A, once the GI is up to date) |
    //   compare live|a|split | diff-file PATH | wait-reference (until the Reference panel's job is done) |
    //   section NAME open|closed (NAME/developer: a section's developer node)
    // (drag: the value set mid-drag; the drag lasts until the next other action, so the GI previews until then)
    // The editor runs the script one action per frame, each once the GI has caught up (giCaughtUp).
    // Throws gi::Error for an unknown action.
    void runAction(const std::string& action);
    bool scriptDone() const { return mScriptNext >= mScript.size(); }
    // The GI frame this UI frame took from the GI thread, if one finished: the renderer runs only
    // when what it would draw has changed (settings, camera, scene, shaders, size), at
    // 1/previewDivisor of the size while a drag or a camera flight is under way, and not at all
    // while paused.
    struct GIFrame {
        float ms = 0.0f;  // wall time on the GI thread, until its GL work had finished
        int width = 0, height = 0;
        uint64_t startUIFrame = 0;  // the UI frame (counted from 1) that started it
    };
    std::optional<GIFrame> renderedFrame() const { return mRendered; }
    // Pauses or resumes the GI work (the last image stays).
    void setPaused(bool paused) { mPaused = paused; }
    // Writes the layout to EditorOptions::layoutFile (atomically); nothing when there is none.
    // Throws gi::Error when it cannot be written.
    void saveLayout() const;
    // F12 (or the Stats panel's button, or the script's screenshot action) asks for the window and
    // the viewport as PNGs: the caller reads the back buffer before and after the panels are drawn
    // and hands the pixels to writeScreenshot.
    std::optional<std::filesystem::path> screenshotRequest() const { return mScreenshotRequest; }
    ViewportRect viewport() const { return mViewport; }
    // Writes PATH-window.png (the whole window) and PATH-viewport.png (the scene between the columns,
    // without the panels); `scene` is read before the panels were drawn, `window` after.
    void writeScreenshot(const std::vector<uint8_t>& scene, const std::vector<uint8_t>& window, int width, int height);
    // The frame that is shown is of the current settings at full size and nothing is rendering:
    // what a screenshot waits for.
    bool giSettled() const { return mPaused || (!mGI.busy() && mRenderedKey == mLiveKey); }
    // The GI shows what the current interaction asks for (the preview during a drag, else the full
    // frame) and nothing is rendering: a script's next action waits for this, as a user looks at
    // the picture before the next change.
    bool giCaughtUp() const { return !mGI.busy() && (mPaused || mRenderedKey == mWantKey || mWantKey == mFailedKey); }
    // What a test reads back: title, file, dirty, the errors and status shown, the path field, the undo history
    // (labels and position) and the preset as it would be saved.
    json state() const;
private:
    Preset mPreset;
    Preset mGoodPreset;                 // the last preset that rendered; restored when a frame fails
    std::filesystem::path mPresetPath;  // the file Save writes; empty for an unsaved preset
    std::string mPathField;             // the Presets panel's path (Open, Save As)
    std::filesystem::path mConfirmOverwrite;  // Save As target the user was warned exists
    bool mDirty = false;                // the preset differs from mDiskPreset
    Preset mDiskPreset;                 // the preset as the file holds it (as opened or last saved)
    PresetHistory mHistory;             // undo/redo: one state per completed edit
    bool mEditPending = false;          // an edit is under way: recorded once no widget is active
    std::vector<std::string> mScript;
    size_t mScriptNext = 0;
    uint64_t mFrames = 0;
    // Previewers of the active passes (Renderer::previewers): which are shown (overlays over
    // the viewport, images in windows), by name; all start hidden, each with its own switch.
    std::map<std::string, bool> mShowPreviewer;
    float mOverlayScale = 1.0f;     // glyph size relative to the previewers' default
    glm::vec2 mPickUV{0.5f};        // the focus pixel of the viewport, 0..1 from the bottom left
    bool mPickPending = true;       // read the G-buffer at mPickUV after this frame's render
    glm::ivec2 mFocusPixel{0};
    std::optional<SurfacePick> mFocus;  // the surface at the focus pixel, for overlays that point at one
    uint64_t mPickGeneration = 0;   // mSceneGeneration the focus was read in
    struct PreviewWindow {
        gl::Texture image;
        uint64_t generation = ~uint64_t(0);  // mLiveGeneration the image was made in
    };
    std::map<std::string, PreviewWindow> mPreviewWindows;
    // What the panels show of the renderer while the GI thread holds it (taken on each UI frame that
    // holds the GI context): the previewers' names, the overlays' lines, the stats.
    std::vector<Previewer> mPreviewers;  // their functions are called only while the context is held
    std::vector<GlyphLine> mOverlayLines;
    glm::mat4 mOverlayViewProj{1.0f};
    std::vector<PassStats> mPassStats;
    // What each pass reports of the last frame (LPV's fitted grid), shown in its section.
    std::vector<std::pair<std::string, PassReport>> mPassReports;
    size_t mMemoryBytes = 0;
    // The passes' own panels (ui/pass_panels.cpp), by section.
    std::vector<std::pair<std::string_view, std::unique_ptr<PassPanel>>> mPanels;
    std::string mLoadedScene;           // header.scene that mScene came from
    Scene mScene;
    Renderer mRenderer;
    FlyCamera mFlyCamera;
    BufferPreviewer mPreviewer;
    ReferencePanel mReference;
    GIThread& mGI;
    bool mLive = false;  // this UI frame holds the GI context: the renderer and GL may be used
    // A GI frame's outcome, written by the GI thread, read by the UI thread once it holds the context again.
    struct GIResult {
        std::string key;    // liveKey() of what it rendered
        Preset preset;      // the settings it rendered
        GIFrame frame;
        std::string error;  // non-empty: it threw, and the image is the previous one
    };
    std::optional<GIResult> mResult;
    std::string mWantKey;               // liveKey() of what this frame asks the GI for (preview or full)
    std::string mFailedKey;             // the last frame that threw: not tried again as such
    gl::Texture mComposite;             // the window's background (composite())
    uint64_t mOutputGeneration = 0;     // grows with each GI frame taken (and each failed one)
    std::string mComposedKey;           // what mComposite shows, when nothing is drawn over the GI image
    gl::Framebuffer mCompositeFBO;
    void collectResult();               // the finished GI frame, if one waits (context held)
    void submitIfNeeded();              // starts the next GI frame, or gives the context back
    uint64_t mSceneGeneration = 0;  // grows with each installed scene
    uint64_t mLiveGeneration = 0;   // grows with each change that can alter the live image
    gl::Framebuffer mOutputFBO;         // wraps the renderer's output for the blit into the composite
    int mWidth, mHeight;
    float mFrameMs = 0.0f;
    float mShownFrameMs = 0.0f;  // mFrameMs as Stats shows it, taken twice a second
    std::chrono::steady_clock::time_point mFrameMsShownAt;
    float mRenderMs = 0.0f;             // the last GI frame's renderer call
    glm::ivec2 mRenderSize{0};          // and its size
    std::optional<GIFrame> mRendered;   // this UI frame's GI frame
    std::string mRenderedKey;           // liveKey() at full size, or with the preview divisor, of the image shown
    std::string mLiveKey;               // liveKey() of this frame at full size
    bool mPaused = false;               // no GI work; the last image stays
    bool mInteracting = false;          // a drag, a typed value or a camera flight is under way
    bool mScriptDrag = false;           // a script's drag is under way (from a drag action to the next other action)
    float mLeftWidth = kLeftWidth;      // the docked columns' widths (dragged by their inner edges)
    float mRightWidth = kRightWidth;
    ViewportRect mViewport;             // the window between them, where the scene is drawn
    float mRightColumnX = 0.0f;         // where the right column's windows stand (read back from ImGui)
    std::function<void(int, int)> mResizeWindow;
    std::filesystem::path mLayoutFile;
    void loadLayout();  // a missing file is no error; a broken one is reported and ignored
    int mPreviewDivisor = 4;            // the preview's width and height are the viewport's / this (1: no preview)
    std::string mGLRenderer;
    std::vector<std::string> mSceneFiles;  // glTF files in the asset search path, as search-path names
    std::vector<std::filesystem::path> mPresetFiles;

    std::string mFrameError, mSceneError, mPresetError, mPresetStatus, mShaderLog;
    bool mOpenLights = false;  // --lights-panel: open the lights section and every light once
    int mScrollToLights = 0;   // frames left to keep the lights section at the top (the layout settles)

    void apply(uint8_t cost);
    // Records the preset in the history once an edit is complete (no widget active, the camera
    // still), and updates mDirty.
    void recordEdit(bool cameraMoved);
    // Undo, redo and history jumps: the preset becomes `p` (its scene reloaded if it differs,
    // keeping p's camera and lights).
    void restore(const Preset& p);
    void undo();
    void redo();
    void resetKey(const std::string& key);        // one setting to its default
    void resetSection(const std::string& name);   // every key of a section
    void resetAll();                              // every section but the camera; scene, technique and lights stay
    // A successful load or save: the file's state, a fresh history, no stale errors.
    void settle(const std::string& label);
    void historyPanel();
    // Cameras: the current view saved as a named bookmark in the preset, a jump to one, and a
    // jump to one of the file's cameras (each an undoable edit).
    void addBookmark(const std::string& name);
    void jumpTo(const CameraBookmark& view);
    void takeFileCamera(size_t index);
    std::string mBookmarkName;
    std::optional<CameraSettings> mFramedView;  // "Frame scene"'s view, traced at its first use
    std::optional<std::filesystem::path> mScreenshotRequest;  // the PNGs' path without "-window.png"
    bool mShowHelp = false;     // the help window: every shortcut and mouse action
    void helpWindow();
    void requestScreenshot();  // PNGs named after the time, in the current folder  // the name field beside "Add view"
    // Loads p's scene, checks it against the memory budget and uploads it; throws gi::Error and
    // then leaves the current scene in place. `resetView` takes the scene's own camera and lights.
    void installScene(Preset& p, bool resetView);
    // The viewport's size and the frame's key; with the context held, the composite: the GI image,
    // a fill view, a pass's view and the reference, and the reference job's update.
    void renderViewport(bool interacting);
    // What the image depends on: the preset, the scene and the live generation (shader reloads,
    // edits), and the size.
    std::string liveKey(int width, int height) const;
    void openPreset(const std::filesystem::path& path);
    void savePresetAs(const std::filesystem::path& path);
    void scanFiles();

    void drawPanels();
    // A section of the left column (a collapsing header), open as the user's layout last had it,
    // else as `defaultOpen` says; `forceOpen` opens it at the start whatever the layout says.
    bool section(const char* name, bool defaultOpen, bool forceOpen = false);
    std::map<std::string, bool> mSectionOpen;  // the left column's sections, open or closed (saved in the layout)
    std::map<std::string, bool> mSectionForce;  // the script's `section` verb, applied at the next draw
    std::vector<std::string> mFieldsShown;      // full keys of the settings the last frame drew
    json openSections() const {
        json open = json::array();
        for (const auto& [name, isOpen] : mSectionOpen)
            if (isOpen) open.push_back(name);
        return open;
    }
    uint8_t scenePanel();
    void presetsPanel();
    uint8_t cameraTools();  // beside the generated camera fields
    uint8_t lightsPanel();
    void statsPanel();
    // A/B comparison (ui/panels/compare_panel.cpp): A holds an image of the GI with its settings,
    // its GI ms and its SSIM against the reference then; the viewport shows the live image (B), A,
    // or a split (A left of the line, B right of it); the settings that differ are listed, and so
    // are those between the editor and any preset file.
    struct Snapshot {
        gl::Texture image;  // the renderer's output when held (GI context)
        Preset preset;
        float ms = 0.0f;
        glm::ivec2 size{0};
        std::optional<double> ssim;  // against the reference at the time
    };
    enum class CompareView { Live, A, Split };
    std::optional<Snapshot> mSnapshotA;
    CompareView mCompareView = CompareView::Live;
    float mCompareSplit = 0.5f;
    bool mHoldRequested = false;    // A is taken once the GI shows the current settings
    gl::Framebuffer mSnapshotFBO;   // wraps A's image for the blit
    std::string mDiffPath;          // the preset file the editor's settings are compared with
    std::optional<std::vector<PresetChange>> mFileDiff;
    std::string mDiffError;
    void comparePanel();
    // Auto-tune (ui/panels/tune_panel.cpp, ui/tune_job.h): the search runs in gi-render processes
    // on a worker thread; the panel shows its progress, best image and path, and applies the winner.
    std::unique_ptr<TuneJob> mTune;
    TuneRequest mTuneRequest;
    TuneSnapshot mTuneSnapshot;        // the panel's copy, taken each frame it is drawn
    gl::Texture mTuneImage;            // the best render's image (GI context)
    std::filesystem::path mTuneImagePath;
    std::string mTuneError;
    void tunePanel();
    void startTune();                  // throws gi::Error for a technique with nothing to tune
    void applyTune();                  // the best within the budget, as an undoable edit
    json tuneState() const;
    // The matrix cells compared in the compare section (ui/panels/matrix_panel.cpp).
    std::string mMatrixDir;
    std::vector<matrix::CellResult> mMatrixCells;
    std::array<size_t, 2> mMatrixPick{0, 0};
    std::array<gl::Texture, 2> mMatrixImages;       // GI context
    std::array<std::string, 2> mMatrixShown;        // the image files they hold
    int mMatrixView = 0;                            // 0: side by side, 1: split
    float mMatrixSplit = 0.5f;
    std::string mMatrixError;
    void loadMatrix(const std::filesystem::path& dir);  // throws gi::Error naming the folder
    void matrixComparePanel();
    json matrixState() const;
    void holdSnapshot();            // context held, the image up to date
    bool comparing() const { return mSnapshotA && mCompareView != CompareView::Live; }
    // F and the Flip button: A, or back to the live image.
    void flipCompare() { mCompareView = mCompareView == CompareView::A ? CompareView::Live : CompareView::A; }
    void drawComparison(const ViewportRect& target, bool drawImages);  // A over the composite, the labels
    void diffWithFile(const std::filesystem::path& path);
    json compareState() const;  // for state(): whether A is held, the view, the keys A -> B and file -> editor
    PanelContext panelContext();
    PassPanel* panel(std::string_view section) const;
    // Under each pass's section: its notes and the switches of its previewers.
    void passExtras(std::string_view section, const FrameSettings& fs, const std::vector<Previewer>& previewers);
    void readFocus();
    void drawOverlays(const FrameSettings& fs, const std::vector<Previewer>& previewers);
    void previewerWindows(const FrameSettings& fs, const std::vector<Previewer>& previewers);
};

}  // namespace gi::ui
