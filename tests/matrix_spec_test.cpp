// The comparison matrix's spec, cells, shards, results and report, without rendering
// (gi/matrix/matrix.h, report.h, process.h). matrix_run_test.cpp runs gi-matrix end to end.
#include "gi/matrix/matrix.h"
#include "gi/matrix/process.h"
#include "gi/matrix/report.h"
#include "gi/preset/preset.h"
#include "gi/scene/scene.h"
#include "gi/util/error.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

namespace gi {
namespace {

using nlohmann::json;
using namespace gi::matrix;

std::string errorOf(const json& j) {
    try {
        specFromJson(j, "spec.json");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

json smallSpec() {
    return json::parse(R"({
        "name": "t", "width": 32, "height": 24,
        "scenes": ["default", {"input": "default", "label": "second", "set": {"camera.fovY": 50}}],
        "cells": [{"technique": "none"},
                  {"technique": "lpv", "label": "LPV", "sweep": {"lpv.gridResolution": [16, 32], "lpv.propagationSteps": {"from": 8, "to": 24, "step": 8}}},
                  {"technique": "vct", "set": {"vct.coneSet": "six"}, "paperScores": {"second": 7.5}}]
    })");
}

size_t techniqueCount() {
    for (const SettingInfo& s : listSettings())
        if (s.key == "technique") return s.choices.size();
    return 0;
}

TEST(MatrixSpec, ExpandsScenesVariantsAndSweeps) {
    MatrixSpec spec = specFromJson(smallSpec(), "spec.json");
    EXPECT_EQ(spec.width, 32);
    EXPECT_EQ(spec.frames, 3) << "the default";
    ASSERT_EQ(spec.scenes.size(), 2u);
    EXPECT_EQ(spec.scenes[0].label, "default");
    EXPECT_EQ(spec.scenes[0].input, "");
    EXPECT_EQ(spec.scenes[1].set, std::vector<std::string>{"camera.fovY=50"});
    std::vector<Cell> cells = expandCells(spec);
    // Per scene: none, LPV's 2 x 3 sweep, vct.
    ASSERT_EQ(cells.size(), 2u * (1 + 6 + 1));
    EXPECT_EQ(cells[0].label, "none");
    EXPECT_EQ(cells[1].technique, "lpv");
    EXPECT_EQ(cells[1].set, (std::vector<std::string>{"lpv.gridResolution=16", "lpv.propagationSteps=8"}));
    EXPECT_EQ(cells[1].label, "LPV lpv.gridResolution=16 lpv.propagationSteps=8");
    EXPECT_EQ(cells[6].set, (std::vector<std::string>{"lpv.gridResolution=32", "lpv.propagationSteps=24"}));
    EXPECT_EQ(cells[7].label, "vct vct.coneSet=six");
    EXPECT_FALSE(cells[7].paperScore.has_value());
    ASSERT_TRUE(cells[15].paperScore.has_value());
    EXPECT_DOUBLE_EQ(*cells[15].paperScore, 7.5);

    // gi-render's arguments: the technique, the scene's overrides, then the cell's.
    std::vector<std::string> args = renderArguments(spec, cells[9], "/tmp/x");
    std::string line;
    for (const std::string& a : args) line += a + " ";
    EXPECT_EQ(line, "--out /tmp/x --width 32 --height 24 --frames 3 --reference --score --spp 256 --set technique=lpv "
                    "--set camera.fovY=50 --set lpv.gridResolution=16 --set lpv.propagationSteps=8 ");
}

TEST(MatrixSpec, EveryTechniqueJoinsThroughTheWildcard) {
    json j = smallSpec();
    j["cells"] = json::parse(R"([{"technique": "*"}, {"technique": "*", "label": "ao", "set": {"ssao.enabled": true}}])");
    std::vector<Cell> cells = expandCells(specFromJson(j, "spec.json"));
    size_t n = techniqueCount();
    ASSERT_GE(n, 3u);
    ASSERT_EQ(cells.size(), 2 * 2 * n);
    std::set<std::string> names;
    for (size_t i = 0; i < n; ++i) names.insert(cells[i].technique);
    EXPECT_EQ(names.size(), n) << "each registered technique once";
    EXPECT_EQ(cells[n].label, "ao " + cells[n].technique);
}

TEST(MatrixSpec, AVariantCanBeLimitedToSomeScenes) {
    json j = smallSpec();
    j["cells"] = json::parse(R"([{"technique": "none"}, {"technique": "lpv", "scenes": ["second"]}])");
    std::vector<Cell> cells = expandCells(specFromJson(j, "spec.json"));
    ASSERT_EQ(cells.size(), 3u);
    EXPECT_EQ(cells[0].sceneLabel, "default");
    EXPECT_EQ(cells[1].sceneLabel, "second");
    EXPECT_EQ(cells[2].technique, "lpv");
    EXPECT_EQ(cells[2].sceneLabel, "second");
    j["cells"][1]["scenes"] = {"third"};
    EXPECT_NE(errorOf(j).find("cells[1].scenes: no scene is labelled \"third\""), std::string::npos) << errorOf(j);
}

TEST(MatrixSpec, SpearmanRanksLikeTheTextbook) {
    EXPECT_DOUBLE_EQ(spearman({1, 2, 3, 4}, {10, 20, 30, 40}), 1.0);
    EXPECT_DOUBLE_EQ(spearman({1, 2, 3, 4}, {4, 3, 2, 1}), -1.0);
    // Monotone but not linear: still 1.
    EXPECT_DOUBLE_EQ(spearman({1, 2, 3, 4}, {1, 8, 27, 1000}), 1.0);
    // Ties share their mean rank: ranks (1.5, 1.5, 3) against (1, 2, 3) give 0.866.
    EXPECT_NEAR(spearman({5, 5, 7}, {1, 2, 3}), std::sqrt(3.0) / 2.0, 1e-12);
    EXPECT_TRUE(std::isnan(spearman({1}, {2})));
    EXPECT_TRUE(std::isnan(spearman({1, 1, 1}, {1, 2, 3})));
}

TEST(MatrixSpec, CellIdsAreStableAndFollowWhatTheRenderDependsOn) {
    MatrixSpec spec = specFromJson(smallSpec(), "spec.json");
    std::vector<Cell> a = expandCells(spec), b = expandCells(spec);
    std::set<std::string> ids;
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].id, b[i].id);
        ids.insert(a[i].id);
    }
    EXPECT_EQ(ids.size(), a.size()) << "every cell its own id";
    EXPECT_NE(a[0].id, a[8].id) << "the second scene changes the camera, so the id";
    spec.width = 64;
    EXPECT_NE(expandCells(spec)[0].id, a[0].id) << "the image size is part of the id";
    spec.width = 32;
    spec.spp = 128;
    EXPECT_NE(expandCells(spec)[0].id, a[0].id) << "the reference's samples are part of the id";
}

