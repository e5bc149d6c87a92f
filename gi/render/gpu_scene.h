// The scene on the GPU: vertices, indices, textures and the draw list. Passes draw it through
// draw(); the renderer owns it.
#pragma once

#include "gi/gl/handle.h"
#include "gi/scene/free_path.h"
#include "gi/scene/scene.h"

#include <glm/glm.hpp>

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
    void draw(F&& bindMaterial, const glm::mat4* cull = nullptr) const {
        drawIf([](const Material&) { return true; }, bindMaterial, cull);
    }
    // The draws whose material `include(material)` accepts, in the scene's order. With `cull`
    // (a view-projection), the clusters of a draw (runs of kClusterTriangles triangles, issue 17
    // item 5) whose bounds lie wholly outside its frustum are left out: they would be clipped
    // whole, so the pixels are the same and the vertex stage does less. The visible clusters of a
    // draw go out in runs, one GL draw each, in index order (the first drawn of two coincident
    // faces still wins), and bindMaterial is called per run with the run's first triangle.
    template <class P, class F>
    void drawIf(P&& include, F&& bindMaterial, const glm::mat4* cull = nullptr) const {
        glBindVertexArray(mVAO.id());
        for (size_t di = 0; di < mDraws.size(); ++di) {
            const Draw& d = mDraws[di];
            if (!include(mMaterials[d.material])) continue;
            auto issue = [&](uint32_t firstIndex, uint32_t indexCount) {
                if constexpr (std::is_invocable_v<F, const Material&, int, int>)
                    bindMaterial(mMaterials[d.material], d.material, int(firstIndex / 3));
                else
                    bindMaterial(mMaterials[d.material], d.material);
                glDrawElements(GL_TRIANGLES, GLsizei(indexCount), GL_UNSIGNED_INT, reinterpret_cast<const void*>(uintptr_t(firstIndex) * 4));
                mDrawn.draws += 1;
                mDrawn.triangles += indexCount / 3;
            };
            if (!cull) {
                issue(d.firstIndex, d.indexCount);
                continue;
            }
            uint32_t runFirst = 0, runCount = 0;
            for (uint32_t c = mClusterFirst[di]; c < mClusterFirst[di + 1]; ++c) {
                const Cluster& k = mClusters[c];
                if (outside(*cull, k)) {
                    if (runCount) issue(runFirst, runCount);
                    runCount = 0;
                    continue;
                }
                if (!runCount) runFirst = k.firstIndex;
                runCount += k.indexCount;
            }
            if (runCount) issue(runFirst, runCount);
        }
    }
    // Triangles and GL draws issued since the last resetDrawn() (the passes' work, stats.json).
    struct Drawn {
        uint64_t draws = 0, triangles = 0;
    };
    Drawn resetDrawn() const {
        Drawn d = mDrawn;
        mDrawn = {};
        return d;
    }
    static constexpr uint32_t kClusterTriangles = 256;
    // Bytes a scene will take on the GPU (vertices, indices, textures with their mips), known
    // before upload so budgets can refuse it first.
    static size_t estimateBytes(const Scene& scene);
    GLuint texture(int index) const { return index >= 0 ? mTextures[index].id() : 0; }
    const std::vector<Material>& materials() const { return mMaterials; }
    // Distinct for every GPUScene made in the process, so techniques can tell a new scene apart.
    uint64_t id() const { return mId; }
    size_t memoryBytes() const { return mBytes; }
    const Bounds& bounds() const { return mBounds; }
    // How far light travels between the scene's surfaces (gi/scene/free_path.h), measured once
    // at upload: LPV fits its grid to it.
    const FreePath& freePath() const { return mFreePath; }
    // The scene's emissive surfaces (Scene::emitters), which area lights name.
    const std::vector<Emitter>& emitters() const { return mEmitters; }
    // Binds the per-triangle emitter index at light::kTriangleEmitterBinding.
    void bindTriangleEmitters() const;

private:
    struct Cluster {
        uint32_t firstIndex = 0, indexCount = 0;
        glm::vec3 min{0.0f}, max{0.0f};
    };
    // True when the box lies wholly on the outer side of one of the frustum's six clip planes.
    static bool outside(const glm::mat4& viewProj, const Cluster& k);

    gl::Buffer mVertices, mIndices;
    std::vector<Cluster> mClusters;
    std::vector<uint32_t> mClusterFirst;  // draw i's clusters are [mClusterFirst[i], mClusterFirst[i + 1])
    mutable Drawn mDrawn;
    gl::VertexArray mVAO;
    std::vector<gl::Texture> mTextures;
    std::vector<Draw> mDraws;
    std::vector<Material> mMaterials;
    std::vector<Emitter> mEmitters;
    gl::Buffer mTriangleEmitter;
    Bounds mBounds;
    FreePath mFreePath;
    size_t mBytes = 0;
    uint64_t mId = 0;
};

}  // namespace gi
