// gi-editor: tune a GI Workbench preset live in a window (GLFW + Dear ImGui). With --screenshot
// it renders a few frames, writes the whole window with its panels to a PNG and exits, so tests
// can run it under Xvfb. With --reference the screenshot waits until the path-traced reference
// has all its samples and its scores, so the picture does not depend on the machine's speed.
#include "gi/gl/debug.h"
#include "gi/render/image_io.h"
#include "gi/util/paths.h"
#include "ui/editor.h"
#include "ui/texture_bridge.h"
#include "ui/window.h"

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdlib>
#include <sstream>
#include <cstdio>
#include <thread>

namespace {

int run(int argc, char** argv) {
    CLI::App app{"gi-editor: tune GI Workbench presets live"};
    gi::ui::EditorOptions options;
    std::string preset, screenshot;
    int frames = 0;
    double referenceTimeout = 120.0;
    app.add_option("--preset", preset, "Preset (.json) or glTF file; default: presets/default.json");
    app.add_option("--frames", frames, "Render this many frames, then exit (default with --screenshot: 3)")->check(CLI::Range(1, 100000));
    app.add_option("--screenshot", screenshot, "After the last frame, write the whole window to this PNG and exit");
    app.add_option("--width", options.width, "Window width in pixels")->check(CLI::Range(64, 16384));
    app.add_option("--height", options.height, "Window height in pixels")->check(CLI::Range(64, 16384));
    app.add_option("--view", options.view, "Debug view the buffer previewer shows first (e.g. depth, shadow0)");
    app.add_flag("--fill-view", options.fillView, "The buffer previewer's view fills the viewport from the start");
    app.add_option("--voxel-view", options.voxelView, "VCT: show the voxels in the viewport, coloured by this")
        ->check(CLI::IsMember({"albedo", "normal", "radiance"}));
    app.add_flag("--voxel-window", options.voxelWindow, "VCT: with --voxel-view, show it in a window instead of the viewport");
    app.add_flag("--phase-plot", options.phasePlot,
                 "Open the Phase function window (the volumetric phase function as a polar plot) from the start (it is off by "
                 "default, like every overlay)");
    app.add_flag("--mips-panel", options.roughnessMips,
                 "Open the environment settings' Roughness mips panel (the prefiltered chain and a preview of one mip) from the start");
    app.add_flag("--lights-panel", options.lightsPanel,
                 "Open the lights section with every light expanded (an area light's placed fields read-only) from the start");
    app.add_option("--previewer", options.previewers,
                   "Show this previewer from the start (a name gi-render --views writes, e.g. environment.mips, or an overlay: "
                   "vct.cones, lpv.cascades); repeatable");
    app.add_option("--reference", options.reference, "Start the Reference panel in this view")
        ->check(CLI::IsMember({"live", "reference", "toggle", "split", "heat"}));
    app.add_option("--reference-spp", options.referenceSPP, "Samples per pixel of the reference (overrides reference.spp)")
        ->check(CLI::Range(1, 1 << 16));
    app.add_option("--reference-timeout", referenceTimeout,
                   "With --screenshot and --reference: seconds to wait for the reference before failing; 0: do not wait")
        ->check(CLI::Range(0.0, 86400.0));
    std::string scriptFile, uiStats, layout;
    app.add_option("--layout", layout,
                   "The user's layout file (column widths, previewers shown, buffer view, drag preview), read at start and "
                   "written at exit; default for an interactive run: $XDG_CONFIG_HOME (or ~/.config)/gi-workbench/layout.json; "
                   "runs with --frames, --seconds, --script or --screenshot use none unless given; 'none': no file");
    int frameDelayMs = 0;
    double seconds = 0.0;
    app.add_option("--seconds", seconds, "Run this many seconds, then exit (with --script: at least until its last action)")
        ->check(CLI::Range(0.0, 86400.0));
    app.add_option("--frame-delay-ms", frameDelayMs,
                   "Sleep this long in every frame, as slow GI would take it (tests of input at low frame rates)")
        ->check(CLI::Range(0, 60000));
    app.add_option("--script", scriptFile,
                   "Run the actions in this file, one per line and one per frame (set KEY=VALUE, undo, redo, reset KEY, "
                   "reset-section NAME, reset-all, save, save-as PATH, open PATH, drag KEY=VALUE (mid-drag: the next frame previews), "
                   "pause, resume, wait; # comments), then exit")
        ->check(CLI::ExistingFile);
    app.add_option("--ui-stats", uiStats,
                   "At exit, write this JSON file: uiFrameMs (each UI frame's work, less any wait for input), giFrameMs (each GI frame the renderer made), giFrames "
                   "(each GI frame's ms, width, height, the UI frame that started it, startUIFrame, and the one that took it, uiFrame) and "
                   "editor (title, dirty, errors, status, undo history, the preset as it would be saved)");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    if (!scriptFile.empty()) {
        std::istringstream lines(gi::readTextFile(scriptFile, size_t(1) << 20));
        for (std::string line; std::getline(lines, line);) {
            while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
            if (!line.empty() && line[0] != '#') options.script.push_back(line);
        }
    }
    options.preset = preset;
    if (!screenshot.empty() && frames == 0 && scriptFile.empty() && seconds == 0.0) frames = 3;
    const bool testRun = frames > 0 || !scriptFile.empty() || seconds > 0.0 || !screenshot.empty();
    if (layout.empty() && !testRun) {
        const char* config = std::getenv("XDG_CONFIG_HOME");
        const char* home = std::getenv("HOME");
        if (config && *config) options.layoutFile = std::filesystem::path(config) / "gi-workbench" / "layout.json";
        else if (home && *home) options.layoutFile = std::filesystem::path(home) / ".config" / "gi-workbench" / "layout.json";
    } else if (layout != "none") {
        options.layoutFile = layout;
    }

    gi::ui::Window window(options.width, options.height, "GI Workbench");
    options.resizeWindow = [&window](int w, int h) { window.setSize(w, h); };
    // The GI renders on its own thread, in a context of its own (ui/gi_thread.h); the editor is
    // made in that context, and each UI frame hands it back and forth.
    gi::ui::GIThread gi([&window] { window.createGIContext(); }, [&window](bool current) { window.bindGI(current); },
                        [&window] { window.bindUI(); }, &gi::ui::Window::wake);
    gi.acquire();
    gi::ui::Editor editor(options, gi);
    gi.release();
    std::string title;
    const bool waitForReference = !screenshot.empty() && !options.reference.empty() && referenceTimeout > 0.0;
    std::chrono::steady_clock::time_point waitStart;
    bool timedOut = false, waitingForReference = false;
    auto last = std::chrono::steady_clock::now();
    double waited = 0.0;  // seconds the last frame waited for input (beginFrame)
    std::vector<float> uiFrameMs, giFrameMs;
    std::vector<bool> uiFrameDrawn;  // whether each UI frame was drawn and presented
    bool drawn = true;
    gi::json giFrames = gi::json::array();
    const auto start = std::chrono::steady_clock::now();
    std::chrono::steady_clock::time_point settleStart;  // when the end began to wait for the GI to catch up
    bool settling = false;
    int scriptEnd = 0;  // with a script and no --frames: the frame after the last action
    for (int frame = 1; !window.shouldClose(); ++frame) {
        auto now = std::chrono::steady_clock::now();
        float dt = std::chrono::duration<float>(now - last).count();
        last = now;
        // A UI frame's time is its work: not the time it waited for input while the GI rendered.
        const float workMs = std::max(dt - float(waited), 0.0f) * 1000.0f;
        if (frame > 1) {
            uiFrameMs.push_back(workMs);
            uiFrameDrawn.push_back(drawn);
        }
        if (!scriptFile.empty() && frames == 0 && scriptEnd == 0 && editor.scriptDone()) scriptEnd = frame + 1;

        // While the GI thread renders, or the last frame showed nothing new, and nothing happens,
        // the UI waits for input (at most 0.1 s, or until the GI frame is done), so the GI gets
        // the cores and an idle editor does not spin.
        waited = window.beginFrame(gi.busy() || !drawn ? 0.1 : 0.0);
        int width, height;
        window.framebufferSize(width, height);
        editor.frame(width, height, dt, workMs);
        if (auto gi = editor.renderedFrame()) {
            giFrameMs.push_back(gi->ms);
            giFrames.push_back({{"ms", gi->ms}, {"width", gi->width}, {"height", gi->height}, {"uiFrame", frame}, {"startUIFrame", gi->startUIFrame}});
        }
        if (frameDelayMs > 0) std::this_thread::sleep_for(std::chrono::milliseconds(frameDelayMs));
        bool done = (frames > 0 && frame >= frames) || (scriptEnd > 0 && frame >= scriptEnd && seconds == 0.0);
        if (seconds > 0.0 && std::chrono::duration<double>(now - start).count() >= seconds && (scriptFile.empty() || scriptEnd > 0))
            done = true;
        // The last composed image under the panels (made in the GI context, copied across by the
        // bridge). A frame that shows nothing new is not drawn or presented (its time is then the
        // editor's work alone); a screenshot's frames always are.
        int backgroundWidth = 0, backgroundHeight = 0;
        const unsigned background = window.bridge().windowTexture(editor.composite(), backgroundWidth, backgroundHeight);
        const bool changed = window.finishUI(background, backgroundWidth, backgroundHeight);
        drawn = changed || editor.screenshotRequest() || (done && !screenshot.empty());
        if (drawn) {
            window.drawBackground(background, backgroundWidth, backgroundHeight);
            // A screenshot the editor asked for: the scene before the panels are drawn, then the window.
            std::vector<uint8_t> scene;
            if (editor.screenshotRequest()) scene = window.readBackBuffer(width, height);
            window.renderUI();
            if (editor.screenshotRequest()) editor.writeScreenshot(scene, window.readBackBuffer(width, height), width, height);
        }
        // A screenshot shows the full frame of the final settings, not a drag's preview: the UI
        // goes on, at a gentle pace, until the GI thread has it (for at most kSettleSeconds).
        constexpr double kSettleSeconds = 600.0;
        if (done && !screenshot.empty() && !editor.giSettled()) {
            if (!settling) settleStart = std::chrono::steady_clock::now();
            settling = true;
            if (std::chrono::duration<double>(std::chrono::steady_clock::now() - settleStart).count() < kSettleSeconds) {
                window.swap();
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
                waited += 0.02;  // a pause of the run's, not UI work
                continue;
            }
            std::fprintf(stderr, "gi-editor: the GI did not finish within %.0f s; the screenshot shows what there is\n", kSettleSeconds);
        }
        if (done && waitForReference && !editor.referenceSettled()) {
            if (!waitingForReference) waitStart = std::chrono::steady_clock::now();
            waitingForReference = true;
            double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - waitStart).count();
            timedOut = waited > referenceTimeout;
            // Frames go on, slowly, so the tracer gets the cores llvmpipe would take.
            if (!timedOut) {
                window.swap();
                std::this_thread::sleep_for(std::chrono::milliseconds(100));
                waited += 0.1;
                continue;
            }
        }
        if (done && !screenshot.empty()) {
            std::vector<uint8_t> pixels = window.readBackBuffer(width, height);
            gi::writePNG(screenshot, width, height, pixels);
            std::printf("%s\n", screenshot.c_str());
            if (!options.reference.empty()) std::printf("%s\n", editor.referenceSummary().c_str());
        }
        if (drawn) window.swap();
        if (done) break;
        if (editor.title() != title) window.setTitle(title = editor.title());
    }
    try {
        editor.saveLayout();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "gi-editor: the layout was not saved: %s\n", e.what());
    }
    if (!uiStats.empty()) {
        gi::json stats = {{"uiFrameMs", uiFrameMs}, {"uiFrameDrawn", uiFrameDrawn}, {"giFrameMs", giFrameMs}, {"giFrames", giFrames}, {"editor", editor.state()}};
        gi::writeFileAtomic(uiStats, stats.dump(2) + "\n");
    }
    if (timedOut)
        throw gi::Error("the reference did not finish within " + std::to_string(int(referenceTimeout)) +
                        " s (screenshot written anyway)");
    if (waitForReference && !editor.referenceError().empty()) throw gi::Error("reference: " + editor.referenceError());
    // Frame-limited runs are tests: a GL error fails them, as it fails gi-render.
    if (frames > 0 && gi::gl::debugErrorCount() > 0)
        throw gi::Error("OpenGL reported " + std::to_string(gi::gl::debugErrorCount()) + " errors (see above)");
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const gi::ui::NoDisplayError& e) {
        std::fprintf(stderr, "gi-editor: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "gi-editor: %s\n", e.what());
        return 1;
    }
}
