// Environment lighting on the GPU (seed 004 chapter 2, with what engines do today): the map is
// loaded on the CPU (gi/envmap/envmap_image.h), turned into a cube, and prefiltered into a
// roughness mip chain; materials read it by roughness with the split-sum approximation.
//
// Passes (timers):
//   environment.prefilter  only when the map or a prefilter setting changed: latlong -> cube
//                          (source, full mips for filtered importance sampling), then one
//                          dispatch per mip of the chain (shaders/envmap/prefilter.comp: GGX
//                          importance sampling, or the seed's Beckmann cone sampling), and a
//                          32^2 cosine-convolved irradiance cube (a large mip in bands of rows,
//                          with progress after each); the time of each mip is kept
//                          (mipTimes()) for the Roughness Mips panel and the benchmark
//   environment.shade      technique none: the indirect term from the irradiance cube, the
//                          indirect specular from the chain at the pixel's roughness
//   environment.sky        the map where no surface is
// The split-sum table (shaders/envmap/brdf_lut.comp, 128^2, GGX with the raster's visibility
// term) is computed once at construction; the composite weighs all indirect specular with it.
//
// Choices where the seed is thin or wrong:
//   - Mips: the seed samples every level from level 0 on the CPU (28 s for 200 samples); here
//     each mip reads the source's mip chain at the level matching each sample's solid angle
//     (Krivanek and Colbert's filtered importance sampling), so 64 samples are smooth.
//   - The seed's roughness-to-mip table (Fig. 3.24) is the default of `mipRoughness`; the chain
//     has one mip per entry, and shading interpolates the table piecewise linearly (Alg. 8).
//     A table longer than the cube's halvings (the seed's 11 levels need 1024^2) keeps its first
//     entries and puts its last on the last mip, so roughness 1 stays reachable.
//   - Beckmann cone radius per mip: interpolated from the seed's table of roughness to sampling
//     disk radius (tan theta); the seed multiplies by pi r^2 unnormalised, here the sum is
//     divided by the count.
//   - Diffuse: the seed reuses the prefiltered level for diffuse light; here a 32^2 irradiance
//     cube evaluated from 9 SH coefficients projected on the CPU (a GGX lobe of roughness 1 is
//     not a cosine lobe). Sampling it by cosine on the GPU instead spread the studio map's small
//     lights across the terminator (dim sides 2-4x too bright against the path tracer).
//   - The environment lights the scene with technique none, and with the techniques that read
//     FrameContext::sky (VCT's cones, through their leftover transparency; LPV, through the sky's
//     visibility in its geometry volume); the others do not
//     gather it, and with any technique it is still drawn as the sky.
// Known limits: no shadowing or occlusion of environment light (besides SSAO on the diffuse
// term); no local probes or parallax correction (as the seed).
#pragma once

#include "gi/envmap/envmap_image.h"
#include "gi/envmap/envmap_settings.h"
#include "gi/gl/handle.h"
#include "gi/gl/shader.h"
#include "gi/gl/timer.h"
#include "gi/gl/uniform_block.h"
#include "gi/render/pass.h"
#include "gi/render/render_settings.h"
#include "gi/util/progress.h"
#include "envmap/envmap_shared.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace gi {

class Environment final : public Pass {
public:
    Environment();  // compiles the programs and computes the BRDF table; throws gi::Error

    // Loads and prefilters when `changes` holds Cost::Reallocate (a setting the maps are built
    // from changed: the file, the prefilter's settings) or no maps are built; releases them when
    // disabled. Throws gi::Error naming the file or key: a map past render.memoryBudgetMB, a
    // prefilter estimated past render.timeBudgetSeconds (both refused before anything is
    // allocated). `progress` hears after each band of a mip.
    void prepare(const EnvironmentSettings& s, gl::GpuTimer& timer, const RenderSettings& render = {},
                 const ProgressSink& progress = {}, uint8_t changes = 0xff);
    bool ready() const { return mPrefiltered.id() != 0; }

    // The pass's stages: the maps and the BRDF table; with technique none, the indirect terms
    // from the maps; the sky behind the lit image.
    void prepare(FrameContext& ctx) override;
    void indirect(FrameContext& ctx) override;
    void afterLighting(FrameContext& ctx) override;

