// Errors for bad input (files, preset keys, shaders). Programming errors use GI_ASSERT instead.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace gi {

// Thrown for bad input. The message is one line that names the file, key or shader at fault.
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// A tool's main(): runs `run`, turning any exception into one line "tool: message" and exit 1.
template <class F>
int reportErrors(const char* tool, F&& run) {
    try {
        return run();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", tool, e.what());
        return 1;
    }
}

}  // namespace gi

#define GI_ASSERT(cond, reason)                                                              \
    do {                                                                                      \
        if (!(cond)) {                                                                        \
            std::fprintf(stderr, "%s:%d: assertion '%s' failed: %s\n", __FILE__, __LINE__, #cond, \
                         reason);                                                             \
            std::abort();                                                                     \
        }                                                                                     \
    } while (0)
