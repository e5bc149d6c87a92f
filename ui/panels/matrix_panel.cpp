// The matrix part of the compare section (issue 15 item 6): load a gi-matrix output folder and
// show any two of its cells side by side, or split at a movable line, with their figures (SSIM,
// ms, brightness, leak, memory) and the settings that differ between them.
#include "ui/editor.h"

#include "ui/panel_util.h"
#include "ui/texture_bridge.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cstdio>

namespace fs = std::filesystem;

namespace gi::ui {

namespace {

std::string cellName(const matrix::CellResult& c) { return c.scene + " / " + c.label; }

std::string figures(const matrix::CellResult& c) {
    if (!c.ok()) return c.status + ": " + c.error;
    char text[200];
    std::snprintf(text, sizeof text, "SSIM %.4f, %.1f ms\n   brightness %.3f, leak %.4f, %.1f MiB", c.ssim, c.msTotal, c.brightness,
                  c.leakFraction, c.memoryBytes / 1048576.0);
    return text;
}

}  // namespace

void Editor::loadMatrix(const fs::path& dir) {
    mMatrixDir = dir.string();
    mMatrixCells = matrix::reportedResults(dir);
    if (mMatrixCells.empty()) throw Error(dir.string() + ": no gi-matrix results (cells/*/*/result.json) there");
    mMatrixPick = {0, std::min<size_t>(1, mMatrixCells.size() - 1)};
    for (auto& t : mMatrixImages) t = gl::Texture();
    mMatrixShown = {std::string(), std::string()};
    mMatrixError.clear();
}

void Editor::matrixComparePanel() {
    ImGui::InputText("results", &mMatrixDir);
    ImGui::SameLine();
    if (ImGui::SmallButton("Load")) {
        try {
            loadMatrix(mMatrixDir);
        } catch (const std::exception& e) {
            mMatrixError = e.what();
            mMatrixCells.clear();
        }
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("a gi-matrix --out folder (results in cells/, index.html beside them)");
    if (!mMatrixError.empty()) wrappedText(kErrorColor, mMatrixError);
    if (mMatrixCells.empty()) {
        hintText("load a matrix to compare two of its cells");
        return;
    }
    for (int side = 0; side < 2; ++side) {
        size_t& pick = mMatrixPick[size_t(side)];
        ImGui::PushID(side);
        if (ImGui::BeginCombo(side == 0 ? "cell A" : "cell B", cellName(mMatrixCells[pick]).c_str())) {
            for (size_t i = 0; i < mMatrixCells.size(); ++i)
                if (ImGui::Selectable(cellName(mMatrixCells[i]).c_str(), i == pick)) pick = i;
            ImGui::EndCombo();
        }
        ImGui::PopID();
    }
    // The two images, loaded into the GI context when the choice changes.
    for (size_t side = 0; side < 2; ++side) {
        const matrix::CellResult& c = mMatrixCells[mMatrixPick[side]];
        fs::path image = fs::path(mMatrixDir) / c.folder / "image.png";
        if (mLive && mMatrixShown[side] != image.string()) {
            mMatrixShown[side] = image.string();
            mMatrixImages[side] = gl::Texture();
            if (c.ok() && fs::exists(image)) {
                try {
                    mMatrixImages[side] = imageFileTexture(image);
                } catch (const std::exception& e) {
                    mMatrixError = e.what();
                }
            }
        }
    }
    ImGui::RadioButton("side by side", &mMatrixView, 0);
    ImGui::SameLine();
    ImGui::RadioButton("split", &mMatrixView, 1);
    if (mMatrixView == 1) ImGui::SliderFloat("A | B##matrix", &mMatrixSplit, 0.0f, 1.0f, "%.2f");
    const gl::Texture& a = mMatrixImages[0];
    const gl::Texture& b = mMatrixImages[1];
    const float avail = ImGui::GetContentRegionAvail().x;
    if (a && b) {
        if (mMatrixView == 0) {
            const float w = 0.5f * (avail - ImGui::GetStyle().ItemSpacing.x);
            giImage(a, ImVec2(w, w * float(a.height()) / float(a.width())));
            ImGui::SameLine();
            giImage(b, ImVec2(w, w * float(b.height()) / float(b.width())));
        } else {
            // A left of the line, B right of it, at A's aspect; B's image is stretched to it.
            const float w = avail, h = w * float(a.height()) / float(a.width()), s = mMatrixSplit;
            ImVec2 at = ImGui::GetCursorScreenPos();
            ImDrawList* draw = ImGui::GetWindowDrawList();
            draw->AddImage(textureBridge().id(a), at, ImVec2(at.x + w * s, at.y + h), ImVec2(0, 1), ImVec2(s, 0));
            draw->AddImage(textureBridge().id(b), ImVec2(at.x + w * s, at.y), ImVec2(at.x + w, at.y + h), ImVec2(s, 1), ImVec2(1, 0));
            draw->AddLine(ImVec2(at.x + w * s, at.y), ImVec2(at.x + w * s, at.y + h), IM_COL32(255, 210, 80, 230), 2.0f);
            ImGui::Dummy(ImVec2(w, h));
        }
    } else {
        hintText("a failed cell has no image");
    }
    ImGui::TextWrapped("A: %s", figures(mMatrixCells[mMatrixPick[0]]).c_str());
    ImGui::TextWrapped("B: %s", figures(mMatrixCells[mMatrixPick[1]]).c_str());
    // The settings that differ: each side's overrides that the other lacks.
    const auto& sa = mMatrixCells[mMatrixPick[0]].settings;
    const auto& sb = mMatrixCells[mMatrixPick[1]].settings;
    for (const std::string& s : sa)
        if (std::find(sb.begin(), sb.end(), s) == sb.end()) ImGui::BulletText("A: %s", s.c_str());
    for (const std::string& s : sb)
        if (std::find(sa.begin(), sa.end(), s) == sa.end()) ImGui::BulletText("B: %s", s.c_str());
    if (mMatrixCells[mMatrixPick[0]].technique != mMatrixCells[mMatrixPick[1]].technique)
        ImGui::BulletText("technique: %s | %s", mMatrixCells[mMatrixPick[0]].technique.c_str(),
                          mMatrixCells[mMatrixPick[1]].technique.c_str());
}

json Editor::matrixState() const {
    json j = {{"cells", mMatrixCells.size()}, {"error", mMatrixError}, {"view", mMatrixView == 0 ? "side" : "split"}};
    if (!mMatrixCells.empty())
        j["pick"] = {cellName(mMatrixCells[mMatrixPick[0]]), cellName(mMatrixCells[mMatrixPick[1]])};
    j["imagesShown"] = bool(mMatrixImages[0]) && bool(mMatrixImages[1]);
    return j;
}

}  // namespace gi::ui
