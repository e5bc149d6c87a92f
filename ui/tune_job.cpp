#include "ui/tune_job.h"

#include "gi/matrix/run.h"
#include "gi/util/paths.h"

#include <chrono>

namespace gi::ui {

namespace fs = std::filesystem;
using nlohmann::json;

TuneJob::TuneJob(const Preset& preset, const TuneRequest& request, const fs::path& renderer, const fs::path& outDir)
    : mRequest(request), mRenderer(renderer), mOutDir(outDir) {
    mSnapshot.maxRenders = request.renders;
    mThread = std::thread([this, preset] { run(preset); });
}

TuneJob::~TuneJob() {
    mCancel = true;
    if (mThread.joinable()) mThread.join();
}

TuneSnapshot TuneJob::snapshot() const {
    std::lock_guard<std::mutex> lock(mMutex);
    return mSnapshot;
}

void TuneJob::run(Preset preset) {
    auto start = std::chrono::steady_clock::now();
    auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    try {
        fs::create_directories(mOutDir);
        // The scene as gi-render will find it from the temporary folder: an absolute path unless
        // it is a built-in scene.
        if (fs::path(preset.header.scene).has_extension())  // else a built-in scene (cornell, basic, ...)
            preset.header.scene = resolveAsset(preset.header.scene, preset.folder).string();
        fs::path input = mOutDir / "scene.json";
        savePreset(preset, input);
        json j = {{"name", "auto-tune " + mRequest.technique},
                  {"width", mRequest.width},
                  {"height", mRequest.height},
                  {"frames", mRequest.frames},
                  {"spp", mRequest.spp},
                  {"scenes", json::array({{{"input", input.string()}, {"label", "scene"}}})},
                  {"cells", json::array({{{"technique", mRequest.technique}}})}};
        matrix::MatrixSpec spec = matrix::specFromJson(j, "auto-tune");
        matrix::TuneOptions options;
        options.technique = mRequest.technique;
        options.base = presetToJson(preset);
        options.budgetMs = mRequest.budgetMs;
        options.maxRenders = mRequest.renders;
        options.run.renderer = mRenderer;
        options.run.outDir = mOutDir;
        options.run.resume = true;
        options.run.cancel = &mCancel;
        if (matrix::tuneSpace(mRequest.technique, options.base).empty())
            throw Error("technique '" + mRequest.technique + "' has no settings to tune");
        options.progress = [&](const matrix::TuneReport& r) {
            std::lock_guard<std::mutex> lock(mMutex);
            mSnapshot.report = r;
            if (r.best && r.best->result.ok()) mSnapshot.bestImage = mOutDir / r.best->result.folder / "image.png";
            mSnapshot.seconds = seconds();
            ++mSnapshot.version;
        };
        matrix::TuneReport report = matrix::tunePatternSearch(spec, options);
        std::lock_guard<std::mutex> lock(mMutex);
        mSnapshot.report = std::move(report);
        mSnapshot.state = mCancel ? TuneSnapshot::State::Cancelled : TuneSnapshot::State::Finished;
        mSnapshot.seconds = seconds();
        ++mSnapshot.version;
    } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(mMutex);
        mSnapshot.state = TuneSnapshot::State::Failed;
        mSnapshot.error = e.what();
        ++mSnapshot.version;
    }
    mDone = true;
}

}  // namespace gi::ui
