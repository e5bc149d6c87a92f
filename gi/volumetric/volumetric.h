// Volumetric lighting (seed 004 chapter 1): single scattering of the punctual lights in a
// homogeneous medium filling the scene's bounds (gi/volumetric/medium.h is the model, shared
// with the path-traced reference), added to the lit HDR image before tone mapping.
//
// Passes (timers), after the lighting pass:
//   volumetric.march      shaders/volumetric/march.comp into an RGBA16F buffer at
//                         resolutionScale: per pixel and light, the view ray clipped to the box and
//                         to the light's cone and range, `samples` jittered points, shadow test
//                         with PCF, unlit points skipped; up to 4 lights per dispatch
//   volumetric.blur       the seed's 5x5 Gaussian, or its depth-aware variant (blur.comp)
//   volumetric.composite  hdr = hdr * T(view) + upsampled in-scatter (composite.comp)
//
// Choices where the seed is thin or wrong (see also phase.h):
//   - Light types: the seed has spot lights only; directional lights light the whole box (a
//     sun shaft enters through the box's faces, shadowed by the scene), point lights their range.
//   - Clipping: the seed's ray-pyramid clip (Alg. 4, six triangles, cases A-F) becomes an exact
//     ray-cone interval (a spot's outer cone is convex up to 90 degrees), intersected with the
//     range sphere; samples go only where the light can reach.
//   - Attenuation: the seed's eq. 3.1 (e^{-x/l} on both legs with flux f / (2 pi (1 - cos phi)
//     x^2)) keeps its optical thickness l as a mean free path (sigma_t = 1/l); our lights carry an
//     intensity, so the flux term is the raster's falloff (1/d^2, range window, spot smoothstep).
//     The seed's sum has no scattering coefficient; here sigma_s = density scales it, so a
//     density of 0 adds nothing and the result is in the same units as surface radiance.
//   - Jitter: the seed seeds by UV and run time; here interleaved gradient noise of the pixel
//     alone, so headless renders are repeatable.
//   - The seed only adds the light; attenuateScene also fades what lies behind the medium.
// Known artefacts: banding at low sample counts without jitter, noise with it (the blur hides
// some); the medium does not dim light reaching surfaces; no multiple scattering; a light with
// no shadow map (castShadows off) lights the medium through walls.
#pragma once

#include "gi/gl/handle.h"
#include "gi/gl/shader.h"
#include "gi/gl/timer.h"
#include "gi/gl/uniform_block.h"
#include "gi/render/pass.h"
#include "gi/scene/scene.h"
#include "gi/volumetric/medium.h"
#include "volumetric/volumetric_shared.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace gi {

class Volumetric final : public Pass {
public:
    Volumetric();  // compiles the programs; throws gi::Error on a shader error

    struct Inputs {
        const FrameSettings& settings;
        const Bounds& sceneBounds;
        const std::vector<ShadowMapView>& shadows;  // one per light (depth 0 where none)
        GLuint depth;                               // the G-buffer's depth
        GLuint hdr;                                 // RGBA16F lit image, updated in place
        int width, height;
        glm::mat4 invViewProj;
        float shadowSize;                           // texels per side of the 2D maps
    };
    // Does nothing (and holds no memory) unless the settings' medium is active.
    void execute(const Inputs& in, gl::GpuTimer& timer);
    // The pass's stage: execute() on the lit image.
    void afterLighting(FrameContext& ctx) override;

    size_t memoryBytes() const override { return mMarch.bytes() + mBlurred.bytes(); }
    // Both buffers count under the march.
    size_t passMemory(const std::string& pass) const override { return pass == "volumetric.march" ? memoryBytes() : 0; }
    std::vector<std::string> passNames(const FrameSettings& fs) const override;
    static size_t estimateBytes(const FrameSettings& fs);
    // "volumetricRaw" (the march) and "volumetric" (after the blur), when active.
    std::vector<DebugView> debugViews() const override;
    // volumetric.phase: the phase function as a polar plot (linear), light travelling along +x.
    std::vector<Previewer> previewers(const FrameSettings& fs) const override;
    bool reloadShaders(std::string& log) override;
    GLuint result() const { return mBlurred.id(); }

private:
    gl::Program mMarchProg, mBlurProg, mCompositeProg;
    gl::UniformBlock<shared::VolumeParams> mBlock;  // every pass reads it
    gl::Sampler mLinear, mPoint, mShadowSampler;
    gl::Texture mMarch, mBlurred;
    int mWidth = 0, mHeight = 0;  // march buffer
    bool mActive = false;
};

}  // namespace gi
