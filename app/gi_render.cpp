// gi-render: renders a preset (or a glTF file with its own cameras and lights) headless through
// EGL, and writes image.png, image.exr, stats.json and, with --views, every debug view (and the
// previewers' images: VCT voxels and cones, the phase plot, each prefiltered environment mip).
#include "gi/platform/egl_context.h"
#include "gi/preset/preset.h"
#include "gi/render/image_io.h"
#include "gi/render/renderer.h"
#include "gi/render/strokes.h"
#include "common/shared.h"
#include "gi/envmap/environment.h"
#include "gi/gl/debug.h"
#include "gi/lpv/lpv.h"
#include "gi/metrics/metrics.h"
#include "gi/reference/reference_cache.h"
#include "gi/util/error.h"
#include "gi/util/paths.h"
#include "gi/util/progress.h"
#include "gi/scene/camera.h"
#include "gi/vct/vct_views.h"
#include "gi/volumetric/phase_plot.h"

#include <CLI/CLI.hpp>

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
        std::printf("%-26s %-6s %-22s default %-18s %s%s%s (change: %s)\n", s.key.c_str(), s.type.c_str(), range.c_str(),
                    s.defaultValue.dump().c_str(), s.description.c_str(), s.unit.empty() ? "" : ", ", s.unit.c_str(),
                    s.cost.c_str());
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

// `text` (digits and '.') as seven-segment strokes, its bottom-left corner at (x, y), y up.
std::vector<gi::Stroke> segmentText(const std::string& text, float x, float y, float height, const glm::vec4& colour) {
    // Segments a (top) b c d e f g (middle), and which of them each digit lights.
    static const char* lit[10] = {"abcdef", "bc", "abged", "abgcd", "fgbc", "afgcd", "afgedc", "abc", "abcdefg", "abcdfg"};
    const float w = 0.5f * height, m = 0.5f * height, thickness = std::max(1.5f, height / 7.0f);
    std::vector<gi::Stroke> strokes;
    for (char ch : text) {
        if (ch == '.') {
            strokes.push_back({{x + 0.5f * thickness, y}, {x + 0.5f * thickness, y}, colour, thickness * 1.2f});
            x += 2.0f * thickness;
            continue;
        }
        if (ch < '0' || ch > '9') {
            x += w + 2.0f * thickness;
            continue;
        }
        for (const char* seg = lit[ch - '0']; *seg; ++seg) {
            glm::vec2 a, b;
            switch (*seg) {
                case 'a': a = {0, height}, b = {w, height}; break;
                case 'b': a = {w, height}, b = {w, m}; break;
                case 'c': a = {w, m}, b = {w, 0}; break;
                case 'd': a = {0, 0}, b = {w, 0}; break;
                case 'e': a = {0, 0}, b = {0, m}; break;
                case 'f': a = {0, m}, b = {0, height}; break;
                default: a = {0, m}, b = {w, m}; break;
            }
            strokes.push_back({glm::vec2(x, y) + a, glm::vec2(x, y) + b, colour, thickness});
        }
        x += w + 2.0f * thickness;
    }
    return strokes;
}