    // technique none: fills `indirect` (E / pi) and `specular` from the maps.
    void shade(const EnvironmentSettings& s, GLuint normal, GLuint material, GLuint depth, GLuint indirect, GLuint specular,
               int width, int height, const glm::mat4& invViewProj, const glm::vec3& eye, gl::GpuTimer& timer) const;
    // The sky into `hdr` where depth is 1.
    void sky(const EnvironmentSettings& s, GLuint depth, GLuint hdr, int width, int height, const glm::mat4& invViewProj,
             const glm::vec3& eye, gl::GpuTimer& timer) const;

    GLuint brdfLUT() const { return mLUT.id(); }
    GLuint prefiltered() const { return mPrefiltered.id(); }
    GLuint irradiance() const { return mIrradiance.id(); }
    const EnvironmentImage& image() const { return mImage; }

    struct MipInfo {
        float roughness = 0.0f;
        int size = 0;        // texels per face
        int samples = 0;     // per texel (0: copied)
        float diskRadius = 0.0f;  // Beckmann cone only
        double ms = 0.0;     // prefilter time of this mip, CPU clock around a finished dispatch
    };
    const std::vector<MipInfo>& mips() const { return mMips; }
    double loadMs() const { return mLoadMs; }

    size_t memoryBytes() const override { return mSource.bytes() + mPrefiltered.bytes() + mIrradiance.bytes() + mLUT.bytes() + mLatLong.bytes(); }
    static size_t estimateBytes(const EnvironmentSettings& s);
    // The prefilter's work: samples over every texel of the mips of roughness above 0, and the
    // time they take on llvmpipe (kPrefilterSamplesPerSecond in environment.cpp; 0 when disabled).
    static double estimateSamples(const EnvironmentSettings& s);
    static double estimateSeconds(const EnvironmentSettings& s);
    // Throws gi::Error naming render.timeBudgetSeconds, the estimate and the settings to lower.
    static void checkTimeBudget(const EnvironmentSettings& s, double budgetSeconds);
    // Everything it holds counts under the prefilter.
    size_t passMemory(const std::string& pass) const override { return pass == "environment.prefilter" ? memoryBytes() : 0; }
    std::vector<std::string> passNames(const FrameSettings& fs) const override;
    std::vector<DebugView> debugViews() const override;
    // environment.mipN: each mip of the prefiltered chain as a latlong image; environment.mips:
    // all of them on one sheet, four to a row, mip 0 at the top left, each labelled with its
    // index (yellow) and roughness (white).
    std::vector<Previewer> previewers(const FrameSettings& fs) const override;
    // The map's source and load time, and the prefilter mip by mip (the Roughness mips panel
    // shows the same): roughness, size, samples, diskRadius, ms.
    PassReport report(const FrameSettings& fs) const override;
    bool reloadShaders(std::string& log) override;

    // The chain the settings give: its mip count (one per mipRoughness entry, at most the cube's
    // halvings and 32), and the mip each table entry feeds, -1 for an entry skipped because the
    // table is longer than the chain (the first entries are kept and the last goes on the last mip).
    static int chainMipCount(const EnvironmentSettings& s);
    static int chainMipOfEntry(const EnvironmentSettings& s, int entry);
    // The roughness of each mip of the chain, mip 0 first.
    static std::vector<float> chainRoughness(const EnvironmentSettings& s);

    // The seed's roughness -> sampling disk radius (tan theta), interpolated (Fig. 3.24).
    static float beckmannDiskRadius(float roughness);

private:
    gl::Program mToCubeProg, mPrefilterProg, mLUTProg, mShadeProg, mSkyProg;
    gl::UniformBlock<shared::EnvParams> mBlock;  // every pass reads it
    gl::Sampler mLinear, mCubeLinear, mPoint;
    gl::Texture mLatLong, mSource, mPrefiltered, mIrradiance, mLUT;
    std::array<glm::vec3, 9> mIrradianceSH{};  // E / pi of the map, as the irradiance cube is built from
    EnvironmentImage mImage;
    std::vector<MipInfo> mMips;
    double mLoadMs = 0.0;
    bool mBuilt = false;  // the maps match the settings of the last prepare that completed

    void computeLUT();
};

}  // namespace gi
