// gi-render: renders a preset (or a glTF file with its own cameras and lights) headless through
// EGL, and writes image.png, image.exr, stats.json and, with --views, every debug view (and the
// previewers' images: VCT voxels and cones, the phase plot, each prefiltered environment mip).
#include "gi/platform/egl_context.h"
#include "gi/preset/preset.h"
#include "gi/render/image_io.h"
#include "gi/render/renderer.h"
#include "gi/render/strokes.h"
#include "common/shared.h"
#include "gi/gl/debug.h"
#include "gi/metrics/metrics.h"
#include "gi/reference/framing.h"
#include "gi/reference/reference_cache.h"
#include "gi/util/error.h"
#include "gi/util/paths.h"
#include "gi/util/progress.h"
#include "gi/scene/camera.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <filesystem>
#include <iostream>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

void printSettings(bool asJson) {
    auto list = gi::listSettings();
    if (asJson) {
        gi::json arr = gi::json::array();
        for (auto& s : list) arr.push_back(gi::settingInfoToJson(s));
        std::cout << arr.dump(2) << "\n";
        return;
    }
    for (auto& s : list) {
        std::string range;
        if (!s.choices.empty()) {
            for (auto& c : s.choices) range += (range.empty() ? "" : "|") + c;
        } else if (std::isfinite(s.min) || std::isfinite(s.max)) {
            range = "[" + gi::detail::formatNumber(s.min) + ", " + gi::detail::formatNumber(s.max) + "]";
        }
        std::printf("%-26s %-6s %-22s default %-18s %s%s%s (change: %s%s)\n", s.key.c_str(), s.type.c_str(), range.c_str(),
                    s.defaultValue.dump().c_str(), s.description.c_str(), s.unit.empty() ? "" : ", ", s.unit.c_str(),
                    s.cost.c_str(), s.developer ? "; developer" : "");
    }
}

// Progress of long work on stderr, terminal or not: on a terminal one line redrawn in place,
// elsewhere (a log, a pipe, CI) a new line at most about once a second, and the last one.
// `quietIfShort`: say nothing about work that is over within a second (a default prefilter).
gi::ProgressSink progressPrinter(bool quietIfShort) {
    struct State {
        bool tty = isatty(fileno(stderr));
        bool printed = false;
        double lastPrint = -1e9;
    };
    auto state = std::make_shared<State>();
    return [state, quietIfShort](const gi::ProgressUpdate& u) {
        bool last = u.done >= u.total;
        bool due = u.seconds - state->lastPrint >= 1.0 && (!quietIfShort || u.seconds >= 1.0);
        if (last) due = state->printed || !quietIfShort || u.seconds >= 1.0;
        if (!due) return;
        std::string line = "gi-render: " + gi::formatProgress(u);
        if (state->tty)
            std::fprintf(stderr, "\r%-100s%s", line.c_str(), last ? "\n" : "");
        else
            std::fprintf(stderr, "%s\n", line.c_str());
        std::fflush(stderr);
        state->printed = !last;
        state->lastPrint = u.seconds;
    };
}

// The cached reference for this frame; a fresh one reports its progress after each pass.
gi::CachedReference referenceFor(const gi::Scene& scene, const gi::FrameSettings& frame, const gi::ReferenceSettings& rs,
                                 const char* what) {
    gi::ProgressSink print = progressPrinter(false);
    auto start = std::chrono::steady_clock::now();
    return gi::cachedReference(scene, frame, rs, [&](int done, int total) {
        gi::ProgressUpdate u;
        u.task = what;
        u.done = done;
        u.total = total;
        u.unit = "spp";
        u.fraction = double(done) / double(std::max(total, 1));
        u.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        print(u);
        return true;
    });
}

