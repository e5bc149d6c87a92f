// Volume-based diffuse global illumination by occupancy-aware SH diffusion: seed 001 (Mavridis,
// Gaitatzes, Papaioannou), digest in seeds/digests/001.md. Light moves through a voxel grid as
// in a light propagation volume, but only through empty cells; where it reaches an occupied cell
// it is absorbed there (what shading reads) and reflected by the cell's albedo, so occlusion and
// further bounces come from the same iterations.
//
// Passes (timer names in brackets):
//   1. Voxelization [diffusion.voxelize]: VCT's (gi/vct/surface_voxels.h) into one dense grid
//      holding the scene's bounding cube (2 % larger): albedo, mean normal and occupancy, again
//      only when the scene or the grid changes. Seed 001 slices the scene along three axes and
//      merges with MAX; the dominant-axis conservative voxelizer catches every orientation too,
//      in one draw.
//   2. Injection [diffusion.inject]: VCT's injection gives the radiance each side of every
//      occupied cell's surface reflects of the direct light (shadow-mapped; area lights exact,
//      emissive surfaces included as area lights); init.comp turns each side into a clamped
//      cosine lobe (seed 001's "hemispherical VPL"; the source gives no lobe) in the light
//      buffer, 2-band SH per colour, and clears the accumulation.
//   3. Propagation [diffusion.propagate], `iterations` steps, each two dispatches: emit.comp,
//      the flux each cell sends through each face, and gather.comp, each cell's six incoming
//      faces (the source's gather). Empty cells pass light on; occupied cells accumulate what
//      arrives and reflect it. shaders/diffusion/{emit,gather}.comp open with the choices.
//      Then, with `smoothing` (the default), smooth.comp averages each surface cell's
//      accumulation with its neighbours on the same surface (mean normals within 18 degrees)
//      into the copy shading reads: a tilted face is voxelized as a staircase whose cells open
//      on two faces take more light than those open on one, which showed as stripes a cell wide
//      on every rotated box (DiffusionGL.ATiltedFaceShadesWithoutVoxelStripes: the panel's
//      adjacent-pixel differences fall from 6.5 % to 2.2 % of its mean, its mean within 1 %).
//      It runs after the steps of a frame that ran any, so a held solve costs nothing more.
//   4. Shading [diffusion.shade]: per pixel, the accumulation of the occupied cells among the
//      eight nearest, renormalised trilinear weights, clamped cosine irradiance; resolve.comp
//      also writes the accumulation into a volume for the debug view diffusion.accumulated.
//
// Where the source is wrong or silent (chosen here, tested in tests/diffusion_test.cpp):
//   - Eq. 3.2.2 calls the face integral an average but never divides by the face's solid angle;
//     as written each step multiplies the flux by 2.09. Here a face passes the integral itself
//     (flux), and the receiving cell holds it as a beam of that flux: free space conserves flux.
//   - 2-band lobes are negative behind: the faces' clamped parts are rescaled to the cell's flux.
//   - Face transfer between two occupied cells is closed, so a lit floor does not light itself.
//   - Reflection is two-sided: light reaching a surface's back is reflected to its back (seed
//     001 reflects along the mean normal only), so a one-voxel wall lit on one side stays dark
//     on the other.
//   - Units: the buffers carry flux per unit of surface area (a side leaving radiance L emits pi
//     L); the cell size cancels between injection and shading.
// Update rate (seed 001 section 4, "decoupled"): with iterationsPerFrame > 0 the solve runs
// that many steps a frame, the picture filling in over frames, and once all `iterations` are
// done it is held (a frame then costs the shading alone) until ctx.changes reports a change of
// a light or a setting, or the scene changes, which restarts it from injection. Camera moves
// keep it. 0 (the default) solves everything in one frame and holds it the same way while
// render.keepStaticWork is on (issue 17 item 4; the editor's steady state); with it off, every
// frame solves again (fully dynamic lights, the benchmarks' everything-dynamic frame).
// Voxelization modes (setting voxelization): VCT's one draw along each triangle's dominant axis,
// grown for conservative rasterization, or seed 001's slicing: three draws, along x, y and z,
// not grown, each fragment writing the one cell its depth falls in; the three merge into the
// same volumes (occupancy is their union, MAX of the indicator as the seed merges; albedo and
// normal are averaged over the fragments of all three, since a MAX of encoded normals is no
// normal).
// Bounce orders: the light carries the flux-weighted mean number of reflections it has had
// (1 for reflected direct light), shown per cell by the diffusion.bounces view.
// Not here yet (issue 16): the sky. Light diffuses rather than travels straight:
// seed 001's "n Y steps for n bounces" describes only the front of it, so the default
// `iterations` is 128, not the seed's 64 for rooms (diffusion_settings.h gives the figures).
#pragma once

