// gi-matrix: runs a comparison matrix (gi/matrix/matrix.h): every scene x technique variant x
// sweep point of a spec, each cell a gi-render process scored against the path-traced
// reference, into results.csv, results.json and a static HTML report (index.html).
#include "gi/matrix/matrix.h"
#include "gi/matrix/report.h"
#include "gi/matrix/run.h"
#include "gi/matrix/tune.h"
#include "gi/preset/preset.h"
#include "gi/util/error.h"
#include "gi/util/paths.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <set>

#include <cstdio>
#include <iostream>
#include <unistd.h>

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

fs::path defaultRenderer() { return gi::matrix::siblingExecutable("gi-render"); }

std::string titleOf(const fs::path& dir) {
    std::error_code ec;
    fs::path p = dir / "matrix.json";
    if (!fs::is_regular_file(p, ec)) return dir.filename().string();
    try {
        return json::parse(gi::readTextFile(p, 1 << 20)).value("name", dir.filename().string());
    } catch (const std::exception&) {
        return dir.filename().string();
    }
}

void printProgress(const gi::matrix::RunProgress& p) {
    std::string what;
    if (p.wasSkipped) {
        what = "done before (--resume)";
    } else if (p.result->ok()) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "SSIM %.4f, %.1f ms (%.1f s)", p.result->ssim, p.result->msTotal, p.result->wallSeconds);
        what = p.result->scene + " / " + p.result->label + ": " + buf;
    } else {
        what = p.result->scene + " / " + p.result->label + ": " + p.result->status + ": " + p.result->error;
    }
    std::string left = p.remainingSeconds >= 0.0 ? ", ~" + gi::matrix::formatDuration(p.remainingSeconds) + " left" : "";
    std::fprintf(stderr, "gi-matrix: [%zu/%zu] %s | %zu done, %zu failed, %zu skipped, %s elapsed%s\n", p.index, p.total, what.c_str(),
                 p.done, p.failed, p.skipped, gi::matrix::formatDuration(p.elapsedSeconds).c_str(), left.c_str());
}

