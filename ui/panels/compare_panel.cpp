// The A/B panel: hold the GI image with its settings as A, then show B (live), A, or a split of the
// two in the viewport, each side with its GI ms and its SSIM against the reference; the settings
// that differ between A and B, and between the editor and any preset file, key by key.
#include "ui/editor.h"

#include "ui/panel_util.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace fs = std::filesystem;

namespace gi::ui {

namespace {

std::string sideText(const char* name, float ms, glm::ivec2 size, std::optional<double> ssim) {
    char text[160];
    if (ssim)
        std::snprintf(text, sizeof text, "%s: SSIM %.4f, GI %.0f ms at %dx%d", name, *ssim, ms, size.x, size.y);
    else
        std::snprintf(text, sizeof text, "%s: GI %.0f ms at %dx%d (no reference)", name, ms, size.x, size.y);
    return text;
}

// Key, before, after; at most `limit` rows, then how many more.
void changeTable(const char* id, const char* before, const char* after, const std::vector<PresetChange>& changes, size_t limit) {
    if (changes.empty()) {
        hintText("no setting differs");
        return;
    }
    if (!ImGui::BeginTable(id, 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerH | ImGuiTableFlags_SizingStretchProp)) return;
    ImGui::TableSetupColumn("setting");
    ImGui::TableSetupColumn(before);
    ImGui::TableSetupColumn(after);
    ImGui::TableHeadersRow();
    for (size_t i = 0; i < std::min(changes.size(), limit); ++i) {
        const PresetChange& c = changes[i];
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(c.key.c_str());
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(c.before.empty() ? "-" : c.before.c_str());
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(c.after.empty() ? "-" : c.after.c_str());
    }
    ImGui::EndTable();
    if (changes.size() > limit) hintText("... and " + std::to_string(changes.size() - limit) + " more");
}

}  // namespace

void Editor::holdSnapshot() {
    Snapshot s;
    s.size = {mRenderer.width(), mRenderer.height()};
    s.image = gl::Texture::create2D(GL_RGBA8, s.size.x, s.size.y);
    glCopyImageSubData(mRenderer.outputTexture(), GL_TEXTURE_2D, 0, 0, 0, 0, s.image.id(), GL_TEXTURE_2D, 0, 0, 0, 0, s.size.x,
                       s.size.y, 1);
    s.preset = mPreset;
    s.ms = mRenderMs;
    s.ssim = mReference.ssim();
    mSnapshotA = std::move(s);
    if (mCompareView == CompareView::Live) mCompareView = CompareView::Split;
    mPresetStatus = "held A";
}

void Editor::drawComparison(const ViewportRect& target, bool drawImages) {
    if (!comparing()) return;
    const Snapshot& a = *mSnapshotA;
    const int splitX = mCompareView == CompareView::A ? target.x + target.width
                                                       : target.x + int(std::lround(mCompareSplit * float(target.width)));
    if (drawImages) {
        if (!mSnapshotFBO) mSnapshotFBO = gl::createFramebuffer();
        glNamedFramebufferTexture(mSnapshotFBO.id(), GL_COLOR_ATTACHMENT0, a.image.id(), 0);
        glEnable(GL_SCISSOR_TEST);
        glScissor(target.x, 0, std::max(splitX - target.x, 0), target.height);
        glBlitNamedFramebuffer(mSnapshotFBO.id(), target.framebuffer, 0, 0, a.size.x, a.size.y, target.x, 0, target.x + target.width,
                               target.height, GL_COLOR_BUFFER_BIT, GL_LINEAR);
        glDisable(GL_SCISSOR_TEST);
    }
    // The line and the labels go with the panels, drawn every frame: A's label in the viewport's
    // lower left corner, B's in its lower right, each in the side it names.
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    auto label = [&](const std::string& text, float y, bool alignLeft) {
        ImVec2 size = ImGui::CalcTextSize(text.c_str());
        ImVec2 pos(alignLeft ? float(target.x) + 10.0f : float(target.x + target.width) - size.x - 10.0f, y);
        draw->AddRectFilled(ImVec2(pos.x - 4.0f, pos.y - 2.0f), ImVec2(pos.x + size.x + 4.0f, pos.y + size.y + 2.0f), IM_COL32(0, 0, 0, 170), 3.0f);
        draw->AddText(pos, IM_COL32(255, 255, 255, 255), text.c_str());
    };
    const float lineHeight = ImGui::GetTextLineHeight() + 8.0f;
    const std::string aText = sideText("A", a.ms, a.size, a.ssim);
    if (mCompareView == CompareView::A) {
        label(aText + "  (F: flip to B)", float(target.height) - lineHeight, true);
        return;
    }
    const float x = float(splitX);
    draw->AddLine(ImVec2(x, 0.0f), ImVec2(x, float(target.height)), IM_COL32(255, 210, 80, 230), 2.0f);
    label(aText, float(target.height) - 2.0f * lineHeight, true);
    label(sideText("B (live)", mRenderMs, mRenderSize, mReference.ssim()), float(target.height) - lineHeight, false);
}

void Editor::diffWithFile(const fs::path& path) {
    mDiffPath = path.string();
    try {
        mFileDiff = presetDiff(loadPreset(path), mPreset);
        mDiffError.clear();
    } catch (const std::exception& e) {
        mFileDiff.reset();
        mDiffError = e.what();
    }
}

void Editor::comparePanel() {
    if (ImGui::Button(mSnapshotA ? "Hold A again" : "Hold A")) mHoldRequested = true;
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("hold the GI image with its settings, GI time and SSIM as A; then change settings and compare with the live image (B)");
    if (mSnapshotA) {
        ImGui::SameLine();
        if (ImGui::Button("Drop A")) {
            mSnapshotA.reset();
            mCompareView = CompareView::Live;
        }
    }
    if (mHoldRequested) hintText("A is taken once the GI shows the current settings");
    if (mSnapshotA) {
        int view = int(mCompareView);
        ImGui::RadioButton("B (live)", &view, int(CompareView::Live));
        ImGui::SameLine();
        ImGui::RadioButton("A", &view, int(CompareView::A));
        ImGui::SameLine();
        ImGui::RadioButton("split", &view, int(CompareView::Split));
        mCompareView = CompareView(view);
        ImGui::SameLine();
        if (ImGui::SmallButton("Flip (F)")) flipCompare();
        if (mCompareView == CompareView::Split) ImGui::SliderFloat("A | B", &mCompareSplit, 0.0f, 1.0f, "%.2f");
        ImGui::TextUnformatted(sideText("A", mSnapshotA->ms, mSnapshotA->size, mSnapshotA->ssim).c_str());
        ImGui::TextUnformatted(sideText("B", mRenderMs, mRenderSize, mReference.ssim()).c_str());
        if (!mReference.enabled()) hintText("enable the Reference panel for each side's SSIM (A keeps the SSIM it had when held)");
        ImGui::TextUnformatted("settings, A -> B");
        changeTable("ab", "A", "B", presetDiff(mSnapshotA->preset, mPreset), 16);
    }
    ImGui::Separator();
    if (mDiffPath.empty()) mDiffPath = mPathField;
    ImGui::InputText("file", &mDiffPath);
    ImGui::SameLine();
    if (ImGui::SmallButton("Diff")) diffWithFile(mDiffPath);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("list the settings that differ between this preset file and the editor's");
    if (!mDiffError.empty()) wrappedText(kErrorColor, mDiffError);
    else if (mFileDiff) changeTable("file", "file", "editor", *mFileDiff, 24);
    ImGui::Separator();
    ImGui::TextUnformatted("matrix cells");
    matrixComparePanel();
}

json Editor::compareState() const {
    auto keys = [](const std::vector<PresetChange>& changes) {
        json k = json::array();
        for (const PresetChange& c : changes) k.push_back(c.key);
        return k;
    };
    static const char* kViews[] = {"live", "a", "split"};
    return {{"held", bool(mSnapshotA)},
            {"view", kViews[int(mCompareView)]},
            {"abDiff", mSnapshotA ? keys(presetDiff(mSnapshotA->preset, mPreset)) : json::array()},
            {"aSSIM", mSnapshotA && mSnapshotA->ssim ? json(*mSnapshotA->ssim) : json()},
            {"fileDiff", mFileDiff ? keys(*mFileDiff) : json()},
            {"diffError", mDiffError}};
}

}  // namespace gi::ui
