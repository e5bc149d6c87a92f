// The scene on the GPU: vertices, indices, textures and the draw list. Passes draw it through
// draw(); the renderer owns it.
#pragma once

#include "gi/gl/handle.h"
#include "gi/scene/scene.h"

#include <cstdint>
#include <type_traits>
#include <vector>

namespace gi {

// GPU copy of a Scene.
class GPUScene {
public:
    explicit GPUScene(const Scene& scene);
    // Issues the scene's draws. `bindMaterial(material, index)` sets per-material uniforms and
    // textures; given a third parameter it also gets the draw's first triangle (the index of its
    // gl_PrimitiveID 0 in per-triangle buffers such as uTriangleEmitter).
    template <class F>
    void draw(F&& bindMaterial) const {
        drawIf([](const Material&) { return true; }, bindMaterial);
    }
    // The draws whose material `include(material)` accepts, in the scene's order.
    template <class P, class F>
    void drawIf(P&& include, F&& bindMaterial) const {
        glBindVertexArray(mVAO.id());
        for (const Draw& d : mDraws) {
            if (!include(mMaterials[d.material])) continue;
            if constexpr (std::is_invocable_v<F, const Material&, int, int>)
                bindMaterial(mMaterials[d.material], d.material, int(d.firstIndex / 3));
            else
                bindMaterial(mMaterials[d.material], d.material);
            glDrawElements(GL_TRIANGLES, GLsizei(d.indexCount), GL_UNSIGNED_INT,
                           reinterpret_cast<const void*>(uintptr_t(d.firstIndex) * 4));
        }
    }
    // Bytes a scene will take on the GPU (vertices, indices, textures with their mips), known
    // before upload so budgets can refuse it first.
    static size_t estimateBytes(const Scene& scene);
    GLuint texture(int index) const { return index >= 0 ? mTextures[index].id() : 0; }
    const std::vector<Material>& materials() const { return mMaterials; }
    // Distinct for every GPUScene made in the process, so techniques can tell a new scene apart.
    uint64_t id() const { return mId; }
    size_t memoryBytes() const { return mBytes; }
    const Bounds& bounds() const { return mBounds; }
    // The scene's emissive surfaces (Scene::emitters), which area lights name.
    const std::vector<Emitter>& emitters() const { return mEmitters; }
    // Binds the per-triangle emitter index at light::kTriangleEmitterBinding.
    void bindTriangleEmitters() const;

private:
    gl::Buffer mVertices, mIndices;
    gl::VertexArray mVAO;
    std::vector<gl::Texture> mTextures;
    std::vector<Draw> mDraws;
    std::vector<Material> mMaterials;
    std::vector<Emitter> mEmitters;
    gl::Buffer mTriangleEmitter;
    Bounds mBounds;
    size_t mBytes = 0;
    uint64_t mId = 0;
};

}  // namespace gi
