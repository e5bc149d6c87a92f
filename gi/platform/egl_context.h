// A headless OpenGL 4.5 core context through EGL surfaceless (Mesa llvmpipe works with no GPU
// and no X server). The context is made current on construction.
#pragma once

#include <string>

namespace gi {

class EGLContextHeadless {
public:
    // Throws gi::Error naming the EGL call that failed.
    explicit EGLContextHeadless(bool debug = true);
    ~EGLContextHeadless();
    EGLContextHeadless(const EGLContextHeadless&) = delete;
    EGLContextHeadless& operator=(const EGLContextHeadless&) = delete;

    std::string renderer() const;
    // Makes the context current on the calling thread (any thread), or leaves the thread with no
    // EGL context. Throws gi::Error when EGL refuses.
    void makeCurrent() const;
    void release() const;

private:
    void* mDisplay = nullptr;
    void* mContext = nullptr;
};

// The GL_RENDERER and GL_VERSION strings of the current context.
std::string glRendererString();

}  // namespace gi
