#include "ui/reference_panel.h"

#include "gi/reference/reference_cache.h"
#include "gi/util/error.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace gi::ui {

namespace {

constexpr float kSplitGrabPixels = 6.0f;  // how near the split line a press grabs it
constexpr double kScoreMinSSIM = 0.99;    // the seed score is shown from this SSIM up (10 x 0.99^1000 = 4e-4)

constexpr std::pair<ReferenceView, const char*> kViewNames[] = {{ReferenceView::Live, "live"},
                                                                {ReferenceView::Reference, "reference"},
                                                                {ReferenceView::Toggle, "toggle"},
                                                                {ReferenceView::Split, "split"},
                                                                {ReferenceView::Heat, "heat"}};

// The scene-free part of the reference key: camera, lights, size, specular and the reference
// settings. Hashing the scene itself (100 MB for Sponza) every frame would cost a frame; scene
// changes are caught by the editor's scene generation instead.
uint64_t viewKey(const FrameSettings& fs, const ReferenceSettings& rs) {
    static const Scene kNoScene;
    return referenceKey(kNoScene, fs, rs);
}

bool sameToneMap(const ToneMapSettings& a, const ToneMapSettings& b) { return a.exposure == b.exposure && a.op == b.op; }

double secondsBetween(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
}

// RGB8 rows, top first, into an RGBA8 texture of the same size (made or remade as needed).
void upload(gl::Texture& texture, const std::vector<uint8_t>& rgb, int width, int height) {
    if (!texture || texture.width() != width || texture.height() != height)
        texture = gl::Texture::create2D(GL_RGBA8, width, height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);  // RGB8 rows need not be 4-byte multiples
    glTextureSubImage2D(texture.id(), 0, 0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
}

void coloredText(const ImVec4& color, const std::string& text) {
    ImGui::PushStyleColor(ImGuiCol_Text, color);
    ImGui::TextWrapped("%s", text.c_str());
    ImGui::PopStyleColor();
}

void hint(const std::string& text) { coloredText(ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled), text); }

// The Reference panel's noise line, warning past 5 %.
std::string formatNoise(double noise) {
    char text[128];
    std::snprintf(text, sizeof text, "reference noise %.1f %% (pixel RMS / mean)%s", noise * 100.0,
                  noise > 0.05 ? ", needs more samples" : "");
    return text;
}

std::string formatPSNR(double psnr) {
    if (!std::isfinite(psnr)) return "inf";
    char text[32];
    std::snprintf(text, sizeof text, "%.2f dB", psnr);
    return text;
}

}  // namespace

ReferenceView referenceViewFromName(const std::string& name) {
    std::string valid;
    for (const auto& [view, viewName] : kViewNames) {
        if (name == viewName) return view;
        valid += valid.empty() ? viewName : std::string(", ") + viewName;
    }
    throw Error("unknown reference view '" + name + "' (valid: " + valid + ")");
}

ReferencePanel::ReferencePanel() = default;

ReferencePanel::~ReferencePanel() {
    // Jobs cancel and join in their destructors; running tasks are waited for here.
    if (mToneTask.valid()) mToneTask.wait();
    if (mMetricsTask.valid()) mMetricsTask.wait();
}

void ReferencePanel::update(const Scene& scene, uint64_t sceneGeneration, uint64_t liveGeneration,
                            const FrameSettings& fs, const ReferenceSettings& rs, const Renderer& renderer, bool giIdle) {
    std::erase_if(mRetired, [](const std::unique_ptr<ReferenceJob>& job) { return job->done(); });
    mLiveGeneration = liveGeneration;
    mToneMap = fs.toneMap;
    if (!mEnabled) {
        stop();
        return;
    }

    const auto now = Clock::now();
    JobKey key{sceneGeneration, viewKey(fs, rs)};
    if (!(key == mPendingKey)) {
        mPendingKey = key;
        mPendingSince = now;
    }
    mStale = mJob && !(key == mJobKey);
    bool inputsSettled = secondsBetween(mPendingSince, now) >= kSettleSeconds;
    if (!mJob || mRestartRequested || (mStale && inputsSettled)) restart(scene, sceneGeneration, key, fs, rs);

    if (mJob) mJob->setAllCores(giIdle);
    pickUpSnapshot();
    updateMetrics(renderer);
}

