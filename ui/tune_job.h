// The editor's auto-tune (issue 15 item 5): gi/matrix/tune.h's pattern search on the open scene,
// run on a worker thread while the editor stays live. Each render is a gi-render process (so
// the editor's own GL context and GI thread are untouched); the worker publishes the search's
// path after every render, and cancel() kills the render in flight.
#pragma once

#include "gi/matrix/tune.h"
#include "gi/preset/preset.h"

#include <atomic>
#include <filesystem>
#include <mutex>
#include <thread>

namespace gi::ui {

struct TuneRequest {
    std::string technique;
    double budgetMs = 200.0;
    size_t renders = 12;
    int width = 128, height = 96;
    int frames = 4;
    int spp = 256;
};

struct TuneSnapshot {
    enum class State { Running, Finished, Cancelled, Failed };
    State state = State::Running;
    matrix::TuneReport report;
    size_t maxRenders = 0;
    std::filesystem::path bestImage;  // the best render's image.png, when there is one
    std::string error;                // Failed: one line
    double seconds = 0.0;
    uint64_t version = 0;             // grows with every publish
};

class TuneJob {
public:
    // Starts at once: `preset` (the editor's, as it is now) is written to `outDir`/scene.json with
    // its scene path made absolute, and searched with the request.
    TuneJob(const Preset& preset, const TuneRequest& request, const std::filesystem::path& renderer, const std::filesystem::path& outDir);
    ~TuneJob();  // cancels and joins
    TuneJob(const TuneJob&) = delete;
    TuneJob& operator=(const TuneJob&) = delete;

    void cancel() { mCancel = true; }
    bool done() const { return mDone; }
    TuneSnapshot snapshot() const;
    const TuneRequest& request() const { return mRequest; }

private:
    void run(Preset preset);
    TuneRequest mRequest;
    std::filesystem::path mRenderer, mOutDir;
    std::atomic<bool> mCancel{false}, mDone{false};
    mutable std::mutex mMutex;
    TuneSnapshot mSnapshot;
    std::thread mThread;
};

}  // namespace gi::ui
