#include "gi/vct/surface_voxels.h"

#include "common/shared.h"
#include "gi/render/gpu_scene.h"
#include "gi/render/lights.h"

#include <algorithm>

namespace gi {

SurfaceVolumes SurfaceVolumes::create(int r) {
    SurfaceVolumes v;
    v.albedo = gl::Texture::create3D(GL_R32UI, r, r, r);
    v.normal = gl::Texture::create3D(GL_R32UI, r, r, r);
    v.position = gl::Texture::create3D(GL_R32UI, r, r, r);
    v.exitFront = gl::Texture::create3D(kExitFormat, r, r, r);
    v.exitBack = gl::Texture::create3D(kExitFormat, r, r, r);
    return v;
}

size_t SurfaceVolumes::bytes() const {
    return albedo.bytes() + normal.bytes() + position.bytes() + exitFront.bytes() + exitBack.bytes();
}

void SurfaceVolumes::bindVoxels(GLenum access) const {
    glBindImageTexture(vct::kVCTImageAlbedo, albedo.id(), 0, GL_TRUE, 0, access, GL_R32UI);
    glBindImageTexture(vct::kVCTImageNormal, normal.id(), 0, GL_TRUE, 0, access, GL_R32UI);
    glBindImageTexture(vct::kVCTImagePosition, position.id(), 0, GL_TRUE, 0, access, GL_R32UI);
}

void SurfaceVolumes::describe(std::vector<VolumeMemory>& out, int resolution, const std::string& suffix) const {
    std::string r = std::to_string(resolution) + "^3 ";
    out.push_back({"albedo" + suffix, r + "R32UI (RGBA8 + count)", albedo.bytes()});
    out.push_back({"normal" + suffix, r + "R32UI (RGBA8 + count)", normal.bytes()});
    out.push_back({"position" + suffix, r + "R32UI (RGBA8 + count)", position.bytes()});
    out.push_back({"exitRadiance" + suffix, r + "R11F_G11F_B10F x 2 (front, back)", exitFront.bytes() + exitBack.bytes()});
}

SurfaceVoxelizer::SurfaceVoxelizer()
    : mClearProg("vct.clear", {{GL_COMPUTE_SHADER, "vct/clear.comp"}}),
      mInjectProg("vct.inject", {{GL_COMPUTE_SHADER, "vct/inject.comp"}}),
      mBlock(vct::kVCTBlockName, vct::kVCTBlockBinding),
      mVoxelizePrograms("vct.voxelize",
                        {{GL_VERTEX_SHADER, "vct/voxelize.vert"},
                         {GL_GEOMETRY_SHADER, "vct/voxelize.geom"},
                         {GL_FRAGMENT_SHADER, "vct/voxelize.frag"}},
                        {}, mMaterialBinding, [this](gl::Program& p) { mBlock.requireIn(p); }) {
    for (gl::Program* p : {&mClearProg, &mInjectProg}) mBlock.requireIn(*p);
    mEmptyFBO = gl::createFramebuffer();
    mRepeat = gl::createSampler({GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_REPEAT});
    mShadowSampler = gl::createSampler({GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE});
    glSamplerParameteri(mShadowSampler.id(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glSamplerParameteri(mShadowSampler.id(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
}

void SurfaceVoxelizer::voxelize(const FrameContext& ctx, const vct::VCTParams& grid, const SurfaceVolumes& v,
                                glm::ivec3 clipMin, glm::ivec3 clipMax, bool slicing, GLuint sides) {
    const int res = grid.resolution;
    vct::VCTParams p = grid;
    p.clipMin = glm::ivec4(clipMin, 0);
    p.clipMax = glm::ivec4(clipMax, 0);
    p.sides = sides != 0 ? 1 : 0;
    if (sides) glBindImageTexture(vct::kVCTImageSides, sides, 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
    mClearProg.use();
    mBlock.set(p);
    v.bindVoxels(GL_WRITE_ONLY);
    gl::dispatch3D(res);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

    if (mFramebufferSize != res) {
        glNamedFramebufferParameteri(mEmptyFBO.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, res);
        glNamedFramebufferParameteri(mEmptyFBO.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, res);
        mFramebufferSize = res;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, mEmptyFBO.id());
    glViewport(0, 0, res, res);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    v.bindVoxels(GL_READ_WRITE);
    mMaterialBinding.begin(mRepeat.id());
    for (int axis = slicing ? 1 : 0; axis <= (slicing ? 3 : 0); ++axis) {
        p.sliceAxis = axis;
        mBlock.set(p);
        ctx.scene.draw([&](const Material& m, int) {
            mVoxelizePrograms.of(m, ctx.settings.render.materialPrograms).use();
            mMaterialBinding.bind(ctx.scene, m);
        });
    }
    mMaterialBinding.end();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDepthMask(GL_TRUE);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    ++mVoxelizationCount;
}

void SurfaceVoxelizer::inject(const FrameContext& ctx, const vct::VCTParams& grid, const SurfaceVolumes& v, GLuint sides,
                              GLuint sidesRadiance) {
    const auto& lights = ctx.settings.lights;
    mInjectProg.use();
    v.bindVoxels(GL_READ_ONLY);
    glBindImageTexture(vct::kVCTImageExitFront, v.exitFront.id(), 0, GL_TRUE, 0, GL_READ_WRITE, SurfaceVolumes::kExitFormat);
    glBindImageTexture(vct::kVCTImageExitBack, v.exitBack.id(), 0, GL_TRUE, 0, GL_READ_WRITE, SurfaceVolumes::kExitFormat);
    if (sides) {
        glBindImageTexture(vct::kVCTImageSides, sides, 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
        glBindImageTexture(vct::kVCTImageSidesRadiance, sidesRadiance, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA16F);
    }
    size_t first = 0;
    do {
        int count = int(std::min(lights.size() - first, size_t(vct::kVCTMaxLights)));
        vct::VCTParams p = grid;
        p.lightFirst = int(first);
        p.lightCount = count;
        p.accumulate = first > 0 ? 1 : 0;
        p.sides = sides != 0 ? 1 : 0;
        mBlock.set(p);
        for (int i = 0; i < count; ++i) {
            const ShadowMapView& sm = ctx.shadows[first + size_t(i)];
            bindBatchShadowMap(i, sm, vct::kVCTUnitShadow2D, vct::kVCTUnitShadowCube);
            if (sm.depth) glBindSampler(GLuint((sm.cube ? vct::kVCTUnitShadowCube : vct::kVCTUnitShadow2D) + i), mShadowSampler.id());
        }
        gl::dispatch3D(grid.resolution);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        first += size_t(count);
    } while (first < lights.size());
    for (int u = 0; u < 2 * vct::kVCTMaxLights; ++u) glBindSampler(GLuint(vct::kVCTUnitShadow2D + u), 0);
}

bool SurfaceVoxelizer::reloadShaders(std::string& log) {
    bool ok = true;
    for (gl::Program* p : {&mClearProg, &mInjectProg})
        if (!p->reload()) {
            ok = false;
            log += p->log() + "\n";
        }
    if (!mVoxelizePrograms.reload(log)) ok = false;
    return ok;
}

}  // namespace gi
