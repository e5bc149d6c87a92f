// The frame pipeline: shadow maps, G-buffer, indirect input, lighting (emission + indirect +
// direct light per light), tone mapping. Every pass is a named debug group timed with GPU
// timestamps and reports the memory it holds.
//
// Passes in order:
//   shadows   one depth map per shadow-casting light (2D for directional and spot, cube for point)
//   gbuffer   albedo RGBA8, normal RGBA16F, roughness/metallic RGBA8, emissive RGBA16F, depth 32F
//   indirect  the technique's indirect irradiance / pi (RGBA16F) and, from VCT, specular radiance
//             (RGBA16F, else 0); technique none fills the constant ambient radiance
//   lighting  emission + albedo * indirect, then each light added with its shadow (HDR RGBA16F)
//   tonemap   exposure, tone curve, sRGB into RGBA8
#pragma once

#include "gi/gl/handle.h"
#include "gi/gl/shader.h"
#include "gi/gl/timer.h"
#include "gi/render/lights.h"
#include "gi/render/render_settings.h"
#include "gi/render/technique.h"
#include "gi/scene/camera.h"
#include "gi/scene/scene.h"
#include "gi/ssao/ssao.h"
#include "gi/volumetric/volumetric.h"
#include "gi/envmap/environment.h"

#include <memory>
#include <span>

