// gi-matrix end to end: a small matrix on the built-in Cornell box rendered by real gi-render
// processes (EGL, llvmpipe), resumed, split into shards and merged, with cells that hang and
// crash, and its HTML report loaded in headless Chromium as a user's browser would.
#include "gi/matrix/matrix.h"
#include "gi/render/render_settings.h"
#include "gi/util/paths.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>

namespace gi {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const char* kSpec = R"({
  "name": "run test", "width": 48, "height": 36, "frames": 2, "spp": 16, "timeoutSeconds": 300,
  "scenes": [{"input": "default", "label": "cornell"}],
  "cells": [{"technique": "*"}, {"technique": "lpv", "label": "LPV 16", "set": {"lpv.gridResolution": 16}}]
})";
// "*" is every registered technique and none; then LPV 16.
const size_t kCells = TechniqueChoice::choices().size() + 1;

std::string matrix(const std::string& args) { return std::string(GI_MATRIX_EXE) + " " + args; }

std::vector<matrix::CellResult> resultsOf(const fs::path& dir) {
    json j = json::parse(readTextFile(dir / "results.json"));
    std::vector<matrix::CellResult> out;
    for (const json& r : j) out.push_back(matrix::resultFromJson(r, "results.json"));
    return out;
}

std::map<std::string, double> ssimById(const std::vector<matrix::CellResult>& results) {
    std::map<std::string, double> m;
    for (const auto& r : results) m[r.id] = r.ssim;
    return m;
}

fs::path writeSpec(const fs::path& dir, const std::string& text) {
    fs::path p = dir / "spec.json";
    std::ofstream(p) << text;
    return p;
}

