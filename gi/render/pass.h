// The one interface of every GI pass (LPV, VCT, SSAO, the environment, volumetric lighting and
// technique none), the frame context they read and write, and the registry that finds them.
// It sits below the techniques: a technique includes this file, never the renderer, and the
// renderer includes no technique.
//
// A frame runs the passes in stages; in each stage every active pass is called in registry order
// (the section list in gi/render/render_settings.h), the selected technique among them:
//   prepare         before the shadow maps (the environment's prefilter)
//   indirect        after the G-buffer: fill the indirect term (every pixel) and set
//                   ctx.indirectWritten; a pass finding it already set leaves it alone
//   beforeLighting  screen-space inputs of the lighting pass (SSAO sets ctx.ambientOcclusion)
//   afterLighting   work on the lit HDR image (the sky, the volumetric march)
// Each pass times its work under its own names (ctx.timer.scope) and reports the memory it holds
// under the same names, so stats.json and the GPU debugger agree.
#pragma once

#include "gi/gl/timer.h"
#include "gi/render/render_settings.h"
#include "gi/render/strokes.h"
#include "gi/scene/scene.h"
#include "gi/util/progress.h"

#include <glm/glm.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <array>
#include <vector>

namespace gi {

class GPUScene;

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

// One timed pass of a frame: GPU ms of the newest finished frame and the memory it holds.
struct PassStats {
    std::string name;
    double gpuMs = 0.0;
    size_t memoryBytes = 0;
    // The raster passes that draw the scene (shadows, gbuffer) count their work: GL draws issued
    // and triangles sent down the pipeline after culling (GPUScene::drawIf), 0 for a pass that
    // kept its result. countsDraws is false for every other pass.
    bool countsDraws = false;
    uint64_t draws = 0, triangles = 0;
};

// Memory of one named volume or buffer a pass holds (stats.json "volumes").
struct VolumeMemory {
    std::string name;
    std::string format;  // e.g. "64^3 RGBA16F, 7 mips"
    size_t bytes = 0;
};

// A shadow map the renderer drew this frame, for passes that test light visibility (VCT
// injection, the volumetric march). depth is 0 for lights that cast no shadows.
struct ShadowMapView {
    GLuint depth = 0;
    bool cube = false;          // point lights: a cube map of distance / far
    glm::mat4 viewProj{1.0f};   // 2D maps
    float far = 1.0f;           // cube maps
};

// The environment's distant light, for the techniques that gather it (prefiltered 0: none).
struct SkyLight {
    GLuint prefiltered = 0;           // cube with the GGX roughness chain (gi/envmap/environment.h)
    GLuint sampler = 0;               // trilinear, seamless, for it
    std::array<glm::vec3, 9> irradianceSH{};  // E / pi as 9 SH coefficients (common/sky.glsl skyIrradiance)
    float intensity = 0.0f;           // radiance scale
    float rotation = 0.0f;            // degrees about +y
    std::vector<float> mipRoughness;  // perceptual roughness of each mip of the chain
};

struct FrameContext {
    const FrameSettings& settings;
    const GPUScene& scene;
    glm::mat4 view, proj, viewProj, invViewProj;
    GLuint albedo, normal, material, emissive, depth;  // the G-buffer
    GLuint indirect;          // RGBA16F image: irradiance / pi, written by the indirect stage
    GLuint indirectSpecular;  // RGBA16F image: specular radiance (cleared to 0 before the stage)
    GLuint hdr;               // RGBA16F lit image (afterLighting updates it in place)
    const std::vector<ShadowMapView>& shadows;  // one per light, as settings.lights
    int shadowSize;           // texels per side of the 2D shadow maps
    int width, height;
    gl::GpuTimer& timer;
    const ProgressSink& progress;  // hears long steps (the environment prefilter)
    // Changes to this pass's inputs since the frame it last completed (the OR of the cost tags of
    // the changed fields, gi/preset/reflect.h diff(); every bit on the first frame). Passes
    // rebuild what the bits say, never by comparing fields themselves.
    uint8_t changes = 0;