namespace gi {

// A texture the previewers can show, with the mode that displays it sensibly.
struct DebugView {
    std::string name;
    GLuint texture = 0;
    GLenum target = GL_TEXTURE_2D;
    int mode = 0;        // shared::kView*
    int width = 0, height = 0;
    float near = 0.0f, far = 1.0f, range = 1.0f;  // for depth linearisation
    GLuint extra[2] = {0, 0};  // SH volumes: the G and B coefficient textures (texture holds R)
    float scale = 1.0f;        // SH volumes: factor from stored values to radiance
    int level = 0;             // mip shown (added to ViewParams::level), e.g. a prefiltered environment mip
};

struct PassStats {
    std::string name;
    double gpuMs = 0.0;
    size_t memoryBytes = 0;
};

// GPU copy of a Scene.
class GPUScene {
public:
    explicit GPUScene(const Scene& scene);
    // Issues the scene's draws. `bindMaterial` sets per-material uniforms and textures.
    template <class F>
    void draw(F&& bindMaterial) const {
        glBindVertexArray(mVAO.id());
        for (const Draw& d : mDraws) {
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

private:
    gl::Buffer mVertices, mIndices;
    gl::VertexArray mVAO;
    std::vector<gl::Texture> mTextures;
    std::vector<Draw> mDraws;
    std::vector<Material> mMaterials;
    Bounds mBounds;
    size_t mBytes = 0;
    uint64_t mId = 0;
};

class Renderer {
public:
    Renderer();  // compiles the programs; throws gi::Error on a shader error
    ~Renderer();

    void setScene(const Scene& scene);
    bool hasScene() const { return bool(mScene); }

    // Bytes the frame resources for these settings will hold (G-buffer, targets, shadow maps).
    static size_t estimateFrameBytes(const FrameSettings& fs);
    // Throws gi::Error when the settings plus the scene would exceed render.memoryBudgetMB, or
    // the environment prefilter is estimated past render.timeBudgetSeconds.
    static void checkBudget(const FrameSettings& fs, size_t sceneBytes);
    // The memory part alone (each frame checks it; the prefilter's time is checked when it runs).
    static void checkMemoryBudget(const FrameSettings& fs, size_t sceneBytes);
    static void checkBudget(const FrameSettings& fs, const Scene& scene) { checkBudget(fs, GPUScene::estimateBytes(scene)); }

    void render(const FrameSettings& fs);
    // Hears the progress of long steps inside render() (the environment prefilter).
    void setProgressSink(ProgressSink sink) { mProgress = std::move(sink); }

    // Rebuilds every program from disk; a failure keeps the old programs and returns the log.
    bool reloadShaders(std::string& log);

    GLuint outputTexture() const { return mLDR.id(); }
    GLuint hdrTexture() const { return mHDR.id(); }
    int width() const { return mWidth; }
    int height() const { return mHeight; }
    std::vector<DebugView> debugViews() const;
    // Per-pass GPU ms (newest finished frame) and memory held.
    std::vector<PassStats> passStats() const;
    size_t memoryBytes() const;
    gl::GpuTimer& timer() { return mTimer; }
    // The technique of the last frame (null for none), for tests and the editor's previewers.
    const Technique* technique() const { return mTechnique.get(); }
    const Environment& environment() const { return mEnvironment; }
    std::vector<Technique::VolumeMemory> techniqueVolumes() const {
        return mTechnique ? mTechnique->volumeMemory() : std::vector<Technique::VolumeMemory>{};
    }

    std::vector<uint8_t> readLDR() const;  // RGBA8, bottom row first
    std::vector<float> readHDR() const;    // RGBA32F, bottom row first
    // The indirect term as the lighting pass adds it (albedo * (1 - metallic) * indirect), RGBA32F,
    // bottom row first: what the leak measure compares with the indirect-only reference.
    std::vector<float> readIndirectRadiance() const;

    // Draws a debug view into the current framebuffer's viewport.
    struct ViewParams {
        glm::vec4 channelMask{1, 1, 1, 0};
        float exposure = 0.0f;  // EV
        float zoom = 1.0f;
        glm::vec2 pan{0.0f};
        float level = 0.0f;
        // Volume views: the slice shown and what a voxel shows.
        int axis = 1;                            // 0 x, 1 y, 2 z: the axis the slice is normal to
        float slice = 0.5f;                      // 0..1 along that axis
        int shComponent = -1;                    // -1: irradiance towards `direction`; 0..3: one coefficient
        glm::vec3 direction{0.0f, 1.0f, 0.0f};   // normal of the surface whose irradiance is shown
        bool falseColour = false;
    };
    void drawView(const DebugView& view, const ViewParams& params) const;
    // Renders a view into a new RGBA8 image of the given size (bottom row first).
    std::vector<uint8_t> renderViewImage(const DebugView& view, int width, int height) const;

private:
    struct ShadowMap {
        gl::Texture depth;
        std::vector<gl::Framebuffer> fbos;  // 1, or 6 for cube faces
        glm::mat4 viewProj{1.0f};           // 2D maps
        float far = 1.0f;
        LightType type = LightType::Directional;
    };

    std::unique_ptr<GPUScene> mScene;
    gl::Program mGBufferProg, mShadowProg, mShadowPointProg, mCompositeProg, mLightProg, mToneProg, mViewProg;
    gl::VertexArray mEmptyVAO;
    gl::Sampler mLinearSampler, mShadowSampler, mPointSampler, mMaterialSampler, mLUTSampler;
    gl::Sampler mMipPointSampler;  // views of one mip (cube maps): nearest texels of the chosen level
    gl::Texture mWhite;

    int mWidth = 0, mHeight = 0;
    gl::Texture mAlbedo, mNormal, mMaterial, mEmissive, mDepth, mIndirect, mIndirectSpecular, mHDR, mLDR;
    gl::Framebuffer mGBufferFBO, mHDRFBO, mLDRFBO;
    std::vector<ShadowMap> mShadows;  // one per light; empty depth when the light casts none
    std::vector<ShadowMapView> mShadowViews;
    LightBuffer mLightBuffer;  // this frame's lights, bound for every pass
    int mShadowSize = 0;
    std::vector<LightType> mShadowTypes;
    std::vector<bool> mShadowCast;
    CameraSettings mCamera;

    gl::GpuTimer mTimer;
    std::unique_ptr<Technique> mTechnique;
    SSAO mSSAO;
    Volumetric mVolumetric;
    Environment mEnvironment;
    ProgressSink mProgress;
    TechniqueKind mTechniqueKind = TechniqueKind::None;

    void resize(int width, int height);
    void prepareShadows(const FrameSettings& fs);
    void renderShadows(const FrameSettings& fs);
    void renderGBuffer(const glm::mat4& viewProj);
    void renderIndirect(const FrameSettings& fs, const glm::mat4& view, const glm::mat4& proj);
    void renderLighting(const FrameSettings& fs, const glm::mat4& viewProj);
    void renderToneMap(const FrameSettings& fs);
};

}  // namespace gi
