// Images made in the GI context and shown by the window's. The GI context is an EGL context of its
// own (ui/gi_thread.h), not shared with the window's: on Mesa llvmpipe, contexts that share
// objects share one rasterizer queue, so the window's frame would wait behind seconds of GI
// work. Nothing is shared, so images cross on the CPU: while the UI thread holds the GI context,
// each image it shows is read back (RGBA8); the window's context then uploads what changed and the
// draw data is pointed at its copies. While the GI thread renders, the last copies are shown.
#pragma once

#include <filesystem>

#include "gi/gl/handle.h"

#include <imgui.h>

#include <cstdint>
#include <map>
#include <vector>

namespace gi::ui {

class TextureBridge {
public:
    // The window's context must be current when the bridge is destroyed (its copies are deleted).
    ~TextureBridge();

    // Whether the GI context is current on this thread this frame (images are read back).
    void setLive(bool live) { mLive = live; }
    bool live() const { return mLive; }
    // The ImTextureID that draws `texture` (an RGBA8 texture of the GI context) in the window:
    // read back now when live, else its last copy.
    ImTextureID id(const gl::Texture& texture);
    // Window's context, after ImGui::Render: uploads the new copies and points the draw data's
    // bridged ids at them; a bridged texture with no copy yet draws as nothing (texture 0).
    void resolve(ImDrawData* drawData);
    // Window's context: the copy of a bridged texture (0 when there is none), for a blit.
    unsigned windowTexture(const gl::Texture& texture, int& width, int& height);
    // How many images the window's context has received so far (a new one changes the window).
    uint64_t uploads() const { return mUploads; }

private:
    struct Copy {
        std::vector<uint8_t> pixels;  // read back, waiting to be uploaded
        int width = 0, height = 0;
        bool fresh = false;           // pixels not yet uploaded
        unsigned texture = 0;         // the window context's copy
        int textureWidth = 0, textureHeight = 0;
        uint64_t lastUsed = 0;        // the frame it was last asked for
    };
    std::map<unsigned, Copy> mCopies;  // by the GI context's texture name
    bool mLive = false;
    uint64_t mFrame = 0;
    uint64_t mUploads = 0;
    std::vector<uint8_t> mScratch;  // a read-back, compared with the copy before it replaces it
    void upload(Copy& c);
};

// The window's bridge (the editor has one window, as ImGui has one context; ui/window.h owns it).
TextureBridge& textureBridge();
void setTextureBridge(TextureBridge* bridge);
// ImGui::Image of a GI-context texture, rows bottom first as GL has them.
void giImage(const gl::Texture& texture, ImVec2 size);
// An image file (PNG, through OpenImageIO) as an RGBA8 texture of the GI context, rows in GL order
// as giImage draws them. Throws gi::Error naming the file.
gl::Texture imageFileTexture(const std::filesystem::path& path);

}  // namespace gi::ui
