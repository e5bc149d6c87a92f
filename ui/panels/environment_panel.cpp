// The environment's panel: the Roughness mips table (each entry's mip, roughness, face size,
// samples, cone radius and prefilter time; entries edited in place, added and removed) and a
// preview of one mip of the built chain as a latlong image or the cube's cross.
#include "common/shared.h"
#include "gi/envmap/environment.h"
#include "ui/editor.h"
#include "ui/panel_util.h"
#include "ui/pass_panel.h"
#include "ui/texture_bridge.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>

namespace gi::ui {

namespace {

class EnvironmentPanel final : public PassPanel {
public:
    explicit EnvironmentPanel(const EditorOptions& options) : mOpen(options.roughnessMips), mScrollTo(mOpen ? 10 : 0) {}

    bool openAtStart() const override { return mOpen; }

    uint8_t drawSection(PanelContext& ctx) override {
        if (mOpen) ImGui::SetNextItemOpen(true, ImGuiCond_Once);
        bool open = ImGui::TreeNodeEx("Roughness mips", ImGuiTreeNodeFlags_Framed);
        if (mScrollTo > 0) {
            // Started with --mips-panel: keep the panel at the top of the window until the layout settles.
            ImGui::SetScrollHereY(0.0f);
            --mScrollTo;
        }
        if (!open) return 0;
        EnvironmentSettings& s = ctx.preset.environment;
        // What the chain holds, read while the GI context is held and shown from that otherwise.
        if (ctx.renderer) {
            const Environment* envPass = ctx.renderer->activePass<Environment>();
            GI_ASSERT(envPass, "the environment is an effect: the renderer always holds it");
            mChain = {envPass->ready(), envPass->loadMs(), envPass->ready() ? envPass->mips() : std::vector<Environment::MipInfo>{},
                      envPass->prefiltered()};
        }
        const Chain& env = mChain;
        // The change tag comes from the settings table, as for every other edit.
        Cost tableCost = Cost::Reallocate;
        s.visit([&](auto&, const FieldMeta& m) {
            if (std::string_view(m.key) == "mipRoughness") tableCost = m.cost;
        });
        uint8_t cost = 0;

        if (!s.enabled) {
            hintText("environment lighting is off (environment.enabled): no mip chain is built; the table below is what one would hold");
        } else if (!env.ready) {
            wrappedText(kErrorColor, "the environment map did not load" + (ctx.frameError.empty() ? std::string(" (see the message above)")
                                                                                              : ": " + ctx.frameError));
        } else if (!ctx.frameError.empty() && lowercase(ctx.frameError).find("environment") != std::string::npos) {
            wrappedText(kErrorColor, "the last change failed, the chain shown is the previous one: " + ctx.frameError);
        }

        // How many mips the cube can hold, and the mip each entry feeds (-1: skipped), by the rule
        // the prefilter uses (Environment::chainMipOfEntry).
        EnvironmentSettings full = s;
        full.mipRoughness.assign(32, 0.0f);
        const int fit = Environment::chainMipCount(full);
        std::vector<float>& table = s.mipRoughness;
        auto mipOf = [&](int entry) { return Environment::chainMipOfEntry(s, entry); };
        const bool cone = s.distribution == PrefilterDistribution::BeckmannCone;
        const std::vector<Environment::MipInfo>& built = env.mips;
        const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerH | ImGuiTableFlags_SizingStretchProp;
        if (ImGui::BeginTable("mips", 6, flags)) {
            ImGui::TableSetupColumn("mip", ImGuiTableColumnFlags_WidthFixed);
            ImGui::TableSetupColumn("roughness", ImGuiTableColumnFlags_WidthStretch, 2.2f);
            ImGui::TableSetupColumn("face", ImGuiTableColumnFlags_WidthStretch, 1.0f);
            ImGui::TableSetupColumn("spp", ImGuiTableColumnFlags_WidthStretch, 1.0f);
            ImGui::TableSetupColumn("disk", ImGuiTableColumnFlags_WidthStretch, 1.0f);
            ImGui::TableSetupColumn("ms", ImGuiTableColumnFlags_WidthStretch, 1.1f);
            static const char* const tips[6] = {"the mip the entry feeds (click: preview it)",
                                                "perceptual roughness (settings: environment.mipRoughness)",
                                                "texels per cube face",
                                                "prefilter samples per texel (copy: roughness 0 copies the source)",
                                                "beckmannCone: the sampling disk's radius, tan theta (seed 004 Fig. 3.24)",
                                                "prefilter time of the mip (CPU clock around the finished dispatch)"};
            ImGui::TableNextRow(ImGuiTableRowFlags_Headers);
            for (int c = 0; c < 6; ++c) {
                ImGui::TableSetColumnIndex(c);
                ImGui::TableHeader(ImGui::TableGetColumnName(c));
                if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tips[c]);
            }
            for (size_t e = 0; e < table.size(); ++e) {
                const int mip = mipOf(int(e));
                ImGui::PushID(int(e));
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                if (mip >= 0) {
                    char label[16];
                    std::snprintf(label, sizeof label, "%d", mip);
                    if (ImGui::Selectable(label, mSelected == mip)) mSelected = mip;
                } else {
                    ImGui::TextDisabled("-");
                    if (ImGui::IsItemHovered()) ImGui::SetTooltip("entry %zu is skipped: the cube has %d mips", e, fit);
                }
                ImGui::TableNextColumn();
                // Dragging one entry past a neighbour pushes the neighbour along: the table stays
                // non-decreasing, as shading's piecewise linear lookup needs.
                float r = table[e];
                ImGui::SetNextItemWidth(-FLT_MIN);
                if (ImGui::DragFloat("##roughness", &r, 0.005f, 0.0f, 1.0f, "%.3f", ImGuiSliderFlags_AlwaysClamp)) {
                    table[e] = r;
                    for (size_t j = 0; j < e; ++j) table[j] = std::min(table[j], r);
                    for (size_t j = e + 1; j < table.size(); ++j) table[j] = std::max(table[j], r);
                    cost |= uint8_t(tableCost);
                }
                if (ImGui::IsItemHovered()) ImGui::SetTooltip("perceptual roughness of entry %zu (dragging past a neighbour moves it too)", e);
                const bool used = mip >= 0;
                auto cell = [](const char* fmt, auto value, bool show) {
                    ImGui::TableNextColumn();
                    if (show) ImGui::Text(fmt, value);
                    else ImGui::TextDisabled("-");
                };
                cell("%d", used ? std::max(s.cubeSize >> mip, 1) : 0, used);
                if (used && table[e] <= 0.0f) {
                    ImGui::TableNextColumn();
                    ImGui::TextDisabled("copy");
                } else {
                    cell("%d", s.samples, used);
                }
                cell("%.2f", Environment::beckmannDiskRadius(table[e]), used && cone);
                const bool timed = used && size_t(mip) < built.size();
                cell("%.1f", timed ? built[size_t(mip)].ms : 0.0, timed);
                ImGui::PopID();
            }
            ImGui::EndTable();
        }
        if (int(table.size()) > fit) {
            const int first = fit - 1, last = int(table.size()) - 2;
            std::string skipped = first == last ? "entry " + std::to_string(first) + " is"
                                                : "entries " + std::to_string(first) + ".." + std::to_string(last) + " are";
            hintText("a " + std::to_string(s.cubeSize) + "^2 cube has " + std::to_string(fit) + " mips: " + skipped +
                     " skipped and the last entry goes on the last mip");
        }
        const bool canAdd = int(table.size()) < fit;
        if (!canAdd) ImGui::BeginDisabled();
        if (ImGui::Button("Add mip")) {
            // Continues the last step, so the table stays non-decreasing and ends at most at 1.
            float last = table.back(), step = table.size() > 1 ? last - table[table.size() - 2] : 0.1f;
            table.push_back(std::min(1.0f, last + std::max(step, 0.0f)));
            cost |= uint8_t(tableCost);
        }
        if (!canAdd) ImGui::EndDisabled();
        ImGui::SameLine();
        const bool canRemove = table.size() > 1;
        if (!canRemove) ImGui::BeginDisabled();
        if (ImGui::Button("Remove last")) {
            table.pop_back();
            cost |= uint8_t(tableCost);
        }
        if (!canRemove) ImGui::EndDisabled();
        ImGui::SameLine();
        if (ImGui::Button("Seed defaults")) {
            table = EnvironmentSettings{}.mipRoughness;
            cost |= uint8_t(tableCost);
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("the seed's 11 levels (seed 004, Fig. 3.24)");
        if (env.ready) {
            double total = env.loadMs;
            for (const Environment::MipInfo& info : built) total += info.ms;
            char line[128];
            std::snprintf(line, sizeof line, "%zu mips (%s): load %.1f ms, with the prefilter %.1f ms", built.size(),
                          enumName(s.distribution), env.loadMs, total);
            hintText(line);
        }

        // The selected mip of the built chain, through the renderer's view pass.
        if (s.enabled && env.ready && !built.empty()) {
            ImGui::Separator();
            mSelected = std::clamp(mSelected, 0, int(built.size()) - 1);
            if (ImGui::RadioButton("cross", !mLatLong)) mLatLong = false;
            ImGui::SameLine();
            if (ImGui::RadioButton("latlong", mLatLong)) mLatLong = true;
            ImGui::SliderInt("preview mip", &mSelected, 0, int(built.size()) - 1);
            ImGui::SliderFloat("mip exposure", &mExposure, -10.0f, 10.0f, "%.1f EV");
            const float width = std::max(std::floor(ImGui::GetContentRegionAvail().x), 64.0f);
            const int w = int(width), h = mLatLong ? w / 2 : w * 3 / 4;
            if (ctx.renderer && (!mImage || mImage.width() != w || mImage.height() != h)) {
                mImage = gl::Texture::create2D(GL_RGBA8, w, h);
                if (!mFBO) mFBO = gl::createFramebuffer();
                glNamedFramebufferTexture(mFBO.id(), GL_COLOR_ATTACHMENT0, mImage.id(), 0);
            }
            DebugView view;
            view.name = "environment.mip" + std::to_string(mSelected);
            view.texture = env.prefiltered;
            view.target = GL_TEXTURE_CUBE_MAP;
            view.mode = mLatLong ? shared::kViewCubeLatLong : shared::kViewCubeCross;
            view.width = w;
            view.height = h;
            view.level = mSelected;
            Renderer::ViewParams params;
            params.exposure = mExposure;
            if (ctx.renderer) {
                glBindFramebuffer(GL_FRAMEBUFFER, mFBO.id());
                glViewport(0, 0, w, h);
                ctx.renderer->drawView(view, params);
                glBindFramebuffer(GL_FRAMEBUFFER, 0);
            }
            giImage(mImage, ImVec2(float(w), float(h)));
            const Environment::MipInfo& info = built[size_t(mSelected)];
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip(mLatLong ? "latlong: the centre looks along -z, +x at three quarters, the zenith at the top"
                                              : "cross: -x +z +x -z in the middle row, +y above +z, -y below");
            ImGui::TextDisabled("mip %d: roughness %.3f, %d^2 a face", mSelected, info.roughness, info.size);
        }
        ImGui::TreePop();
        return cost;
    }

private:
    bool mOpen = false;     // open the section and the table at start (--mips-panel)
    int mScrollTo = 0;      // frames left in which the settings window scrolls to the table
    int mSelected = 0;
    bool mLatLong = true;   // the preview as a latlong image, else as the cube's cross
    float mExposure = 0.0f; // EV
    gl::Texture mImage;     // the preview, rendered by Renderer::drawView at the panel's width
    gl::Framebuffer mFBO;
    struct Chain {
        bool ready = false;
        double loadMs = 0.0;
        std::vector<Environment::MipInfo> mips;
        GLuint prefiltered = 0;
    };
    Chain mChain;  // the environment pass's chain as last read (the GI thread may hold the renderer)
};

}  // namespace

std::unique_ptr<PassPanel> makeEnvironmentPanel(const EditorOptions& options) { return std::make_unique<EnvironmentPanel>(options); }

}  // namespace gi::ui