TEST(MatrixRun, RendersResumesShardsAndMerges) {
    fs::path dir = test::tempDir();
    fs::path spec = writeSpec(dir, kSpec);
    test::CommandResult r = test::runCommand(matrix(spec.string() + " --out " + (dir / "all").string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string count = std::to_string(kCells);
    EXPECT_NE(r.output.find("[" + count + "/" + count + "]"), std::string::npos) << "progress per cell\n" << r.output;
    EXPECT_NE(r.output.find(count + " done, 0 failed"), std::string::npos) << r.output;

    std::vector<matrix::CellResult> all = resultsOf(dir / "all");
    ASSERT_EQ(all.size(), kCells);
    for (const auto& c : all) {
        EXPECT_TRUE(c.ok()) << c.label << ": " << c.error;
        EXPECT_GT(c.ssim, 0.3) << c.label;
        EXPECT_LE(c.ssim, 1.0) << c.label;
        EXPECT_GT(c.msTotal, 0.0) << c.label;
        EXPECT_FALSE(c.passMs.empty()) << c.label;
        EXPECT_FALSE(c.renderer.empty()) << c.label;
        EXPECT_TRUE(fs::exists(dir / "all" / c.folder / "image.png")) << c.folder;
        EXPECT_TRUE(fs::exists(dir / "all" / c.folder / "heat_map.png")) << c.folder;
    }
    std::string csv = readTextFile(dir / "all" / "results.csv");
    EXPECT_EQ(size_t(std::count(csv.begin(), csv.end(), '\n')), kCells + 1) << csv;

    // Resumed: nothing left to do.
    r = test::runCommand(matrix(spec.string() + " --out " + (dir / "all").string() + " --resume"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("0 done, 0 failed, " + count + " skipped"), std::string::npos) << r.output;

    // The spec edited to name fewer cells, into the same folder: the report lists the spec's
    // cells only, and the editor's loader (reportedResults) reads the same list; the dropped
    // cell's folder stays on disk.
    {
        fs::path fewer = dir / "fewer";
        fs::create_directories(fewer);
        std::string text = kSpec;
        text.replace(text.find(", {\"technique\": \"lpv\", \"label\": \"LPV 16\""), std::string::npos, "]}");
        fs::path shortSpec = writeSpec(fewer, text);
        r = test::runCommand(matrix(shortSpec.string() + " --out " + (dir / "all").string() + " --resume"));
        ASSERT_EQ(r.exitCode, 0) << r.output;
        EXPECT_NE(r.output.find("0 done, 0 failed, " + std::to_string(kCells - 1) + " skipped"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("1 cells in"), std::string::npos) << r.output;
        EXPECT_EQ(resultsOf(dir / "all").size(), kCells - 1);
        EXPECT_EQ(matrix::reportedResults(dir / "all").size(), kCells - 1);
        EXPECT_EQ(matrix::collectResults(dir / "all").size(), kCells) << "left on disk";
        // Back to the whole spec: all of them again.
        r = test::runCommand(matrix(spec.string() + " --out " + (dir / "all").string() + " --resume"));
        ASSERT_EQ(r.exitCode, 0) << r.output;
        EXPECT_EQ(resultsOf(dir / "all").size(), kCells);
    }

    // Two shards into their own folders, merged: the same cells with the same figures (the
    // runner is deterministic).
    for (int i = 0; i < 2; ++i) {
        r = test::runCommand(matrix(spec.string() + " --out " + (dir / ("shard" + std::to_string(i))).string() + " --shard " +
                                    std::to_string(i) + "/2"));
        ASSERT_EQ(r.exitCode, 0) << r.output;
        EXPECT_EQ(resultsOf(dir / ("shard" + std::to_string(i))).size(), i == 0 ? (kCells + 1) / 2 : kCells / 2);
    }
    r = test::runCommand(matrix("--merge " + (dir / "shard0").string() + " " + (dir / "shard1").string() + " --out " +
                                (dir / "merged").string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::map<std::string, double> merged = ssimById(resultsOf(dir / "merged")), single = ssimById(all);
    ASSERT_EQ(merged.size(), single.size());
    for (const auto& [id, ssim] : single) {
        ASSERT_TRUE(merged.count(id)) << id;
        EXPECT_NEAR(merged[id], ssim, 1e-9) << id;
    }
    EXPECT_TRUE(fs::exists(dir / "merged" / resultsOf(dir / "merged")[0].folder / "image.png"));
}

TEST(MatrixRun, AHangingOrCrashingCellFailsAloneAndTheReportSaysWhy) {
    fs::path dir = test::tempDir();
    // 10 s: the hanging cell is killed well before its 120 s sleep ends, while a real cell
    // (about 1.5 s alone) keeps room under a loaded CI machine's parallel tests.
    std::string spec = kSpec;
    spec.replace(spec.find("\"timeoutSeconds\": 300"), 21, "\"timeoutSeconds\": 10");
    fs::path specPath = writeSpec(dir, spec);
    // A renderer that hangs on VCT and crashes on LPV, and renders the rest.
    fs::path wrapper = dir / "flaky-render.sh";
    std::ofstream(wrapper) << "#!/bin/sh\ncase \"$*\" in\n  *technique=vct*) sleep 120 ;;\n"
                           << "  *technique=lpv*) echo 'simulated crash'; kill -SEGV $$ ;;\nesac\nexec " << GI_RENDER_EXE
                           << " \"$@\"\n";
    fs::permissions(wrapper, fs::perms::owner_all);
    test::CommandResult r =
        test::runCommand(matrix(specPath.string() + " --out " + (dir / "out").string() + " --renderer " + wrapper.string()));
    EXPECT_EQ(r.exitCode, 3) << "some cells failed\n" << r.output;
    // lpv and LPV 16 crash, vct hangs; none and the other techniques render.
    const size_t rendered = kCells - 3;
    EXPECT_NE(r.output.find(std::to_string(rendered) + " done, 3 failed"), std::string::npos) << r.output;
    std::vector<matrix::CellResult> results = resultsOf(dir / "out");
    ASSERT_EQ(results.size(), kCells);
    for (const auto& c : results) {
        if (c.technique != "vct" && c.technique != "lpv") {
            EXPECT_TRUE(c.ok()) << c.error;
        } else if (c.technique == "vct") {
            EXPECT_EQ(c.status, "timeout");
            EXPECT_NE(c.error.find("timed out after 10 s"), std::string::npos) << c.error;
            EXPECT_LT(c.wallSeconds, 40.0) << "killed at the limit";
        } else {
            EXPECT_EQ(c.status, "failed");
            EXPECT_NE(c.error.find("crashed (signal 11"), std::string::npos) << c.error;
            EXPECT_NE(c.error.find("simulated crash"), std::string::npos) << c.error;
        }
    }
    std::string html = readTextFile(dir / "out" / "index.html");
    EXPECT_NE(html.find("timed out after 10 s"), std::string::npos);
    // --resume runs the failed cells again (with the real renderer they now pass), under the
    // spec's ordinary timeout, as a user would after fixing the cause: the limit is not part of a
    // cell's identity, so the cells done before are still skipped. (The short limit here once
    // killed a real LPV cell on a loaded CI machine.)
    writeSpec(dir, kSpec);
    r = test::runCommand(matrix(specPath.string() + " --out " + (dir / "out").string() + " --resume"));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("3 done, 0 failed, " + std::to_string(rendered) + " skipped"), std::string::npos) << r.output;
}

TEST(MatrixRun, ReportLoadsInChromiumWithEveryImageAndOneRowPerCell) {
    fs::path dir = test::tempDir();
    fs::path spec = writeSpec(dir, kSpec);
    test::CommandResult r = test::runCommand(matrix(spec.string() + " --out " + (dir / "out").string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    // Chromium comes from scripts/install-deps.sh; its absence is a set-up error, not a skip.
    test::CommandResult which = test::runCommand("command -v chromium");
    ASSERT_EQ(which.exitCode, 0) << "chromium is not installed: run scripts/install-deps.sh";
    // The DOM after the page's scripts ran (the load check writes its counts on <body>).
    fs::path profile = dir / "chromium-profile";
    r = test::runCommand("timeout 180 chromium --headless --no-sandbox --disable-gpu --user-data-dir=" + profile.string() +
                         " --virtual-time-budget=10000 --dump-dom file://" + fs::absolute(dir / "out" / "index.html").string() +
                         " 2>/dev/null");
    ASSERT_EQ(r.exitCode, 0) << r.output.substr(0, 2000);
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.output, m, std::regex("data-images-total=\"(\\d+)\" data-images-loaded=\"(\\d+)\"")))
        << r.output.substr(0, 2000);
    size_t total = std::stoul(m[1]), loaded = std::stoul(m[2]);
    EXPECT_EQ(total, kCells * 3 + 1) << "image, heat and leak map per cell, and the reference";
    EXPECT_EQ(loaded, total);
    size_t rows = 0;
    for (size_t at = r.output.find("<tr class=\"cell"); at != std::string::npos; at = r.output.find("<tr class=\"cell", at + 1)) ++rows;
    EXPECT_EQ(rows, kCells);
    EXPECT_NE(r.output.find("All " + std::to_string(total) + " images loaded."), std::string::npos);

    // A moved image is caught by the same check.
    fs::remove(dir / "out" / resultsOf(dir / "out")[0].folder / "heat_map.png");
    r = test::runCommand("timeout 180 chromium --headless --no-sandbox --disable-gpu --user-data-dir=" + profile.string() +
                         " --virtual-time-budget=10000 --dump-dom file://" + fs::absolute(dir / "out" / "index.html").string() +
                         " 2>/dev/null");
    ASSERT_TRUE(std::regex_search(r.output, m, std::regex("data-images-total=\"(\\d+)\" data-images-loaded=\"(\\d+)\"")));
    EXPECT_EQ(std::stoul(m[2]), total - 1);
}

}  // namespace
}  // namespace gi