TEST(MatrixSpec, ShardsAreDisjointAndCoverEveryCell) {
    std::vector<Cell> cells = expandCells(specFromJson(smallSpec(), "spec.json"));
    for (int n = 1; n <= 5; ++n) {
        std::multiset<std::string> seen;
        for (int i = 0; i < n; ++i)
            for (const Cell& c : shardOf(cells, i, n)) seen.insert(c.sceneLabel + "/" + c.id);
        EXPECT_EQ(seen.size(), cells.size()) << n << " shards";
        for (const Cell& c : cells) EXPECT_EQ(seen.count(c.sceneLabel + "/" + c.id), 1u) << n << " shards";
    }
    EXPECT_EQ(parseShard("1/3"), std::make_pair(1, 3));
    for (const char* bad : {"3/3", "-1/2", "1", "a/b", "0/0", "1/2x"}) EXPECT_THROW(parseShard(bad), Error) << bad;
}

TEST(MatrixSpec, BadSpecsNameTheKey) {
    json j = smallSpec();
    j["colour"] = 1;
    EXPECT_NE(errorOf(j).find("unknown key 'colour'"), std::string::npos) << errorOf(j);
    j = smallSpec();
    j["cells"][1]["set"] = {{"lpv.gridResolutoin", 8}};
    EXPECT_NE(errorOf(j).find("cells[1].set"), std::string::npos) << errorOf(j);
    EXPECT_NE(errorOf(j).find("did you mean 'lpv.gridResolution'"), std::string::npos) << errorOf(j);
    j = smallSpec();
    j["cells"][1]["sweep"]["lpv.gridResolution"] = {16, 100000};
    EXPECT_NE(errorOf(j).find("out of range"), std::string::npos) << errorOf(j);
    j = smallSpec();
    j["cells"][0]["technique"] = "pathtracer";
    EXPECT_NE(errorOf(j).find("unknown technique 'pathtracer'"), std::string::npos) << errorOf(j);
    j = smallSpec();
    j["scenes"][1]["label"] = "default";
    EXPECT_NE(errorOf(j).find("'default' is used twice"), std::string::npos) << errorOf(j);
    j = smallSpec();
    j["width"] = -4;
    EXPECT_NE(errorOf(j).find("'width' is -4"), std::string::npos) << errorOf(j);
    j = smallSpec();
    j["cells"][2]["paperScores"] = {{"nowhere", 1.0}};
    EXPECT_NE(errorOf(j).find("no scene is labelled 'nowhere'"), std::string::npos) << errorOf(j);
    j = smallSpec();
    j["cells"][1]["sweep"]["lpv.propagationSteps"] = {{"from", 8}, {"to", 1}};
    EXPECT_NE(errorOf(j).find("'to' is below 'from'"), std::string::npos) << errorOf(j);
    j = smallSpec();
    j["cells"][1]["set"] = {{"technique", "vct"}};
    EXPECT_NE(errorOf(j).find("not in 'set'"), std::string::npos) << errorOf(j);
    j = smallSpec();
    j["scenes"] = json::array({"no_such_scene_anywhere.gltf"});
    EXPECT_NE(errorOf(j).find("no_such_scene_anywhere.gltf"), std::string::npos) << errorOf(j);
    // An absurd sweep is refused before anything runs.
    j = smallSpec();
    j["cells"][1]["sweep"] = {{"lpv.intensity", {{"from", 0}, {"to", 100}, {"step", 1e-6}}}};
    EXPECT_NE(errorOf(j).find("more than"), std::string::npos) << errorOf(j);
    j = smallSpec();
    j["cells"][1]["sweep"] = {{"lpv.intensity", {{"from", 0}, {"to", 99}, {"step", 1}}},
                              {"lpv.damping", {{"from", 0}, {"to", 0.99}, {"step", 0.01}}},
                              {"lpv.nudge", {{"from", 0}, {"to", 3.9}, {"step", 0.1}}}};
    EXPECT_NE(errorOf(j).find("more than"), std::string::npos) << errorOf(j);
    EXPECT_EQ(errorOf(smallSpec()), "");
}

