// Auto-tune (issue 15 item 5): the settings of one technique that give the best SSIM against the
// reference while the measured frame time stays within a budget.
//
// The space: the technique's artist settings (not the developer ones) from the settings table,
// each as an ordered ladder of values around its default: integers with a wide range on powers
// of two (gridResolution 32: 8, 16, 32, 64, 128), small integer ranges whole (bounces 1..4),
// floats at x0.25, x0.5, x0.71, x1, x1.41, x2, x4 of the default, bools and enums every value;
// "the default" is the scene preset's value where it sets one. Floats at 0 (meaning
// "automatic") are left alone.
//
// The search is a coordinate pattern search: from the defaults, each sweep walks every ladder
// from the current best, one step at a time while that improves it, up first (down first while
// the best is over the budget) and the other way if the first step did not improve; an enum or
// bool tries every other value; it ends when a sweep improves nothing or the
// renders run out. "Better" is lexicographic: within the budget beats over it; within it, higher
// SSIM (by kTuneCostlyGain when it costs more); over it, lower ms (so a start over budget first
// walks down in cost). Each render is a
// matrix cell (run.h), so a repeated point is not rendered twice and an interrupted tune resumes.
//
// The baseline it is compared with (tuneGrid): a grid over the same ladders: the first ladders
// (table order) at their lowest, default and highest value, as many as keep the product within
// the renders, the rest at their defaults. It may use fewer renders than allowed (LPV: 18 of
// 27); compare the search at the grid's count.
#pragma once

#include "gi/matrix/matrix.h"
#include "gi/matrix/run.h"

#include <functional>
#include <optional>

namespace gi::matrix {

struct TuneParameter {
    std::string key;
    std::vector<std::string> values;  // ordered (enums in table order)
    size_t start = 0;                 // the default's index
    bool ordered = true;              // false for enums and bools: try every other value
};

// The ladders of `technique`'s artist settings, each around its value in `base` (presetToJson of
// the scene's preset: the search starts from what the scene already uses), or its default.
std::vector<TuneParameter> tuneSpace(const std::string& technique, const nlohmann::json& base = nullptr);

struct TuneStep {
    size_t render = 0;                // 1-based
    bool reused = false;              // read from an earlier run's cell folder, not rendered now
    std::vector<std::string> settings;
    std::string change;               // "lpv.gridResolution 32 -> 16", "defaults"
    CellResult result;
    bool withinBudget = false;
    bool best = false;                // the best so far after this step
};

struct TuneReport {
    std::vector<TuneStep> steps;
    std::optional<TuneStep> best;
    size_t renders = 0;               // points evaluated, rendered now or reused
    size_t reused = 0;                // of them, read from earlier runs in the output folder
    std::string method;               // "pattern search" or "grid"
};

struct TuneOptions {
    std::string technique;
    nlohmann::json base;              // presetToJson of the scene's preset (the starting point)
    double budgetMs = 0.0;
    size_t maxRenders = 24;
    RunOptions run;                   // where the renders go, the renderer, cancellation
    // Renders one point; empty: runCell (a gi-render process). Tests hand in a model.
    std::function<CellResult(const MatrixSpec&, const Cell&, const RunOptions&)> render;
    std::function<void(const TuneReport&)> progress;  // after every render
};

// The SSIM a point must gain over the best so far: any gain at no more cost, and at least
// kTuneCostlyGain when it costs more (below that, llvmpipe's timing noise and a fourth-decimal
// SSIM difference would trade real milliseconds for nothing visible).
inline constexpr double kTuneGain = 1e-5;
inline constexpr double kTuneCostlyGain = 1e-3;

// True when a beats b in the order above.
bool tuneBetter(const CellResult& a, const CellResult& b, double budgetMs);

TuneReport tunePatternSearch(const MatrixSpec& spec, const TuneOptions& options);
TuneReport tuneGrid(const MatrixSpec& spec, const TuneOptions& options);

nlohmann::json tuneReportToJson(const TuneReport& r, double budgetMs);

}  // namespace gi::matrix
