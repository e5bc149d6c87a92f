#include "ui/window.h"

#include "ui/input_queue.h"
#include "ui/texture_bridge.h"

#include "gi/gl/debug.h"
#include "gi/platform/egl_context.h"

// libepoxy must come before GLFW, which is told (GLFW_INCLUDE_NONE) not to pull in a GL header.
#include <epoxy/gl.h>
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <functional>
#include <iterator>
#include <string_view>

namespace gi::ui {

Window::Window(int width, int height, const char* title) : mKeys(std::make_unique<KeyEventQueue>()) {
    if (!glfwInit())
        throw NoDisplayError("no display available (set DISPLAY or use gi-render for headless rendering)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
    mWindow = glfwCreateWindow(width, height, title, nullptr, nullptr);
    if (!mWindow) {
        const char* reason = nullptr;
        glfwGetError(&reason);
        std::string message = std::string("cannot open an OpenGL 4.5 core window: ") + (reason ? reason : "unknown GLFW error");
        glfwTerminate();
        throw NoDisplayError(message);
    }
    glfwMakeContextCurrent(mWindow);
    mBridge = std::make_unique<TextureBridge>();
    setTextureBridge(mBridge.get());
    glfwSwapInterval(1);
    gl::installDebugOutput();

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    // No imgui.ini: the layout is the same on every start, so screenshots are reproducible.
    ImGui::GetIO().IniFilename = nullptr;
    ImGui::StyleColorsDark();
    // The backend's callbacks, except the key and character ones, which go through mKeys (ui/input_queue.h).
    ImGui_ImplGlfw_InitForOpenGL(mWindow, false);
    glfwSetWindowUserPointer(mWindow, this);
    glfwSetWindowFocusCallback(mWindow, ImGui_ImplGlfw_WindowFocusCallback);
    glfwSetCursorEnterCallback(mWindow, ImGui_ImplGlfw_CursorEnterCallback);
    glfwSetMouseButtonCallback(mWindow, ImGui_ImplGlfw_MouseButtonCallback);
    glfwSetScrollCallback(mWindow, ImGui_ImplGlfw_ScrollCallback);
    glfwSetCharCallback(mWindow, [](GLFWwindow* w, unsigned int c) {
        if (c != 0) static_cast<Window*>(glfwGetWindowUserPointer(w))->mKeys->push({0, 0, 0, 0, c});
    });
    glfwSetWindowRefreshCallback(mWindow, [](GLFWwindow* w) { static_cast<Window*>(glfwGetWindowUserPointer(w))->mDamaged = true; });
    glfwSetKeyCallback(mWindow, [](GLFWwindow* w, int key, int scancode, int action, int mods) {
        static_cast<Window*>(glfwGetWindowUserPointer(w))->mKeys->push({key, scancode, action, mods});
    });
    ImGui_ImplOpenGL3_Init("#version 450");
}

Window::~Window() {
    if (mGIContext) mGIContext->release();
    glfwMakeContextCurrent(mWindow);
    if (mBackgroundFBO) glDeleteFramebuffers(1, &mBackgroundFBO);
    setTextureBridge(nullptr);
    mBridge.reset();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(mWindow);
    mGIContext.reset();
    glfwTerminate();
}

void Window::createGIContext() {
    // EGL surfaceless, as gi-render's, with its own llvmpipe rasterizer.
    try {
        mGIContext = std::make_unique<EGLContextHeadless>(true);
    } catch (const std::exception& e) {
        throw NoDisplayError(std::string("cannot make the GI's OpenGL context: ") + e.what());
    }
}

void Window::bindGI(bool current) {
    if (current) {
        glfwMakeContextCurrent(nullptr);
        mGIContext->makeCurrent();
    } else {
        mGIContext->release();
    }
}

void Window::bindUI() {
    mGIContext->release();
    glfwMakeContextCurrent(mWindow);
}

void Window::drawBackground(unsigned texture, int width, int height) {
    int w, h;
    framebufferSize(w, h);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, w, h);
    glClearColor(0.08f, 0.08f, 0.09f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    if (!texture || width <= 0 || height <= 0) return;
    if (!mBackgroundFBO) glCreateFramebuffers(1, &mBackgroundFBO);
    // Attached every frame: a resized texture may reuse an old name.
    glNamedFramebufferTexture(mBackgroundFBO, GL_COLOR_ATTACHMENT0, texture, 0);
    glBlitNamedFramebuffer(mBackgroundFBO, 0, 0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

bool Window::shouldClose() const { return glfwWindowShouldClose(mWindow); }

double Window::beginFrame(double waitSeconds) {
    double waited = 0.0;
    if (waitSeconds > 0.0 && mKeys->pending() == 0) {
        const double start = glfwGetTime();
        glfwWaitEventsTimeout(waitSeconds);
        waited = glfwGetTime() - start;
    } else {
        glfwPollEvents();
    }
    // At most one press or release per key this frame; the rest wait for the next frames.
    mKeys->drain([&](const KeyEvent& e) {
        if (e.codepoint != 0) ImGui_ImplGlfw_CharCallback(mWindow, e.codepoint);
        else ImGui_ImplGlfw_KeyCallback(mWindow, e.key, e.scancode, e.action, e.mods);
    });
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    return waited;
}

void Window::wake() { glfwPostEmptyEvent(); }

namespace {
// Folds the bytes of a range into a running hash.
template <class T>
size_t hashInto(size_t seed, const T* data, size_t count) {
    size_t h = std::hash<std::string_view>{}(std::string_view(reinterpret_cast<const char*>(data), count * sizeof(T)));
    return seed ^ (h + 0x9e3779b97f4a7c15ull + (seed << 6) + (seed >> 2));
}
}  // namespace

bool Window::finishUI(unsigned background, int backgroundWidth, int backgroundHeight) {
    ImGui::Render();
    ImDrawData* data = ImGui::GetDrawData();
    mBridge->resolve(data);
    int width, height;
    framebufferSize(width, height);
    const uint64_t frame[] = {uint64_t(width), uint64_t(height), background, uint64_t(backgroundWidth),
                              uint64_t(backgroundHeight), mBridge->uploads()};
    size_t h = hashInto(0, frame, std::size(frame));
    for (int i = 0; data && i < data->CmdListsCount; ++i) {
        const ImDrawList* list = data->CmdLists[i];
        h = hashInto(h, list->VtxBuffer.Data, size_t(list->VtxBuffer.Size));
        h = hashInto(h, list->IdxBuffer.Data, size_t(list->IdxBuffer.Size));
        for (const ImDrawCmd& cmd : list->CmdBuffer) {
            const uint64_t c[] = {uint64_t(uintptr_t(cmd.TextureId)), cmd.VtxOffset, cmd.IdxOffset, cmd.ElemCount,
                                  uint64_t(uintptr_t(cmd.UserCallback))};
            h = hashInto(hashInto(h, c, std::size(c)), &cmd.ClipRect.x, 4);
        }
    }
    mFingerprint = h;
    return mDamaged || h != mPresented || glfwGetTime() - mPresentedAt > 1.0;
}

void Window::renderUI() {
    int width, height;
    framebufferSize(width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

std::vector<uint8_t> Window::readBackBuffer(int& width, int& height) const {
    framebufferSize(width, height);
    std::vector<uint8_t> pixels(size_t(width) * size_t(height) * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    // The back buffer: under Xvfb the front buffer reads back black.
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    // ImGui's blending leaves partial alpha in the window; a screenshot is opaque.
    for (size_t i = 3; i < pixels.size(); i += 4) pixels[i] = 255;
    return pixels;
}

void Window::swap() {
    glfwSwapBuffers(mWindow);
    mPresented = mFingerprint;
    mPresentedAt = glfwGetTime();
    mDamaged = false;
}

void Window::framebufferSize(int& width, int& height) const { glfwGetFramebufferSize(mWindow, &width, &height); }

void Window::setSize(int width, int height) { glfwSetWindowSize(mWindow, width, height); }

void Window::setTitle(const std::string& title) { glfwSetWindowTitle(mWindow, title.c_str()); }

}  // namespace gi::ui
