// Buffer previewer: any of the renderer's debug views (G-buffer channels, linearised depth,
// shadow maps, RSMs, LPV and geometry volume slices) with channel select, exposure, zoom (mouse
// wheel), pan (left drag) and a readout of the source texel under the mouse. Volume views add the
// slice axis and position, and what a voxel shows: the irradiance towards a chosen direction (or
// the blocking towards it, for the geometry volume) or one SH coefficient, in false colour or not.
#pragma once

#include "gi/gl/handle.h"
#include "gi/render/renderer.h"
#include "ui/panel_util.h"

#include <glm/vec2.hpp>

#include <string>

namespace gi::ui {

class BufferPreviewer {
public:
    explicit BufferPreviewer(std::string view = "final") : mView(std::move(view)) {}

    // Draws the controls and the view into the current ImGui window, filling its content region.
    // A null renderer (the GI thread holds it): the controls, the last image, no readout.
    void draw(const Renderer* renderer);
    // With "fill viewport" on: the view, at the viewport's size and with the same channel,
    // exposure, zoom and pan, into viewport.framebuffer, and its texel readout by the mouse when
    // it hovers the viewport. Returns whether it drew. A null renderer: nothing (the last one stands).
    bool drawViewport(const Renderer* renderer, const ViewportRect& viewport);
    bool fill() const { return mFill; }
    void setFill(bool fill) { mFill = fill; }
    const std::string& view() const { return mView; }
    void setView(const std::string& view) { mView = view; }

private:
    std::string mView;  // by name, so the choice survives the views being rebuilt
    int mChannel = 0;   // RGB, R, G, B, A
    float mExposure = 0.0f;
    float mZoom = 1.0f;
    glm::vec2 mPan{0.0f};
    Renderer::ViewParams mVolume;  // slice, axis and what a voxel shows, for volume views
    bool mFill = false;  // the view fills the viewport
    struct Target {
        gl::Texture image;  // rendered by drawView at the size it is shown
        gl::Framebuffer fbo;
    };
    Target mPanel, mViewport;
    std::vector<DebugView> mViews;  // the renderer's, as last read

    const DebugView* findView(const std::vector<DebugView>& views) const;
    void renderImage(const Renderer& renderer, const DebugView& view, Target& target, int width, int height);
    void volumeControls(const DebugView& view);
    void interact(glm::vec2 screenUV, glm::vec2 size, bool dragging);
    static void readout(const DebugView& view, glm::vec2 uv);
};

}  // namespace gi::ui
