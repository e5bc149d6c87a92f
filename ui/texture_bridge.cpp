#include "ui/texture_bridge.h"

#include "gi/render/image_io.h"
#include "gi/util/error.h"

#include <epoxy/gl.h>

#include <algorithm>

namespace gi::ui {

namespace {

// Bridged ids carry this bit above any GL name, so resolve() tells them from the window's own
// textures (the font atlas).
constexpr uintptr_t kBridgeTag = uintptr_t(1) << 40;
// A copy nobody asked for in this many frames is dropped.
constexpr uint64_t kKeepFrames = 600;

}  // namespace

TextureBridge::~TextureBridge() {
    for (auto& [name, c] : mCopies)
        if (c.texture) glDeleteTextures(1, &c.texture);
}

ImTextureID TextureBridge::id(const gl::Texture& texture) {
    if (!texture) return ImTextureID(nullptr);
    Copy& c = mCopies[texture.id()];
    c.lastUsed = mFrame;
    if (mLive) {
        // Read into a scratch buffer: an image that did not change is not uploaded again, so a
        // frame that shows nothing new stays undrawn (Window::finishUI).
        mScratch.resize(size_t(texture.width()) * size_t(texture.height()) * 4);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glGetTextureImage(texture.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(mScratch.size()), mScratch.data());
        if (c.width != texture.width() || c.height != texture.height() || c.texture == 0 || mScratch != c.pixels) {
            c.width = texture.width();
            c.height = texture.height();
            c.pixels.swap(mScratch);
            c.fresh = true;
        }
    }
    return ImTextureID(uintptr_t(texture.id()) | kBridgeTag);
}

void TextureBridge::upload(Copy& c) {
    if (!c.fresh) return;
    c.fresh = false;
    if (!c.texture || c.textureWidth != c.width || c.textureHeight != c.height) {
        if (c.texture) glDeleteTextures(1, &c.texture);
        glCreateTextures(GL_TEXTURE_2D, 1, &c.texture);
        glTextureStorage2D(c.texture, 1, GL_RGBA8, c.width, c.height);
        glTextureParameteri(c.texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(c.texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(c.texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(c.texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        c.textureWidth = c.width;
        c.textureHeight = c.height;
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(c.texture, 0, 0, 0, c.width, c.height, GL_RGBA, GL_UNSIGNED_BYTE, c.pixels.data());
    ++mUploads;
}

void TextureBridge::resolve(ImDrawData* drawData) {
    for (auto it = mCopies.begin(); it != mCopies.end();) {
        if (mFrame - it->second.lastUsed > kKeepFrames) {
            if (it->second.texture) glDeleteTextures(1, &it->second.texture);
            it = mCopies.erase(it);
        } else {
            upload(it->second);
            ++it;
        }
    }
    for (int i = 0; drawData && i < drawData->CmdListsCount; ++i)
        for (ImDrawCmd& cmd : drawData->CmdLists[i]->CmdBuffer) {
            uintptr_t id = uintptr_t(cmd.TextureId);
            if (!(id & kBridgeTag)) continue;
            auto found = mCopies.find(unsigned(id & ~kBridgeTag));
            cmd.TextureId = ImTextureID(uintptr_t(found == mCopies.end() ? 0u : found->second.texture));
        }
    ++mFrame;
}

unsigned TextureBridge::windowTexture(const gl::Texture& texture, int& width, int& height) {
    auto found = mCopies.find(texture.id());
    if (!texture || found == mCopies.end()) return 0;
    Copy& c = found->second;
    c.lastUsed = mFrame;
    upload(c);
    width = c.textureWidth;
    height = c.textureHeight;
    return c.texture;
}

namespace {
TextureBridge* gBridge = nullptr;
}

TextureBridge& textureBridge() {
    GI_ASSERT(gBridge, "no window: the texture bridge belongs to ui::Window");
    return *gBridge;
}

void setTextureBridge(TextureBridge* bridge) { gBridge = bridge; }

gl::Texture imageFileTexture(const std::filesystem::path& path) {
    ImageRGBA8 img = readImage8(path);
    std::vector<uint8_t> rows(img.rgba.size());
    const size_t stride = size_t(img.width) * 4;
    for (int y = 0; y < img.height; ++y)  // the file's top row last
        std::copy_n(img.rgba.begin() + long(size_t(img.height - 1 - y) * stride), stride, rows.begin() + long(size_t(y) * stride));
    gl::Texture t = gl::Texture::create2D(GL_RGBA8, img.width, img.height);
    glTextureSubImage2D(t.id(), 0, 0, 0, img.width, img.height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    return t;
}

void giImage(const gl::Texture& texture, ImVec2 size) {
    ImGui::Image(textureBridge().id(texture), size, ImVec2(0, 1), ImVec2(1, 0));
}

}  // namespace gi::ui
