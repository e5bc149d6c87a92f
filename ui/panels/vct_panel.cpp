// VCT's panel: the voxel grid seen from the camera, in the viewport or in a window, with the
// source (albedo, normal, radiance), level, mip and exposure to show.
#include "gi/vct/vct_views.h"
#include "ui/editor.h"
#include "ui/panel_util.h"
#include "ui/pass_panel.h"
#include "ui/texture_bridge.h"

#include <algorithm>

namespace gi::ui {

namespace {

class VCTPanel final : public PassPanel {
public:
    explicit VCTPanel(const EditorOptions& options) {
        if (options.voxelView.empty()) return;
        bool known = false;
        std::string names;
        for (const auto& [value, name] : EnumNames<VoxelViewSource>::values) {
            names += std::string(names.empty() ? "" : ", ") + name;
            if (options.voxelView == name) {
                mParams.source = value;
                known = true;
            }
        }
        if (!known) throw Error("unknown voxel view '" + options.voxelView + "' (valid: " + names + ")");
        mDisplay = options.voxelWindow ? Display::Window : Display::Viewport;
    }

    uint8_t drawSection(PanelContext& ctx) override {
        ImGui::Separator();
        int display = int(mDisplay);
        ImGui::Combo("voxel view", &display, "off\0in the viewport\0in a window\0");
        mDisplay = Display(display);
        if (mDisplay == Display::Off) return 0;
        int source = int(mParams.source);
        ImGui::Combo("voxels show", &source, "albedo\0normal\0radiance\0");
        mParams.source = VoxelViewSource(source);
        const VCTSettings& s = ctx.preset.vct;
        int levels = s.mode == VCTMode::Dense ? 1 : s.levelCount;
        if (levels > 1) {
            ImGui::Checkbox("auto level", &mAutoLevel);
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("the finest level that holds the camera's target");
            ImGui::SameLine();
            if (mAutoLevel) ImGui::BeginDisabled();
            ImGui::SliderInt("voxel level", &mParams.level, 0, levels - 1);
            if (mAutoLevel) ImGui::EndDisabled();
        }
        mParams.level = std::clamp(mParams.level, 0, levels - 1);
        if (mParams.source == VoxelViewSource::Radiance) {
            ImGui::SliderInt("voxel mip", &mParams.mip, 0, vctMipCount(s.gridResolution) - 1);
            ImGui::SliderFloat("solid from", &mParams.opacityThreshold, 0.01f, 1.0f, "opacity %.2f");
            ImGui::SliderFloat("voxel exposure", &mParams.exposure, -10.0f, 10.0f, "%.1f EV");
        }
        ImGui::Checkbox("voxel edges", &mParams.edges);
        return 0;
    }

    bool drawsViewport(const FrameSettings& fs) const override {
        return mDisplay == Display::Viewport && fs.technique == VCTSettings::kSection;
    }

    void drawViewport(PanelContext& ctx, const FrameSettings& fs, const ViewportRect& viewport) override {
        if (!drawsViewport(fs)) return;
        render(ctx, fs, viewport.framebuffer, viewport.width, viewport.height, viewport.x);
    }

    void drawWindows(PanelContext& ctx) override {
        if (mDisplay != Display::Window || ctx.preset.header.technique != VCTSettings::kSection || ctx.width <= 0) return;
        const ImVec2 display = ImGui::GetIO().DisplaySize;
        ImGui::SetNextWindowPos(ImVec2(kLeftWidth + 2 * kMargin, display.y - 300.0f - kMargin), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowSize(ImVec2(400.0f, 300.0f), ImGuiCond_FirstUseEver);
        bool open = true;
        if (ImGui::Begin("Voxel view", &open, ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse)) {
            ImVec2 avail = ImGui::GetContentRegionAvail();
            int w = std::max(int(avail.x), 16), h = std::max(int(avail.y), 16);
            if (ctx.renderer && (!mImage || mImage.width() != w || mImage.height() != h)) {
                mImage = gl::Texture::create2D(GL_RGBA8, w, h);
                if (!mFBO) mFBO = gl::createFramebuffer();
                glNamedFramebufferTexture(mFBO.id(), GL_COLOR_ATTACHMENT0, mImage.id(), 0);
            }
            render(ctx, frameSettings(ctx.preset, ctx.scene, ctx.width, ctx.height), mFBO.id(), w, h);
            giImage(mImage, ImVec2(float(w), float(h)));
        }
        ImGui::End();
        if (!open) mDisplay = Display::Off;
    }

private:
    enum class Display { Off, Viewport, Window };
    Display mDisplay = Display::Off;
    VoxelViewParams mParams;
    bool mAutoLevel = true;  // the finest level holding the camera's target
    VoxelView mView;
    gl::Texture mImage;      // the window's picture
    gl::Framebuffer mFBO;

    void render(PanelContext& ctx, const FrameSettings& fs, GLuint framebuffer, int width, int height, int x = 0) {
        if (!ctx.renderer) return;  // the GI thread holds it: the last picture stands
        std::vector<VoxelGridView> grids = voxelGrids(ctx.renderer->debugViews(), fs, ctx.scene.bounds);
        VoxelViewParams params = mParams;
        params.viewProj = projectionMatrix(fs.camera, float(width) / float(height)) * viewMatrix(fs.camera);
        if (mAutoLevel) params.level = finestLevelHolding(grids, fs.camera.target);
        mView.render(grids, params, framebuffer, width, height, x);
    }
};

}  // namespace

std::unique_ptr<PassPanel> makeVCTPanel(const EditorOptions& options) { return std::make_unique<VCTPanel>(options); }

}  // namespace gi::ui