void ReferencePanel::restart(const Scene& scene, uint64_t sceneGeneration, const JobKey& key, const FrameSettings& fs,
                             const ReferenceSettings& rs) {
    retireJob();
    if (mSceneCopyGeneration != sceneGeneration) {
        mSceneCopy = std::make_shared<const Scene>(scene);
        mSceneCopyGeneration = sceneGeneration;
        mTracer.reset();
    }
    mJob = std::make_unique<ReferenceJob>(mSceneCopy, mTracer, fs, rs);
    ++mJobSerial;
    mJobKey = key;
    mStale = false;
    mRestartRequested = false;
    mSnapshot.reset();
    mShownImage.reset();
    mHaveMetrics = false;
    mTaskError.clear();
}

void ReferencePanel::retireJob() {
    if (!mJob) return;
    // The BVH depends on the scene alone: the next job over the same scene reuses it (restart
    // drops it when the scene has changed).
    if (auto tracer = mJob->tracer()) mTracer = std::move(tracer);
    mJob->cancel();
    mRetired.push_back(std::move(mJob));
}

void ReferencePanel::stop() {
    if (!mJob) return;
    retireJob();
    ++mJobSerial;
    mStale = false;
    mSnapshot.reset();
    mShownImage.reset();
    mHaveMetrics = false;
    mTaskError.clear();
}

void ReferencePanel::pickUpSnapshot() {
    if (mToneTask.valid() && mToneTask.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        try {
            std::vector<uint8_t> rgb = mToneTask.get();
            // An image of a job that has since been replaced is dropped.
            if (mToneJob == mJobSerial) {
                upload(mReferenceTexture, rgb, mToneImage->width, mToneImage->height);
                mShownImage = mToneImage;
                mShownToneMap = mToneTaskToneMap;
            }
        } catch (const std::exception& e) {
            mTaskError = std::string("tone mapping: ") + e.what();
        }
    }
    if (!mJob) return;
    if (!mSnapshot || mJob->version() != mSnapshot->version) mSnapshot = mJob->snapshot();
    std::shared_ptr<const ImageRGB> image = mSnapshot->image;
    if (!image || mToneTask.valid() || (image == mShownImage && sameToneMap(mToneMap, mShownToneMap))) return;
    // Tone mapping a full frame takes tens of milliseconds: off the UI thread, like the metrics.
    mToneImage = image;
    mToneTaskToneMap = mToneMap;
    mToneJob = mJobSerial;
    mToneTask = std::async(std::launch::async, [image, toneMap = mToneMap] { return encodeSRGB8(toneMapped(*image, toneMap)); });
}

