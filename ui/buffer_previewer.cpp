#include "ui/buffer_previewer.h"

#include "ui/texture_bridge.h"

#include "common/shared.h"

#include <glm/common.hpp>
#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace gi::ui {

namespace {

constexpr glm::vec4 kChannelMasks[] = {{1, 1, 1, 0}, {1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
constexpr float kMinZoom = 0.1f, kMaxZoom = 512.0f;

// The texture coordinate drawView samples at a point of the panel (view.frag's mapping).
glm::vec2 sourceUV(glm::vec2 screenUV, float zoom, glm::vec2 pan) { return (screenUV - 0.5f) / zoom + 0.5f + pan; }

}  // namespace

const DebugView* BufferPreviewer::findView(const std::vector<DebugView>& views) const {
    for (const DebugView& v : views)
        if (v.name == mView) return &v;
    return nullptr;
}

bool BufferPreviewer::drawViewport(const Renderer* renderer, const ViewportRect& viewport) {
    if (!mFill || viewport.width <= 0 || viewport.height <= 0 || !renderer) return false;
    mViews = renderer->debugViews();
    const DebugView* view = findView(mViews);
    if (!view) return false;
    renderImage(*renderer, *view, mViewport, viewport.width, viewport.height);
    glBlitNamedFramebuffer(mViewport.fbo.id(), viewport.framebuffer, 0, 0, viewport.width, viewport.height, viewport.x, 0, viewport.x + viewport.width,
                           viewport.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    const ImGuiIO& io = ImGui::GetIO();
    if (!io.WantCaptureMouse && viewport.contains(io.MousePos) && view->target == GL_TEXTURE_2D) {
        glm::vec2 screenUV((io.MousePos.x - float(viewport.x)) / float(viewport.width), 1.0f - io.MousePos.y / float(viewport.height));
        ImGui::BeginTooltip();
        readout(*view, sourceUV(screenUV, mZoom, mPan));
        ImGui::EndTooltip();
    }
    return true;
}

void BufferPreviewer::draw(const Renderer* renderer) {
    if (renderer) mViews = renderer->debugViews();
    const std::vector<DebugView>& views = mViews;
    const DebugView* view = findView(views);

    if (ImGui::BeginCombo("view", mView.c_str())) {
        for (const DebugView& v : views)
            if (ImGui::Selectable(v.name.c_str(), v.name == mView)) mView = v.name;
        ImGui::EndCombo();
    }
    ImGui::Combo("channel", &mChannel, "RGB\0R\0G\0B\0A\0");
    ImGui::SliderFloat("exposure", &mExposure, -10.0f, 10.0f, "%.1f EV");
    if (ImGui::Button("Reset zoom")) {
        mZoom = 1.0f;
        mPan = glm::vec2(0.0f);
    }
    ImGui::SameLine();
    ImGui::Checkbox("fill viewport", &mFill);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("show this view in the viewport instead of the final image; hover it for the texel readout");
    ImGui::SameLine();
    ImGui::TextDisabled("%.2fx", mZoom);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("wheel over the image: zoom, drag: pan");
    if (!view) {
        ImGui::TextDisabled("view '%s' is not available", mView.c_str());
        return;
    }
    if (view->target == GL_TEXTURE_3D) volumeControls(*view);

    // Fit the view's aspect into the space left above one readout line.
    ImVec2 avail = ImGui::GetContentRegionAvail();
    avail.y -= ImGui::GetTextLineHeightWithSpacing();
    float aspect = float(std::max(view->width, 1)) / float(std::max(view->height, 1));
    glm::vec2 size = avail.x / aspect <= avail.y ? glm::vec2(avail.x, avail.x / aspect) : glm::vec2(avail.y * aspect, avail.y);
    size = glm::max(glm::floor(size), glm::vec2(16.0f));
    if (renderer) renderImage(*renderer, *view, mPanel, int(size.x), int(size.y));

    ImVec2 pos = ImGui::GetCursorScreenPos();
    giImage(mPanel.image, ImVec2(size.x, size.y));
    // An invisible button over the image takes the clicks, so dragging pans instead of moving the window.
    ImGui::SetCursorScreenPos(pos);
    ImGui::InvisibleButton("##image", ImVec2(size.x, size.y));
    bool hovered = ImGui::IsItemHovered();
    const ImGuiIO& io = ImGui::GetIO();
    // Screen y grows down, texture v grows up.
    glm::vec2 screenUV((io.MousePos.x - pos.x) / size.x, 1.0f - (io.MousePos.y - pos.y) / size.y);
    if (hovered || ImGui::IsItemActive()) interact(screenUV, size, ImGui::IsItemActive());

    if (!hovered) {
        ImGui::TextDisabled("%s: %dx%d", view->name.c_str(), view->width, view->height);
    } else if (!renderer) {
        ImGui::TextDisabled("readout once the GI frame in flight is done");
    } else if (view->target == GL_TEXTURE_CUBE_MAP) {
        ImGui::TextDisabled("no texel readout for cube maps");
    } else {
        if (view->target == GL_TEXTURE_3D) ImGui::TextDisabled("volume slice: no texel readout");
        else readout(*view, sourceUV(screenUV, mZoom, mPan));
    }
}

void BufferPreviewer::renderImage(const Renderer& renderer, const DebugView& view, Target& target, int width, int height) {
    if (!target.image || target.image.width() != width || target.image.height() != height) {
        target.image = gl::Texture::create2D(GL_RGBA8, width, height);
        if (!target.fbo) target.fbo = gl::createFramebuffer();
        glNamedFramebufferTexture(target.fbo.id(), GL_COLOR_ATTACHMENT0, target.image.id(), 0);
    }
    Renderer::ViewParams params;
    params.channelMask = kChannelMasks[mChannel];
    params.exposure = mExposure;
    params.zoom = mZoom;
    params.pan = mPan;
    params.axis = mVolume.axis;
    params.slice = mVolume.slice;
    params.shComponent = mVolume.shComponent;
    params.direction = mVolume.direction;
    params.falseColour = mVolume.falseColour;
    glBindFramebuffer(GL_FRAMEBUFFER, target.fbo.id());
    glViewport(0, 0, width, height);
    renderer.drawView(view, params);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void BufferPreviewer::volumeControls(const DebugView& view) {
    // Two compact lines, so the slice image keeps its room in a small window.
    float half = ImGui::GetContentRegionAvail().x * 0.5f - ImGui::GetStyle().ItemSpacing.x;
    ImGui::SetNextItemWidth(half * 0.35f);
    ImGui::Combo("##axis", &mVolume.axis, "X\0Y\0Z\0");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(half * 1.65f);
    ImGui::SliderFloat("slice", &mVolume.slice, 0.0f, 1.0f, "%.3f");
    // -1 shows the irradiance (SH volumes) or blocking (geometry) towards the direction.
    int show = mVolume.shComponent + 1;
    bool sh = view.mode == shared::kViewSHVolume;
    ImGui::SetNextItemWidth(half * 0.8f);
    ImGui::Combo("##shows", &show, sh ? "irradiance\0SH 0\0SH 1\0SH 2\0SH 3\0" : "blocking\0SH 0\0SH 1\0SH 2\0SH 3\0");
    mVolume.shComponent = show - 1;
    ImGui::SameLine();
    if (mVolume.shComponent < 0) {
        ImGui::SetNextItemWidth(half * 0.9f);
        ImGui::DragFloat3("##direction", &mVolume.direction.x, 0.01f, -1.0f, 1.0f, "%.1f");
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("normal of the surface whose irradiance (or blocking) is shown");
        ImGui::SameLine();
    }
    ImGui::Checkbox("false colour", &mVolume.falseColour);
}

void BufferPreviewer::interact(glm::vec2 screenUV, glm::vec2 size, bool dragging) {
    const ImGuiIO& io = ImGui::GetIO();
    if (io.MouseWheel != 0.0f) {
        // Zoom about the mouse: the texel under it stays put.
        glm::vec2 anchor = sourceUV(screenUV, mZoom, mPan);
        mZoom = std::clamp(mZoom * std::pow(1.2f, io.MouseWheel), kMinZoom, kMaxZoom);
        mPan = anchor - (screenUV - 0.5f) / mZoom - 0.5f;
    }
    if (dragging) mPan -= glm::vec2(io.MouseDelta.x, -io.MouseDelta.y) / size / mZoom;
}

void BufferPreviewer::readout(const DebugView& view, glm::vec2 uv) {
    if (uv.x < 0.0f || uv.y < 0.0f || uv.x >= 1.0f || uv.y >= 1.0f) {
        ImGui::TextDisabled("outside the texture");
        return;
    }
    int x = std::min(int(uv.x * float(view.width)), view.width - 1);
    int y = std::min(int(uv.y * float(view.height)), view.height - 1);
    GLint depthBits = 0;
    glGetTextureLevelParameteriv(view.texture, 0, GL_TEXTURE_DEPTH_SIZE, &depthBits);
    float texel[4] = {};
    if (depthBits > 0) {
        glGetTextureSubImage(view.texture, 0, x, y, 0, 1, 1, 1, GL_DEPTH_COMPONENT, GL_FLOAT, sizeof(float), texel);
        if (view.mode == shared::kViewLinearDepth) {
            // The same linearisation view.frag applies, as a distance.
            float distance = shared::viewDepthOf(texel[0], view.near, view.far);
            ImGui::Text("(%d, %d)  depth %.6f (%.3f m)", x, y, texel[0], distance);
        } else {
            ImGui::Text("(%d, %d)  depth %.6f", x, y, texel[0]);
        }
    } else {
        glGetTextureSubImage(view.texture, 0, x, y, 0, 1, 1, 1, GL_RGBA, GL_FLOAT, sizeof texel, texel);
        ImGui::Text("(%d, %d)  %.4g %.4g %.4g %.4g", x, y, texel[0], texel[1], texel[2], texel[3]);
    }
}

}  // namespace gi::ui
