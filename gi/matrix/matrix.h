// The comparison matrix (issue 15): which technique, with which settings, gives the best picture
// on a scene for its cost. A spec (JSON) names scenes, technique variants and sweeps; every cell
// of the product is one gi-render run (its own process, so a crash or a hang fails that cell
// only), scored against the path-traced reference; the results are one row per cell in CSV and
// JSON and a static HTML report (report.h).
//
// The spec, with every key but "scenes" and "cells" optional:
//
//   { "name": "smoke",
//     "width": 64, "height": 48,      image size of every cell
//     "frames": 3,                    frames rendered; stats are the last frame's (steady state)
//     "spp": 256,                     samples per pixel of each scene's reference
//     "timeoutSeconds": 600,          a cell still running after this is killed and fails
//     "scenes": [ "presets/basic.json",
//                 { "input": "scene.gltf", "label": "engine", "camera": 0,
//                   "set": { "camera.fovY": 50 } } ],
//     "cells": [ { "technique": "none" },
//                { "technique": "lpv", "label": "LPV 32", "set": { "lpv.gridResolution": 32 } },
//                { "technique": "vct", "sweep": { "vct.gridResolution": [32, 64],
//                                                 "vct.nudge": { "from": 1, "to": 4, "step": 1 } } },
//                { "technique": "*" } ] }
//
// Paths are relative to the spec's folder (or absolute); "" or "default" is the built-in default
// preset. A cell's "technique" "*" stands for every registered technique, so a new technique
// joins a matrix with no change here. "sweep" takes lists or {from, to, step} ranges and expands
// to their product. "scenes" ([labels]) limits a variant to some scenes. "paperScores" ({scene
// label: number}) puts a published score beside the cell, and the report ranks against it.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace gi::matrix {

struct SceneSpec {
    std::string label;              // unique within the spec; names the scene in results and folders
    std::string input;              // absolute preset or glTF path, or "" for the built-in default
    int camera = -1;                // the glTF file's camera (-1: its first, or a framing)
    std::vector<std::string> set;   // key=value overrides for every cell of this scene
};

struct Sweep {
    std::string key;
    std::vector<std::string> values;  // as --set writes them
};

struct VariantSpec {
    std::string technique;          // a technique name, or "*" for each registered one
    std::string label;              // shown in the report; default: the technique and its overrides
    std::vector<std::string> set;   // key=value overrides
    std::vector<Sweep> sweeps;      // expanded to their product
    std::map<std::string, double> paperScores;  // scene label -> published score
    std::vector<std::string> scenes;            // the scene labels it runs on; empty: every scene
};

struct MatrixSpec {
    std::string name = "matrix";
    std::filesystem::path file;     // where it was read (empty when built in code)
    int width = 128, height = 96;
    int frames = 3;
    int spp = 256;
    double timeoutSeconds = 600.0;
    std::vector<SceneSpec> scenes;
    std::vector<VariantSpec> variants;
};

// One render: a scene, a technique and the overrides of its variant and sweep point.
struct Cell {
    std::string id;                 // stable: the label's slug and a hash of everything the render depends on
    size_t scene = 0;               // index into MatrixSpec::scenes
    std::string sceneLabel;
    std::string technique;
    std::string label;
    std::vector<std::string> set;   // the variant's overrides and its sweep point (not the scene's)
    std::optional<double> paperScore;
};

// Throws gi::Error naming the file and key for malformed specs, unknown settings keys (with the
// valid range or the nearest key, as presets do), duplicate scene labels and empty products.
MatrixSpec specFromJson(const nlohmann::json& j, const std::string& context,
                        const std::filesystem::path& folder = {});
MatrixSpec loadSpec(const std::filesystem::path& path);

// One cell: its id hashes the scene (input, camera, overrides), the technique, `set` and the
// spec's image size, frames and samples, so equal renders share a folder and --resume finds them.
Cell makeCell(const MatrixSpec& spec, size_t sceneIndex, const std::string& technique, const std::string& label,
              const std::vector<std::string>& set);

