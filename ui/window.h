// The editor's window: a GLFW window with a GL 4.5 core debug context, and Dear ImGui set up on
// it. The GI core never sees GLFW; it only needs the current GL context.
#pragma once

#include "gi/util/error.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

struct GLFWwindow;

namespace gi {
class EGLContextHeadless;
}

namespace gi::ui {

class KeyEventQueue;
class TextureBridge;

// No window could be opened (no X display, or no GL 4.5): the caller exits with its own code.
class NoDisplayError : public Error {
public:
    using Error::Error;
};

class Window {
public:
    // Throws NoDisplayError when GLFW cannot start or the window cannot be created.
    Window(int width, int height, const char* title);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    bool shouldClose() const;
    // Takes the window's events and starts an ImGui frame. With waitSeconds > 0 it first waits up
    // to that long for an event (input, a resize, or wake()), unless queued keys are pending: a UI
    // with nothing to show gives the cores to the GI. Returns the seconds it waited.
    double beginFrame(double waitSeconds = 0.0);
    // Ends a wait in beginFrame; any thread.
    static void wake();
    // Ends the ImGui frame: ImGui::Render, the bridge's new images uploaded and the draw data
    // pointed at them. Returns whether the window would show anything other than what it last
    // presented: the draw data (vertices, indices, commands), the background texture, an image the
    // bridge uploaded, the framebuffer's size, or the window system asking for a redraw (an
    // expose), or a second gone by. A frame that shows nothing new need not be drawn or swapped,
    // which leaves the cores to the GI.
    bool finishUI(unsigned background, int backgroundWidth, int backgroundHeight);
    // Draws the ImGui frame (after finishUI) over whatever the back buffer holds.
    void renderUI();
    // The back buffer as RGBA8, bottom row first, alpha forced opaque. Call before swap().
    std::vector<uint8_t> readBackBuffer(int& width, int& height) const;
    // Presents the back buffer; what finishUI fingerprinted is now what the window shows.
    void swap();

    void framebufferSize(int& width, int& height) const;
    void setTitle(const std::string& title);
    void setSize(int width, int height);

    // The GI context (ui/gi_thread.h): an EGL context of its own, sharing nothing with the
    // window's (ui/texture_bridge.h says why). bindGI(true) makes it current on the calling thread
    // (any thread), bindGI(false) leaves the thread with none; bindUI() makes the window's own
    // context current (the UI thread). Throws gi::Error when EGL refuses.
    void bindGI(bool current);
    void bindUI();
    // Makes the GI context (any thread; ui/gi_thread.h calls it on its worker) and leaves it
    // current there. Throws NoDisplayError when EGL cannot make it.
    void createGIContext();
    // Window's context: clears the back buffer and copies the texture's lower-left width x height
    // texels into it at the same place, under the panels.
    void drawBackground(unsigned texture, int width, int height);
    TextureBridge& bridge() { return *mBridge; }

private:
    GLFWwindow* mWindow = nullptr;
    std::unique_ptr<EGLContextHeadless> mGIContext;
    std::unique_ptr<TextureBridge> mBridge;  // images from the GI context; its copies live in the window's
    unsigned mBackgroundFBO = 0;      // the window context's own (framebuffers are not shared)
    std::unique_ptr<KeyEventQueue> mKeys;  // GLFW's key events, handed to ImGui one change per key per frame
    size_t mFingerprint = 0;          // finishUI's, of the frame being made
    size_t mPresented = 0;            // that of the frame last presented
    double mPresentedAt = -1.0;       // glfwGetTime() then
    bool mDamaged = true;             // the window system asked for a redraw
};

}  // namespace gi::ui