void ReferencePanel::updateMetrics(const Renderer& renderer) {
    if (mMetricsTask.valid() && mMetricsTask.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        MetricsResult r = mMetricsTask.get();
        // A result for a job that has since been replaced is dropped.
        if (mMetricsJob == mJobSerial) {
            if (r.error.empty()) {
                mMetrics = r.metrics;
                mHaveMetrics = true;
                mTaskError.clear();
                upload(mHeatTexture, r.heat, r.width, r.height);
            } else {
                mTaskError = "metrics: " + r.error;
            }
        }
    }
    if (mMetricsTask.valid() || mStale || !mSnapshot || !mSnapshot->image) return;
    std::shared_ptr<const ImageRGB> reference = mSnapshot->image;
    if (reference->width != renderer.width() || reference->height != renderer.height()) return;
    const auto now = Clock::now();
    bool changed = mMetricsJob != mJobSerial || reference != mMetricsImage || mLiveGeneration != mMetricsLiveGeneration ||
                   !sameToneMap(mToneMap, mMetricsToneMap);
    if (!changed || secondsBetween(mLastMetrics, now) < kMetricsInterval) return;

    ImageRGB live = imageFromGL(renderer.width(), renderer.height(), renderer.readHDR());
    mMetricsJob = mJobSerial;
    mMetricsImage = reference;
    mMetricsLiveGeneration = mLiveGeneration;
    mMetricsToneMap = mToneMap;
    mLastMetrics = now;
    // SSIM over a full-size frame takes tens of milliseconds: off the UI thread.
    mMetricsTask = std::async(std::launch::async, [live = std::move(live), reference, toneMap = mToneMap] {
        MetricsResult r;
        try {
            r.metrics = scoreRender(RenderScoreInputs{&live, reference.get(), nullptr, nullptr, toneMap});
            // As writeMetricMaps: a difference as large as the mean reference luminance saturates.
            double luminance = 0.0;
            for (size_t i = 0; i + 2 < reference->rgb.size(); i += 3)
                luminance += 0.2126 * reference->rgb[i] + 0.7152 * reference->rgb[i + 1] + 0.0722 * reference->rgb[i + 2];
            luminance /= std::max<size_t>(reference->rgb.size() / 3, 1);
            r.heat = differenceHeatMap(live, *reference, luminance > 0.0 ? float(1.0 / luminance) : 1.0f);
            r.width = live.width;
            r.height = live.height;
        } catch (const std::exception& e) {
            r.error = e.what();
        }
        return r;
    });
}

bool ReferencePanel::referenceShown() const {
    return mEnabled && !mStale && mShownImage && mReferenceTexture;
}

void ReferencePanel::blit(const gl::Texture& texture, const ViewportRect& v) {
    if (!mReadFBO) mReadFBO = gl::createFramebuffer();
    glNamedFramebufferTexture(mReadFBO.id(), GL_COLOR_ATTACHMENT0, texture.id(), 0);
    // The images' rows are top first, the window's bottom first: the blit flips them.
    glBlitNamedFramebuffer(mReadFBO.id(), v.framebuffer, 0, 0, texture.width(), texture.height(), v.x, v.height, v.x + v.width, 0,
                           GL_COLOR_BUFFER_BIT, GL_LINEAR);
}

void ReferencePanel::splitInteraction(const ViewportRect& v) {
    const ImGuiIO& io = ImGui::GetIO();
    if (v.width <= 0) return;
    float lineX = float(v.x) + mSplit * float(v.width);
    bool nearLine = !io.WantCaptureMouse && std::abs(io.MousePos.x - lineX) <= kSplitGrabPixels;
    if (nearLine && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) mDraggingSplit = true;
    if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) mDraggingSplit = false;
    if (mDraggingSplit) mSplit = std::clamp((io.MousePos.x - float(v.x)) / float(v.width), 0.0f, 1.0f);
    if (nearLine || mDraggingSplit) ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeEW);
}

void ReferencePanel::drawViewport(const ViewportRect& viewport, bool drawImages) {
    if (!mEnabled) return;
    ReferenceView view = mView;
    if (view == ReferenceView::Toggle) {
        bool spaceHeld = !ImGui::GetIO().WantCaptureKeyboard && ImGui::IsKeyDown(GLFW_KEY_SPACE);
        view = mHoldButton || spaceHeld ? ReferenceView::Reference : ReferenceView::Live;
    }
    if (view == ReferenceView::Split) splitInteraction(viewport);
    if (!referenceShown()) return;

    if (view == ReferenceView::Reference) {
        if (drawImages) blit(mReferenceTexture, viewport);
    } else if (view == ReferenceView::Heat) {
        if (drawImages && mHaveMetrics && mHeatTexture) blit(mHeatTexture, viewport);
    } else if (view == ReferenceView::Split) {
        if (drawImages) {
            int splitX = viewport.x + int(std::lround(mSplit * float(viewport.width)));
            glEnable(GL_SCISSOR_TEST);
            glScissor(splitX, 0, viewport.x + viewport.width - splitX, viewport.height);
            blit(mReferenceTexture, viewport);
            glDisable(GL_SCISSOR_TEST);
        }

        // The line and the labels go behind the panels, like the viewport itself.
        ImDrawList* draw = ImGui::GetBackgroundDrawList();
        float x = std::round(float(viewport.x) + mSplit * float(viewport.width));
        draw->AddLine(ImVec2(x, 0.0f), ImVec2(x, float(viewport.height)), IM_COL32(255, 255, 255, 220), 2.0f);
        auto label = [&](const char* text, bool leftOfLine) {
            ImVec2 size = ImGui::CalcTextSize(text);
            ImVec2 pos(leftOfLine ? x - size.x - 10.0f : x + 10.0f, 12.0f);
            draw->AddRectFilled(ImVec2(pos.x - 4.0f, pos.y - 2.0f), ImVec2(pos.x + size.x + 4.0f, pos.y + size.y + 2.0f),
                                IM_COL32(0, 0, 0, 160), 3.0f);
            draw->AddText(pos, IM_COL32(255, 255, 255, 255), text);
        };
        char referenceLabel[64];
        std::snprintf(referenceLabel, sizeof referenceLabel, "reference (%d spp)", mSnapshot->samplesDone);
        label("live", true);
        label(referenceLabel, false);
    }
}

