#include "gi/platform/egl_context.h"

#include "gi/gl/debug.h"
#include "gi/platform/memory.h"
#include "gi/util/error.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstdio>

namespace gi {

static std::string eglErrorText() {
    char buf[32];
    std::snprintf(buf, sizeof buf, "0x%04x", eglGetError());
    return buf;
}

EGLContextHeadless::EGLContextHeadless(bool debug) {
    keepFreedMemory();  // llvmpipe frees and reallocates megabytes per draw (gi/platform/memory.h)
    if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless") &&
        !epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_base"))
        throw Error("EGL: no surfaceless platform (install libegl-mesa0)");
    // epoxy refuses the core eglGetPlatformDisplay until it knows the EGL version, so use the EXT.
    EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY) throw Error("EGL: eglGetPlatformDisplayEXT(surfaceless) failed " + eglErrorText());
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) throw Error("EGL: eglInitialize failed " + eglErrorText());
    if (!eglBindAPI(EGL_OPENGL_API)) throw Error("EGL: eglBindAPI(OpenGL) failed " + eglErrorText());

    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4,
                              EGL_CONTEXT_MINOR_VERSION, 5,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                              EGL_CONTEXT_OPENGL_DEBUG, debug ? EGL_TRUE : EGL_FALSE,
                              EGL_NONE};
    EGLContext ctx = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    if (ctx == EGL_NO_CONTEXT) {
        eglTerminate(display);
        throw Error("EGL: cannot create an OpenGL 4.5 core context " + eglErrorText());
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
        eglDestroyContext(display, ctx);
        eglTerminate(display);
        throw Error("EGL: eglMakeCurrent failed " + eglErrorText());
    }
    mDisplay = display;
    mContext = ctx;
    if (epoxy_gl_version() < 45) throw Error("EGL: context is OpenGL " + std::to_string(epoxy_gl_version()) + ", need 45");
    gl::installDebugOutput();
}

EGLContextHeadless::~EGLContextHeadless() {
    if (mDisplay) {
        eglMakeCurrent(mDisplay, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (mContext) eglDestroyContext(mDisplay, mContext);
        eglTerminate(mDisplay);
    }
}

std::string EGLContextHeadless::renderer() const { return glRendererString(); }

void EGLContextHeadless::makeCurrent() const {
    if (!eglMakeCurrent(mDisplay, EGL_NO_SURFACE, EGL_NO_SURFACE, mContext)) throw Error("EGL: eglMakeCurrent failed " + eglErrorText());
}

void EGLContextHeadless::release() const { eglMakeCurrent(mDisplay, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT); }

std::string glRendererString() {
    const char* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const char* v = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    return std::string(r ? r : "?") + " | " + (v ? v : "?");
}

}  // namespace gi
