#include "gi/vct/vct.h"

#include "gi/render/lights.h"

#include "common/shared.h"
#include "gi/render/gpu_scene.h"
#include "gi/util/error.h"
#include "vct/vct_shared.h"

#include <algorithm>
#include <cmath>

namespace gi {

namespace {

// The radiance leaving each side of a voxel's surface (inject, bounce, resolve): positive HDR
// colour, no alpha, so the packed float format at half RGBA16F's size (5-6 bit mantissas, about
// 3% steps, far below the voxelization's own error).
constexpr GLenum kExitFormat = SurfaceVolumes::kExitFormat;
constexpr size_t kVoxelBytes = SurfaceVolumes::kBytesPerVoxel;

size_t voxels(int res) { return size_t(res) * res * res; }

size_t mipChain(size_t bytesPerTexel, int res, int levels) {
    size_t total = 0;
    for (int l = 0; l < levels; ++l) total += bytesPerTexel * voxels(std::max(res >> l, 1));
    return total;
}

int levelCountOf(const VCTSettings& s) { return s.mode == VCTMode::Dense ? 1 : s.levelCount; }
bool shOn(const VCTSettings& s) { return s.sh && s.mode == VCTMode::Dense; }

// Positive remainder, for toroidal texel offsets.
glm::ivec3 wrapOf(const glm::ivec3& origin, int res) { return ((origin % res) + res) % res; }

gl::Sampler makeSampler(GLenum wrap, GLenum minFilter) { return gl::createSampler({minFilter, GL_LINEAR, wrap}); }

}  // namespace

int vctMipCount(int resolution) {
    int count = 1;
    for (int r = resolution; r > 1 && r % 2 == 0; r /= 2) ++count;
    return count;
}

std::vector<VoxelBox> vctLevels(const VCTSettings& s, const glm::vec3& sceneMin, const glm::vec3& sceneMax,
                                const glm::vec3& camera) {
    std::vector<VoxelBox> boxes;
    int res = s.gridResolution;
    if (s.mode == VCTMode::Dense) {
        VoxelBox b;
        const Bounds bounds{sceneMin, sceneMax};  // unset extent: the scene's grid cube
        float extent = s.levelExtent > 0.0f ? s.levelExtent : bounds.gridCubeSize();
        b.cellSize = extent / float(res);
        b.min = s.levelExtent > 0.0f ? camera - glm::vec3(0.5f * extent) : bounds.gridCubeMin();
        boxes.push_back(b);
        return boxes;
    }
    // Fitting the scene: the coarsest level, centred on the camera, holds the whole scene.
    glm::vec3 reach = glm::max(glm::abs(camera - sceneMin), glm::abs(sceneMax - camera));
    float coarsest = 2.04f * std::max(reach.x, std::max(reach.y, reach.z));
    float finest = s.levelExtent > 0.0f ? s.levelExtent : coarsest / float(1 << (s.levelCount - 1));
    // Cascaded levels move in steps of res/8 voxels (seed 000), clipmap levels in single voxels.
    int snap = s.mode == VCTMode::Cascaded ? std::max(res / 8, 1) : 1;
    for (int k = 0; k < s.levelCount; ++k) {
        VoxelBox b;
        b.cellSize = finest * float(1 << k) / float(res);
        glm::vec3 corner = camera / b.cellSize - glm::vec3(0.5f * float(res));
        b.origin = glm::ivec3(glm::round(corner / float(snap))) * snap;
        b.min = glm::vec3(b.origin) * b.cellSize;
        boxes.push_back(b);
    }
    return boxes;
}

VCT::VCT()
    : mResolveProg("vct.resolve", {{GL_COMPUTE_SHADER, "vct/resolve.comp"}}),
      mMipProg("vct.mip", {{GL_COMPUTE_SHADER, "vct/mip.comp"}}),
      mOctantsProg("vct.octants", {{GL_COMPUTE_SHADER, "vct/octants.comp"}}),
      mUpsampleProg("vct.upsample", {{GL_COMPUTE_SHADER, "vct/upsample.comp"}}),
      mCompactProg("vct.compact", {{GL_COMPUTE_SHADER, "vct/compact.comp"}}),
      mBlock(vct::kVCTBlockName, vct::kVCTBlockBinding) {
    for (gl::Program* p : {&mResolveProg, &mMipProg, &mOctantsProg, &mUpsampleProg, &mCompactProg}) mBlock.requireIn(*p);
    mLinear = makeSampler(GL_CLAMP_TO_BORDER, GL_LINEAR_MIPMAP_LINEAR);
    mRepeat = makeSampler(GL_REPEAT, GL_LINEAR_MIPMAP_LINEAR);
}

VCT::~VCT() = default;

size_t VCT::estimateBytes(const FrameSettings& fs) {
    const VCTSettings& s = fs.vct;
    int res = s.gridResolution, mips = vctMipCount(res);
    size_t perLevel = voxels(res) * kVoxelBytes + mipChain(8, res, mips);
    if (s.bounceCount > 1) perLevel += 2 * voxels(res) * 8 + voxels(res) * 4;  // bounced radiance, occupied list
    size_t bytes = perLevel * size_t(levelCountOf(s));
    double traced = std::ceil(double(fs.width) * s.traceScale) * std::ceil(double(fs.height) * s.traceScale);
    bytes += size_t(traced) * 32;  // the traced images the upsampling filter reads: light, specular, guide
    if (vctAnisotropicOn(s)) bytes += 6 * mipChain(8, res, mips);  // the atlas, from level 0 up
    if (vctFaceSidesOn(s)) {
        bytes += 6 * mipChain(2, res, mips) + mipChain(8, res, mips);   // the coverage atlas, the centroids
        bytes += 8 * mipChain(8, res, mips);                            // the coverage by octant
        bytes += 6 * voxels(res) * (4 + 8) * size_t(levelCountOf(s));  // sides, their radiance
        if (s.bounceCount > 1) bytes += 6 * voxels(res) * 8 * size_t(levelCountOf(s));  // and with the bounced light
    }
    if (shOn(s)) bytes += 3 * mipChain(8, res, mips);
    return bytes;
}

void VCT::allocate(const FrameSettings& fs, uint8_t changes) {
    const VCTSettings& s = fs.vct;
    int count = levelCountOf(s);
    if (any(Cost(changes), Cost::Recompile)) {
        // The level count and the voxel layout are compiled into the bounce and trace programs.
        mAnisotropic = vctAnisotropicOn(s);
        mFaceSides = vctFaceSidesOn(s);
        mSHVoxels = shOn(s);
        std::vector<std::string> defines = {"VCT_LEVELS " + std::to_string(count),
                                            std::string("VCT_ANISO ") + (mAnisotropic ? "1" : "0"),
                                            std::string("VCT_SIDES ") + (mFaceSides ? "1" : "0"),
                                            std::string("VCT_SH ") + (mSHVoxels ? "1" : "0")};
        mBounceProg = gl::Program("vct.bounce", {{GL_COMPUTE_SHADER, "vct/bounce.comp"}}, defines);
        mTraceProg = gl::Program("vct.trace", {{GL_COMPUTE_SHADER, "vct/trace.comp"}}, defines);
        mBlock.requireIn(mBounceProg);
        mBlock.requireIn(mTraceProg);
    }
    if (!any(Cost(changes), Cost::Reallocate)) return;
    mMode = s.mode;
    mResolution = s.gridResolution;
    mMipCount = vctMipCount(mResolution);
    mLevels.clear();
    mVoxelBytes = mRadianceBytes = 0;
    int r = mResolution;
    for (int k = 0; k < count; ++k) {
        Level l;
        l.surface = SurfaceVolumes::create(r);
        l.radiance = gl::Texture::create3D(GL_RGBA16F, r, r, r, mMipCount);
        mVoxelBytes += l.surface.bytes();
        if (mFaceSides) {
            l.sides = gl::Texture::create3D(GL_R32UI, 6 * r, r, r);
            l.sidesRadiance = gl::Texture::create3D(GL_RGBA16F, 6 * r, r, r);
            mVoxelBytes += l.sides.bytes() + l.sidesRadiance.bytes();
        }
        mRadianceBytes += l.radiance.bytes();
        mLevels.push_back(std::move(l));
    }
    mAniso = gl::Texture();
    mAnisoCoverage = gl::Texture();
    mCoverageOctants = gl::Texture();
    for (auto& t : mSH) t = gl::Texture();
    mCentroid = gl::Texture();
    if (mAnisotropic) {
        mAniso = gl::Texture::create3D(GL_RGBA16F, 6 * r, r, r, mMipCount);
        mRadianceBytes += mAniso.bytes();
    }
    if (mFaceSides) {
        mAnisoCoverage = gl::Texture::create3D(GL_R16F, 6 * r, r, r, mMipCount);
        mCoverageOctants = gl::Texture::create3D(GL_RGBA16F, 8 * r, r, r, mMipCount);
        mCentroid = gl::Texture::create3D(GL_RGBA16F, r, r, r, mMipCount);
        mRadianceBytes += mAnisoCoverage.bytes() + mCoverageOctants.bytes() + mCentroid.bytes();
    }
    if (mSHVoxels)
        for (auto& t : mSH) {
            t = gl::Texture::create3D(GL_RGBA16F, r, r, r, mMipCount);
            mRadianceBytes += t.bytes();
        }
    mVoxelizedVoxels.assign(size_t(count), 0);
}

void VCT::indirect(FrameContext& ctx) {
    allocate(ctx.settings, ctx.changes);
    bool revoxelized = updateGrids(ctx);
    // The lit volumes, their mips and bounces depend on the voxels, the lights with their shadow
    // maps, and VCT's settings alone, so static geometry under static lights keeps them (issue 17
    // item 4): ctx.changes holds the cost tags of every light and VCT setting changed since the
    // last frame, a moved grid revoxelizes, and the maps change with the lights, the scene and
    // their size. The passes still open their timers.
    bool relight = !mLit || revoxelized || ctx.changes != 0 || ctx.shadowSize != mLitShadowSize ||
                   !ctx.settings.render.keepStaticWork;
    if (relight) ++mLightings;
    mLit = true;
    mLitShadowSize = ctx.shadowSize;
    inject(ctx, relight);
    {
        auto pass = ctx.timer.scope("vct.mip");
        if (relight) {
            for (Level& l : mLevels) resolve(l, false);
            buildMips(false);
        }
    }
    bounce(ctx, relight);
    trace(ctx);
    ctx.indirectWritten = true;
}

vct::VCTParams VCT::gridParams(const Level& level) const {
    vct::VCTParams p{};
    p.resolution = mResolution;
    p.gridMin = glm::vec4(level.box.min, 0.0f);
    p.cellSize = level.box.cellSize;
    // The finest level injects and bounces at its surfaces' positions, the coarser ones at their
    // voxels' centres (wrapOffset.w, vct_shared.h).
    p.wrapOffset = glm::ivec4(mMode == VCTMode::Clipmap ? wrapOf(level.box.origin, mResolution) : glm::ivec3(0),
                              &level == &mLevels.front() ? 1 : 0);
    return p;
}

bool VCT::updateGrids(const FrameContext& ctx) {
    auto pass = ctx.timer.scope("vct.voxelize");
    const Bounds& b = ctx.scene.bounds();
    std::vector<VoxelBox> boxes = vctLevels(ctx.settings.vct, b.min, b.max, ctx.settings.camera.eye);
    bool newScene = ctx.scene.id() != mSceneId;
    if (newScene) mSceneId = ctx.scene.id();
    const int r = mResolution;
    bool any = false;
    for (size_t k = 0; k < mLevels.size(); ++k) {
        Level& l = mLevels[k];
        const VoxelBox& nb = boxes[k];
        bool sameLattice = l.voxelized && !newScene && l.box.cellSize == nb.cellSize && !ctx.settings.vct.revoxelizeEveryFrame;
        mVoxelizedVoxels[k] = 0;
        if (sameLattice && l.box.min == nb.min && l.box.origin == nb.origin) continue;
        any = true;
        glm::ivec3 delta = nb.origin - l.box.origin;
        bool partial = sameLattice && mMode == VCTMode::Clipmap && glm::all(glm::lessThan(glm::abs(delta), glm::ivec3(r)));
        l.box = nb;
        l.voxelized = true;
        if (!partial) {
            mSurfaces.voxelize(ctx, gridParams(l), l.surface, glm::ivec3(0), glm::ivec3(r), false, l.sides.id());
            mVoxelizedVoxels[k] = voxels(r);
            continue;
        }
        // Clipmap: only the slabs the move exposed, in the new grid's coordinates.
        for (int axis = 0; axis < 3; ++axis) {
            if (delta[axis] == 0) continue;
            glm::ivec3 lo(0), hi(r);
            if (delta[axis] > 0) lo[axis] = r - delta[axis];
            else hi[axis] = -delta[axis];
            mSurfaces.voxelize(ctx, gridParams(l), l.surface, lo, hi, false, l.sides.id());
            glm::ivec3 size = hi - lo;
            mVoxelizedVoxels[k] += size_t(size.x) * size_t(size.y) * size_t(size.z);
        }
    }
    return any;
}

void VCT::inject(const FrameContext& ctx, bool relight) {
    auto pass = ctx.timer.scope("vct.inject");
    if (!relight) return;
    for (Level& l : mLevels)
        mSurfaces.inject(ctx, gridParams(l), l.surface, l.sides.id(), l.sidesRadiance.id());
}

void VCT::bindVoxelImages(const Level& l) const {
    l.surface.bindVoxels(GL_READ_ONLY);
    glBindImageTexture(vct::kVCTImageExitFront, l.surface.exitFront.id(), 0, GL_TRUE, 0, GL_READ_ONLY, kExitFormat);
    glBindImageTexture(vct::kVCTImageExitBack, l.surface.exitBack.id(), 0, GL_TRUE, 0, GL_READ_ONLY, kExitFormat);
}

void VCT::resolve(Level& level, bool bounced) {
    vct::VCTParams p = gridParams(level);
    p.sh = mSHVoxels ? 1 : 0;
    p.sides = mFaceSides ? 1 : 0;
    mResolveProg.use();
    mBlock.set(p);
    level.surface.bindVoxels(GL_READ_ONLY);  // albedo, normal, and the position for the centroids
    glBindImageTexture(vct::kVCTImageExitFront, (bounced ? level.bouncedFront : level.surface.exitFront).id(), 0, GL_TRUE, 0, GL_READ_ONLY,
                       kExitFormat);
    glBindImageTexture(vct::kVCTImageExitBack, (bounced ? level.bouncedBack : level.surface.exitBack).id(), 0, GL_TRUE, 0, GL_READ_ONLY,
                       kExitFormat);
    glBindImageTexture(vct::kVCTImageRadiance, level.radiance.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    if (mSHVoxels) {
        glBindImageTexture(vct::kVCTImageSHR, mSH[0].id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glBindImageTexture(vct::kVCTImageSHG, mSH[1].id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glBindImageTexture(vct::kVCTImageSHB, mSH[2].id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    }
    if (mFaceSides) glBindImageTexture(vct::kVCTImageCentroid, mCentroid.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    gl::dispatch3D(mResolution);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void VCT::buildMips(bool bounced) {
    mMipProg.use();
    // size: the destination's voxels per side; srcOffset, dstOffset: the first x of the
    // direction's slab in the anisotropic atlas (0 elsewhere).
    // level0 (vct.faceSides only): 1 writes the atlas's mip 0 from level 0's sides; with
    // vct.faceSides the anisotropic passes also write the coverage atlas.
    auto level = [&](const gl::Texture& src, int srcLevel, const gl::Texture& dst, int dstLevel, int direction, int size,
                     int srcOffset, int dstOffset, int level0 = 0) {
        vct::VCTParams p{};
        p.resolution = mResolution;
        p.level0 = level0;
        p.sides = mFaceSides ? 1 : 0;
        p.sourceLevel = srcLevel;
        p.destSize = glm::ivec4(glm::ivec3(size), 0);
        p.direction = direction;
        p.sourceOffsetX = srcOffset;
        p.destOffsetX = dstOffset;
        mBlock.set(p);
        glBindTextureUnit(vct::kVCTUnitMipSource, src.id());
        glBindImageTexture(vct::kVCTImageMipDest, dst.id(), dstLevel, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        if (direction >= 0 && mFaceSides) {
            glBindTextureUnit(vct::kVCTUnitMipSourceCoverage, mAnisoCoverage.id());
            glBindImageTexture(vct::kVCTImageMipDestCoverage, mAnisoCoverage.id(), dstLevel, GL_TRUE, 0, GL_WRITE_ONLY, GL_R16F);
        }
        gl::dispatch3D(size);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    };
    for (Level& l : mLevels)
        for (int m = 1; m < mMipCount; ++m) level(l.radiance, m - 1, l.radiance, m, -1, mResolution >> m, 0, 0);
    if (mSHVoxels)
        for (auto& t : mSH)
            for (int m = 1; m < mMipCount; ++m) level(t, m - 1, t, m, -1, mResolution >> m, 0, 0);
    if (mFaceSides)
        for (int m = 1; m < mMipCount; ++m) level(mCentroid, m - 1, mCentroid, m, -1, mResolution >> m, 0, 0);
    if (mAnisotropic) {
        // Mip 0 is level 0 (its sides with vct.faceSides), the rest from the mip below, each with
        // its coverage (mip.comp).
        if (mFaceSides)
            glBindTextureUnit(vct::kVCTUnitMipSides, (bounced ? mLevels[0].sidesBounced : mLevels[0].sidesRadiance).id());
        const int r = mResolution;
        for (int d = 0; d < 6; ++d) {
            if (mFaceSides)
                level(mLevels[0].radiance, 0, mAniso, 0, d, r, 0, d * r, 1);
            else  // a copy (mip.comp's level0 pass took 4x the whole mip chain's time on llvmpipe)
                glCopyImageSubData(mLevels[0].radiance.id(), GL_TEXTURE_3D, 0, 0, 0, 0, mAniso.id(), GL_TEXTURE_3D, 0, d * r, 0, 0, r, r, r);
            for (int m = 1; m < mMipCount; ++m) level(mAniso, m - 1, mAniso, m, d, r >> m, d * (r >> (m - 1)), d * (r >> m));
        }
        if (mFaceSides) {  // the coverage regrouped by octant for the trace, every mip (octants.comp)
            mOctantsProg.use();
            glBindTextureUnit(vct::kVCTUnitMipSourceCoverage, mAnisoCoverage.id());
            for (int m = 0; m < mMipCount; ++m) {
                vct::VCTParams p{};
                p.sourceLevel = m;
                p.destSize = glm::ivec4(glm::ivec3(r >> m), 0);
                mBlock.set(p);
                glBindImageTexture(vct::kVCTImageOctants, mCoverageOctants.id(), m, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
                gl::dispatch3D(r >> m);
            }
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        }
    }
}

void VCT::bindRadiance() const {
    for (size_t k = 0; k < mLevels.size(); ++k) {
        GLuint unit = GLuint(vct::kVCTUnitRadiance + int(k));
        glBindTextureUnit(unit, mLevels[k].radiance.id());
        glBindSampler(unit, mMode == VCTMode::Clipmap ? mRepeat.id() : mLinear.id());
    }
    glBindTextureUnit(GLuint(vct::kVCTUnitAniso), mAniso.id());
    glBindSampler(GLuint(vct::kVCTUnitAniso), mLinear.id());
    glBindSampler(GLuint(vct::kVCTUnitCoverageOctants), mLinear.id());
    glBindTextureUnit(GLuint(vct::kVCTUnitCoverageOctants), mCoverageOctants.id());
    glBindSampler(GLuint(vct::kVCTUnitCentroid), mLinear.id());
    glBindTextureUnit(GLuint(vct::kVCTUnitCentroid), mCentroid.id());
    for (int c = 0; c < 3; ++c) {
        glBindTextureUnit(GLuint(vct::kVCTUnitSH + c), mSH[size_t(c)].id());
        glBindSampler(GLuint(vct::kVCTUnitSH + c), mLinear.id());
    }
}

void VCT::setConeParams(vct::VCTParams& p, const VCTSettings& s) const {
    ConeSet set = makeConeSet(s);
    GI_ASSERT(set.cones.size() <= size_t(vct::kVCTMaxCones), "VCTParams::cones holds kVCTMaxCones cones");
    p.coneCount = int(set.cones.size());
    for (size_t i = 0; i < set.cones.size(); ++i) p.cones[i] = glm::vec4(set.cones[i].direction, set.cones[i].weight);
    p.tanHalf = std::tan(0.5f * set.aperture);
    p.levelCount = int(mLevels.size());
    for (size_t k = 0; k < mLevels.size(); ++k) {
        const VoxelBox& b = mLevels[k].box;
        p.levelMinCell[k] = glm::vec4(b.min, b.cellSize);
        p.levelWrap[k] = glm::ivec4(mMode == VCTMode::Clipmap ? wrapOf(b.origin, mResolution) : glm::ivec3(0), 0);
    }
    p.maxLod = float(mMipCount - 1);
    p.nudge = s.nudge;
    p.stepMultiplier = s.stepMultiplier;
    const VoxelBox& outer = mLevels.back().box;
    p.maxDistance = s.maxDistance > 0.0f ? s.maxDistance : outer.extent(mResolution) * shared::kSqrt3;
}

void VCT::bounce(const FrameContext& ctx, bool relight) {
    const VCTSettings& s = ctx.settings.vct;
    if (s.bounceCount <= 1) return;
    auto pass = ctx.timer.scope("vct.bounce");
    if (!relight) return;
    // Each bounce leaves direct light (exitFront/Back, kept) + the light gathered through the
    // volumes, in bouncedFront/Back, which resolve() then reads.
    for (Level& l : mLevels)
        if (l.bouncedFront.width() != mResolution) {
            l.bouncedFront = gl::Texture::create3D(kExitFormat, mResolution, mResolution, mResolution);
            l.bouncedBack = gl::Texture::create3D(kExitFormat, mResolution, mResolution, mResolution);
            l.occupiedList = gl::createBuffer(voxels(mResolution) * 4, nullptr, 0);
            l.occupiedDispatch = gl::createBuffer(16, nullptr, GL_DYNAMIC_STORAGE_BIT);
            mVoxelBytes += l.bouncedFront.bytes() * 2 + voxels(mResolution) * 4;
            // The sides with their gathered light; only occupied voxels' texels are written, and
            // mip.comp reads the others as empty (their opacity is 0).
            if (mFaceSides) {
                l.sidesBounced = gl::Texture::create3D(GL_RGBA16F, 6 * mResolution, mResolution, mResolution);
                mVoxelBytes += l.sidesBounced.bytes();
            }
        }
    // The occupied voxels of each level, listed once per frame (clipmap slabs change them).
    mCompactProg.use();
    for (Level& l : mLevels) {
        const GLuint start[4] = {0, 1, 1, 0};
        glNamedBufferSubData(l.occupiedDispatch.id(), 0, 16, start);
        mBlock.set(gridParams(l));
        glBindImageTexture(vct::kVCTImageAlbedo, l.surface.albedo.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, vct::kVCTBufferDispatch, l.occupiedDispatch.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, vct::kVCTBufferVoxels, l.occupiedList.id());
        gl::dispatch3D(mResolution);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    for (int b = 1; b < s.bounceCount; ++b) {
        mBounceProg.use();
        bindRadiance();
        for (Level& l : mLevels) {
            vct::VCTParams p = gridParams(l);
            setConeParams(p, s);
            // Start at least a voxel diagonal out so a voxel does not gather its own light.
            p.nudge = std::max(s.nudge, 1.0f);
            p.gridMin.w = s.bounceTail && b + 1 == s.bounceCount ? 1.0f : 0.0f;
            mBlock.set(p);
            bindVoxelImages(l);
            glBindImageTexture(vct::kVCTImageBouncedFront, l.bouncedFront.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, kExitFormat);
            glBindImageTexture(vct::kVCTImageBouncedBack, l.bouncedBack.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, kExitFormat);
            if (mFaceSides) {
                glBindImageTexture(vct::kVCTImageSides, l.sides.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
                glBindImageTexture(vct::kVCTImageSidesDirect, l.sidesRadiance.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA16F);
                glBindImageTexture(vct::kVCTImageSidesBounced, l.sidesBounced.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
            }
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, vct::kVCTBufferDispatch, l.occupiedDispatch.id());
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, vct::kVCTBufferVoxels, l.occupiedList.id());
            glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, l.occupiedDispatch.id());
            glDispatchComputeIndirect(0);
        }
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        for (GLuint u = GLuint(vct::kVCTUnitRadiance); u <= GLuint(vct::kVCTUnitSH + 2); ++u) glBindSampler(u, 0);
        for (Level& l : mLevels) resolve(l, true);
        buildMips(true);
    }
}

void VCT::trace(const FrameContext& ctx) {
    auto pass = ctx.timer.scope("vct.trace");
    const VCTSettings& s = ctx.settings.vct;
    vct::VCTParams p = gridParams(mLevels[0]);
    setConeParams(p, s);
    p.occlusionDistance = s.vaoDistance > 0.0f ? s.vaoDistance : p.maxDistance;
    p.vao = s.vao ? 1 : 0;
    p.vaoStrength = s.vaoStrength;
    p.intensity = s.intensity;
    p.specularCone = s.specularCone ? 1 : 0;
    p.specularAperture = glm::vec4(glm::radians(glm::vec2(s.specularApertureMin, s.specularApertureMax)), 0.0f, 0.0f);
    p.invViewProj = ctx.invViewProj;
    p.cameraPos = glm::vec4(ctx.settings.camera.eye, 0.0f);
    // The sky through the cones' leftover transparency (trace.comp), when the environment offers it.
    const SkyLight& sky = ctx.sky;
    if (sky.prefiltered != 0 && !sky.mipRoughness.empty()) {
        int mips = std::min(int(sky.mipRoughness.size()), shared::kSkyMaxMips);
        float apertureRange = std::max(s.specularApertureMax - s.specularApertureMin, 1e-3f);
        float diffuseRoughness = std::clamp((s.coneAperture - s.specularApertureMin) / apertureRange, 0.0f, 1.0f);
        p.sky = glm::vec4(sky.intensity, sky.rotation, float(mips), diffuseRoughness);
        for (int m = 0; m < shared::kSkyMaxMips; ++m)
            p.skyMipRoughness[m / 4][m % 4] = m < mips ? sky.mipRoughness[size_t(m)] : 1.0f;
        glBindTextureUnit(vct::kVCTUnitSky, sky.prefiltered);
        glBindSampler(vct::kVCTUnitSky, sky.sampler);
    }
    glm::ivec2 full(ctx.width, ctx.height);
    glm::ivec2 low = glm::max(glm::ivec2(glm::ceil(glm::vec2(full) * s.traceScale)), glm::ivec2(1));
    // The trace writes its own images at every scale: the upsampling filter averages out the
    // trace's 2 x 2 sample pattern (upsample.comp), at traceScale 1 too.
    if (mLowIndirect.width() != low.x || mLowIndirect.height() != low.y) {
        mLowIndirect = gl::Texture::create2D(GL_RGBA16F, low.x, low.y);
        mLowSpecular = gl::Texture::create2D(GL_RGBA16F, low.x, low.y);
        mLowGuide = gl::Texture::create2D(GL_RGBA32F, low.x, low.y);
    }
    glm::vec2 toFull = glm::vec2(full) / glm::vec2(low);
    p.imageSize = glm::ivec4(low, full);
    p.toFull = glm::vec4(toFull, 0.0f, 0.0f);
    // The clip planes of the projection drawn with (the renderer's rasterCamera), from its matrix:
    // the trace writes its pixels' view depth for the upsampling filter (viewDepthOf).
    p.nearPlane = ctx.proj[3][2] / (ctx.proj[2][2] - 1.0f);
    p.farPlane = ctx.proj[3][2] / (ctx.proj[2][2] + 1.0f);
    mTraceProg.use();
    mBlock.set(p);
    bindRadiance();
    glBindTextureUnit(shared::kUnitNormal, ctx.normal);
    glBindTextureUnit(shared::kUnitMaterial, ctx.material);
    glBindTextureUnit(shared::kUnitDepth, ctx.depth);
    glBindImageTexture(vct::kVCTImageIndirect, mLowIndirect.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(vct::kVCTImageSpecular, mLowSpecular.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(vct::kVCTImageGuide, mLowGuide.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    if (!mWork.id()) mWork = gl::createBuffer(2 * vct::kVCTWorkCount * sizeof(GLuint), nullptr, 0);
    glClearNamedBufferData(mWork.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, vct::kVCTBufferWork, mWork.id());
    glDispatchCompute(gl::groupCount(low.x, shared::kGroup2D), gl::groupCount(low.y, shared::kGroup2D), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    for (GLuint u = GLuint(vct::kVCTUnitRadiance); u <= GLuint(vct::kVCTUnitSH + 2); ++u) glBindSampler(u, 0);
    glBindSampler(vct::kVCTUnitSky, 0);
    auto up = ctx.timer.scope("vct.upsample");
    vct::VCTParams u{};
    u.imageSize = glm::ivec4(low, full);
    u.toFull = glm::vec4(toFull, 0.0f, 0.0f);
    u.nearPlane = p.nearPlane;
    u.farPlane = p.farPlane;
    mUpsampleProg.use();
    mBlock.set(u);
    glBindTextureUnit(vct::kVCTUnitLowIndirect, mLowIndirect.id());
    glBindTextureUnit(vct::kVCTUnitLowSpecular, mLowSpecular.id());
    glBindTextureUnit(vct::kVCTUnitLowGuide, mLowGuide.id());
    glBindImageTexture(vct::kVCTImageIndirect, ctx.indirect, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(vct::kVCTImageSpecular, ctx.indirectSpecular, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute(gl::groupCount(full.x, shared::kGroup2D), gl::groupCount(full.y, shared::kGroup2D), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

std::vector<DebugView> VCT::debugViews() const {
    std::vector<DebugView> v;
    int r = mResolution;
    for (size_t k = 0; k < mLevels.size(); ++k) {
        const Level& l = mLevels[k];
        std::string s = mLevels.size() > 1 ? std::to_string(k) : "";
        v.push_back({"vct.radiance" + s, l.radiance.id(), GL_TEXTURE_3D, shared::kViewVoxelColor, r, r, 0, 1, 1});
        v.push_back({"vct.opacity" + s, l.radiance.id(), GL_TEXTURE_3D, shared::kViewVoxelAlpha, r, r, 0, 1, 1});
        v.push_back({"vct.albedo" + s, l.surface.albedo.id(), GL_TEXTURE_3D, shared::kViewVoxelPacked, r, r, 0, 1, 1});
        v.push_back({"vct.normal" + s, l.surface.normal.id(), GL_TEXTURE_3D, shared::kViewVoxelPackedNormal, r, r, 0, 1, 1});
    }
    if (mAnisotropic) {  // +X -X +Y -Y +Z -Z from left to right, from mip 1 (mip 0 is level 0 in every slab)
        DebugView aniso{"vct.anisotropic", mAniso.id(), GL_TEXTURE_3D, shared::kViewVoxelColor, 6 * (r / 2), r / 2, 0, 1, 1};
        aniso.level = 1;
        v.push_back(aniso);
    }
    if (mSHVoxels) {
        DebugView sh{"vct.sh", mSH[0].id(), GL_TEXTURE_3D, shared::kViewSHVolume, r, r, 0, 1, 1};
        sh.extra[0] = mSH[1].id();
        sh.extra[1] = mSH[2].id();
        v.push_back(sh);
    }
    return v;
}

size_t VCT::passMemory(const std::string& pass) const {
    if (pass == "vct.voxelize") return mVoxelBytes;
    if (pass == "vct.upsample") return traceTargetBytes();
    if (pass == "vct.mip") return mRadianceBytes;
    return 0;
}

std::vector<VolumeMemory> VCT::volumeMemory() const {
    std::vector<VolumeMemory> v;
    std::string r = std::to_string(mResolution) + "^3 ";
    std::string mips = ", " + std::to_string(mMipCount) + " mips";
    for (size_t k = 0; k < mLevels.size(); ++k) {
        const Level& l = mLevels[k];
        std::string s = mLevels.size() > 1 ? "[" + std::to_string(k) + "]" : "";
        l.surface.describe(v, mResolution, s);
        if (l.bouncedFront.bytes())
            v.push_back({"bouncedRadiance" + s, r + "R11F_G11F_B10F x 2", l.bouncedFront.bytes() + l.bouncedBack.bytes()});
        v.push_back({"radiance" + s, r + "RGBA16F" + mips, l.radiance.bytes()});
        if (l.sides.bytes()) {
            v.push_back({"sides" + s, r + "R32UI x 6 (normal + count per side)", l.sides.bytes()});
            v.push_back({"sidesRadiance" + s, r + "RGBA16F x 6 (direct, and with the bounced light)", l.sidesRadiance.bytes() + l.sidesBounced.bytes()});
        }
    }
    if (mAnisotropic)
        v.push_back({"anisotropic", r + "RGBA16F x 6 (one atlas)" + mips,
                     mAniso.bytes()});
    if (mFaceSides) {
        v.push_back({"coverage", r + "R16F x 6 (one atlas)" + mips, mAnisoCoverage.bytes()});
        v.push_back({"coverageOctants", r + "RGBA16F x 8 (one atlas)" + mips, mCoverageOctants.bytes()});
        v.push_back({"centroid", r + "RGBA16F" + mips, mCentroid.bytes()});
    }
    if (mSHVoxels) v.push_back({"sh", r + "RGBA16F x 3" + mips, 3 * mSH[0].bytes()});
    if (mLowIndirect.bytes())
        v.push_back({"traceTargets", std::to_string(mLowIndirect.width()) + "x" + std::to_string(mLowIndirect.height()) + " RGBA16F x 2, RGBA32F",
                     traceTargetBytes()});
    return v;
}

std::vector<std::string> VCT::passNames(const FrameSettings& fs) const {
    std::vector<std::string> names{"vct.voxelize", "vct.inject", "vct.mip"};
    if (fs.vct.bounceCount > 1) names.push_back("vct.bounce");
    names.push_back("vct.trace");
    names.push_back("vct.upsample");
    return names;
}

PassReport VCT::report(const FrameSettings&) const {
    PassReport r;
    if (!mWork.id()) return r;
    std::array<GLuint, 2 * vct::kVCTWorkCount> words{};
    glGetNamedBufferSubData(mWork.id(), 0, GLsizeiptr(sizeof(words)), words.data());
    auto count = [&](int i) { return double(uint64_t(words[size_t(2 * i)]) | uint64_t(words[size_t(2 * i + 1)]) << 32); };
    double pixels = count(vct::kVCTWorkPixels), cones = count(vct::kVCTWorkCones);
    double samples = count(vct::kVCTWorkSamples), fetches = count(vct::kVCTWorkFetches);
    auto ratio = [](double a, double b) { return b > 0.0 ? a / b : 0.0; };
    r.numbers = {{"tracedPixels", pixels},
                 {"cones", cones},
                 {"samples", samples},
                 {"textureCalls", fetches},
                 {"samplesPerPixel", ratio(samples, pixels)},
                 {"samplesPerCone", ratio(samples, cones)},
                 {"textureCallsPerSample", ratio(fetches, samples)}};
    return r;
}

std::unique_ptr<Pass> VCTSettings::createPass() { return std::make_unique<VCT>(); }
size_t VCTSettings::estimateBytes(const FrameSettings& fs) { return VCT::estimateBytes(fs); }

size_t VCT::memoryBytes() const { return mVoxelBytes + mRadianceBytes + traceTargetBytes(); }

bool VCT::reloadShaders(std::string& log) {
    mLit = false;  // the edited shaders light the volumes afresh
    bool ok = mSurfaces.reloadShaders(log);
    for (gl::Program* p : {&mResolveProg, &mMipProg, &mUpsampleProg, &mCompactProg, &mBounceProg, &mTraceProg})
        if (!p->reload()) {
            ok = false;
            log += p->log() + "\n";
        }
    return ok;
}

}  // namespace gi