TEST(MatrixSpec, LoadingNamesTheFileAndTheByte) {
    std::filesystem::path dir = test::tempDir();
    std::ofstream(dir / "bad.json") << "{\"scenes\": [\n";
    try {
        loadSpec(dir / "bad.json");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("bad.json: invalid JSON at byte"), std::string::npos) << e.what();
    }
    EXPECT_THROW(loadSpec(dir / "missing.json"), Error);
    // Relative inputs are found beside the spec.
    std::filesystem::copy_file(std::filesystem::path(GI_PRESET_DIR) / "basic.json", dir / "mine.json");
    std::ofstream(dir / "good.json") << R"({"scenes": ["mine.json"], "cells": [{"technique": "none"}]})";
    MatrixSpec spec = loadSpec(dir / "good.json");
    EXPECT_EQ(spec.scenes[0].input, (dir / "mine.json").lexically_normal().string());
    EXPECT_EQ(spec.scenes[0].label, "mine");
}

CellResult result(const std::string& technique, double ssim, double ms, const std::string& status = "ok") {
    CellResult r;
    r.id = technique + std::to_string(ms);
    r.scene = "s";
    r.technique = technique;
    r.label = technique + " " + std::to_string(int(ms));
    r.status = status;
    r.ssim = ssim;
    r.msTotal = ms;
    r.folder = "cells/s/" + r.id;
    return r;
}

TEST(MatrixResults, ParetoFrontKeepsCellsNothingCheaperBeats) {
    std::vector<CellResult> r = {result("a", 0.80, 10), result("b", 0.70, 20), result("c", 0.90, 30), result("d", 0.85, 5),
                                 result("e", 0.99, 1, "failed"), result("f", 0.90, 40), result("g", 0.95, 50)};
    std::vector<size_t> front = paretoFront(r);
    // d (5 ms, 0.85) beats a (10 ms, 0.80) and b; c improves on d; f ties c but costs more; g improves.
    EXPECT_EQ(front, (std::vector<size_t>{3, 2, 6}));
    EXPECT_TRUE(paretoFront({}).empty());
}

