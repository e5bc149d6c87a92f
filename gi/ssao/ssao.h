// Screen-space ambient occlusion, a pass any technique combines with by multiplying its
// indirect term by aoTexture().
//
// Source: seed 000 (ten Brug 2017), Sec 3.5.1, which follows John Chapman's 2011 SSAO tutorial:
// a kernel of points in the hemisphere about the normal, denser near the origin, oriented per
// pixel by a tiled random rotation, each point occluded when it lies behind the stored depth,
// AO = the unoccluded fraction, then a blur that removes the tile's banding.
//
// Passes, in order:
//   ssao      per pixel: view-space position from depth through the inverse projection, the
//             G-buffer's world normal rotated into view space, sampleCount kernel points scaled
//             by radius and projected to the screen; visibility = 1 - occluded / count -> R8
//   ssaoBlur  box blur 2 * blurRadius pixels wide (the 4x4 noise tile for blurRadius 2), then
//             pow(visibility, strength) -> R8, the texture aoTexture() returns
//
// Choices where the source is silent:
//   - Kernel: Chapman's direction (u*2-1, u*2-1, u) normalised, with length lerp(0.1, 1, t^2)
//     for t = (i + u) / N: his accelerating scale over stratified, jittered t. Chapman also
//     multiplies by a random length in [0,1); that leaves a mean reach of 0.2 radius, so at the
//     default settings a floor-wall crease only darkens to 0.81 (measured), where the
//     stratified kernel gives 0.65 and varies less between 16 and 64 samples. The
//     generator is mt19937 with a fixed seed and a hand-written float conversion, because the
//     std distributions differ between standard libraries: renders are repeatable, and the
//     kernel does not change with the compiler.
//   - Noise: a 4x4 tile of rotation angles about the normal, stratified (one per sixteenth of
//     the circle, jittered) and shuffled with the same seed, applied to a branchless orthonormal
//     basis (Duff et al. 2017). Chapman Gram-Schmidts a random vector instead; rotating a fixed
//     basis gives the same distribution without the case where that vector is parallel to the
//     normal, and stratifying means every 4x4 blur window averages 16 evenly spread rotations.
//   - Units: radius and bias are fractions of the scene bounds' diagonal (the source gives
//     world units, tuned per scene), so the same settings fit a scene at any scale; the pass
//     multiplies them by the diagonal before upload.
//   - Occlusion test: the stored surface must lie more than `bias` in front of the sample.
//     Range check smoothstep(0, 1, radius / |z_pixel - z_stored|): an occluder far in front of
//     the pixel (a foreground object) fades out instead of drawing a dark halo around itself.
//   - Samples that project off screen or behind the eye count as unoccluded: nothing is known
//     there, and counting them occluded darkens every frame border.
//   - Blur: offsets -r..r-1 in x and y, background pixels (depth 1) left out so silhouettes
//     against the sky are not lightened; strength is applied after the blur.
//   - With enabled false, execute() fills aoTexture() with 1 so a composite can multiply by it
//     unconditionally.
//
// Known artefacts:
//   - Only what the camera sees occludes: occluders off screen or hidden behind the visible
//     surface do not count, so AO changes as objects enter the frame (seed 000 Sec 6).
//   - The depth buffer is a height field: thin objects occlude as if infinitely thick, until the
//     range check fades them out.
//   - At grazing view angles the depth at a sample's pixel centre differs from the sample's own
//     depth by up to half a pixel of slope; where that exceeds `bias`, flat ground self-occludes
//     (not seen at the defaults on a floor 2 m away at 128 px, down to 4 degrees elevation).
//   - The box blur is not depth aware: a dark crease bleeds blurRadius pixels onto neighbouring
//     surfaces across silhouettes.
//   - With blurRadius 0, 1 or 3 (a window not a multiple of 4 wide) the noise tile shows as a
//     faint 4x4 pattern (seed 000 Sec 6).
#pragma once

#include "gi/gl/handle.h"
#include "gi/gl/shader.h"
#include "gi/gl/timer.h"
#include "gi/gl/uniform_block.h"
#include "gi/render/pass.h"
#include "gi/ssao/ssao_settings.h"
#include "ssao/ssao_shared.h"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace gi {

// The seed of the kernel and the noise tile: fixed so renders are deterministic.
inline constexpr uint32_t kSSAOSeed = 20110101u;

// Chapman's hemisphere kernel about +Z: `count` points with z >= 0 and length <= 1, their
// distance from the origin growing with the index.
std::vector<glm::vec3> ssaoKernel(int count, uint32_t seed = kSSAOSeed);
// The 4x4 noise tile as (cos, sin) of a rotation about the normal, row-major by (y & 3, x & 3).
std::array<glm::vec2, 16> ssaoNoise(uint32_t seed = kSSAOSeed);
// The unit of SSAOSettings::radius and bias: the length of the bounds' diagonal, or 1 (world
// units) for a scene with no extent.
float ssaoSceneDiagonal(const Bounds& sceneBounds);

class SSAO final : public Pass {
public:
    SSAO();  // compiles the programs; throws gi::Error on a shader error

    // Computes AO (1 = unoccluded) into aoTexture() at width x height. The depth texture is the
    // G-buffer's DEPTH_COMPONENT32F, the normal texture its world-space normals; view and proj
    // are the raster's camera matrices, so the pass sees exactly what the G-buffer holds.
    // sceneDiagonal is the length of the scene bounds' diagonal, the unit of s.radius and s.bias.
    void execute(const SSAOSettings& s, GLuint depthTexture, GLuint normalTexture, int width, int height,
                 const glm::mat4& view, const glm::mat4& proj, float sceneDiagonal, gl::GpuTimer& timer);

    // The pass's stage: execute() on the G-buffer, then aoTexture() as the frame's AO.
    void beforeLighting(FrameContext& ctx) override;

    GLuint aoTexture() const { return mAO.id(); }  // R8, after blur and strength; reads as (ao, ao, ao, 1)
    size_t memoryBytes() const override { return mRaw.bytes() + mAO.bytes(); }
    // Both AO targets count under "ssao"; the blur pass holds none of its own.
    size_t passMemory(const std::string& pass) const override { return pass == "ssao" ? memoryBytes() : 0; }
    std::vector<std::string> passNames(const FrameSettings& fs) const override;
    // Bytes execute() allocates at this size, known before allocation for budgets.
    static size_t estimateBytes(int width, int height);
    // "ssaoRaw" (visibility before blur and strength) and "ssao" (aoTexture()).
    std::vector<DebugView> debugViews() const override;
    // Rebuilds the programs from disk; a failure keeps the old ones and appends the log.
    bool reloadShaders(std::string& log) override;

private:
    gl::Program mSSAOProg, mBlurProg;
    gl::UniformBlock<shared::SSAOParams> mBlock;  // both passes read it
    shared::SSAOParams mParams{};  // the kernel and noise persist between frames
    gl::VertexArray mEmptyVAO;
    gl::Sampler mPointSampler;
    gl::Texture mRaw, mAO;
    gl::Framebuffer mRawFBO, mAOFBO;
    int mWidth = 0, mHeight = 0;
    int mKernelCount = 0;  // sample count of the kernel now in mParams

    void resize(int width, int height);
    void buildKernel(int count);
};

}  // namespace gi
