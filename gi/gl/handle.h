// Move-only RAII owners for GL object names, created with DSA (glCreate*).
#pragma once

#include <epoxy/gl.h>

#include <utility>

namespace gi::gl {

template <void (*Delete)(GLuint)>
class Handle {
public:
    Handle() = default;
    explicit Handle(GLuint id) : mId(id) {}
    ~Handle() { reset(); }
    Handle(Handle&& o) noexcept : mId(std::exchange(o.mId, 0)) {}
    Handle& operator=(Handle&& o) noexcept {
        if (this != &o) {
            reset();
            mId = std::exchange(o.mId, 0);
        }
        return *this;
    }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;

    GLuint id() const { return mId; }
    explicit operator bool() const { return mId != 0; }
    void reset() {
        if (mId) Delete(mId);
        mId = 0;
    }

private:
    GLuint mId = 0;
};

namespace detail {
inline void deleteBuffer(GLuint id) { glDeleteBuffers(1, &id); }
inline void deleteTexture(GLuint id) { glDeleteTextures(1, &id); }
inline void deleteFramebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
inline void deleteVertexArray(GLuint id) { glDeleteVertexArrays(1, &id); }
inline void deleteProgram(GLuint id) { glDeleteProgram(id); }
inline void deleteShader(GLuint id) { glDeleteShader(id); }
inline void deleteQuery(GLuint id) { glDeleteQueries(1, &id); }
inline void deleteSampler(GLuint id) { glDeleteSamplers(1, &id); }
}  // namespace detail

using Buffer = Handle<detail::deleteBuffer>;
using Framebuffer = Handle<detail::deleteFramebuffer>;
using VertexArray = Handle<detail::deleteVertexArray>;
using ProgramHandle = Handle<detail::deleteProgram>;
using ShaderHandle = Handle<detail::deleteShader>;
using Query = Handle<detail::deleteQuery>;
using Sampler = Handle<detail::deleteSampler>;
// A texture name without the shape gl::Texture keeps: buffer textures, which view a buffer's
// storage (glTextureBuffer) and take no storage of their own.
using TextureHandle = Handle<detail::deleteTexture>;

inline TextureHandle createBufferTexture() {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &id);
    return TextureHandle(id);
}

inline Buffer createBuffer(size_t bytes, const void* data, GLbitfield flags = 0) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    glNamedBufferStorage(id, GLsizeiptr(bytes), data, flags);
    return Buffer(id);
}

// A sampler object: filters, wrap modes (wrapT and wrapR follow wrapS unless given), and depth
// comparison (LEQUAL) for shadow samplers. The border colour stays GL's default, transparent black.
struct SamplerDesc {
    GLenum minFilter = GL_LINEAR;
    GLenum magFilter = GL_LINEAR;
    GLenum wrapS = GL_CLAMP_TO_EDGE;
    GLenum wrapT = 0, wrapR = 0;  // 0: as wrapS
    bool compare = false;
};
inline Sampler createSampler(const SamplerDesc& d) {
    GLuint s = 0;
    glCreateSamplers(1, &s);
    glSamplerParameteri(s, GL_TEXTURE_MIN_FILTER, GLint(d.minFilter));
    glSamplerParameteri(s, GL_TEXTURE_MAG_FILTER, GLint(d.magFilter));
    glSamplerParameteri(s, GL_TEXTURE_WRAP_S, GLint(d.wrapS));
    glSamplerParameteri(s, GL_TEXTURE_WRAP_T, GLint(d.wrapT ? d.wrapT : d.wrapS));
    glSamplerParameteri(s, GL_TEXTURE_WRAP_R, GLint(d.wrapR ? d.wrapR : d.wrapS));
    if (d.compare) {
        glSamplerParameteri(s, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glSamplerParameteri(s, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    }
    return Sampler(s);
}

inline Framebuffer createFramebuffer() {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    return Framebuffer(id);
}

// Framebuffers are built from formats this project controls: incompleteness is a programming error.
void checkFramebuffer(GLuint fbo, const char* what);

// Unbinds every texture unit. A texture left bound to a unit while a later draw renders into it
// (a G-buffer target or a shadow map bound by the previous frame's lighting) makes Mesa's
// llvmpipe shade that draw about 10x slower, even when the program never samples that unit: the
// built-in Cornell box at 640x360 took 2110 ms from its second frame on instead of 235 ms.
// The renderer calls this at the start of each frame and after each pass.
void unbindTextureUnits();

// Bytes per texel of the internal formats this project allocates (for memory reports).
size_t bytesPerTexel(GLenum internalFormat);

// A texture that remembers its shape and the bytes it holds.
class Texture {
public:
    Texture() = default;
    static Texture create2D(GLenum internalFormat, int width, int height, int levels = 1);
    static Texture createCube(GLenum internalFormat, int size, int levels = 1);
    static Texture create3D(GLenum internalFormat, int width, int height, int depth, int levels = 1);

    GLuint id() const { return mHandle.id(); }
    explicit operator bool() const { return bool(mHandle); }
    GLenum target() const { return mTarget; }
    GLenum format() const { return mFormat; }
    int width() const { return mWidth; }
    int height() const { return mHeight; }
    int depth() const { return mDepth; }
    size_t bytes() const { return mBytes; }

private:
    Handle<detail::deleteTexture> mHandle;
    GLenum mTarget = 0, mFormat = 0;
    int mWidth = 0, mHeight = 0, mDepth = 0;
    size_t mBytes = 0;
};

}  // namespace gi::gl