TEST(MatrixResults, JsonRoundTripAndCSVQuoting) {
    CellResult r = result("lpv", 0.75, 12.5);
    r.label = "LPV \"big\", 64";
    r.settings = {"lpv.gridResolution=64", "camera.eye=[1,2,3]"};
    r.passMs = {{"lpv.propagate", 10.0}, {"shade", 2.5}};
    r.paperScore = 7.1;
    r.error = "";
    CellResult back = resultFromJson(resultToJson(r), "x");
    EXPECT_EQ(back.label, r.label);
    EXPECT_EQ(back.settings, r.settings);
    EXPECT_EQ(back.passMs, r.passMs);
    ASSERT_TRUE(back.paperScore.has_value());
    EXPECT_DOUBLE_EQ(*back.paperScore, 7.1);
    std::string csv = resultsCSV({r});
    EXPECT_NE(csv.find("\"LPV \"\"big\"\", 64\""), std::string::npos) << csv;
    EXPECT_NE(csv.find("\"lpv.gridResolution=64;camera.eye=[1,2,3]\""), std::string::npos) << csv;
    EXPECT_NE(csv.find("lpv.propagate=10;shade=2.5"), std::string::npos) << csv;
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 2) << "a header and one row";
    EXPECT_THROW(resultFromJson(json::parse(R"({"id": "x"})"), "r.json"), Error);
}

TEST(MatrixReport, MarksTheBestCellOfEachTechniqueAndEscapes) {
    std::vector<CellResult> r = {result("lpv", 0.80, 10), result("lpv", 0.85, 20), result("vct", 0.83, 30),
                                 result("vct", 0.0, 0, "timeout")};
    r[0].label = "<script>alert(1)</script>";
    r[3].error = "timed out after 5 s (killed)";
    std::string html = reportHTML("t", r);
    EXPECT_EQ(html.find("<script>alert(1)"), std::string::npos) << "labels are escaped";
    EXPECT_NE(html.find("&lt;script&gt;alert(1)"), std::string::npos);
    auto rowOf = [&](const std::string& id) {
        size_t at = html.find("data-id=\"" + id + "\"");
        return html.substr(html.rfind("<tr", at), at - html.rfind("<tr", at));
    };
    EXPECT_NE(rowOf(r[1].id).find("best"), std::string::npos);
    EXPECT_EQ(rowOf(r[0].id).find("best"), std::string::npos);
    EXPECT_NE(rowOf(r[2].id).find("best"), std::string::npos);
    EXPECT_NE(rowOf(r[3].id).find("failed"), std::string::npos);
    EXPECT_NE(html.find("timed out after 5 s"), std::string::npos);
    size_t rows = 0;
    for (size_t at = html.find("<tr class=\"cell"); at != std::string::npos; at = html.find("<tr class=\"cell", at + 1)) ++rows;
    EXPECT_EQ(rows, r.size());
    // The plot: one point per finished cell, the front ringed.
    std::string svg = paretoSVG(r);
    size_t points = 0;
    for (size_t at = svg.find("<circle cx"); at != std::string::npos; at = svg.find("<circle cx", at + 1)) ++points;
    EXPECT_EQ(points, 3u + 2u) << "three cells and two legend dots";
}

// A cell that costs nothing on the axis (technique none's GI passes) sits at the left edge of a
// padded linear axis; the ms ticks start at 0, not below it (the report once read "-8.68").
TEST(MatrixReport, NoTickNamesANegativeTime) {
    std::vector<CellResult> r = {result("none", 0.80, 8), result("vct", 0.86, 41), result("diffusion", 0.84, 25)};
    r[0].msGI = 0.0;
    r[1].msGI = 30.0;
    r[2].msGI = 15.0;
    for (CostAxis axis : {CostAxis::GI, CostAxis::Frame}) {
        std::string svg = paretoSVG(r, axis);
        size_t ticks = 0;
        for (size_t at = svg.find("text-anchor=\"middle\">"); at != std::string::npos; at = svg.find("text-anchor=\"middle\">", at + 1)) {
            std::string label = svg.substr(at + 21, svg.find('<', at) - at - 21);
            if (label.empty() || !(std::isdigit(static_cast<unsigned char>(label[0])) || label[0] == '-')) continue;  // the axis title
            ++ticks;
            EXPECT_NE(label[0], '-') << "tick " << label << (axis == CostAxis::GI ? " on the GI axis" : " on the frame axis");
        }
        EXPECT_EQ(ticks, 5u);
    }
}

