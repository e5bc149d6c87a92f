// Buffer previewer: any of the renderer's debug views (G-buffer channels, linearised depth,
// shadow maps, RSMs, LPV and geometry volume slices) with channel select, exposure, zoom (mouse
// wheel), pan (left drag) and a readout of the source texel under the mouse. Volume views add the
// slice axis and position, and what a voxel shows: the irradiance towards a chosen direction (or
// the blocking towards it, for the geometry volume) or one SH coefficient, in false colour or not.
#pragma once

#include "gi/gl/handle.h"
#include "gi/render/renderer.h"

#include <glm/vec2.hpp>

#include <string>

namespace gi::ui {

class BufferPreviewer {
public:
    explicit BufferPreviewer(std::string view = "final") : mView(std::move(view)) {}

    // Draws the controls and the view into the current ImGui window, filling its content region.
    void draw(const Renderer& renderer);

private:
    std::string mView;  // by name, so the choice survives the views being rebuilt
    int mChannel = 0;   // RGB, R, G, B, A
    float mExposure = 0.0f;
    float mZoom = 1.0f;
    glm::vec2 mPan{0.0f};
    Renderer::ViewParams mVolume;  // slice, axis and what a voxel shows, for volume views
    gl::Texture mImage;  // what the panel shows, rendered by drawView at the panel's size
    gl::Framebuffer mFBO;

    void renderImage(const Renderer& renderer, const DebugView& view, int width, int height);
    void volumeControls(const DebugView& view);
    void interact(glm::vec2 screenUV, glm::vec2 size, bool dragging);
    static void readout(const DebugView& view, glm::vec2 uv);
};

}  // namespace gi::ui
