// The GI thread: the renderer's frames run on a worker thread in a GL context of their own (the
// "GI context"), so the UI thread keeps drawing panels at display rate while a frame takes
// seconds on llvmpipe.
//
// One thread holds the GI context at a time. The UI thread takes it between GI frames (tryAcquire)
// to read what the last frame made (previews, picks, the viewport image), hands it to the worker
// with the next frame's job (submit), or gives it back (release); either way its own (window)
// context is current again afterwards. Every object the renderer and the editor's previews make
// lives in the GI context; the window shows their images through ui/texture_bridge.h.
#pragma once

#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace gi::ui {

class GIThread {
public:
    // createGI() makes the GI context; it runs on the worker, after the worker has lowered its own
    // priority (nice + kNice), so the threads a GL driver starts with the context (llvmpipe's
    // rasterizer) run below the UI too: the UI keeps its frame rate, the GI takes what is left.
    // Its exception is rethrown here. bindGI(true) makes the GI context current on the calling
    // thread, bindGI(false) leaves the thread with none; bindUI() makes the window's context
    // current on the UI thread. onDone (optional) is called on the worker when a job has
    // finished (e.g. to wake the UI).
    GIThread(const std::function<void()>& createGI, std::function<void(bool)> bindGI, std::function<void()> bindUI,
             std::function<void()> onDone = {});
    static constexpr int kNice = 10;
    ~GIThread();  // waits for the job in flight
    GIThread(const GIThread&) = delete;
    GIThread& operator=(const GIThread&) = delete;

    // UI thread. Whether a job is running (the worker holds the GI context).
    bool busy() const;
    // Whether the UI thread holds the GI context now.
    bool held() const { return mHeld; }
    // Takes the GI context if no job is running: true, and it is current on this thread. True
    // at once when already held.
    bool tryAcquire();
    // Takes the GI context, waiting for the job in flight.
    void acquire();
    // Held: hands the GI context to the worker, which runs `job` and finishes its GL work before
    // it counts as done; the window's context is current on return. A job's exceptions are the
    // job's to catch.
    void submit(std::function<void()> job);
    // Held: gives the GI context up; the window's context is current on return.
    void release();

private:
    void loop(const std::function<void()>& createGI);
    // Ends the UI thread's use of the GI context: the window's context current again.
    void handBack();

    std::function<void(bool)> mBindGI;
    std::function<void()> mBindUI;
    std::function<void()> mOnDone;
    mutable std::mutex mMutex;
    std::condition_variable mWake, mDone;
    std::function<void()> mJob;  // the job waiting or running
    bool mRunning = false;       // a job is queued or running
    bool mStop = false;
    bool mStarted = false;           // createGI has run
    std::exception_ptr mStartError;  // and threw this
    bool mHeld = false;          // UI thread only
    std::thread mThread;
};

}  // namespace gi::ui
