#include "gi/matrix/process.h"

#include <chrono>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <spawn.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

extern char** environ;

namespace gi::matrix {

ProcessResult runProcess(const std::filesystem::path& program, const std::vector<std::string>& args,
                         const std::filesystem::path& logPath, double timeoutSeconds, const std::atomic<bool>* cancel) {
    ProcessResult r;
    std::vector<std::string> argv{program.string()};
    argv.insert(argv.end(), args.begin(), args.end());
    std::vector<char*> cargv;
    for (std::string& a : argv) cargv.push_back(a.data());
    cargv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    std::string log = logPath.string();
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attr, 0);  // its own group, so a kill reaches its children too

    auto start = std::chrono::steady_clock::now();
    pid_t pid = -1;
    int err = posix_spawn(&pid, cargv[0], &actions, &attr, cargv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attr);
    if (err != 0) {
        std::ofstream(logPath) << "cannot run " << program.string() << ": " << std::strerror(err) << "\n";
        return r;
    }
    r.started = true;
    int status = 0;
    for (;;) {
        pid_t w = waitpid(pid, &status, WNOHANG);
        if (w == pid) break;
        if (w < 0 && errno != EINTR) break;
        double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        bool stop = cancel && cancel->load();
        if (elapsed > timeoutSeconds || stop) {
            kill(-pid, SIGKILL);
            kill(pid, SIGKILL);
            while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
            r.timedOut = !stop;
            r.cancelled = stop;
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (r.timedOut || r.cancelled) return r;
    if (WIFEXITED(status)) r.exitCode = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
    return r;
}

std::string lastLine(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return "";
    in.seekg(0, std::ios::end);
    std::streamoff size = in.tellg();
    std::streamoff from = size > 65536 ? size - 65536 : 0;
    in.seekg(from);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    size_t end = text.find_last_not_of(" \t\r\n");
    if (end == std::string::npos) return "";
    size_t begin = text.find_last_of("\r\n", end);
    return text.substr(begin == std::string::npos ? 0 : begin + 1, end + 1 - (begin == std::string::npos ? 0 : begin + 1));
}

std::string failureText(const ProcessResult& r, const std::filesystem::path& logPath, double timeoutSeconds) {
    char buf[128];
    if (!r.started) return lastLine(logPath);
    if (r.timedOut) {
        std::snprintf(buf, sizeof buf, "timed out after %g s (killed)", timeoutSeconds);
        return buf;
    }
    if (r.cancelled) return "cancelled";
    if (r.signal != 0) {
        std::snprintf(buf, sizeof buf, "crashed (signal %d: %s)", r.signal, strsignal(r.signal));
        std::string tail = lastLine(logPath);
        return tail.empty() ? buf : std::string(buf) + "; last output: " + tail;
    }
    std::snprintf(buf, sizeof buf, "exit %d", r.exitCode);
    std::string tail = lastLine(logPath);
    return tail.empty() ? buf : std::string(buf) + ": " + tail;
}

}  // namespace gi::matrix