// Every mip of the prefiltered environment as a latlong image (views/environment.mipN.png), and
// all of them on one sheet (views/environment.mips.png, four to a row, mip 0 at the top left),
// each labelled with its index (yellow) and roughness (white).
void writeEnvironmentMips(const gi::Renderer& renderer, const fs::path& dir) {
    const gi::Environment* envPass = renderer.activePass<gi::Environment>();
    if (!envPass || !envPass->ready() || envPass->mips().empty()) return;
    const gi::Environment& env = *envPass;
    const std::vector<gi::Environment::MipInfo>& mips = env.mips();
    const int tileW = 256, tileH = 128, gap = 4, columns = std::min(int(mips.size()), 4);
    const int rows = (int(mips.size()) + columns - 1) / columns;
    const int sheetW = columns * tileW + (columns - 1) * gap, sheetH = rows * tileH + (rows - 1) * gap;
    std::vector<uint8_t> sheet(size_t(sheetW) * size_t(sheetH) * 4, 24);
    for (size_t i = 3; i < sheet.size(); i += 4) sheet[i] = 255;
    for (size_t m = 0; m < mips.size(); ++m) {
        gi::DebugView view;
        view.name = "environment.mip" + std::to_string(m);
        view.texture = env.prefiltered();
        view.target = GL_TEXTURE_CUBE_MAP;
        view.mode = gi::shared::kViewCubeLatLong;
        view.width = tileW;
        view.height = tileH;
        view.level = int(m);
        std::vector<uint8_t> tile = renderer.renderViewImage(view, tileW, tileH);
        gi::writePNG(dir / (view.name + ".png"), tileW, tileH, tile);
        // Rows of the sheet count from the top; the images from the bottom.
        int x0 = int(m) % columns * (tileW + gap), y0 = sheetH - (int(m) / columns + 1) * tileH - int(m) / columns * gap;
        for (int y = 0; y < tileH; ++y)
            std::copy_n(&tile[size_t(y) * tileW * 4], size_t(tileW) * 4, &sheet[(size_t(y0 + y) * sheetW + size_t(x0)) * 4]);
        char roughness[16];
        std::snprintf(roughness, sizeof roughness, "%.2f", double(mips[m].roughness));
        const float h = 12.0f, top = float(y0 + tileH) - 6.0f - h, left = float(x0) + 6.0f;
        gi::fillPolygon(sheet, sheetW, sheetH,
                        {{left - 3, top - 4}, {left + 66, top - 4}, {left + 66, top + h + 4}, {left - 3, top + h + 4}},
                        {0, 0, 0, 0.55f});
        std::vector<gi::Stroke> label = segmentText(std::to_string(m), left, top, h, {1.0f, 0.85f, 0.2f, 1.0f});
        std::vector<gi::Stroke> value = segmentText(roughness, left + 28.0f, top, h, {1, 1, 1, 1});
        label.insert(label.end(), value.begin(), value.end());
        gi::drawStrokes(sheet, sheetW, sheetH, label);
    }
    gi::writePNG(dir / "environment.mips.png", sheetW, sheetH, sheet);
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
    for (const auto& w : scene.warnings) std::fprintf(stderr, "gi-render: warning: %s: %s\n", scene.name.c_str(), w.c_str());
    if (preset.lightsFromScene && scene.lights.empty())
        std::fprintf(stderr, "gi-render: warning: %s has no lights and the preset names none; a default sun is used\n",
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
    for (int f = 0; f < frames; ++f) renderer.render(frame);
    renderer.timer().resolve(true);
    if (gi::gl::debugErrorCount() > 0) throw gi::Error("OpenGL reported errors while rendering (see above)");

    fs::path out(outDir);
    gi::writePNG(out / "image.png", width, height, renderer.readLDR());
    gi::writeEXR(out / "image.exr", width, height, renderer.readHDR());

    gi::json passes = gi::json::array();
    double total = 0;
    for (const auto& p : renderer.passStats()) {
        passes.push_back({{"name", p.name}, {"gpuMs", p.gpuMs}, {"memoryBytes", p.memoryBytes}});
        total += p.gpuMs;
    }
    // Each volume the passes hold (name, format, bytes): the per-volume memory.
    gi::json volumes = gi::json::array();
    for (const auto& v : renderer.volumeMemory())
        volumes.push_back({{"name", v.name}, {"format", v.format}, {"bytes", v.bytes}});
    // The environment's prefilter, mip by mip (the Roughness Mips panel shows the same).
    gi::json environment = nullptr;
    const gi::Environment* env = renderer.activePass<gi::Environment>();
    if (frame.environment.enabled && env && env->ready()) {
        gi::json mips = gi::json::array();
        for (const auto& m : env->mips())
            mips.push_back({{"roughness", m.roughness}, {"size", m.size}, {"samples", m.samples}, {"diskRadius", m.diskRadius}, {"ms", m.ms}});
        environment = {{"source", env->image().source}, {"loadMs", env->loadMs()}, {"mips", mips}};
    }
    gi::json stats = {{"input", input},
                      {"width", width},
                      {"height", height},
                      {"frames", frames},
                      {"renderer", context.renderer()},
                      {"passes", passes},
                      {"gpuMsTotal", total},
                      {"memoryBytes", renderer.memoryBytes()},
                      {"volumes", volumes},
                      {"environment", environment},
                      {"scene", {{"name", scene.name}, {"triangles", scene.triangleCount()}, {"warnings", scene.warnings}}},
                      {"settings", gi::presetToJson(preset)}};
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
        if (frame.technique == "vct") {
            // The voxels from the camera (the finest level holding its target): albedo, and the radiance the cones trace.
            gi::VoxelView voxels;
            gi::VoxelViewParams vp;
            vp.viewProj = gi::projectionMatrix(frame.camera, float(width) / float(height)) * gi::viewMatrix(frame.camera);
            std::vector<gi::VoxelGridView> grids = gi::voxelGrids(renderer.debugViews(), frame, scene.bounds);
            vp.level = gi::finestLevelHolding(grids, frame.camera.target);
            gi::writePNG(out / "views" / "vct.voxels.png", width, height, voxels.renderImage(grids, vp, width, height));
            vp.source = gi::VoxelViewSource::Radiance;
            gi::writePNG(out / "views" / "vct.voxels.radiance.png", width, height, voxels.renderImage(grids, vp, width, height));
            // The cone set traced at the centre pixel, over the final image (as the editor draws it).
            gi::SurfacePick pick;
            if (gi::pickSurface(renderer, frame.camera, {width / 2, height / 2}, pick)) {
                float voxel = gi::vctLevels(frame.vct, scene.bounds.min, scene.bounds.max, frame.camera.eye).front().cellSize;
                std::vector<gi::ConeGlyph> glyphs =
                    gi::vctConeGlyphs(frame.vct, pick.position, pick.normal, frame.camera.eye, pick.roughness, voxel);
                std::vector<uint8_t> image = renderer.readLDR();
                gi::drawGlyphLines(image, width, height, vp.viewProj, gi::coneGlyphLines(glyphs, 12.0f * voxel));
                gi::writePNG(out / "views" / "vct.cones.png", width, height, image);
            }
        }
        if (frame.environment.enabled) writeEnvironmentMips(renderer, out / "views");
        if (frame.volumetric.enabled) {
            // The phase function as a polar plot (linear), light travelling along +x.
            const int plotSize = 256;
            gi::writePNG(out / "views" / "volumetric.phase.png", plotSize, plotSize,
                         gi::phasePlotImage(gi::phaseParams(frame.volumetric), plotSize, false));
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
            std::printf("  score: ssim %.4f  score %.3f  rmse %.4f  psnr %.2f dB  leak %.4f (energy %.4f)\n", m.ssim,
                        m.score, m.rmse, m.psnr, m.leakFraction, m.leakEnergy);
        }
    }
    gi::writeFileAtomic(out / "stats.json", stats.dump(2) + "\n");
    std::printf("gi-render: %s -> %s (%dx%d, %.1f ms GPU)\n", input.c_str(), (out / "image.png").c_str(), width, height, total);
    for (const auto& p : renderer.passStats()) std::printf("  %-10s %8.2f ms %8.1f MiB\n", p.name.c_str(), p.gpuMs, double(p.memoryBytes) / (1 << 20));
    return 0;
}

}  // namespace

int main(int argc, char** argv) { return gi::reportErrors("gi-render", [&] { return run(argc, argv); }); }
