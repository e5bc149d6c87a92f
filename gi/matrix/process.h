// Runs a program as a child process with its output in a log file and a time limit, so a cell of
// the matrix that crashes or hangs fails alone (POSIX: posix_spawn, its own process group, killed
// whole at the limit).
#pragma once

#include <atomic>
#include <filesystem>
#include <string>
#include <vector>

namespace gi::matrix {

struct ProcessResult {
    int exitCode = -1;       // the exit status; -1 when it did not exit normally
    int signal = 0;          // the signal that ended it (a crash), else 0
    bool timedOut = false;   // killed at the time limit
    bool cancelled = false;  // killed because `cancel` was set
    bool started = false;    // false when the program could not be run at all
    double seconds = 0.0;
    bool ok() const { return started && !timedOut && !cancelled && signal == 0 && exitCode == 0; }
};

// Runs `program` with `args`; stdout and stderr go to `logPath` (truncated). Polls every 20 ms;
// past `timeoutSeconds`, or once `cancel` becomes true, kills the child's process group.
ProcessResult runProcess(const std::filesystem::path& program, const std::vector<std::string>& args,
                         const std::filesystem::path& logPath, double timeoutSeconds,
                         const std::atomic<bool>* cancel = nullptr);

// The last non-empty line of a text file (at most its last 64 KiB are read); "" if none.
std::string lastLine(const std::filesystem::path& path);

// One line saying why a run failed: "timed out after 12 s", "crashed (signal 11: ...)",
// "exit 1: <last line of its log>".
std::string failureText(const ProcessResult& r, const std::filesystem::path& logPath, double timeoutSeconds);

}  // namespace gi::matrix