void ReferencePanel::draw() {
    ImGui::Checkbox("enabled", &mEnabled);
    if (!mEnabled) {
        hint("traces the current view on the CPU while you tune; spp, bounces and seed are in the reference section");
        return;
    }
    ImGui::SameLine();
    if (ImGui::Button("Restart")) mRestartRequested = true;

    const ReferenceSnapshot* s = mSnapshot.get();
    int done = s ? s->samplesDone : 0, total = s ? s->samplesTotal : 0;
    char progress[128];
    if (s && s->fromCache)
        std::snprintf(progress, sizeof progress, "%d / %d samples, from the cache", done, total);
    else
        std::snprintf(progress, sizeof progress, "%d / %d samples, %.2f Mrays/s, %.1f s", done, total,
                      s ? s->raysPerSecond * 1e-6 : 0.0, s ? s->seconds : 0.0);
    ImGui::ProgressBar(total > 0 ? float(done) / float(total) : 0.0f, ImVec2(-FLT_MIN, 0.0f), progress);
    // How far the reference itself may stand off its converged image: an SSIM against it cannot be
    // trusted much beyond that.
    if (s && s->noise >= 0.0) {
        const ImVec4 colour = s->noise > 0.05 ? kWarningColor : ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled);
        coloredText(colour, formatNoise(s->noise));
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("the RMS standard error of a reference pixel over the mean brightness, from the difference of two\n"
                              "halves of its samples (alternate passes); it falls as 1/sqrt(spp): 4x the samples halve it");
    } else if (s && s->fromCache) {
        hint("noise: not known for a cached reference");
    }

    if (mStale) {
        coloredText(kWarningColor, "view changed: restarting when it holds still");
    } else if (s && s->state == ReferenceSnapshot::State::Failed) {
        coloredText(kErrorColor, s->error);
    } else if (!s || s->state == ReferenceSnapshot::State::Starting) {
        hint("building the BVH...");
    } else if (s->state == ReferenceSnapshot::State::Finished) {
        hint(s->fromCache ? "finished (read from the cache)" : "finished");
    } else {
        hint("tracing on " + std::to_string(mJob ? mJob->threads() : 1) + " thread(s)" +
             (mJob && mJob->threads() == ReferenceJob::allThreads() ? " (every core: the GI is idle)" : ""));
    }
    if (s && !s->warning.empty()) coloredText(kWarningColor, s->warning);

    int view = int(mView);
    ImGui::RadioButton("Live", &view, int(ReferenceView::Live));
    ImGui::SameLine();
    ImGui::RadioButton("Reference", &view, int(ReferenceView::Reference));
    ImGui::SameLine();
    ImGui::RadioButton("Toggle", &view, int(ReferenceView::Toggle));
    ImGui::RadioButton("Split", &view, int(ReferenceView::Split));
    ImGui::SameLine();
    ImGui::RadioButton("Heat map", &view, int(ReferenceView::Heat));
    mView = ReferenceView(view);

    mHoldButton = false;
    if (mView == ReferenceView::Toggle) {
        ImGui::Button("Hold to compare");
        mHoldButton = ImGui::IsItemActive();
        ImGui::SameLine();
        ImGui::TextDisabled("or hold Space");
    } else if (mView == ReferenceView::Split) {
        ImGui::SliderFloat("split", &mSplit, 0.0f, 1.0f, "%.2f");
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("or drag the line in the viewport");
    } else if (mView == ReferenceView::Heat) {
        ImGui::TextDisabled("red: live brighter, blue: live darker");
    }

    // Numbers of an older view stay in place, greyed, until the new reference has a pass.
    if (mStale) ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    // The seed's score, 10 SSIM^1000, is below 0.5 for any SSIM under 0.997: it says something
    // only for near-identical images, so it is shown only there.
    const bool showScore = mHaveMetrics && mMetrics.ssim >= kScoreMinSSIM;
    if (mHaveMetrics) {
        ImGui::SetWindowFontScale(1.4f);
        ImGui::Text("SSIM %.4f", mMetrics.ssim);
        ImGui::SetWindowFontScale(1.0f);
    }
    if (mHaveMetrics && ImGui::BeginTable("metrics", showScore ? 3 : 2, ImGuiTableFlags_BordersInnerV)) {
        if (showScore) ImGui::TableSetupColumn("seed score");
        for (const char* name : {"RMSE", "PSNR"}) ImGui::TableSetupColumn(name);
        ImGui::TableHeadersRow();
        ImGui::TableNextRow();
        if (showScore) {
            ImGui::TableNextColumn();
            ImGui::Text("%.3g", mMetrics.score);
        }
        ImGui::TableNextColumn();
        ImGui::Text("%.4f", mMetrics.rmse);
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(formatPSNR(mMetrics.psnr).c_str());
        ImGui::EndTable();
    } else if (!mStale && !(s && s->state == ReferenceSnapshot::State::Failed)) {
        hint("SSIM: after the first pass");
    }
    if (mStale) ImGui::PopStyleColor();
    if (!mTaskError.empty()) coloredText(kErrorColor, mTaskError);
}

