// A path-traced reference rendered progressively on a worker thread while the editor keeps
// running. The job traces passes of growing size (1, 2, 4, ... up to kMaxPassSamples samples per
// pixel) until the reference settings' spp, and publishes the running mean after each pass, so
// the editor can show a noisy reference at once and a clean one later. Alternate passes add into
// two halves, whose difference estimates the noise left (ReferenceSnapshot::noise).
//
// Threads: the job owns one std::thread, and the path tracer's oneTBB work runs in a task arena
// of hardware_concurrency - 1 slots (at least one), so one core stays free for the UI thread
// (which also drives llvmpipe), or of every core while the editor says its GI is idle
// (setAllCores, read before each pass). The worker only touches CPU data; GL stays on the main thread.
//
// Cancelling: cancel() sets a flag the tracer checks before each 16x16 tile, so tracing stops
// within one tile; building the BVH cannot be interrupted. cancel() does not wait: the editor
// keeps cancelled jobs until done() and only then destroys them, so a restart never blocks the
// UI behind a BVH build. The destructor cancels and joins.
//
// Cache: before tracing, a finished reference for the same referenceKey is read from
// referenceCacheDir() (the file gi-render and the tests use); a job that completes stores its
// image there. Partial images are never stored.
#pragma once

#include "gi/reference/path_tracer.h"

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

namespace gi::ui {

struct ReferenceSnapshot {
    enum class State { Starting, Tracing, Finished, Failed };
    State state = State::Starting;
    std::shared_ptr<const ImageRGB> image;  // mean radiance of the samples done; null before the first pass
    int samplesDone = 0;
    int samplesTotal = 0;
    double seconds = 0.0;        // since the job started, BVH build included
    double raysPerSecond = 0.0;  // over the tracing so far
    // The noise left in the image (gi::relativeNoise of the passes' two halves, alternate passes
    // in each): the RMS standard error of a pixel over the mean luminance; < 0 while unknown (one
    // pass so far, or read from the cache).
    double noise = -1.0;
    bool fromCache = false;
    std::string error;    // Failed: why (one line)
    std::string warning;  // Finished: the cache file could not be written
    uint64_t version = 0;  // grows with every publish
};

class ReferenceJob {
public:
    static constexpr int kMaxPassSamples = 16;

    // Starts at once. `tracer` may be one built earlier for this same scene (it is shared, not
    // rebuilt); null builds a new one on the worker from `scene`.
    ReferenceJob(std::shared_ptr<const Scene> scene, std::shared_ptr<const PathTracer> tracer, const FrameSettings& fs,
                 const ReferenceSettings& rs);
    ~ReferenceJob();
    ReferenceJob(const ReferenceJob&) = delete;
    ReferenceJob& operator=(const ReferenceJob&) = delete;

    void cancel() { mCancel = true; }
    // Every core for the passes from now on (the editor is idle: no GI frame to render), or all
    // but one (the UI thread drives llvmpipe).
    void setAllCores(bool all) { mAllCores = all; }
    int threads() const { return mAllCores ? allThreads() : allThreads() > 1 ? allThreads() - 1 : 1; }
    static int allThreads();
    bool done() const { return mDone.load(); }
    uint64_t version() const { return mVersion.load(); }
    std::shared_ptr<const ReferenceSnapshot> snapshot() const;
    // The job's tracer once it is built, for the next job over the same scene.
    std::shared_ptr<const PathTracer> tracer() const;

private:
    std::shared_ptr<const Scene> mScene;
    std::shared_ptr<const PathTracer> mTracer;  // guarded by mMutex once the thread runs
    FrameSettings mFrame;
    ReferenceSettings mSettings;
    std::atomic<bool> mCancel{false};
    std::atomic<bool> mDone{false};
    std::atomic<uint64_t> mVersion{0};
    mutable std::mutex mMutex;
    std::shared_ptr<const ReferenceSnapshot> mSnapshot;
    std::atomic<bool> mAllCores{false};
    std::thread mThread;  // last: starts after every other member is ready

    void run();
    void publish(ReferenceSnapshot s);
};

}  // namespace gi::ui
