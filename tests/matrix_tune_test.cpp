// Auto-tune (gi/matrix/tune.h): the search space from the settings table, the order of results,
// the pattern search and the grid baseline on a model of a technique (no rendering), and one real
// tune through gi-matrix.
#include "gi/matrix/tune.h"
#include "gi/preset/preset.h"
#include "gi/util/paths.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>

namespace gi {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace gi::matrix;

const TuneParameter* find(const std::vector<TuneParameter>& space, const std::string& key) {
    for (const TuneParameter& p : space)
        if (p.key == key) return &p;
    return nullptr;
}

TEST(MatrixTune, SpaceIsTheArtistSettingsAroundTheScenesValues) {
    std::vector<TuneParameter> space = tuneSpace("lpv");
    const TuneParameter* grid = find(space, "lpv.gridResolution");
    ASSERT_NE(grid, nullptr);
    EXPECT_EQ(grid->values, (std::vector<std::string>{"8", "16", "32", "64", "128"}));
    EXPECT_EQ(grid->values[grid->start], "32") << "the default";
    EXPECT_TRUE(grid->ordered);
    const TuneParameter* bounces = find(space, "lpv.bounces");
    ASSERT_NE(bounces, nullptr);
    EXPECT_EQ(bounces->values, (std::vector<std::string>{"1", "2", "3", "4"})) << "a small range whole";
    const TuneParameter* occlusion = find(space, "lpv.occlusion");
    ASSERT_NE(occlusion, nullptr);
    EXPECT_FALSE(occlusion->ordered);
    EXPECT_EQ(find(space, "lpv.nudge"), nullptr) << "developer settings are not tuned";
    EXPECT_EQ(find(space, "lpv.cascadeExtent"), nullptr) << "0 means automatic";
    EXPECT_EQ(find(space, "vct.gridResolution"), nullptr) << "only the technique's own section";
    const TuneParameter* intensity = find(space, "lpv.intensity");
    ASSERT_NE(intensity, nullptr);
    EXPECT_EQ(intensity->values, (std::vector<std::string>{"0.25", "0.5", "0.7071", "1", "1.414", "2", "4"}));

    // Around the preset's value.
    Preset p = builtinDefaultPreset();
    applySetting(p, "lpv.gridResolution=16");
    applySetting(p, "lpv.intensity=2");
    applySetting(p, "lpv.occlusion=false");
    std::vector<TuneParameter> fromPreset = tuneSpace("lpv", presetToJson(p));
    grid = find(fromPreset, "lpv.gridResolution");
    ASSERT_NE(grid, nullptr);
    EXPECT_EQ(grid->values[grid->start], "16");
    EXPECT_EQ(grid->values.front(), "4");
    const TuneParameter* scaled = find(fromPreset, "lpv.intensity");
    ASSERT_NE(scaled, nullptr);
    EXPECT_EQ(scaled->values[scaled->start], "2") << "a float from the preset";
    EXPECT_EQ(scaled->values.back(), "8");
    occlusion = find(fromPreset, "lpv.occlusion");
    ASSERT_NE(occlusion, nullptr);
    EXPECT_EQ(occlusion->values[occlusion->start], "false");

    std::vector<TuneParameter> vct = tuneSpace("vct");
    const TuneParameter* mode = find(vct, "vct.mode");
    ASSERT_NE(mode, nullptr);
    EXPECT_EQ(mode->values, (std::vector<std::string>{"dense", "cascaded", "clipmap"}));
    EXPECT_TRUE(tuneSpace("none").empty());
}

CellResult made(double ssim, double ms, const char* status = "ok") {
    CellResult r;
    r.status = status;
    r.ssim = ssim;
    r.msTotal = ms;
    return r;
}

TEST(MatrixTune, WithinTheBudgetBeatsOverItThenSSIMThenCost) {
    EXPECT_TRUE(tuneBetter(made(0.5, 90), made(0.9, 110), 100));
    EXPECT_TRUE(tuneBetter(made(0.9, 90), made(0.8, 10), 100));
    EXPECT_FALSE(tuneBetter(made(0.8, 10), made(0.8, 90), 100)) << "equal SSIM is no improvement";
    EXPECT_TRUE(tuneBetter(made(0.8001, 10), made(0.8, 90), 100)) << "any gain at less cost";
    EXPECT_FALSE(tuneBetter(made(0.8005, 95), made(0.8, 90), 100)) << "a costlier point must gain kTuneCostlyGain";
    EXPECT_TRUE(tuneBetter(made(0.8015, 95), made(0.8, 90), 100));
    EXPECT_TRUE(tuneBetter(made(0.1, 150), made(0.9, 200), 100)) << "over budget: cheaper is better";
    EXPECT_FALSE(tuneBetter(made(0.99, 1, "failed"), made(0.1, 500), 100));
    EXPECT_TRUE(tuneBetter(made(0.1, 500), made(0.99, 1, "failed"), 100));
}

// A model of LPV: SSIM peaks at gridResolution 16 and propagationSteps 64; ms grows with both.
struct Model {
    size_t renders = 0;
    CellResult operator()(const MatrixSpec&, const Cell& cell, const RunOptions&) {
        ++renders;
        std::map<std::string, double> v = {{"lpv.gridResolution", 32}, {"lpv.propagationSteps", 32}};
        for (const std::string& s : cell.set) {
            size_t eq = s.find('=');
            if (v.count(s.substr(0, eq))) v[s.substr(0, eq)] = std::stod(s.substr(eq + 1));
        }
        double g = std::log2(v["lpv.gridResolution"]), st = std::log2(v["lpv.propagationSteps"]);
        CellResult r = made(0.9 - 0.02 * (g - 4) * (g - 4) - 0.01 * (st - 6) * (st - 6),
                            std::pow(2.0, g) * std::pow(2.0, g) * std::pow(2.0, g) / 1000.0 * std::pow(2.0, st) / 8.0);
        r.id = cell.id;
        return r;
    }
};

TuneOptions modelOptions(Model& m, double budget, size_t renders) {
    TuneOptions o;
    o.technique = "lpv";
    o.budgetMs = budget;
    o.maxRenders = renders;
    o.run.outDir = test::tempDir();
    o.render = [&m](const MatrixSpec& s, const Cell& c, const RunOptions& r) { return m(s, c, r); };
    return o;
}

MatrixSpec oneScene() {
    return specFromJson(json::parse(R"({"scenes": ["default"], "cells": [{"technique": "lpv"}]})"), "tune");
}

std::string setting(const TuneStep& s, const std::string& key) {
    for (const std::string& a : s.settings)
        if (a.rfind(key + "=", 0) == 0) return a.substr(key.size() + 1);
    return "";
}

TEST(MatrixTune, PatternSearchFindsTheModelsOptimumWithinBudgetAndBeatsTheGrid) {
    MatrixSpec spec = oneScene();
    Model m;
    TuneReport r = tunePatternSearch(spec, modelOptions(m, 400.0, 27));
    ASSERT_TRUE(r.best.has_value());
    EXPECT_TRUE(r.best->withinBudget);
    EXPECT_EQ(setting(*r.best, "lpv.gridResolution"), "16");
    EXPECT_EQ(setting(*r.best, "lpv.propagationSteps"), "64");
    EXPECT_NEAR(r.best->result.ssim, 0.9, 1e-9);
    EXPECT_EQ(r.renders, m.renders) << "each point rendered once";
    EXPECT_LE(r.renders, 27u);
    EXPECT_EQ(r.steps.front().change, "defaults");

    // The grid: gridResolution x cascadeCount x propagationSteps at their lowest, default and
    // highest (cascadeCount's default is its lowest), 18 renders; the next ladder would pass 27.
    Model g;
    TuneReport grid = tuneGrid(spec, modelOptions(g, 400.0, 27));
    EXPECT_EQ(grid.renders, 18u);
    ASSERT_TRUE(grid.best.has_value());
    Model same;
    TuneReport matched = tunePatternSearch(spec, modelOptions(same, 400.0, grid.renders));
    ASSERT_TRUE(matched.best.has_value());
    EXPECT_LT(grid.best->result.ssim, matched.best->result.ssim) << "with as many renders, the grid's coarse levels miss the optimum";

    // A budget below the optimum's cost: the best point within it.
    Model tight;
    TuneReport t = tunePatternSearch(spec, modelOptions(tight, 30.0, 40));
    ASSERT_TRUE(t.best.has_value());
    EXPECT_TRUE(t.best->withinBudget);
    EXPECT_LE(t.best->result.msTotal, 30.0);
    for (const TuneStep& s : t.steps) {
        if (s.withinBudget) {
            EXPECT_LE(s.result.ssim, t.best->result.ssim + 1e-12);
        }
    }
}

TEST(MatrixTune, AStartOverBudgetWalksDownInCostAndTheRenderLimitHolds) {
    MatrixSpec spec = oneScene();
    Model m;
    TuneReport r = tunePatternSearch(spec, modelOptions(m, 2.0, 6));
    EXPECT_EQ(r.renders, 6u);
    ASSERT_TRUE(r.best.has_value());
    EXPECT_LT(r.best->result.msTotal, r.steps.front().result.msTotal) << "the defaults cost 512 ms";
    ASSERT_GE(r.steps.size(), 2u);
    EXPECT_EQ(r.steps[1].change, "lpv.gridResolution 32 -> 16") << "over the budget, down first";
    // Within it, up first.
    Model roomy;
    TuneReport u = tunePatternSearch(spec, modelOptions(roomy, 1e9, 2));
    ASSERT_EQ(u.steps.size(), 2u);
    EXPECT_EQ(u.steps[1].change, "lpv.gridResolution 32 -> 64");
}

TEST(MatrixTune, PointsFromAnEarlierRunAreReusedAndCountAsRenders) {
    // A model that leaves each point's result.json where runCell would.
    MatrixSpec spec = oneScene();
    Model m;
    TuneOptions o = modelOptions(m, 400.0, 12);
    o.run.resume = true;
    o.render = [&m](const MatrixSpec& s, const Cell& c, const RunOptions& r) {
        CellResult result = m(s, c, r);
        fs::create_directories(cellFolder(r.outDir, c));
        std::ofstream(cellFolder(r.outDir, c) / "result.json") << resultToJson(result).dump();
        return result;
    };
    TuneReport first = tunePatternSearch(spec, o);
    EXPECT_EQ(first.reused, 0u);
    EXPECT_EQ(first.renders, m.renders);
    // The same search again into the same folder: the same path and result, nothing rendered,
    // and every point counted.
    size_t rendered = m.renders;
    TuneReport again = tunePatternSearch(spec, o);
    EXPECT_EQ(m.renders, rendered);
    EXPECT_EQ(again.renders, first.renders);
    EXPECT_EQ(again.reused, again.renders);
    ASSERT_TRUE(again.best && first.best);
    EXPECT_EQ(again.best->settings, first.best->settings);
    for (const TuneStep& st : again.steps) EXPECT_TRUE(st.reused);
    // The grid into the same folder reuses the points it shares with the search, and they count.
    TuneReport grid = tuneGrid(spec, o);
    EXPECT_EQ(grid.renders, 6u) << "gridResolution x cascadeCount; propagationSteps would pass 12";
    EXPECT_GT(grid.reused, 0u) << "the defaults at least";
}

TEST(MatrixTune, GiMatrixTuneWritesTheWinningPresetAndItsPath) {
    fs::path out = test::tempDir() / "tune";
    test::CommandResult r = test::runCommand(std::string(GI_MATRIX_EXE) + " --tune " + GI_PRESET_DIR +
                                             "/lpv_cornell.json --technique lpv --budget-ms 100000 --renders 3 --width 32 --height 24"
                                             " --frames 2 --spp 16 --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("tune [3/3]"), std::string::npos) << r.output;
    json report = json::parse(readTextFile(out / "tune.json"));
    EXPECT_EQ(report["method"], "pattern search");
    EXPECT_EQ(report["steps"].size(), 3u);
    EXPECT_EQ(report["steps"][0]["change"], "defaults");
    Preset tuned = loadPreset(out / "tuned.json");
    EXPECT_EQ(tuned.header.technique.name, "lpv");
    EXPECT_TRUE(fs::exists(out / "index.html"));
    // Bad requests are one line naming what is wrong.
    r = test::runCommand(std::string(GI_MATRIX_EXE) + " --tune " + GI_PRESET_DIR + "/default.json --technique none --budget-ms 10 --out " +
                         out.string());
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("'none' has no settings to tune"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace gi