#include "diffusion/diffusion_shared.h"
#include "gi/diffusion/diffusion_settings.h"
#include "gi/gl/handle.h"
#include "gi/gl/shader.h"
#include "gi/gl/uniform_block.h"
#include "gi/render/pass.h"
#include "gi/vct/surface_voxels.h"
#include "gi/vct/vct.h"

namespace gi {

class Diffusion : public Pass {
public:
    Diffusion();

    static size_t estimateBytes(const FrameSettings& fs);

    void indirect(FrameContext& ctx) override;
    std::vector<DebugView> debugViews() const override;
    size_t passMemory(const std::string& pass) const override;
    size_t memoryBytes() const override;
    std::vector<VolumeMemory> volumeMemory() const override;
    std::vector<std::string> passNames(const FrameSettings& fs) const override;
    bool reloadShaders(std::string& log) override;

    // One propagation step (emit, then gather) on volumes the caller owns (tests): `albedo` and
    // `normal` as the voxelizer writes them (r32ui, res^3), `source` and `destination` 3 vec4 per
    // cell, `outgoing` 6 vec4 per cell, `accum` 3 vec4 per cell (added to).
    void propagateStep(GLuint albedo, GLuint normal, GLuint source, GLuint destination, GLuint outgoing, GLuint accum, int res,
                       DiffusionAlbedo albedoMode);

    // Starts the bounce orders of propagateStep() at res afresh (tests): the light in flight is
    // order 1, nothing accumulated.
    void resetBounceOrders(int res);

    int resolution() const { return mResolution; }
    // Solves started (from injection) since creation (tests: a held solve starts none).
    int solveCount() const { return mSolves; }
    const VoxelBox& box() const { return mBox; }
    // The accumulated light, 3 vec4 (R, G, B SH) per cell, and the volumes it was made with.
    const gl::Buffer& accumulated() const { return mAccum; }
    // The flux-weighted bounce order summed over the accumulation, one float per cell (orders
    // times flux; divide by the accumulation's flux, 2 sqrt(pi) times band 0 summed over colours).
    const gl::Buffer& accumulatedOrder() const { return mOrderAccum; }
    const gl::Texture& albedoVolume() const { return mSurface.albedo; }
    int voxelizationCount() const { return mSurfaces.voxelizationCount(); }

private:
    SurfaceVoxelizer mSurfaces;
    gl::Program mInitProg, mEmitProg, mGatherProg, mShadeProg, mResolveProg, mSmoothProg;
    gl::UniformBlock<shared::DiffusionParams> mBlock;
    SurfaceVolumes mSurface;  // albedo, normal, position; the radiance each side leaves
    gl::Texture mView;  // the accumulation, RGBA16F (diffusion.accumulated)
    gl::Texture mViewInFlight, mViewBounces;  // diffusion.inFlight, diffusion.bounces
    gl::Buffer mLight[2], mOutgoing, mAccum;
    gl::Buffer mShaded;  // the accumulation shade reads: smoothed (smooth.comp) when `smoothing` is on
    // Bounce orders (diffusion_shared.h): in flight, ping-pong beside the light, and accumulated;
    // sized by ensureOrderBuffers() for the resolution a step runs at.
    gl::Buffer mOrder[2], mOrderAccum;
    // emit's and gather's views of the grids (propagateStep)
    gl::TextureHandle mSourceView = gl::createBufferTexture(), mOrderSourceView = gl::createBufferTexture(),
                      mOutgoingView = gl::createBufferTexture(), mDestinationView = gl::createBufferTexture(),
                      mAccumView = gl::createBufferTexture(), mOrderDestinationView = gl::createBufferTexture(),
                      mOrderAccumView = gl::createBufferTexture();
    int mOrderResolution = 0, mOrderParity = 0;
    DiffusionVoxelization mVoxelizedWith = DiffusionVoxelization::Conservative;
    VoxelBox mBox;
    int mResolution = 0;
    uint64_t mSceneId = 0;
    bool mVoxelized = false;
    size_t mVoxelBytes = 0, mBufferBytes = 0;

    int mStepsDone = -1;  // propagation steps of the current solve; -1: none started
    int mSolves = 0;
    int mSolveShadowSize = 0;  // of the shadow maps its injection read
    void allocate(const FrameSettings& fs);
    // mShaded from mAccum (smooth.comp), after the propagation steps of a frame that ran any.
    void smooth(const shared::DiffusionParams& p);
    void ensureOrderBuffers(int res);
    shared::DiffusionParams params(const FrameSettings& fs) const;
    void injectLight(const FrameContext& ctx, const vct::VCTParams& grid, const shared::DiffusionParams& p);
    void shade(FrameContext& ctx, shared::DiffusionParams p);
};

}  // namespace gi