gi::json referenceStats(const gi::CachedReference& ref, const gi::ReferenceSettings& rs) {
    gi::json j = gi::toJson(rs);  // the settings as the table writes them, then what happened
    j.update({{"fromCache", ref.fromCache},
            {"seconds", ref.seconds},
            {"rays", ref.rays},
            {"raysPerSecond", ref.seconds > 0 ? double(ref.rays) / ref.seconds : 0.0},
              {"cacheFile", ref.file.string()}});
    return j;
}

// The frame's lights as stats.json lists them: each light's settings, and for an area light its
// surface (name, triangles, area, power).
gi::json lightsJson(const gi::FrameSettings& frame, const gi::Scene& scene) {
    gi::json lights = gi::json::array();
    for (const gi::LightSettings& l : frame.lights) {
        gi::json j = gi::toJson(l);
        if (l.type == gi::LightType::Area) {
            const gi::Emitter& e = scene.emitters[size_t(l.emitter)];
            j["surface"] = {{"name", e.name},
                            {"triangles", e.triangles.size()},
                            {"area", e.area},
                            {"power", {e.power.x, e.power.y, e.power.z}}};
        }
        lights.push_back(j);
    }
    return lights;
}

int run(int argc, char** argv) {
    CLI::App app{"gi-render: render a GI Workbench preset or a glTF file headless"};
    std::string input, outDir;
    int width = 640, height = 360, frames = 1, camera = -1;
    std::vector<std::string> sets;
    bool views = false, list = false, listJson = false, reference = false, score = false;
    int spp = 0;
    app.add_option("input", input, "Preset (.json) or glTF file (.gltf, .glb); none: the built-in default preset");
    app.add_option("--out", outDir, "Output folder (created if missing)");
    app.add_option("--width", width, "Image width in pixels")->check(CLI::Range(1, 16384));
    app.add_option("--height", height, "Image height in pixels")->check(CLI::Range(1, 16384));
    app.add_option("--frames", frames, "Frames to render before writing (for temporal techniques)")->check(CLI::Range(1, 10000));
    app.add_option("--camera", camera, "Use the glTF file's camera N")->check(CLI::Range(0, 1023));
    app.add_option("--set", sets, "Override a setting: key=value (see --list-settings)");
    app.add_flag("--views", views, "Also write every debug view as DIR/views/NAME.png");
    app.add_flag("--reference", reference, "Also write the path-traced reference as DIR/reference.exr (cached)");
    app.add_option("--spp", spp, "Samples per pixel of the reference (reference.spp)")->check(CLI::Range(1, 1 << 16));
    app.add_flag("--score", score,
                 "Score the image against the cached reference: metrics in stats.json, maps beside the image");
    app.add_flag("--list-settings", list, "Print every settings key and exit");
    app.add_flag("--json", listJson, "With --list-settings: print a JSON list");
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        // One line, like every other error of the runner.
        std::fprintf(stderr, "gi-render: %s (see --help)\n", e.what());
        return 2;
    }
    if (list) {
        printSettings(listJson);
        return 0;
    }
    if (outDir.empty()) throw gi::Error("no output folder: give --out DIR");

    // No input: the built-in default preset, which needs no files.
    gi::Preset preset = input.empty() ? gi::builtinDefaultPreset() : gi::presetForInput(input, camera);
    if (input.empty()) input = "(built-in default)";
    for (const auto& s : sets) gi::applySetting(preset, s);
    if (spp > 0) preset.reference.spp = spp;

    gi::Scene scene = gi::loadScene(preset.header.scene, preset.folder, preset.render.memoryBudgetMB);
    if (std::string how = gi::frameCameraless(scene); !how.empty())
        std::fprintf(stderr, "gi-render: %s has no camera; viewed %s\n", scene.name.c_str(), how.c_str());
    for (const auto& w : scene.warnings) std::fprintf(stderr, "gi-render: warning: %s: %s\n", scene.name.c_str(), w.c_str());
    if (gi::usesDefaultSun(preset, scene))
        std::fprintf(stderr,
                     "gi-render: warning: %s has no lights, no emissive surfaces and the preset names none; a default sun is used\n",
                     scene.name.c_str());
    gi::FrameSettings frame = gi::frameSettings(preset, scene, width, height);
    for (const gi::PassInfo& info : gi::passRegistry())
        if (info.notes && gi::passActive(info, frame))
            if (std::string note = info.notes(frame); !note.empty()) std::fprintf(stderr, "gi-render: warning: %s\n", note.c_str());
    gi::Renderer::checkBudget(frame, scene);  // refuse before any GL allocation (memory, prefilter time)
    // The references this run traces (those not cached) must fit the time budget too.
    gi::ReferenceSettings indirectSettings = preset.reference;
    indirectSettings.mode = gi::ReferenceMode::Indirect;
    if (reference || score) {
        int fresh = !gi::referenceCached(scene, frame, preset.reference);
        if (score) fresh += !gi::referenceCached(scene, frame, indirectSettings);
        gi::checkReferenceTimeBudget(frame, preset.reference, fresh);
    }

    fs::create_directories(outDir);
    gi::EGLContextHeadless context;
    gi::Renderer renderer;
    renderer.setScene(scene);
    renderer.setProgressSink(progressPrinter(true));
    // Each frame's passes added up; the first frame also builds what later ones reuse (shader
    // variants, voxels), so the steady-state figure is the median of the others.
    std::vector<double> frameMs;
    for (int f = 0; f < frames; ++f) {
        renderer.render(frame);
        renderer.timer().resolve(true);
        double sum = 0.0;
        for (const auto& p : renderer.passStats()) sum += p.gpuMs;
        frameMs.push_back(sum);
    }
    std::vector<double> steady(frameMs.size() > 1 ? frameMs.begin() + 1 : frameMs.begin(), frameMs.end());
    std::sort(steady.begin(), steady.end());
    size_t mid = steady.size() / 2;
    double medianMs = steady.size() % 2 ? steady[mid] : 0.5 * (steady[mid - 1] + steady[mid]);
    if (gi::gl::debugErrorCount() > 0) throw gi::Error("OpenGL reported errors while rendering (see above)");

    fs::path out(outDir);
    gi::writePNG(out / "image.png", width, height, renderer.readLDR());
    gi::writeEXR(out / "image.exr", width, height, renderer.readHDR());

    gi::json passes = gi::json::array();
    double total = 0;
    for (const auto& p : renderer.passStats()) {
        passes.push_back({{"name", p.name}, {"gpuMs", p.gpuMs}, {"memoryBytes", p.memoryBytes}});
        if (p.countsDraws) {
            passes.back()["draws"] = p.draws;
            passes.back()["triangles"] = p.triangles;
        }
        total += p.gpuMs;
    }
    // Each volume the passes hold (name, format, bytes): the per-volume memory.
    gi::json volumes = gi::json::array();
    for (const auto& v : renderer.volumeMemory())
        volumes.push_back({{"name", v.name}, {"format", v.format}, {"bytes", v.bytes}});
    gi::json stats = {{"input", input},
                      {"width", width},
                      {"height", height},
                      {"frames", frames},
                      {"renderer", context.renderer()},
                      {"passes", passes},
                      {"gpuMsTotal", total},
                      {"frameMs", frameMs},
                      {"gpuMsMedian", medianMs},
                      {"memoryBytes", renderer.memoryBytes()},
                      {"volumes", volumes},
                      {"scene", {{"name", scene.name}, {"triangles", scene.triangleCount()}, {"warnings", scene.warnings}}},
                      {"lights", lightsJson(frame, scene)},
                      {"settings", gi::presetToJson(preset)}};
    // What each pass reports beyond time and memory (the environment's prefilter, mip by mip),
    // under its name.
    for (const auto& [name, report] : renderer.passReports(frame)) {
        gi::json r = gi::json::object();
        for (const auto& [key, text] : report.texts) r[key] = text;
        for (const auto& [key, value] : report.numbers) r[key] = value;
        if (!report.tableName.empty()) {
            gi::json rows = gi::json::array();
            for (const std::vector<double>& row : report.rows) {
                gi::json entry = gi::json::object();
                for (size_t c = 0; c < report.columns.size() && c < row.size(); ++c) entry[report.columns[c]] = row[c];
                rows.push_back(entry);
            }
            r[report.tableName] = rows;
        }
        stats[name] = r;
    }
    if (views) {
        fs::create_directories(out / "views");
        for (const auto& v : renderer.debugViews()) {
            int w = v.width, h = v.height;
            // Keep view images modest: the longest side at most 1024.
            float scale = std::min(1.0f, 1024.0f / float(std::max(w, h)));
            w = std::max(1, int(float(w) * scale));
            h = std::max(1, int(float(h) * scale));
            gi::writePNG(out / "views" / (v.name + ".png"), w, h, renderer.renderViewImage(v, w, h));
        }
        // Each active pass's previewers: pictures of their own, and overlays drawn over the image
        // (at the centre pixel where they need a surface to point at).
        gi::PreviewContext preview = renderer.previewContext(frame, glm::ivec2(width / 2, height / 2));
        for (const gi::Previewer& p : renderer.previewers(frame)) {
            if (p.image) {
                gi::PreviewImage img = p.image(preview);
                if (img.width > 0) gi::writePNG(out / "views" / (p.name + ".png"), img.width, img.height, img.rgba);
            } else if (p.overlay) {
                std::vector<gi::GlyphLine> lines = p.overlay(preview);
                if (lines.empty()) continue;
                std::vector<uint8_t> image = renderer.readLDR();
                gi::drawGlyphLines(image, width, height, preview.viewProj, lines);
                gi::writePNG(out / "views" / (p.name + ".png"), width, height, image);
            }
        }
    }
    if (reference || score) {
        gi::ImageRGB image = gi::imageFromGL(width, height, renderer.readHDR());
        gi::ImageRGB indirect = gi::imageFromGL(width, height, renderer.readIndirectRadiance());
        gi::CachedReference full = referenceFor(scene, frame, preset.reference, "reference");
        gi::writeEXR(out / "reference.exr", full.image);
        gi::writePNGTopFirst(out / "reference.png", width, height, gi::encodeSRGB8(gi::toneMapped(full.image, frame.toneMap)));
        stats["reference"] = referenceStats(full, preset.reference);
        if (score) {
            gi::CachedReference indirectRef = referenceFor(scene, frame, indirectSettings, "indirect reference");
            stats["referenceIndirect"] = referenceStats(indirectRef, indirectSettings);
            gi::RenderScoreInputs in{&image, &full.image, &indirect, &indirectRef.image, frame.toneMap};
            gi::Metrics m = gi::scoreRender(in);
            stats["metrics"] = gi::metricsToJson(m);
            gi::writeRenderScoreMaps(out, in);
            std::printf("  score: ssim %.4f  score %.3g  rmse %.4f  psnr %.2f dB  leak %.4f (energy %.4f)  brightness %.3f\n",
                        m.ssim, m.score, m.rmse, m.psnr, m.leakFraction, m.leakEnergy, m.brightness);
        }
    }
    gi::writeFileAtomic(out / "stats.json", stats.dump(2) + "\n");
    std::printf("gi-render: %s -> %s (%dx%d, %.1f ms GPU)\n", input.c_str(), (out / "image.png").c_str(), width, height, total);
    for (const auto& p : renderer.passStats()) std::printf("  %-10s %8.2f ms %8.1f MiB\n", p.name.c_str(), p.gpuMs, double(p.memoryBytes) / (1 << 20));
    return 0;
}

}  // namespace

int main(int argc, char** argv) { return gi::reportErrors("gi-render", [&] { return run(argc, argv); }); }
