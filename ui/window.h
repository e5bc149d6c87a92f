// The editor's window: a GLFW window with a GL 4.5 core debug context, and Dear ImGui set up on
// it. The GI core never sees GLFW; it only needs the current GL context.
#pragma once

#include "gi/util/error.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

struct GLFWwindow;

namespace gi::ui {

class KeyEventQueue;

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
    // Polls events and starts an ImGui frame.
    void beginFrame();
    // Draws the ImGui frame over whatever the back buffer holds.
    void renderUI();
    // The back buffer as RGBA8, bottom row first, alpha forced opaque. Call before swap().
    std::vector<uint8_t> readBackBuffer(int& width, int& height) const;
    void swap();

    void framebufferSize(int& width, int& height) const;
    void setTitle(const std::string& title);
    void setSize(int width, int height);

    // The GI context (ui/gi_thread.h): a hidden window's GL context shared with this one.
    // bindGI(true) makes it current on the calling thread (any thread), bindGI(false) leaves the
    // thread with none; bindUI() makes the window's own context current (the UI thread).
    void bindGI(bool current);
    void bindUI();
    // Window's context: copies the texture's lower-left width x height texels (made in the GI
    // context and finished there) into the back buffer at the same place, under the panels.
    void drawBackground(unsigned texture, int width, int height);

private:
    GLFWwindow* mWindow = nullptr;
    GLFWwindow* mGIWindow = nullptr;  // hidden; only its context is used
    unsigned mBackgroundFBO = 0;      // the window context's own (framebuffers are not shared)
    std::unique_ptr<KeyEventQueue> mKeys;  // GLFW's key events, handed to ImGui one change per key per frame
};

}  // namespace gi::ui