    // Written by the passes for the stages after them.
    bool indirectWritten = false;
    GLuint ambientOcclusion = 0;  // R8 texture multiplying the indirect term (white when none)
    GLuint brdfLUT = 0;           // split-sum table of the lighting pass's specular (0: none)
    SkyLight sky;                 // the environment (prepare stage), when it lights the scene
};

// The surface under a pixel of the last frame, reconstructed from the G-buffer as the passes
// see it (position, normal, roughness).
struct SurfacePick {
    glm::vec3 position{0.0f}, normal{0.0f, 1.0f, 0.0f};
    float roughness = 1.0f;
};

// What a previewer reads: the frame the renderer drew last.
struct PreviewContext {
    const FrameSettings& settings;
    Bounds sceneBounds;
    std::vector<DebugView> views;      // every active pass's views, as Renderer::debugViews
    glm::mat4 viewProj{1.0f};          // the camera of the frame
    int width = 0, height = 0;         // of the frame
    std::optional<SurfacePick> focus;  // the surface the user points at (the editor's click, the runner's centre)
    float overlayScale = 1.0f;         // size of overlay glyphs relative to their default (the editor's slider)
    // Draws a view into a new RGBA8 image (bottom row first), as the buffer previewer shows it.
    std::function<std::vector<uint8_t>(const DebugView&, int width, int height)> renderView;
};

// An RGBA8 picture, bottom row first (as GL reads back and writePNG takes).
struct PreviewImage {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;
};

// A previewer a pass offers beside its debug views. gi-render --views writes each as
// views/NAME.png; the editor lists them. Exactly one of the two functions is set.
struct Previewer {
    std::string name;         // e.g. "vct.cones"
    std::string description;  // one line for the editor's tooltip
    // A picture of its own (the voxels from the camera, the phase plot, the mip sheet); empty
    // (width 0) when there is nothing to show this frame.
    std::function<PreviewImage(const PreviewContext&)> image;
    // World-space lines drawn over the final image (cone glyphs at the focus, cascade boxes).
    std::function<std::vector<GlyphLine>(const PreviewContext&)> overlay;
};

// Figures a pass reports beside its timers (gi-render's stats.json, under the pass's name):
// named texts and numbers, and one table of rows (the environment's mips). Empty: nothing to say.
struct PassReport {
    std::vector<std::pair<std::string, std::string>> texts;
    std::vector<std::pair<std::string, double>> numbers;
    std::string tableName;
    std::vector<std::string> columns;
    std::vector<std::vector<double>> rows;  // each as long as columns
    bool empty() const { return texts.empty() && numbers.empty() && rows.empty(); }
};

class Pass {
public:
    virtual ~Pass() = default;
    virtual void prepare(FrameContext&) {}
    virtual void indirect(FrameContext&) {}
    virtual void beforeLighting(FrameContext&) {}
    virtual void afterLighting(FrameContext&) {}

    virtual std::vector<DebugView> debugViews() const { return {}; }
    // Its previewers when active with these settings.
    virtual std::vector<Previewer> previewers(const FrameSettings&) const { return {}; }
    // What it did in the last frame beyond time and memory.
    virtual PassReport report(const FrameSettings&) const { return {}; }
    // Memory held by the pass of that timer name (0 for names it does not own).
    virtual size_t passMemory(const std::string& pass) const = 0;
    virtual size_t memoryBytes() const = 0;
    virtual std::vector<VolumeMemory> volumeMemory() const { return {}; }
    // The timer names it reports when active with these settings (tests check stats.json).
    virtual std::vector<std::string> passNames(const FrameSettings& fs) const = 0;
    // Rebuilds its programs from disk; a failure keeps the old ones and appends the log.
    virtual bool reloadShaders(std::string& log) = 0;
};

// One registered pass: what the section list declares about it.
struct PassInfo {
    std::string_view name;  // its settings section, e.g. "lpv"
    PassRole role;
    std::unique_ptr<Pass> (*create)();
    size_t (*estimateBytes)(const FrameSettings&);
    void (*checkTime)(const FrameSettings&);        // null when the pass has no long work
    std::string (*notes)(const FrameSettings&);     // null when it never has any
    uint8_t (*changes)(const FrameSettings& before, const FrameSettings& after);  // diff of its section
    bool gathersSky = false;  // a technique that lights the scene with FrameContext::sky (S::kGathersSky)
};

// Every pass, in the order of the section list.
const std::vector<PassInfo>& passRegistry();
// The entry of that name, or null.
const PassInfo* findPass(std::string_view name);
// Whether the pass runs in a frame with these settings: effects always, a technique when chosen.
bool passActive(const PassInfo& info, const FrameSettings& fs);

}  // namespace gi
