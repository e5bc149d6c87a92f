// KHR_debug output: installed in every context. Errors are counted so tests can fail on them.
#pragma once

#include <epoxy/gl.h>

#include <cstdint>

namespace gi::gl {

// Installs the callback on the current context (synchronous output, so the count is exact).
void installDebugOutput();
// Number of GL_DEBUG_TYPE_ERROR messages seen since start.
uint64_t debugErrorCount();

// A named debug group for the scope's lifetime, so GL debuggers show the pass names.
class DebugGroup {
public:
    explicit DebugGroup(const char* name) { glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, name); }
    ~DebugGroup() { glPopDebugGroup(); }
    DebugGroup(const DebugGroup&) = delete;
    DebugGroup& operator=(const DebugGroup&) = delete;
};

}  // namespace gi::gl