int run(int argc, char** argv) {
    CLI::App app{"gi-matrix: render every cell of a comparison matrix and report SSIM against the reference, cost and leaks"};
    std::string specPath, outDir, shard, renderer;
    std::vector<std::string> mergeDirs;
    bool resume = false, list = false;
    app.add_option("spec", specPath, "The matrix spec (.json; format in gi/matrix/matrix.h and the README)");
    app.add_option("--out", outDir, "Output folder: cells/, results.csv, results.json, index.html")->required();
    app.add_flag("--resume", resume, "Skip cells whose result is already in --out");
    app.add_option("--shard", shard, "Run only the i-th of n disjoint slices of the cells, as i/n (0-based)");
    app.add_option("--renderer", renderer, "The gi-render executable (default: the one beside gi-matrix)");
    app.add_flag("--list", list, "Print the cells (and the shard's) and exit");
    app.add_option("--merge", mergeDirs, "Join the results of these output folders (e.g. one per shard) into --out")->expected(1, -1);
    std::string tuneInput, technique;
    double budgetMs = 0.0;
    size_t renders = 27;
    bool grid = false;
    int width = 128, height = 96, frames = 4, spp = 256, camera = -1;
    app.add_option("--tune", tuneInput, "Auto-tune: search --technique's settings on this preset or glTF file");
    app.add_option("--technique", technique, "--tune: the technique whose settings are searched");
    app.add_option("--budget-ms", budgetMs, "--tune: the frame time the result must stay within, ms (as measured here)")->check(CLI::PositiveNumber);
    app.add_option("--renders", renders, "--tune: renders the search may spend")->check(CLI::Range(1, 1000));
    app.add_flag("--grid", grid, "--tune: search a grid of the same number of renders instead (the baseline)");
    app.add_option("--width", width, "--tune: image width")->check(CLI::Range(1, 16384));
    app.add_option("--height", height, "--tune: image height")->check(CLI::Range(1, 16384));
    app.add_option("--frames", frames, "--tune: frames per render (the last one is timed)")->check(CLI::Range(1, 10000));
    app.add_option("--spp", spp, "--tune: samples per pixel of the reference")->check(CLI::Range(1, 65536));
    app.add_option("--camera", camera, "--tune: the glTF file's camera")->check(CLI::Range(-1, 1023));
    double renderTimeout = 0.0;
    app.add_option("--render-timeout", renderTimeout, "--tune: seconds one render may take (default: 60 + 10 x frames x budget)")
        ->check(CLI::PositiveNumber);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "gi-matrix: %s (see --help)\n", e.what());
        return 2;
    }

    if (!mergeDirs.empty()) {
        if (!specPath.empty()) throw gi::Error("--merge takes output folders, not a spec");
        fs::create_directories(outDir);
        std::string title;
        for (const std::string& d : mergeDirs) {
            if (!fs::is_directory(fs::path(d) / "cells")) throw gi::Error(d + ": no cells/ folder (not a gi-matrix output folder)");
            if (title.empty()) title = titleOf(d);
            if (fs::equivalent(d, outDir)) continue;
            fs::copy(fs::path(d) / "cells", fs::path(outDir) / "cells", fs::copy_options::recursive | fs::copy_options::overwrite_existing);
        }
        auto results = gi::matrix::collectResults(outDir);
        gi::matrix::writeResults(outDir, title, results);
        if (fs::path(mergeDirs.front()) / "matrix.json" != fs::path(outDir) / "matrix.json" &&
            fs::exists(fs::path(mergeDirs.front()) / "matrix.json"))
            fs::copy_file(fs::path(mergeDirs.front()) / "matrix.json", fs::path(outDir) / "matrix.json", fs::copy_options::overwrite_existing);
        size_t failed = size_t(std::count_if(results.begin(), results.end(), [](const auto& r) { return !r.ok(); }));
        std::fprintf(stderr, "gi-matrix: merged %zu cells (%zu failed) into %s/index.html\n", results.size(), failed, outDir.c_str());
        return failed ? 3 : 0;
    }

    if (!tuneInput.empty()) {
        if (!specPath.empty()) throw gi::Error("--tune takes a scene, not a spec");
        if (technique.empty()) throw gi::Error("--tune needs --technique");
        if (budgetMs <= 0.0) throw gi::Error("--tune needs --budget-ms");
        json j = {{"name", "auto-tune " + technique + " within " + std::to_string(int(budgetMs)) + " ms"},
                  {"width", width}, {"height", height}, {"frames", frames}, {"spp", spp},
                  {"scenes", json::array({{{"input", fs::absolute(tuneInput).string()}, {"camera", camera}}})},
                  {"cells", json::array({{{"technique", technique}}})}};
        // A render far over the budget cannot win: it is stopped after a minute plus ten times the
        // budget per frame (the reference and the first frame included), and counts as over budget.
        if (renderTimeout <= 0.0) renderTimeout = 60.0 + 10.0 * frames * budgetMs / 1000.0;
        j["timeoutSeconds"] = renderTimeout;
        gi::matrix::MatrixSpec spec = gi::matrix::specFromJson(j, tuneInput);
        // The scene's own preset is where the search starts.
        gi::Preset preset = gi::presetForInput(fs::absolute(tuneInput), camera);
        gi::matrix::TuneOptions options;
        options.technique = technique;
        options.base = gi::presetToJson(preset);
        options.budgetMs = budgetMs;
        options.maxRenders = renders;
        options.run.renderer = renderer.empty() ? defaultRenderer() : fs::path(renderer);
        if (access(options.run.renderer.c_str(), X_OK) != 0)
            throw gi::Error(options.run.renderer.string() + ": no such executable (build gi-render, or name it with --renderer)");
        options.run.outDir = outDir;
        options.run.resume = true;  // a point rendered before (this search's or another's) is not rendered again
        if (gi::matrix::tuneSpace(technique, options.base).empty()) throw gi::Error("--technique '" + technique + "' has no settings to tune");
        options.progress = [&](const gi::matrix::TuneReport& r) {
            const gi::matrix::TuneStep& s = r.steps.back();
            std::string figures = s.result.ok() ? "SSIM " + std::to_string(s.result.ssim).substr(0, 6) + ", " +
                                                      std::to_string(s.result.msTotal).substr(0, 7) + " ms" + (s.withinBudget ? "" : " (over budget)")
                                                : s.result.status + ": " + s.result.error;
            std::fprintf(stderr, "gi-matrix: tune [%zu/%zu] %s: %s%s%s\n", r.renders, renders, s.change.c_str(), figures.c_str(),
                         s.reused ? " (reused)" : "", s.best ? "  <- best" : "");
        };
        fs::create_directories(outDir);
        gi::matrix::TuneReport report = grid ? gi::matrix::tuneGrid(spec, options) : gi::matrix::tunePatternSearch(spec, options);
        gi::writeFileAtomic(fs::path(outDir) / "tune.json", gi::matrix::tuneReportToJson(report, budgetMs).dump(2) + "\n");
        gi::writeFileAtomic(fs::path(outDir) / "matrix.json", json({{"name", spec.name}}).dump(2) + "\n");
        gi::matrix::writeResults(outDir, spec.name, gi::matrix::collectResults(outDir));
        if (!report.best || !report.best->withinBudget) {
            std::fprintf(stderr, "gi-matrix: no setting of %s stays within %g ms here (the cheapest took %.1f ms)\n", technique.c_str(),
                         budgetMs, report.best ? report.best->result.msTotal : 0.0);
            return 3;
        }
        // The winner as a preset: the scene's own, with the technique and its settings.
        gi::applySetting(preset, "technique=" + technique);
        for (const std::string& a : report.best->settings) gi::applySetting(preset, a);
        fs::path tuned = fs::path(outDir) / "tuned.json";
        gi::savePreset(preset, tuned);
        std::string settings;
        for (const std::string& a : report.best->settings) settings += " " + a;
        std::fprintf(stderr, "gi-matrix: %s in %zu renders (%zu reused): SSIM %.4f at %.1f ms (budget %g ms) with%s; preset: %s\n",
                     report.method.c_str(), report.renders, report.reused, report.best->result.ssim, report.best->result.msTotal, budgetMs,
                     settings.empty() ? " the defaults" : settings.c_str(), tuned.c_str());
        return 0;
    }

    if (specPath.empty()) throw gi::Error("no spec given (gi-matrix SPEC.json --out DIR, or --merge DIR... --out DIR)");
    gi::matrix::MatrixSpec spec = gi::matrix::loadSpec(specPath);
    std::vector<gi::matrix::Cell> cells = gi::matrix::expandCells(spec);
    size_t all = cells.size();
    if (!shard.empty()) {
        auto [i, n] = gi::matrix::parseShard(shard);
        cells = gi::matrix::shardOf(cells, i, n);
    }
    if (list) {
        for (const auto& c : cells) std::printf("%s\t%s\t%s\n", c.sceneLabel.c_str(), c.technique.c_str(), c.label.c_str());
        std::fprintf(stderr, "gi-matrix: %zu cells%s\n", cells.size(), shard.empty() ? "" : (" of " + std::to_string(all)).c_str());
        return 0;
    }
    gi::matrix::RunOptions options;
    options.renderer = renderer.empty() ? defaultRenderer() : fs::path(renderer);
    if (access(options.renderer.c_str(), X_OK) != 0)
        throw gi::Error(options.renderer.string() + ": no such executable (build gi-render, or name it with --renderer)");
    options.outDir = outDir;
    options.resume = resume;
    options.progress = printProgress;
    fs::create_directories(outDir);
    json info = {{"name", spec.name}, {"spec", fs::absolute(specPath).string()}, {"width", spec.width}, {"height", spec.height},
                 {"frames", spec.frames}, {"spp", spec.spp}, {"cells", all}};
    gi::writeFileAtomic(fs::path(outDir) / "matrix.json", info.dump(2) + "\n");
    std::fprintf(stderr, "gi-matrix: %s: %zu cells%s at %dx%d, reference %d spp, timeout %g s per cell\n", spec.name.c_str(),
                 cells.size(), shard.empty() ? "" : (" (shard " + shard + " of " + std::to_string(all) + ")").c_str(), spec.width,
                 spec.height, spec.spp, spec.timeoutSeconds);
    gi::matrix::RunSummary s = gi::matrix::runCells(spec, cells, options);
    // The report covers the spec's cells found in the folder (other shards' too when they share
    // it), not cells of an earlier spec that names them no more: those stay on disk, left out.
    std::set<std::string> named;
    for (const auto& c : gi::matrix::expandCells(spec)) named.insert(c.id);
    auto results = gi::matrix::collectResults(outDir);
    size_t before = results.size();
    results.erase(std::remove_if(results.begin(), results.end(), [&](const auto& r) { return !named.count(r.id); }), results.end());
    if (results.size() < before)
        std::fprintf(stderr, "gi-matrix: %zu cells in %s/cells are not in this spec (an earlier spec's?) and are left out of the report\n",
                     before - results.size(), outDir.c_str());
    gi::matrix::writeResults(outDir, spec.name, results);
    std::fprintf(stderr, "gi-matrix: %zu done, %zu failed, %zu skipped in %s; report: %s\n", s.done, s.failed, s.skipped,
                 gi::matrix::formatDuration(s.seconds).c_str(), (fs::path(outDir) / "index.html").c_str());
    return s.failed ? 3 : 0;
}

}  // namespace

int main(int argc, char** argv) { return gi::reportErrors("gi-matrix", [&] { return run(argc, argv); }); }
