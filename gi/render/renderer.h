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
// The GI passes (gi/render/pass.h) run at their stages around these: the renderer finds them in
// the pass registry and knows none of them by name.
#pragma once

#include "gi/gl/handle.h"
#include "gi/gl/shader.h"
#include "gi/gl/timer.h"
#include "gi/gl/uniform_block.h"
#include "gi/render/gpu_scene.h"
#include "gi/render/lights.h"
#include "gi/render/material_binding.h"
#include "gi/render/material_programs.h"
#include "gi/render/pass.h"
#include "gi/render/render_settings.h"
#include "gi/scene/camera.h"
#include "gi/scene/scene.h"
#include "render/render_shared.h"

#include <memory>
#include <optional>
#include <span>

namespace gi {

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

    // The light pass's program for LIGHT_KIND `kind` (render/light.frag): 0 a 2D shadow map
    // (directional, spot), 1 a cube map (point), 2 an area light. Throws gi::Error on a shader error.
    static constexpr int kLightKinds = 3;
    static gl::Program lightPassProgram(int kind);

    void render(const FrameSettings& fs);
    // Shadow-map redraws since creation: with render.keepStaticWork a frame redraws them only when
    // the scene, a light (its packed entry, type or castShadows) or the map size changed.
    int shadowDrawCount() const { return mShadowDraws; }
    // Hears the progress of long steps inside render() (the environment prefilter).
    void setProgressSink(ProgressSink sink) { mProgress = std::move(sink); }

    // Rebuilds every program from disk; a failure keeps the old programs and returns the log.
    bool reloadShaders(std::string& log);

    GLuint outputTexture() const { return mLDR.id(); }
    GLuint hdrTexture() const { return mHDR.id(); }
    int width() const { return mWidth; }
    int height() const { return mHeight; }
    std::vector<DebugView> debugViews() const;
    // Every active pass's previewers for these settings (the last frame's).
    std::vector<Previewer> previewers(const FrameSettings& fs) const;
    // The last frame as the previewers read it; `focus` is the pixel the user points at.
    PreviewContext previewContext(const FrameSettings& fs, std::optional<glm::ivec2> focus) const;
    // The surface under pixel `px` (y up) of the last frame; false where there is none (the sky).
    bool pickSurface(glm::ivec2 px, SurfacePick& out) const;
    // Per-pass GPU ms (newest finished frame) and memory held.
    std::vector<PassStats> passStats() const;
    // Reads the last frame's timings, waiting for them if need be. passStats() otherwise shows a
    // frame's timings only once the next frame has been rendered; an editor that renders only on
    // change calls this between frames.
    void resolveTimings() { mTimer.resolve(true); }
    size_t memoryBytes() const;
    gl::GpuTimer& timer() { return mTimer; }
    // The technique pass of the last frame (technique none's pass for none).
    const Pass* technique() const;
    // The active pass of that type, or null (tests and the previewers of one pass).
    template <class T>
    const T* activePass() const {
        for (const ActivePass& p : mPasses)
            if (auto* t = dynamic_cast<const T*>(p.pass.get())) return t;
        return nullptr;
    }
    // Each active pass's report (name, report) where it has one.
    std::vector<std::pair<std::string, PassReport>> passReports(const FrameSettings& fs) const;
    // Every volume or buffer the active passes hold.
    std::vector<VolumeMemory> volumeMemory() const;

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
        std::vector<gl::Framebuffer> fbos;  // 1, or 6 for cube faces (the projection is mLightBuffer's)
        LightType type = LightType::Directional;
    };

    std::unique_ptr<GPUScene> mScene;
    GPUScene::Drawn mShadowDrawn, mGBufferDrawn;  // the last frame's work (passStats)
    // The G-buffer and directional shadow programs come in two variants: for Opaque materials
    // without discard (early depth testing), and for Mask and Blend ones (their draws go last).
    gl::Program mDepthProg, mShadowProg, mShadowOpaqueProg, mShadowPointProg, mCompositeProg, mToneProg, mViewProg;
    // The light pass's, one per kind of light (lightProgram() in renderer.cpp).
    gl::Program mLightProgs[kLightKinds];
    gl::UniformBlock<shared::RenderParams> mBlock;  // every program above and below reads it
    gl::UniformBlock<light::GPULightWithTriangles> mLightBlock;  // the light pass's light
    MaterialBinding mMaterialBinding;  // the G-buffer and shadow programs read it
    // The G-buffer's, one program per set of material textures (material_programs.h).
    MaterialPrograms mGBufferProgs, mGBufferOpaqueProgs;
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
    uint64_t mShadowKey = 0;  // what the shadow maps hold (render()), 0: nothing yet
    int mShadowDraws = 0;
    std::vector<LightType> mShadowTypes;
    std::vector<bool> mShadowCast;
    CameraSettings mCamera;

    gl::GpuTimer mTimer;
    // The registry's passes in its order: every effect, the chosen technique (created when it
    // is chosen), and technique none's ambient fill last. `info` is null for the ambient fill.
    struct ActivePass {
        const PassInfo* info = nullptr;
        std::unique_ptr<Pass> pass;
        std::optional<FrameSettings> completed;  // the settings of the last frame it completed
    };
    std::vector<ActivePass> mPasses;
    ProgressSink mProgress;
    std::string mTechniqueName;

    void selectPasses(const FrameSettings& fs);
    // Calls `stage` on every active pass with ctx.changes set for that pass: what changed since
    // the last frame it completed (everything on its first).
    template <class F>
    void runStage(FrameContext& ctx, F&& stage);

    void resize(int width, int height);
    void prepareShadows(const FrameSettings& fs);
    void renderShadows(const FrameSettings& fs, uint64_t key);
    void renderGBuffer(const glm::mat4& viewProj, const RenderSettings& settings);
    void renderLighting(const FrameSettings& fs, const glm::mat4& viewProj, const FrameContext& ctx);
    void renderToneMap(const FrameSettings& fs);
};

}  // namespace gi
