#include "ui/gi_thread.h"

#include <epoxy/gl.h>

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace gi::ui {

namespace {

// Waits until every command issued so far in the current context has run. A fence and a client
// wait rather than glFinish, so a driver may return as soon as the work is done.
void finishCommands() {
    GLsync fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    if (!fence) {
        glFinish();
        return;
    }
    while (glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, 1'000'000'000) == GL_TIMEOUT_EXPIRED) {
    }
    glDeleteSync(fence);
}

}  // namespace

GIThread::GIThread(const std::function<void()>& createGI, std::function<void(bool)> bindGI, std::function<void()> bindUI,
                   std::function<void()> onDone)
    : mBindGI(std::move(bindGI)), mBindUI(std::move(bindUI)), mOnDone(std::move(onDone)) {
    mThread = std::thread([this, &createGI] { loop(createGI); });
    std::unique_lock lock(mMutex);
    mDone.wait(lock, [&] { return mStarted; });
    if (mStartError) {
        mStop = true;
        lock.unlock();
        mThread.join();
        std::rethrow_exception(mStartError);
    }
}

GIThread::~GIThread() {
    {
        std::unique_lock lock(mMutex);
        mDone.wait(lock, [&] { return !mRunning; });
        mStop = true;
    }
    mWake.notify_all();
    mThread.join();
}

bool GIThread::busy() const {
    std::lock_guard lock(mMutex);
    return mRunning;
}

bool GIThread::tryAcquire() {
    if (mHeld) return true;
    if (busy()) return false;
    mBindGI(true);
    mHeld = true;
    return true;
}

void GIThread::acquire() {
    if (mHeld) return;
    {
        std::unique_lock lock(mMutex);
        mDone.wait(lock, [&] { return !mRunning; });
    }
    tryAcquire();
}

void GIThread::handBack() {
    mBindGI(false);
    mHeld = false;
    mBindUI();
}

void GIThread::submit(std::function<void()> job) {
    if (!mHeld) acquire();
    handBack();
    {
        std::lock_guard lock(mMutex);
        mJob = std::move(job);
        mRunning = true;
    }
    mWake.notify_all();
}

void GIThread::release() {
    if (mHeld) handBack();
}

void GIThread::loop(const std::function<void()>& createGI) {
    // Below the UI thread; threads started from here inherit it (a thread's nice value on Linux).
    setpriority(PRIO_PROCESS, pid_t(syscall(SYS_gettid)), getpriority(PRIO_PROCESS, 0) + kNice);
    std::exception_ptr error;
    try {
        createGI();
        mBindGI(false);
    } catch (...) {
        error = std::current_exception();
    }
    std::unique_lock lock(mMutex);
    mStarted = true;
    mStartError = error;
    mDone.notify_all();
    if (error) return;
    for (;;) {
        mWake.wait(lock, [&] { return mStop || mJob; });
        if (mStop) return;
        std::function<void()> job = std::move(mJob);
        mJob = nullptr;
        lock.unlock();
        mBindGI(true);
        job();
        // The frame's GL work is done before the UI thread is told: the UI thread's first use of
        // the context must not wait on it.
        finishCommands();
        mBindGI(false);
        lock.lock();
        mRunning = false;
        mDone.notify_all();
        if (mOnDone) mOnDone();
    }
}

}  // namespace gi::ui
