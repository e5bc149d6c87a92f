// Runs the cells of a matrix, one gi-render process each (process.h), into DIR/cells/SCENE/ID/,
// each cell's result.json written atomically when it ends, so an interrupted run resumes where
// it stopped.
#pragma once

#include "gi/matrix/matrix.h"

#include <atomic>
#include <filesystem>
#include <functional>

namespace gi::matrix {

struct RunProgress {
    size_t index = 0, total = 0;      // the cell just finished (1-based) of this run's cells
    size_t done = 0, failed = 0, skipped = 0;
    double elapsedSeconds = 0.0;
    double remainingSeconds = -1.0;   // from the mean time of the cells run so far; -1 before any
    const CellResult* result = nullptr;
    bool wasSkipped = false;          // resumed: the cell was done before
};

struct RunOptions {
    std::filesystem::path renderer;   // the gi-render executable
    std::filesystem::path outDir;
    bool resume = false;              // skip cells whose result.json says ok
    std::function<void(const RunProgress&)> progress;
    const std::atomic<bool>* cancel = nullptr;
};

std::filesystem::path cellFolder(const std::filesystem::path& outDir, const Cell& cell);

// Runs one cell and writes its result.json (also for a failure, which it records, not throws).
CellResult runCell(const MatrixSpec& spec, const Cell& cell, const RunOptions& options);

struct RunSummary {
    size_t done = 0, failed = 0, skipped = 0;
    double seconds = 0.0;
};
RunSummary runCells(const MatrixSpec& spec, const std::vector<Cell>& cells, const RunOptions& options);

// An executable beside this process's own (gi-render beside gi-matrix or gi-editor: the build
// tree and an install keep them together); the bare name when that cannot be told.
std::filesystem::path siblingExecutable(const std::string& name);

// "1m05s", "42s", "2h03m".
std::string formatDuration(double seconds);

}  // namespace gi::matrix
