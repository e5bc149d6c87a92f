// The Auto-tune panel (issue 15 item 5): gi-matrix --tune's search on the open scene, live: a
// technique, a frame-time budget and a number of renders; a progress bar, the best render so far
// (its image, SSIM, ms and the settings that differ), the path the search took, Cancel, and
// Apply, which makes the winner an undoable edit of the preset. The renders are gi-render
// processes (ui/tune_job.h), so the editor stays live while they run.
#include "ui/editor.h"

#include "gi/matrix/run.h"
#include "ui/panel_util.h"
#include "ui/texture_bridge.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <unistd.h>

namespace fs = std::filesystem;

namespace gi::ui {

namespace {

std::vector<std::string> tunableTechniques() {
    std::vector<std::string> out;
    for (const SettingInfo& s : listSettings())
        if (s.key == "technique")
            for (const std::string& t : s.choices)
                if (!matrix::tuneSpace(t).empty()) out.push_back(t);
    return out;
}

const char* stateName(TuneSnapshot::State s) {
    switch (s) {
        case TuneSnapshot::State::Running: return "running";
        case TuneSnapshot::State::Finished: return "finished";
        case TuneSnapshot::State::Cancelled: return "cancelled";
        case TuneSnapshot::State::Failed: return "failed";
    }
    return "";
}

}  // namespace

void Editor::startTune() {
    if (mTuneRequest.technique.empty()) mTuneRequest.technique = mPreset.header.technique.name;
    std::vector<std::string> techniques = tunableTechniques();
    if (std::find(techniques.begin(), techniques.end(), mTuneRequest.technique) == techniques.end())
        throw Error("auto-tune: technique '" + mTuneRequest.technique + "' has no settings to tune");
    static int runs = 0;
    fs::path out = fs::temp_directory_path() / ("gi-editor-tune-" + std::to_string(getpid())) / std::to_string(++runs);
    mTune = std::make_unique<TuneJob>(mPreset, mTuneRequest, matrix::siblingExecutable("gi-render"), out);
    mTuneSnapshot = TuneSnapshot();
    mTuneImagePath.clear();
}

void Editor::applyTune() {
    if (!mTune) throw Error("auto-tune: nothing to apply (start a search first)");
    const TuneSnapshot s = mTune->snapshot();
    if (!s.report.best || !s.report.best->withinBudget) throw Error("auto-tune: no render within the budget to apply");
    Preset p = mPreset;
    applySetting(p, "technique=" + mTune->request().technique);
    for (const std::string& a : s.report.best->settings) applySetting(p, a);
    mPreset = p;
    apply(uint8_t(Cost::Uniform));
    mPresetStatus = "applied the auto-tune's best settings";
}

void Editor::tunePanel() {
    static const std::vector<std::string> techniques = tunableTechniques();
    if (mTuneRequest.technique.empty())
        mTuneRequest.technique = std::find(techniques.begin(), techniques.end(), mPreset.header.technique.name) != techniques.end()
                                     ? mPreset.header.technique.name
                                     : (techniques.empty() ? "" : techniques.front());
    const bool running = mTune && !mTune->done();
    if (mTune) mTuneSnapshot = mTune->snapshot();

    ImGui::BeginDisabled(running);
    if (ImGui::BeginCombo("technique", mTuneRequest.technique.c_str())) {
        for (const std::string& t : techniques)
            if (ImGui::Selectable(t.c_str(), t == mTuneRequest.technique)) mTuneRequest.technique = t;
        ImGui::EndCombo();
    }
    float budget = float(mTuneRequest.budgetMs);
    if (ImGui::DragFloat("budget", &budget, 1.0f, 1.0f, 100000.0f, "%.0f ms")) mTuneRequest.budgetMs = std::max(budget, 1.0f);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("the frame time the result must stay within, as measured on this machine");
    int renders = int(mTuneRequest.renders);
    if (ImGui::SliderInt("renders", &renders, 3, 64)) mTuneRequest.renders = size_t(renders);
    int size[2] = {mTuneRequest.width, mTuneRequest.height};
    if (ImGui::InputInt2("size", size)) {
        mTuneRequest.width = std::clamp(size[0], 16, 1024);
        mTuneRequest.height = std::clamp(size[1], 16, 1024);
    }
    ImGui::EndDisabled();

    if (!running) {
        if (ImGui::Button("Start")) {
            try {
                startTune();
            } catch (const std::exception& e) {
                mTuneError = e.what();
            }
        }
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("search the technique's settings on this scene, each render a gi-render process scored against the reference");
    } else if (ImGui::Button("Cancel")) {
        mTune->cancel();
    }
    if (!mTuneError.empty()) wrappedText(kErrorColor, mTuneError);
    if (!mTune) {
        hintText("a coordinate pattern search from the preset's values (gi-matrix --tune)");
        return;
    }
    const TuneSnapshot& s = mTuneSnapshot;
    const float fraction = s.maxRenders ? float(s.report.renders) / float(s.maxRenders) : 0.0f;
    char label[96];
    std::snprintf(label, sizeof label, "%zu / %zu renders, %s (%s)", s.report.renders, s.maxRenders,
                  matrix::formatDuration(s.seconds).c_str(), stateName(s.state));
    ImGui::ProgressBar(s.state == TuneSnapshot::State::Running ? fraction : 1.0f, ImVec2(-1.0f, 0.0f), label);
    if (s.state == TuneSnapshot::State::Failed) wrappedText(kErrorColor, s.error);

    if (s.report.best) {
        const matrix::TuneStep& b = *s.report.best;
        // The best render's image, loaded into the GI context when it changes.
        if (mLive && s.bestImage != mTuneImagePath && fs::exists(s.bestImage)) {
            try {
                mTuneImage = imageFileTexture(s.bestImage);
                mTuneImagePath = s.bestImage;
            } catch (const std::exception& e) {
                mTuneError = e.what();
                mTuneImagePath = s.bestImage;
            }
        }
        char best[160];
        std::snprintf(best, sizeof best, "best: SSIM %.4f at %.1f ms%s", b.result.ssim, b.result.msTotal,
                      b.withinBudget ? "" : " (over the budget)");
        ImGui::TextUnformatted(best);
        if (mTuneImage) {
            float width = std::min(ImGui::GetContentRegionAvail().x, 256.0f);
            giImage(mTuneImage, ImVec2(width, width * float(mTuneImage.height()) / float(mTuneImage.width())));
        }
        if (b.settings.empty()) hintText("the preset's own settings");
        for (const std::string& a : b.settings) ImGui::BulletText("%s", a.c_str());
        ImGui::BeginDisabled(running || !b.withinBudget);
        if (ImGui::Button("Apply")) {
            try {
                applyTune();
            } catch (const std::exception& e) {
                mTuneError = e.what();
            }
        }
        ImGui::EndDisabled();
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
            ImGui::SetTooltip("set the technique and the best settings in the editor (undoable)");
    }
    // The path: newest first.
    if (!s.report.steps.empty() && ImGui::BeginTable("tunepath", 4, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
        ImGui::TableSetupColumn("#");
        ImGui::TableSetupColumn("change");
        ImGui::TableSetupColumn("SSIM");
        ImGui::TableSetupColumn("ms");
        ImGui::TableHeadersRow();
        size_t shown = 0;
        for (auto it = s.report.steps.rbegin(); it != s.report.steps.rend() && shown < 12; ++it, ++shown) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::Text("%zu%s", it->render, it->best ? "*" : "");
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(it->change.c_str());
            ImGui::TableNextColumn();
            if (it->result.ok())
                ImGui::Text("%.4f", it->result.ssim);
            else
                ImGui::TextUnformatted(it->result.status.c_str());
            ImGui::TableNextColumn();
            if (it->result.ok()) ImGui::TextColored(it->withinBudget ? ImVec4(1, 1, 1, 1) : kErrorColor, "%.0f", it->result.msTotal);
        }
        ImGui::EndTable();
    }
}

json Editor::tuneState() const {
    if (!mTune) return {{"started", false}};
    const TuneSnapshot s = mTune->snapshot();
    json j = {{"started", true},
              {"state", stateName(s.state)},
              {"technique", mTune->request().technique},
              {"renders", s.report.renders},
              {"steps", s.report.steps.size()},
              {"error", s.error},
              {"imageShown", bool(mTuneImage)}};
    if (s.report.best)
        j["best"] = {{"ssim", s.report.best->result.ssim},
                     {"ms", s.report.best->result.msTotal},
                     {"withinBudget", s.report.best->withinBudget},
                     {"settings", s.report.best->settings}};
    return j;
}

}  // namespace gi::ui
