#include "gi/matrix/run.h"

#include "gi/matrix/process.h"
#include "gi/util/error.h"
#include "gi/util/paths.h"

#include <chrono>
#include <cmath>
#include <cstdio>

namespace gi::matrix {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path cellFolder(const fs::path& outDir, const Cell& cell) { return outDir / "cells" / slug(cell.sceneLabel) / cell.id; }

namespace {

bool doneBefore(const fs::path& folder) {
    std::error_code ec;
    fs::path p = folder / "result.json";
    if (!fs::is_regular_file(p, ec)) return false;
    try {
        return resultFromJson(json::parse(readTextFile(p, size_t(16) << 20)), p.string()).ok();
    } catch (const std::exception&) {
        return false;  // unreadable: run it again
    }
}

}  // namespace

CellResult runCell(const MatrixSpec& spec, const Cell& cell, const RunOptions& options) {
    fs::path folder = cellFolder(options.outDir, cell);
    fs::create_directories(folder);
    fs::remove(folder / "result.json");
    fs::remove(folder / "stats.json");
    fs::path log = folder / "log.txt";
    ProcessResult p = runProcess(options.renderer, renderArguments(spec, cell, folder), log, spec.timeoutSeconds, options.cancel);
    CellResult r;
    if (p.ok()) {
        try {
            r = resultFromStats(cell, folder);
        } catch (const Error& e) {
            r = resultOf(cell, "failed");
            r.error = e.what();
        }
    } else {
        r = resultOf(cell, p.timedOut ? "timeout" : p.cancelled ? "cancelled" : "failed");
        r.error = failureText(p, log, spec.timeoutSeconds);
    }
    r.wallSeconds = p.seconds;
    r.folder = fs::relative(folder, options.outDir).generic_string();
    if (!p.cancelled) writeFileAtomic(folder / "result.json", resultToJson(r).dump(2) + "\n");
    return r;
}

RunSummary runCells(const MatrixSpec& spec, const std::vector<Cell>& cells, const RunOptions& options) {
    RunSummary s;
    auto start = std::chrono::steady_clock::now();
    double ranSeconds = 0.0;
    size_t ran = 0;
    for (size_t i = 0; i < cells.size(); ++i) {
        if (options.cancel && options.cancel->load()) break;
        RunProgress p;
        CellResult r;
        if (options.resume && doneBefore(cellFolder(options.outDir, cells[i]))) {
            ++s.skipped;
            p.wasSkipped = true;
        } else {
            r = runCell(spec, cells[i], options);
            if (r.status == "cancelled") break;
            ++ran;
            ranSeconds += r.wallSeconds;
            if (r.ok())
                ++s.done;
            else
                ++s.failed;
            p.result = &r;
        }
        s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (options.progress) {
            p.index = i + 1;
            p.total = cells.size();
            p.done = s.done;
            p.failed = s.failed;
            p.skipped = s.skipped;
            p.elapsedSeconds = s.seconds;
            if (ran > 0) p.remainingSeconds = ranSeconds / double(ran) * double(cells.size() - i - 1);
            options.progress(p);
        }
    }
    s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return s;
}

fs::path siblingExecutable(const std::string& name) {
    std::error_code ec;
    fs::path self = fs::read_symlink("/proc/self/exe", ec);
    return ec ? fs::path(name) : self.parent_path() / name;
}

std::string formatDuration(double seconds) {
    char buf[32];
    long t = std::lround(std::max(seconds, 0.0));
    if (t < 60)
        std::snprintf(buf, sizeof buf, "%lds", t);
    else if (t < 3600)
        std::snprintf(buf, sizeof buf, "%ldm%02lds", t / 60, t % 60);
    else
        std::snprintf(buf, sizeof buf, "%ldh%02ldm", t / 3600, (t % 3600) / 60);
    return buf;
}

}  // namespace gi::matrix
