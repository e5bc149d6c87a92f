#include "ui/reference_job.h"

#include "gi/metrics/metrics.h"
#include "gi/reference/reference_cache.h"
#include "gi/util/error.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

namespace gi::ui {

int ReferenceJob::allThreads() { return std::max(1, int(std::thread::hardware_concurrency())); }

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::filesystem::path cacheFile(const Scene& scene, const FrameSettings& fs, const ReferenceSettings& rs) {
    char name[32];
    std::snprintf(name, sizeof name, "%016llx.exr", static_cast<unsigned long long>(referenceKey(scene, fs, rs)));
    return referenceCacheDir() / name;
}

}  // namespace

ReferenceJob::ReferenceJob(std::shared_ptr<const Scene> scene, std::shared_ptr<const PathTracer> tracer,
                           const FrameSettings& fs, const ReferenceSettings& rs)
    : mScene(std::move(scene)), mTracer(std::move(tracer)), mFrame(fs), mSettings(rs),
      mSnapshot(std::make_shared<ReferenceSnapshot>()), mThread([this] { run(); }) {}

ReferenceJob::~ReferenceJob() {
    cancel();
    mThread.join();
}

std::shared_ptr<const ReferenceSnapshot> ReferenceJob::snapshot() const {
    std::lock_guard lock(mMutex);
    return mSnapshot;
}

std::shared_ptr<const PathTracer> ReferenceJob::tracer() const {
    std::lock_guard lock(mMutex);
    return mTracer;
}

void ReferenceJob::publish(ReferenceSnapshot s) {
    std::lock_guard lock(mMutex);
    s.version = mSnapshot->version + 1;
    mSnapshot = std::make_shared<const ReferenceSnapshot>(std::move(s));
    mVersion = mSnapshot->version;
}

void ReferenceJob::run() {
    const auto start = Clock::now();
    ReferenceSnapshot s;
    s.samplesTotal = mSettings.spp;
    try {
        std::filesystem::path file = cacheFile(*mScene, mFrame, mSettings);
        std::error_code ec;
        if (std::filesystem::exists(file, ec)) {
            try {
                ImageRGB cached = readEXR(file);
                if (cached.width == mFrame.width && cached.height == mFrame.height) {
                    s.state = ReferenceSnapshot::State::Finished;
                    s.image = std::make_shared<const ImageRGB>(std::move(cached));
                    s.samplesDone = mSettings.spp;
                    s.fromCache = true;
                    s.seconds = secondsSince(start);
                    publish(s);
                    mDone = true;
                    return;
                }
            } catch (const Error&) {
                // A damaged cache file is traced again and replaced.
            }
        }

        // One slot fewer than the machine has, so the UI thread keeps a core, unless the editor
        // says it is idle: then every core (chosen again before each pass).
        tbb::task_arena spared(std::max(1, allThreads() - 1)), all(allThreads());
        std::shared_ptr<const PathTracer> tracer = this->tracer();
        if (!tracer) {
            spared.execute([&] { tracer = std::make_shared<const PathTracer>(*mScene); });
            std::lock_guard lock(mMutex);
            mTracer = tracer;
        }
        s.state = ReferenceSnapshot::State::Tracing;
        s.seconds = secondsSince(start);
        publish(s);

        const auto traceStart = Clock::now();
        const uint64_t raysBefore = tracer->raysTraced();
        std::vector<double> sums[2];  // alternate passes: two independent halves of the samples
        int counts[2] = {0, 0};
        int pass = 1, passIndex = 0;
        while (s.samplesDone < mSettings.spp && !mCancel) {
            int count = std::min(pass, mSettings.spp - s.samplesDone);
            bool complete = false;
            std::vector<double>& sum = sums[passIndex % 2];
            (mAllCores ? all : spared).execute([&] { complete = tracer->trace(mFrame, mSettings, s.samplesDone, count, sum, &mCancel); });
            if (!complete) break;
            counts[passIndex % 2] += count;
            ++passIndex;
            s.samplesDone += count;
            pass = std::min(pass * 2, kMaxPassSamples);

            auto mean = [&](const std::vector<double>& a, const std::vector<double>& b, double n) {
                auto image = std::make_shared<ImageRGB>();
                image->width = mFrame.width;
                image->height = mFrame.height;
                image->rgb.resize(std::max(a.size(), b.size()));
                for (size_t i = 0; i < image->rgb.size(); ++i)
                    image->rgb[i] = float(((i < a.size() ? a[i] : 0.0) + (i < b.size() ? b[i] : 0.0)) / n);
                return image;
            };
            s.image = mean(sums[0], sums[1], double(s.samplesDone));
            if (counts[0] > 0 && counts[1] > 0)
                s.noise = relativeNoise(*mean(sums[0], {}, counts[0]), counts[0], *mean(sums[1], {}, counts[1]), counts[1]);
            s.seconds = secondsSince(start);
            // Another job may share the tracer's ray counter for a tile or two after a restart.
            double traceSeconds = std::max(secondsSince(traceStart), 1e-6);
            s.raysPerSecond = double(tracer->raysTraced() - raysBefore) / traceSeconds;
            if (s.samplesDone == mSettings.spp) {
                s.state = ReferenceSnapshot::State::Finished;
                std::filesystem::create_directories(file.parent_path(), ec);
                try {
                    writeEXR(file, *s.image);
                } catch (const Error& e) {
                    s.warning = std::string("reference cache not written: ") + e.what();
                }
            }
            publish(s);
        }
    } catch (const std::exception& e) {
        s.state = ReferenceSnapshot::State::Failed;
        s.error = e.what();
        s.seconds = secondsSince(start);
        publish(s);
    }
    mDone = true;
}

}  // namespace gi::ui
