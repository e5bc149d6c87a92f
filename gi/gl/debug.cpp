#include "gi/gl/debug.h"

#include <atomic>
#include <cstdio>

namespace gi::gl {

static std::atomic<uint64_t> gErrorCount{0};

static void GLAPIENTRY onDebugMessage(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei,
                                      const GLchar* message, const void*) {
    if (type == GL_DEBUG_TYPE_PUSH_GROUP || type == GL_DEBUG_TYPE_POP_GROUP) return;
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
    // Compiler diagnostics are bad input, not GL misuse: Program reports them as gi::Error with
    // the file and line, so they are neither printed nor counted here.
    if (source == GL_DEBUG_SOURCE_SHADER_COMPILER) return;
    if (type == GL_DEBUG_TYPE_ERROR) ++gErrorCount;
    const char* kind = type == GL_DEBUG_TYPE_ERROR ? "error"
                       : type == GL_DEBUG_TYPE_PERFORMANCE ? "performance"
                       : type == GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR ? "deprecated"
                       : type == GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR ? "undefined behaviour"
                                                                   : "message";
    // Performance notes from llvmpipe are frequent and harmless; only print them on errors' level.
    if (type == GL_DEBUG_TYPE_PERFORMANCE || type == GL_DEBUG_TYPE_OTHER) return;
    std::fprintf(stderr, "GL %s %u: %s\n", kind, id, message);
}

void installDebugOutput() {
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(onDebugMessage, nullptr);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
}

uint64_t debugErrorCount() { return gErrorCount.load(); }

}  // namespace gi::gl
