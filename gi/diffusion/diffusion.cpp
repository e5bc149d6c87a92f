#include "gi/diffusion/diffusion.h"

#include "common/shared.h"
#include "gi/gl/buffer_texture.h"
#include "gi/render/gpu_scene.h"
#include "gi/render/render_settings.h"
#include "gi/util/budget.h"

#include <algorithm>

namespace gi {

namespace {

size_t cellsOf(int res) { return size_t(res) * size_t(res) * size_t(res); }
// Light in flight twice (ping-pong), the accumulation and its smoothed copy: 3 vec4 each;
// outgoing faces: 6 vec4; bounce orders in flight (twice) and accumulated: a float each.
constexpr size_t kBufferBytesPerCell = (3 * 16) * 4 + 6 * 16 + 3 * 4;
constexpr size_t kViewBytesPerCell = 3 * 8;  // the RGBA16F views: accumulated, in flight, bounces
// Cell-steps a second for the time budget: llvmpipe on two cores ran 32^3 x 64 steps in 0.48 s
// (4.4e6/s); a GPU is far faster, so this refuses only what would stall a CPU renderer.
constexpr double kCellStepsPerSecond = 4e6;

}  // namespace

Diffusion::Diffusion()
    : mInitProg("diffusion.init", {{GL_COMPUTE_SHADER, "diffusion/init.comp"}}),
      mEmitProg("diffusion.emit", {{GL_COMPUTE_SHADER, "diffusion/emit.comp"}}),
      mGatherProg("diffusion.gather", {{GL_COMPUTE_SHADER, "diffusion/gather.comp"}}),
      mShadeProg("diffusion.shade", {{GL_COMPUTE_SHADER, "diffusion/shade.comp"}}),
      mResolveProg("diffusion.resolve", {{GL_COMPUTE_SHADER, "diffusion/resolve.comp"}}),
      mSmoothProg("diffusion.smooth", {{GL_COMPUTE_SHADER, "diffusion/smooth.comp"}}),
      mBlock(shared::kDiffusionBlockName, shared::kDiffusionBlockBinding) {
    for (gl::Program* p : {&mInitProg, &mEmitProg, &mGatherProg, &mShadeProg, &mResolveProg, &mSmoothProg}) mBlock.requireIn(*p);
}

size_t Diffusion::estimateBytes(const FrameSettings& fs) {
    return cellsOf(fs.diffusion.gridResolution) * (SurfaceVolumes::kBytesPerVoxel + kViewBytesPerCell + kBufferBytesPerCell);
}

void Diffusion::allocate(const FrameSettings& fs) {
    // Only the grid's resolution sizes anything here (a Reallocate bit may come from the image's size).
    int res = fs.diffusion.gridResolution;
    if (res == mResolution) return;
    // emit.comp and gather.comp view the outgoing flux as a buffer texture of 6 texels per cell.
    gl::requireBufferTexels(size_t(res) * res * res * 6, "diffusion.gridResolution");
    mResolution = res;
    mSurface = SurfaceVolumes::create(res);
    mView = gl::Texture::create3D(GL_RGBA16F, res, res, res);
    mViewInFlight = gl::Texture::create3D(GL_RGBA16F, res, res, res);
    mViewBounces = gl::Texture::create3D(GL_RGBA16F, res, res, res);
    size_t cells = cellsOf(res);
    for (auto& b : mLight) b = gl::createBuffer(cells * 3 * 16, nullptr, 0);
    mAccum = gl::createBuffer(cells * 3 * 16, nullptr, 0);
    mShaded = gl::createBuffer(cells * 3 * 16, nullptr, 0);
    mOutgoing = gl::createBuffer(cells * 6 * 16, nullptr, 0);
    ensureOrderBuffers(res);
    mVoxelBytes = mSurface.bytes() + mView.bytes() + mViewInFlight.bytes() +
                  mViewBounces.bytes();
    mBufferBytes = cells * kBufferBytesPerCell;
    mVoxelized = false;
}

void Diffusion::ensureOrderBuffers(int res) {
    if (res == mOrderResolution) return;
    mOrderResolution = res;
    size_t bytes = cellsOf(res) * 4;
    for (gl::Buffer* b : {&mOrder[0], &mOrder[1], &mOrderAccum}) {
        *b = gl::createBuffer(bytes, nullptr, 0);
        glClearNamedBufferData(b->id(), GL_R32F, GL_RED, GL_FLOAT, nullptr);
    }
    mOrderParity = 0;
}

void Diffusion::resetBounceOrders(int res) {
    ensureOrderBuffers(res);
    const float one = 1.0f;
    for (gl::Buffer* b : {&mOrder[0], &mOrder[1]}) glClearNamedBufferData(b->id(), GL_R32F, GL_RED, GL_FLOAT, &one);
    glClearNamedBufferData(mOrderAccum.id(), GL_R32F, GL_RED, GL_FLOAT, nullptr);
    mOrderParity = 0;
}

shared::DiffusionParams Diffusion::params(const FrameSettings& fs) const {
    shared::DiffusionParams p{};
    p.gridMin = glm::vec4(mBox.min, mBox.cellSize);
    p.resolution = mResolution;
    p.albedoMode = fs.diffusion.bounceAlbedo == DiffusionAlbedo::Half ? 1 : 0;
    p.intensity = fs.diffusion.intensity;
    p.nudge = fs.diffusion.nudge;
    return p;
}

void Diffusion::indirect(FrameContext& ctx) {
    const FrameSettings& fs = ctx.settings;
    allocate(fs);
    const int res = mResolution;
    vct::VCTParams grid{};
    {
        auto pass = ctx.timer.scope("diffusion.voxelize");
        const Bounds& b = ctx.scene.bounds();
        VCTSettings dense;
        dense.mode = VCTMode::Dense;
        dense.gridResolution = res;
        VoxelBox box = vctLevels(dense, b.min, b.max, fs.camera.eye).front();
        grid.resolution = res;
        grid.gridMin = glm::vec4(box.min, 0.0f);
        grid.cellSize = box.cellSize;
        grid.wrapOffset.w = 1;  // inject at the surfaces' positions in their voxels (vct_shared.h)
        bool newScene = ctx.scene.id() != mSceneId;
        const DiffusionVoxelization mode = fs.diffusion.voxelization;
        if (!mVoxelized || newScene || box.min != mBox.min || box.cellSize != mBox.cellSize || mode != mVoxelizedWith) {
            mSurfaces.voxelize(ctx, grid, mSurface, glm::ivec3(0), glm::ivec3(res),
                               mode == DiffusionVoxelization::Slicing);
            mVoxelizedWith = mode;
            mBox = box;
            mSceneId = ctx.scene.id();
            mVoxelized = true;
            mStepsDone = -1;  // the solve starts again
        }
    }
    shared::DiffusionParams p = params(fs);
    // The solve: all iterations in one frame (iterationsPerFrame 0), or iterationsPerFrame steps a
    // frame, until all are done; then held until a light, a setting, the scene or the size of the
    // shadow maps the injection reads changes. With render.keepStaticWork off, iterationsPerFrame
    // 0 solves every frame.
    const DiffusionSettings& s = fs.diffusion;
    const bool restart = (s.iterationsPerFrame == 0 && !fs.render.keepStaticWork) || ctx.changes != 0 || mStepsDone < 0 ||
                         ctx.shadowSize != mSolveShadowSize;
    if (restart) ++mSolves;
    mSolveShadowSize = ctx.shadowSize;
    {
        auto pass = ctx.timer.scope("diffusion.inject");
        if (restart) injectLight(ctx, grid, p);
    }
    {
        auto pass = ctx.timer.scope("diffusion.propagate");
        if (restart) mStepsDone = 0;
        int steps = std::min(s.iterationsPerFrame > 0 ? s.iterationsPerFrame : s.iterations, s.iterations - mStepsDone);
        for (int k = 0; k < steps; ++k, ++mStepsDone)
            propagateStep(mSurface.albedo.id(), mSurface.normal.id(), mLight[mStepsDone % 2].id(), mLight[(mStepsDone + 1) % 2].id(), mOutgoing.id(),
                          mAccum.id(), res, s.bounceAlbedo);
        // The accumulation changed (a restart clears it, steps add to it): smooth it again.
        if (s.smoothing && (restart || steps > 0)) smooth(p);
    }
    shade(ctx, p);
    ctx.indirectWritten = true;
}

void Diffusion::smooth(const shared::DiffusionParams& p) {
    mSmoothProg.use();
    mBlock.set(p);
    glBindImageTexture(shared::kDiffusionImageAlbedo, mSurface.albedo.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
    glBindImageTexture(shared::kDiffusionImageNormal, mSurface.normal.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
    glTextureBuffer(mAccumView.id(), GL_RGBA32F, mAccum.id());
    glTextureBuffer(mDestinationView.id(), GL_RGBA32F, mShaded.id());
    glBindTextureUnit(shared::kDiffusionUnitSmoothSource, mAccumView.id());
    glBindImageTexture(shared::kDiffusionImageSmoothDestination, mDestinationView.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    gl::dispatch3D(mResolution);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glBindTextureUnit(shared::kDiffusionUnitSmoothSource, 0);
}

void Diffusion::injectLight(const FrameContext& ctx, const vct::VCTParams& grid, const shared::DiffusionParams& p) {
    {
        mSurfaces.inject(ctx, grid, mSurface);
        mInitProg.use();
        mBlock.set(p);
        glBindImageTexture(shared::kDiffusionImageAlbedo, mSurface.albedo.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
        glBindImageTexture(shared::kDiffusionImageNormal, mSurface.normal.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
        glBindImageTexture(shared::kDiffusionImageExitFront, mSurface.exitFront.id(), 0, GL_TRUE, 0, GL_READ_ONLY, SurfaceVolumes::kExitFormat);
        glBindImageTexture(shared::kDiffusionImageExitBack, mSurface.exitBack.id(), 0, GL_TRUE, 0, GL_READ_ONLY, SurfaceVolumes::kExitFormat);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shared::kDiffusionBufferDestination, mLight[0].id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shared::kDiffusionBufferAccum, mAccum.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shared::kDiffusionBufferOrderDestination, mOrder[0].id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shared::kDiffusionBufferOrderAccum, mOrderAccum.id());
        mOrderParity = 0;
        gl::dispatch3D(mResolution);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
}

void Diffusion::shade(FrameContext& ctx, shared::DiffusionParams p) {
    {
        auto pass = ctx.timer.scope("diffusion.shade");
        p.invViewProj = ctx.invViewProj;
        p.width = ctx.width;
        p.height = ctx.height;
        mShadeProg.use();
        mBlock.set(p);
        glBindTextureUnit(shared::kUnitNormal, ctx.normal);
        glBindTextureUnit(shared::kUnitDepth, ctx.depth);
        glBindImageTexture(shared::kDiffusionImageAlbedo, mSurface.albedo.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
        glBindImageTexture(shared::kDiffusionImageNormal, mSurface.normal.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
        glBindImageTexture(shared::kDiffusionImageIndirect, ctx.indirect, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glTextureBuffer(mAccumView.id(), GL_RGBA32F, ctx.settings.diffusion.smoothing ? mShaded.id() : mAccum.id());
        glBindTextureUnit(shared::kDiffusionUnitShadeAccum, mAccumView.id());
        glDispatchCompute(gl::groupCount(ctx.width, shared::kGroup2D), gl::groupCount(ctx.height, shared::kGroup2D), 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glBindTextureUnit(shared::kDiffusionUnitShadeAccum, 0);
        mResolveProg.use();
        glBindImageTexture(shared::kDiffusionImageView, mView.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glBindImageTexture(shared::kDiffusionImageViewInFlight, mViewInFlight.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glBindImageTexture(shared::kDiffusionImageViewBounces, mViewBounces.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shared::kDiffusionBufferAccum, mAccum.id());
        // The light in flight after the last step: step k writes mLight[(k + 1) % 2].
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shared::kDiffusionBufferSource, mLight[std::max(mStepsDone, 0) % 2].id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shared::kDiffusionBufferOrderAccum, mOrderAccum.id());
        gl::dispatch3D(mResolution);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
}

void Diffusion::propagateStep(GLuint albedo, GLuint normal, GLuint source, GLuint destination, GLuint outgoing, GLuint accum, int res,
                              DiffusionAlbedo albedoMode) {
    shared::DiffusionParams p{};
    p.resolution = res;
    p.albedoMode = albedoMode == DiffusionAlbedo::Half ? 1 : 0;
    ensureOrderBuffers(res);
    // Buffer views of the grids (emit.comp and gather.comp read and write through them).
    glTextureBuffer(mSourceView.id(), GL_RGBA32F, source);
    glTextureBuffer(mOrderSourceView.id(), GL_R32F, mOrder[mOrderParity].id());
    glTextureBuffer(mOutgoingView.id(), GL_RGBA32F, outgoing);
    glTextureBuffer(mDestinationView.id(), GL_RGBA32F, destination);
    glTextureBuffer(mAccumView.id(), GL_RGBA32F, accum);
    glTextureBuffer(mOrderDestinationView.id(), GL_R32F, mOrder[1 - mOrderParity].id());
    glTextureBuffer(mOrderAccumView.id(), GL_R32F, mOrderAccum.id());
    mOrderParity = 1 - mOrderParity;
    mBlock.set(p);
    const GLbitfield written = GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT;
    glBindImageTexture(shared::kDiffusionImageAlbedo, albedo, 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
    glBindImageTexture(shared::kDiffusionImageNormal, normal, 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
    mEmitProg.use();
    glBindTextureUnit(shared::kDiffusionUnitStepSource, mSourceView.id());
    glBindTextureUnit(shared::kDiffusionUnitStepOrder, mOrderSourceView.id());
    glBindImageTexture(shared::kDiffusionImageStepOutgoing, mOutgoingView.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    gl::dispatch3D(res);
    glMemoryBarrier(written);
    mGatherProg.use();
    glBindTextureUnit(shared::kDiffusionUnitStepSource, mOutgoingView.id());
    glBindImageTexture(shared::kDiffusionImageStepDestination, mDestinationView.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glBindImageTexture(shared::kDiffusionImageStepAccum, mAccumView.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glBindImageTexture(shared::kDiffusionImageStepOrderDestination, mOrderDestinationView.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    glBindImageTexture(shared::kDiffusionImageStepOrderAccum, mOrderAccumView.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
    gl::dispatch3D(res);
    glMemoryBarrier(written);
    glBindTextureUnit(shared::kDiffusionUnitStepSource, 0);
    glBindTextureUnit(shared::kDiffusionUnitStepOrder, 0);
}

std::vector<DebugView> Diffusion::debugViews() const {
    int r = mResolution;
    return {{"diffusion.occupancy", mSurface.albedo.id(), GL_TEXTURE_3D, shared::kViewVoxelPacked, r, r, 0, 1, 1},
            {"diffusion.normal", mSurface.normal.id(), GL_TEXTURE_3D, shared::kViewVoxelPackedNormal, r, r, 0, 1, 1},
            {"diffusion.accumulated", mView.id(), GL_TEXTURE_3D, shared::kViewVoxelColor, r, r, 0, 1, 1},
            {"diffusion.inFlight", mViewInFlight.id(), GL_TEXTURE_3D, shared::kViewVoxelColor, r, r, 0, 1, 1},
            {"diffusion.bounces", mViewBounces.id(), GL_TEXTURE_3D, shared::kViewVoxelColor, r, r, 0, 1, 1}};
}

size_t Diffusion::passMemory(const std::string& pass) const {
    if (pass == "diffusion.voxelize") return mVoxelBytes;
    if (pass == "diffusion.propagate") return mBufferBytes;
    return 0;
}

size_t Diffusion::memoryBytes() const { return mVoxelBytes + mBufferBytes; }

std::vector<VolumeMemory> Diffusion::volumeMemory() const {
    std::string r = std::to_string(mResolution) + "^3 ";
    size_t cells = cellsOf(mResolution);
    std::vector<VolumeMemory> v;
    mSurface.describe(v, mResolution);
    v.insert(v.end(),
             {{"light", r + "3 x vec4 SH x 2 (ping-pong)", 2 * cells * 3 * 16},
              {"outgoing", r + "6 x vec4 (flux per face)", cells * 6 * 16},
              {"accumulated", r + "3 x vec4 SH", cells * 3 * 16},
              {"shaded", r + "3 x vec4 SH (the accumulation smoothed over each surface)", cells * 3 * 16},
              {"bounceOrder", r + "float x 3 (in flight x 2, accumulated)", cells * 3 * 4},
              {"views", r + "RGBA16F x 3 (accumulated, in flight, bounces)", mView.bytes() + mViewInFlight.bytes() + mViewBounces.bytes()}});
    return v;
}

std::vector<std::string> Diffusion::passNames(const FrameSettings&) const {
    return {"diffusion.voxelize", "diffusion.inject", "diffusion.propagate", "diffusion.shade"};
}

bool Diffusion::reloadShaders(std::string& log) {
    bool ok = mSurfaces.reloadShaders(log);
    for (gl::Program* p : {&mInitProg, &mEmitProg, &mGatherProg, &mShadeProg, &mResolveProg, &mSmoothProg})
        if (!p->reload()) {
            ok = false;
            log += p->log() + "\n";
        }
    return ok;
}

void DiffusionSettings::checkTime(const FrameSettings& fs) {
    const DiffusionSettings& s = fs.diffusion;
    double cellSteps = double(cellsOf(s.gridResolution)) * double(s.iterations);
    gi::checkTimeBudget(cellSteps / kCellStepsPerSecond, fs.render.timeBudgetSeconds, "diffusion propagation per frame",
                        "gridResolution " + std::to_string(s.gridResolution) + "^3, iterations " + std::to_string(s.iterations),
                        "lower diffusion.iterations or diffusion.gridResolution");
}

std::unique_ptr<Pass> DiffusionSettings::createPass() { return std::make_unique<Diffusion>(); }
size_t DiffusionSettings::estimateBytes(const FrameSettings& fs) { return Diffusion::estimateBytes(fs); }

}  // namespace gi