TEST(MatrixProcess, TimeoutsCrashesAndFailuresAreReportedNotThrown) {
    std::filesystem::path dir = test::tempDir();
    ProcessResult ok = runProcess("/bin/sh", {"-c", "echo fine"}, dir / "ok.txt", 10.0);
    EXPECT_TRUE(ok.ok());
    EXPECT_EQ(lastLine(dir / "ok.txt"), "fine");

    ProcessResult slow = runProcess("/bin/sh", {"-c", "sleep 30"}, dir / "slow.txt", 0.3);
    EXPECT_TRUE(slow.timedOut);
    EXPECT_LT(slow.seconds, 5.0) << "killed at the limit, not waited for";
    EXPECT_NE(failureText(slow, dir / "slow.txt", 0.3).find("timed out after 0.3 s"), std::string::npos);

    ProcessResult crash = runProcess("/bin/sh", {"-c", "echo about to crash; kill -SEGV $$"}, dir / "crash.txt", 10.0);
    EXPECT_EQ(crash.signal, 11);
    EXPECT_NE(failureText(crash, dir / "crash.txt", 10.0).find("crashed (signal 11"), std::string::npos);
    EXPECT_NE(failureText(crash, dir / "crash.txt", 10.0).find("about to crash"), std::string::npos);

    ProcessResult bad = runProcess("/bin/sh", {"-c", "echo 'gi-render: key x: unknown' >&2; exit 1"}, dir / "bad.txt", 10.0);
    EXPECT_EQ(bad.exitCode, 1);
    EXPECT_EQ(failureText(bad, dir / "bad.txt", 10.0), "exit 1: gi-render: key x: unknown");

    ProcessResult missing = runProcess(dir / "no-such-program", {}, dir / "missing.txt", 10.0);
    EXPECT_FALSE(missing.started);
    EXPECT_NE(failureText(missing, dir / "missing.txt", 10.0).find("cannot run"), std::string::npos);

    std::atomic<bool> cancel{true};
    ProcessResult cancelled = runProcess("/bin/sh", {"-c", "sleep 30"}, dir / "c.txt", 60.0, &cancel);
    EXPECT_TRUE(cancelled.cancelled);
}

// Every spec shipped in presets/matrix loads and expands, and the scenes it keeps in the
// repository (not those under ../shared) load with a light and a camera of their own, as its
// cells render them with no preset. A spec that names ../shared's scenes loads only where they
// are (loadSpec refuses a missing asset); elsewhere it must still be valid JSON.
TEST(MatrixSpec, ShippedSpecsLoadAndTheirOwnScenesToo) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::path(GI_PRESET_DIR) / "matrix";
    const fs::path shared = fs::weakly_canonical(GI_SHARED_DIR);
    auto underShared = [&](const fs::path& p) {
        fs::path q = fs::weakly_canonical(p);
        return std::mismatch(shared.begin(), shared.end(), q.begin(), q.end()).first == shared.end();
    };
    int specs = 0, scenes = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (entry.path().extension() != ".json") continue;
        ++specs;
        json j = json::parse(std::ifstream(entry.path()));
        bool needsShared = false;
        for (const json& s : j.value("scenes", json::array()))
            if (s.is_object() && underShared(dir / s.value("input", std::string()))) needsShared = true;
        if (needsShared && !fs::exists(shared / "scenes")) continue;
        MatrixSpec spec = loadSpec(entry.path());
        EXPECT_FALSE(expandCells(spec).empty()) << entry.path();
        for (const SceneSpec& s : spec.scenes) {
            if (s.input.empty() || underShared(s.input)) continue;
            ++scenes;
            ASSERT_TRUE(fs::exists(s.input)) << entry.path() << ": " << s.input;
            if (fs::path(s.input).extension() != ".gltf") continue;
            Scene scene = loadGLTF(s.input);
            EXPECT_FALSE(scene.indices.empty()) << s.input;
            EXPECT_FALSE(scene.lights.empty()) << s.input << ": no light of its own";
            EXPECT_FALSE(scene.framedCamera) << s.input << ": no camera of its own";
        }
    }
    EXPECT_GE(specs, 5);
    EXPECT_GE(scenes, 5) << "presets/matrix/rooms";
}

}  // namespace
}  // namespace gi
