// The Reference panel: a path-traced reference of the current view, rendered progressively by a
// ReferenceJob while the user keeps tuning, and compared with the live image.
//
// Restarts: the job depends on the scene, the resolved camera and lights, the image size,
// render.specular and the reference settings (referenceKey). When any of them changes the
// running job goes on until the change has held still for kSettleSeconds, so dragging the camera
// does not restart the tracer every frame; then the old job is cancelled and a new one starts.
// A reference of an older view is never shown or scored.
//
// Views: Live; Reference; Toggle (the reference while Space or "Hold to compare" is held);
// Split (live left of a draggable vertical line, reference right); Heat map (differenceHeatMap,
// red where live is brighter, blue where darker, full colour at the reference's mean luminance).
// The reference is tone-mapped with the preset's toneMap section and shown at the render size.
//
// Metrics: SSIM, score, RMSE and PSNR of the live HDR image against the latest snapshot
// (scoreRender, as gi-render --score), computed on a helper thread from a readback, at most every
// kMetricsInterval seconds and only when the live image or the snapshot has changed since.
// Tone mapping the snapshots for display also runs on a helper thread; the UI thread only reads
// the live image back and uploads textures.
#pragma once

#include "gi/gl/handle.h"
#include "ui/panel_util.h"
#include "gi/metrics/metrics.h"
#include "gi/render/renderer.h"
#include "ui/reference_job.h"

#include <chrono>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace gi::ui {

enum class ReferenceView { Live, Reference, Toggle, Split, Heat };

// "live", "reference", "toggle", "split" or "heat"; throws gi::Error naming the valid ones.
ReferenceView referenceViewFromName(const std::string& name);

class ReferencePanel {
public:
    static constexpr double kSettleSeconds = 0.3;
    static constexpr double kMetricsInterval = 0.5;

    ReferencePanel();
    ~ReferencePanel();

    bool enabled() const { return mEnabled; }
    // The live image's SSIM against the reference, when metrics of the current view are shown.
    std::optional<double> ssim() const { return mEnabled && mHaveMetrics && !mStale ? std::optional<double>(mMetrics.ssim) : std::nullopt; }
    void setEnabled(bool enabled) { mEnabled = enabled; }
    void setView(ReferenceView view) { mView = view; }

    // Once per frame, after the live image is rendered: restarts the job when its inputs changed
    // and have settled, picks up new snapshots, and starts or collects the metrics.
    // `sceneGeneration` changes whenever another scene is installed; `liveGeneration` whenever
    // anything that changes the live image does. `giIdle`: the editor has no GI frame to render,
    // so the tracer's next passes take every core.
    void update(const Scene& scene, uint64_t sceneGeneration, uint64_t liveGeneration, const FrameSettings& fs,
                const ReferenceSettings& rs, const Renderer& renderer, bool giIdle);
    // Draws the chosen view over the live image already in viewport.framebuffer (drawImages: the
    // GI context is held), and the split line and labels with the panels (always).
    void drawViewport(const ViewportRect& viewport, bool drawImages);
    // The panel's widgets, into the current ImGui window.
    void draw();

    // The job has finished its spp (or failed) and the shown image and metrics are of its final
    // snapshot: what a screenshot waits for.
    bool settled() const;
    std::string error() const;
    // One line: samples, SSIM, score, RMSE, PSNR.
    std::string summary() const;

private:
    struct MetricsResult {
        Metrics metrics;
        std::vector<uint8_t> heat;  // RGB8, top row first
        int width = 0, height = 0;
        std::string error;
    };
    struct JobKey {
        uint64_t scene = 0;  // scene generation
        uint64_t view = 0;   // referenceKey of everything else
        bool operator==(const JobKey&) const = default;
    };
    using Clock = std::chrono::steady_clock;

    bool mEnabled = false;
    ReferenceView mView = ReferenceView::Split;
    float mSplit = 0.5f;  // split line, fraction of the viewport width from the left
    bool mDraggingSplit = false;
    bool mHoldButton = false;  // "Hold to compare" is pressed
    bool mRestartRequested = false;

    std::unique_ptr<ReferenceJob> mJob;
    std::vector<std::unique_ptr<ReferenceJob>> mRetired;  // cancelled, destroyed once done
    JobKey mJobKey, mPendingKey;
    Clock::time_point mPendingSince;
    bool mStale = false;  // the inputs have changed since the job started
    std::shared_ptr<const Scene> mSceneCopy;  // the scene the jobs trace
    uint64_t mSceneCopyGeneration = ~0ull;
    std::shared_ptr<const PathTracer> mTracer;  // built by an earlier job for mSceneCopy

    uint64_t mJobSerial = 0;  // counts jobs started and stopped, so late results for an old job are dropped
    uint64_t mLiveGeneration = 0;
    ToneMapSettings mToneMap;  // the preset's, this frame

    std::shared_ptr<const ReferenceSnapshot> mSnapshot;
    std::shared_ptr<const ImageRGB> mShownImage;  // the image in mReferenceTexture
    ToneMapSettings mShownToneMap;                // and the tone mapping it was shown with
    std::future<std::vector<uint8_t>> mToneTask;  // RGB8 of mToneImage, tone-mapped with mToneTaskToneMap
    std::shared_ptr<const ImageRGB> mToneImage;
    ToneMapSettings mToneTaskToneMap;
    uint64_t mToneJob = 0;
    gl::Texture mReferenceTexture, mHeatTexture;
    gl::Framebuffer mReadFBO;

    // The inputs of the running or last metrics task.
    std::future<MetricsResult> mMetricsTask;
    uint64_t mMetricsJob = ~0ull;
    std::shared_ptr<const ImageRGB> mMetricsImage;
    uint64_t mMetricsLiveGeneration = ~0ull;
    ToneMapSettings mMetricsToneMap;
    Clock::time_point mLastMetrics;
    bool mHaveMetrics = false;
    Metrics mMetrics;
    std::string mTaskError;  // a metrics or tone-mapping task failed

    void restart(const Scene& scene, uint64_t sceneGeneration, const JobKey& key, const FrameSettings& fs,
                 const ReferenceSettings& rs);
    void retireJob();  // cancels mJob and keeps it until its thread ends
    void stop();
    void pickUpSnapshot();
    void updateMetrics(const Renderer& renderer);
    bool referenceShown() const;
    void blit(const gl::Texture& texture, const ViewportRect& viewport);
    void splitInteraction(const ViewportRect& viewport);
};

}  // namespace gi::ui