bool ReferencePanel::settled() const {
    if (!mEnabled || !mJob || !mJob->done() || mStale) return false;
    if (!mSnapshot || mSnapshot->version != mJob->version()) return false;
    if (mSnapshot->state == ReferenceSnapshot::State::Failed) return true;
    if (mSnapshot->state != ReferenceSnapshot::State::Finished || mShownImage != mSnapshot->image) return false;
    // The metrics must be of this final image and of the live image as it is now.
    return !mMetricsTask.valid() && mMetricsJob == mJobSerial && mMetricsImage == mSnapshot->image &&
           mMetricsLiveGeneration == mLiveGeneration && sameToneMap(mMetricsToneMap, mToneMap) &&
           (mHaveMetrics || !mTaskError.empty());
}

std::string ReferencePanel::error() const {
    if (mSnapshot && mSnapshot->state == ReferenceSnapshot::State::Failed) return mSnapshot->error;
    return mTaskError;
}

std::string ReferencePanel::summary() const {
    char text[256];
    int done = mSnapshot ? mSnapshot->samplesDone : 0, total = mSnapshot ? mSnapshot->samplesTotal : 0;
    if (!mHaveMetrics) {
        std::snprintf(text, sizeof text, "reference %d/%d spp, no metrics", done, total);
    } else {
        std::snprintf(text, sizeof text, "reference %d/%d spp: SSIM %.4f, score %.3g, RMSE %.4f, PSNR %s", done, total,
                      mMetrics.ssim, mMetrics.score, mMetrics.rmse, formatPSNR(mMetrics.psnr).c_str());
    }
    std::string out = text;
    if (mSnapshot && mSnapshot->noise >= 0.0) {
        std::snprintf(text, sizeof text, ", reference noise %.1f %%", mSnapshot->noise * 100.0);
        out += text;
    }
    return out;
}

}  // namespace gi::ui
