// The path-traced reference (Embree 3 for rays, oneTBB for threads), over the same scene,
// camera, lights and materials as the raster pipeline.
//
// Source: seed 000 section 1 ("a custom backward Monte-Carlo path tracer"); the seed gives no
// details, so the choices below are ours, made to agree with the raster pipeline term by term:
//   - BSDF: Lambert diffuse (1 - metallic) * baseColor / pi plus the raster's GGX lobe (same D,
//     height-correlated Smith V, Schlick F, alpha = max(roughness^2, 0.002)), or diffuse alone when
//     render.specular is off. One lobe is picked per bounce (probability from the lobes' albedo
//     estimates) and the mixture pdf is used, so both lobes stay unbiased.
//   - Punctual lights (directional, point, spot) by next-event estimation with the raster's
//     falloff, the one light model of common/light.h (inverse square, glTF range window,
//     smoothstep spot cone, outer cone at most 90 degrees). Emissive triangles are area lights,
//     sampled by power with multiple importance sampling (power heuristic) against BSDF sampling.
//     Emission leaves the side the shading normal points to.
//   - All surfaces are two-sided, as in the raster pipeline: the shading normal faces the ray.
//   - Alpha-masked materials are honoured by Embree filter functions (texture alpha * factor).
//   - Russian roulette after `rouletteDepth` bounces with survival max(throughput), capped 0.95.
//   - Modes split paths by bounce count: direct = emission seen by the camera plus light that
//     reaches the camera after one bounce; indirect = everything with two or more bounces.
//   - Deterministic: each pixel sample draws from a PCG32 stream keyed by (pixel, sample, seed),
//     so the image depends on neither thread count nor how samples are split into passes.
//   - Pixel filter: a box over the pixel (uniform jitter).
//   - Volumetric lighting (seed 004; the model is gi/volumetric/medium.h, shared with the raster
//     march): a homogeneous medium filling the scene's bounds acts on the camera ray only. The
//     radiance of the path from its first surface on (emission seen directly included) is faded
//     by T(eye, hit) when attenuateScene is on, and single scattering of each punctual light is
//     added: one distance per light, uniform on the part of the camera ray inside the box and
//     the light's cone and range, with a shadow ray as in next-event estimation, the light's
//     falloff, T along the light's path inside the box and T back to where the ray entered the
//     box. It is direct light: counted in full and direct, not indirect. As in the raster
//     technique, light reaching surfaces (and every later path segment) is not attenuated, and
//     there is no multiple scattering. Its random numbers are drawn after the path's, so the
//     surface paths are the same with and without the medium.
//   - Environment lighting (seed 004 chapter 2; the latlong convention of gi/envmap/envmap_image.h):
//     the radiance arriving from a direction d with nothing in the way is intensity x
//     sampleEnvironment(d, rotation) (the bilinear lookup the raster's cube is made from). The
//     camera sees it only as the skybox (black without), every later escaping ray gathers it.
//     It is a light sampled by next-event estimation at each surface vertex: a 2D
//     piecewise-constant distribution over the map's cells by luminance x sin(theta) (the
//     cell's mean of the bilinear lookup, so no lit direction has zero density), density in
//     solid angle pdf_uv / (2 pi^2 sin theta), an unbounded shadow ray, and the power heuristic
//     against BSDF sampling, as for emissive triangles; the modes split it the same way. The
//     map is loaded once per PathTracer and file name (not again if the file changes). The
//     medium fades the skybox like any emission seen directly, but does not in-scatter the
//     environment. Without the environment no random number or operation changes: the same
//     pixels as before it existed.
// Known limits: no refraction (glass is a dark dielectric, as in the scene files), no textures
// besides base colour, textures sampled bilinearly at full resolution (no mips).
#pragma once

#include "gi/reference/reference_settings.h"
#include "gi/render/image.h"
#include "gi/render/render_settings.h"
#include "gi/scene/scene.h"

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace gi {

class PathTracer {
public:
    explicit PathTracer(const Scene& scene);  // builds the BVH
    ~PathTracer();
    PathTracer(const PathTracer&) = delete;
    PathTracer& operator=(const PathTracer&) = delete;

    // Adds samples [firstSample, firstSample + count) of every pixel to `sum` (resized if empty).
    // Returns false when `cancel` became true before the pass finished (sum is then partial).
    bool trace(const FrameSettings& fs, const ReferenceSettings& rs, int firstSample, int count,
               std::vector<double>& sum, const std::atomic<bool>* cancel = nullptr) const;

    // Renders rs.spp samples in passes; `progress(samplesDone, total)` after each pass returns
    // false to stop early. The image is the mean radiance of the samples done.
    ImageRGB render(const FrameSettings& fs, const ReferenceSettings& rs,
                         const std::function<bool(int, int)>& progress = {}) const;

    uint64_t raysTraced() const { return mRays.load(); }

    // The nearest surface along a ray from `origin` (alpha masks honoured): its distance and the
    // interpolated vertex normal as authored, not turned to face the ray (framing.h reads which
    // side of a surface a point sees). t < 0 when the ray escapes.
    struct SurfaceHit {
        float t = -1.0f;
        glm::vec3 normal{0.0f};
    };
    SurfaceHit nearestSurface(const glm::vec3& origin, const glm::vec3& dir, float tnear = 0.0f) const;

    // Tests only: off leaves the environment to BSDF sampling alone (unbiased, noisier), the
    // brute-force estimate that next-event estimation must agree with.
    void setEnvironmentSampling(bool on) { mEnvironmentSampling = on; }

    struct Impl;

private:
    std::unique_ptr<Impl> mImpl;
    mutable std::atomic<uint64_t> mRays{0};
    bool mEnvironmentSampling = true;
};

}  // namespace gi