// Every cell of the spec, scene by scene, in spec order. Refused past kMaxCells.
constexpr size_t kMaxCells = 100000;
std::vector<Cell> expandCells(const MatrixSpec& spec);

// The i-th of n disjoint slices (cells whose index modulo n is i, so slow scenes spread over the
// slices); together they hold every cell once. Throws gi::Error unless 0 <= i < n.
std::vector<Cell> shardOf(const std::vector<Cell>& cells, int i, int n);
// "i/n" as --shard takes it; throws gi::Error naming the text otherwise.
std::pair<int, int> parseShard(const std::string& text);

// gi-render's arguments for a cell (after the program name), writing into `outDir`.
std::vector<std::string> renderArguments(const MatrixSpec& spec, const Cell& cell, const std::filesystem::path& outDir);

// What one cell gave: read back from its folder's result.json.
struct CellResult {
    std::string id;
    std::string scene, technique, label;
    std::vector<std::string> settings;   // the cell's overrides
    std::string status;                  // "ok", "failed" or "timeout"
    std::string error;                   // the failure's last line of output
    double ssim = 0, score = 0, rmse = 0, psnr = 0, brightness = 0, leakFraction = 0, leakEnergy = 0;
    double msTotal = 0;                  // the frame: the median of the frames after the first, passes added up
    double msGI = 0;                     // the technique's own passes (named "technique.*"), last frame
    std::vector<std::pair<std::string, double>> passMs;
    double memoryBytes = 0;
    std::string renderer;
    double wallSeconds = 0;              // the whole gi-render process, reference included
    std::optional<double> paperScore;
    std::string folder;                  // relative to the results' folder: image.png and the maps
    bool ok() const { return status == "ok"; }
};

// A result that names the cell (id, scene, technique, label, settings, paper score) and has
// `status`, its figures still zero.
CellResult resultOf(const Cell& cell, const std::string& status);

nlohmann::json resultToJson(const CellResult& r);
CellResult resultFromJson(const nlohmann::json& j, const std::string& context);

// The result of a finished gi-render run: its stats.json's metrics and passes. Throws gi::Error
// when stats.json is missing or holds no metrics.
CellResult resultFromStats(const Cell& cell, const std::filesystem::path& cellDir);

// Every result.json under `dir`/cells, sorted by scene, then technique, then label.
std::vector<CellResult> collectResults(const std::filesystem::path& dir);

// The cells the folder's report lists: collectResults, less the cells its results.json does not
// name (an earlier spec's, left on disk); every cell when there is no results.json yet.
std::vector<CellResult> reportedResults(const std::filesystem::path& dir);

// results.csv (RFC 4180 quoting) and results.json.
std::string resultsCSV(const std::vector<CellResult>& results);
nlohmann::json resultsJSON(const std::vector<CellResult>& results);

// What a cell costs on a plot's x axis: the whole frame (what a budget is about), or the GI
// technique's own passes (on llvmpipe a large scene's raster, shadows and G-buffer, can be most
// of the frame and its noise hides the GI's cost).
enum class CostAxis { Frame, GI };
double costOf(const CellResult& r, CostAxis axis);

// Indices of the Pareto front among `results` (ok cells only): no other cell has a higher SSIM
// for no more ms (ties: the cheaper, then the first). Sorted by ms.
std::vector<size_t> paretoFront(const std::vector<CellResult>& results, CostAxis axis = CostAxis::Frame);

// Spearman's rank correlation of two lists (ties share their mean rank); NaN for fewer than two
// values or a constant list. The report ranks the cells' SSIM against a paper's scores with it.
double spearman(const std::vector<double>& a, const std::vector<double>& b);

// A name safe as a folder: letters, digits, '-', '_' and '.', the rest as '_'.
std::string slug(const std::string& text);

}  // namespace gi::matrix
