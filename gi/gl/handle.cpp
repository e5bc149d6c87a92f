#include "gi/gl/handle.h"

#include "gi/util/error.h"

namespace gi::gl {

void checkFramebuffer(GLuint fbo, const char* what) {
    GLenum status = glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER);
    GI_ASSERT(status == GL_FRAMEBUFFER_COMPLETE, what);
}

void unbindTextureUnits() {
    static const GLint units = [] {
        GLint n = 0;
        glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &n);
        return n;
    }();
    glBindTextures(0, units, nullptr);
}

size_t bytesPerTexel(GLenum f) {
    switch (f) {
        case GL_R8: return 1;
        case GL_RG8: case GL_R16F: return 2;
        case GL_RGBA8: case GL_SRGB8_ALPHA8: case GL_R32F: case GL_R32UI: case GL_RG16F:
        case GL_DEPTH_COMPONENT32F: case GL_DEPTH_COMPONENT24: case GL_DEPTH24_STENCIL8: case GL_RGB10_A2: case GL_R11F_G11F_B10F:
            return 4;
        case GL_RGBA16F: case GL_RG32F: case GL_DEPTH32F_STENCIL8: return 8;
        case GL_RGB32F: return 12;
        case GL_RGBA32F: return 16;
    }
    GI_ASSERT(false, "bytesPerTexel: add the format to the table");
    return 0;
}

static size_t mipChainBytes(size_t base, int w, int h, int d, int levels) {
    size_t total = 0;
    for (int l = 0; l < levels; ++l) {
        total += base * size_t(std::max(w >> l, 1)) * size_t(std::max(h >> l, 1)) * size_t(std::max(d >> l, 1));
    }
    return total;
}

Texture Texture::create2D(GLenum internalFormat, int width, int height, int levels) {
    Texture t;
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &id);
    glTextureStorage2D(id, levels, internalFormat, width, height);
    t.mHandle = Handle<detail::deleteTexture>(id);
    t.mTarget = GL_TEXTURE_2D;
    t.mFormat = internalFormat;
    t.mWidth = width;
    t.mHeight = height;
    t.mDepth = 1;
    t.mBytes = mipChainBytes(bytesPerTexel(internalFormat), width, height, 1, levels);
    return t;
}

Texture Texture::createCube(GLenum internalFormat, int size, int levels) {
    Texture t;
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &id);
    glTextureStorage2D(id, levels, internalFormat, size, size);
    t.mHandle = Handle<detail::deleteTexture>(id);
    t.mTarget = GL_TEXTURE_CUBE_MAP;
    t.mFormat = internalFormat;
    t.mWidth = t.mHeight = size;
    t.mDepth = 6;
    t.mBytes = 6 * mipChainBytes(bytesPerTexel(internalFormat), size, size, 1, levels);
    return t;
}

Texture Texture::create3D(GLenum internalFormat, int width, int height, int depth, int levels) {
    Texture t;
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_3D, 1, &id);
    glTextureStorage3D(id, levels, internalFormat, width, height, depth);
    t.mHandle = Handle<detail::deleteTexture>(id);
    t.mTarget = GL_TEXTURE_3D;
    t.mFormat = internalFormat;
    t.mWidth = width;
    t.mHeight = height;
    t.mDepth = depth;
    t.mBytes = mipChainBytes(bytesPerTexel(internalFormat), width, height, depth, levels);
    return t;
}

}  // namespace gi::gl
