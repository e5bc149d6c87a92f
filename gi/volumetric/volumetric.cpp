#include "gi/volumetric/volumetric.h"

#include "common/shared.h"
#include "gi/render/gpu_scene.h"
#include "gi/render/lights.h"
#include "gi/util/error.h"
#include "gi/volumetric/phase.h"
#include "gi/volumetric/phase_plot.h"

#include <algorithm>
#include <cmath>

namespace gi {

using namespace shared;

namespace {

gl::Sampler makeSampler(GLenum filter, bool compare) { return gl::createSampler({filter, filter, GL_CLAMP_TO_EDGE, 0, 0, compare}); }

glm::ivec2 marchSize(const FrameSettings& fs) {
    float s = fs.volumetric.resolutionScale;
    return {std::max(1, int(std::lround(float(fs.width) * s))), std::max(1, int(std::lround(float(fs.height) * s)))};
}


// The fields of medium.glsl, which the march and the composite read.
void setMedium(VolumeParams& p, const Medium& m) {
    p.boxMin = glm::vec4(m.box.min, 1.0f);
    p.boxMax = glm::vec4(m.box.max, 1.0f);
    p.sigmaS = m.sigmaS;
    p.sigmaT = m.sigmaT;
}

}  // namespace

Volumetric::Volumetric()
    : mMarchProg("volumetric.march", {{GL_COMPUTE_SHADER, "volumetric/march.comp"}}),
      mBlurProg("volumetric.blur", {{GL_COMPUTE_SHADER, "volumetric/blur.comp"}}),
      mCompositeProg("volumetric.composite", {{GL_COMPUTE_SHADER, "volumetric/composite.comp"}}),
      mBlock(kVolumeBlockName, kVolumeBlockBinding) {
    for (gl::Program* p : {&mMarchProg, &mBlurProg, &mCompositeProg}) mBlock.requireIn(*p);
    mLinear = makeSampler(GL_LINEAR, false);
    mPoint = makeSampler(GL_NEAREST, false);
    mShadowSampler = makeSampler(GL_LINEAR, true);
}

size_t Volumetric::estimateBytes(const FrameSettings& fs) {
    if (!fs.volumetric.enabled) return 0;
    glm::ivec2 s = marchSize(fs);
    return size_t(s.x) * size_t(s.y) * 8 * 2;
}

void Volumetric::execute(const Inputs& in, gl::GpuTimer& timer) {
    const FrameSettings& fs = in.settings;
    const VolumetricSettings& s = fs.volumetric;
    Medium medium = makeMedium(s, in.sceneBounds);
    mActive = medium.active;
    if (!mActive) {
        mMarch = gl::Texture();
        mBlurred = gl::Texture();
        mWidth = mHeight = 0;
        return;
    }
    glm::ivec2 size = marchSize(fs);
    if (size.x != mWidth || size.y != mHeight) {
        mWidth = size.x;
        mHeight = size.y;
        mMarch = gl::Texture::create2D(GL_RGBA16F, mWidth, mHeight);
        mBlurred = gl::Texture::create2D(GL_RGBA16F, mWidth, mHeight);
    }
    {
        auto pass = timer.scope("volumetric.march");
        mMarchProg.use();
        glBindTextureUnit(kUnitDepth, in.depth);
        glBindSampler(kUnitDepth, mPoint.id());
        glBindImageTexture(kVolumeImageTarget, mMarch.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
        for (int u = 0; u < kVolumeMaxLights; ++u) {
            glBindSampler(GLuint(kVolumeUnitShadow2D + u), mShadowSampler.id());
            glBindSampler(GLuint(kVolumeUnitShadowCube + u), mShadowSampler.id());
        }
        size_t lightCount = fs.lights.size();
        for (size_t first = 0; first == 0 || first < lightCount; first += kVolumeMaxLights) {
            int n = int(std::min<size_t>(kVolumeMaxLights, lightCount - std::min(first, lightCount)));
            VolumeParams p{};
            setMedium(p, medium);
            p.invViewProj = in.invViewProj;
            p.eye = glm::vec4(fs.camera.eye, 1.0f);
            p.lowWidth = mWidth;
            p.lowHeight = mHeight;
            p.fullWidth = in.width;
            p.fullHeight = in.height;
            p.toFullX = float(in.width) / float(mWidth);
            p.toFullY = float(in.height) / float(mHeight);
            p.samples = s.samples;
            p.jitter = s.jitter ? 1 : 0;
            p.pcf = s.pcf ? 1 : 0;
            p.phase = int(medium.phase.function);
            p.g = medium.phase.g;
            p.k = medium.phase.k;
            p.intensity = medium.intensity;
            p.shadowSize = in.shadowSize;
            p.lightFirst = int(first);
            p.lightCount = n;
            p.accumulate = first > 0 ? 1 : 0;
            mBlock.set(p);
            for (int i = 0; i < kVolumeMaxLights; ++i) {
                // Units of the unused type still need a texture of the sampler's type: 0 is fine.
                glBindTextureUnit(GLuint(kVolumeUnitShadow2D + i), 0);
                glBindTextureUnit(GLuint(kVolumeUnitShadowCube + i), 0);
            }
            for (int i = 0; i < n; ++i)
                bindBatchShadowMap(i, in.shadows[first + size_t(i)], kVolumeUnitShadow2D, kVolumeUnitShadowCube);
            glDispatchCompute(gl::groupCount(mWidth, shared::kGroup2D), gl::groupCount(mHeight, shared::kGroup2D), 1);
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        }
        for (int u = 0; u < kVolumeMaxLights; ++u) {
            glBindSampler(GLuint(kVolumeUnitShadow2D + u), 0);
            glBindSampler(GLuint(kVolumeUnitShadowCube + u), 0);
        }
    }
    GLuint source = mMarch.id();
    if (s.blur != VolumeBlur::None) {
        auto pass = timer.scope("volumetric.blur");
        mBlurProg.use();
        VolumeParams p{};
        p.lowWidth = mWidth;
        p.lowHeight = mHeight;
        p.depthAware = s.blur == VolumeBlur::DepthAware ? 1 : 0;
        mBlock.set(p);
        glBindTextureUnit(kVolumeUnitSource, mMarch.id());
        glBindSampler(kVolumeUnitSource, mPoint.id());
        glBindImageTexture(kVolumeImageTarget, mBlurred.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glDispatchCompute(gl::groupCount(mWidth, shared::kGroup2D), gl::groupCount(mHeight, shared::kGroup2D), 1);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        source = mBlurred.id();
    } else {
        glCopyImageSubData(mMarch.id(), GL_TEXTURE_2D, 0, 0, 0, 0, mBlurred.id(), GL_TEXTURE_2D, 0, 0, 0, 0, mWidth, mHeight, 1);
        source = mBlurred.id();
    }
    {
        auto pass = timer.scope("volumetric.composite");
        mCompositeProg.use();
        VolumeParams p{};
        setMedium(p, medium);
        p.invViewProj = in.invViewProj;
        p.eye = glm::vec4(fs.camera.eye, 1.0f);
        p.fullWidth = in.width;
        p.fullHeight = in.height;
        p.lowWidth = mWidth;
        p.lowHeight = mHeight;
        p.depthAware = s.blur == VolumeBlur::DepthAware ? 1 : 0;
        p.attenuateScene = medium.attenuateScene ? 1 : 0;
        mBlock.set(p);
        glBindTextureUnit(kUnitDepth, in.depth);
        glBindSampler(kUnitDepth, mPoint.id());
        glBindTextureUnit(kVolumeUnitSource, source);
        glBindSampler(kVolumeUnitSource, mLinear.id());
        glBindImageTexture(kVolumeImageTarget, in.hdr, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
        glDispatchCompute(gl::groupCount(in.width, shared::kGroup2D), gl::groupCount(in.height, shared::kGroup2D), 1);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
        glBindSampler(kVolumeUnitSource, 0);
        glBindSampler(kUnitDepth, 0);
    }
}

void Volumetric::afterLighting(FrameContext& ctx) {
    execute({ctx.settings, ctx.scene.bounds(), ctx.shadows, ctx.depth, ctx.hdr, ctx.width, ctx.height, ctx.invViewProj,
             float(ctx.shadowSize)},
            ctx.timer);
}

std::vector<std::string> Volumetric::passNames(const FrameSettings& fs) const {
    const VolumetricSettings& s = fs.volumetric;
    if (!s.enabled || s.density <= 0.0f) return {};
    std::vector<std::string> names{"volumetric.march"};
    if (s.blur != VolumeBlur::None) names.push_back("volumetric.blur");
    names.push_back("volumetric.composite");
    return names;
}

std::vector<Previewer> Volumetric::previewers(const FrameSettings& fs) const {
    if (!fs.volumetric.enabled) return {};
    auto plot = [](const PreviewContext& ctx) {
        const int size = 256;
        return PreviewImage{size, size, phasePlotImage(phaseParams(ctx.settings.volumetric), size, false)};
    };
    return {{"volumetric.phase", "The phase function as a polar plot, light travelling along +x", plot, {}}};
}

std::unique_ptr<Pass> VolumetricSettings::createPass() { return std::make_unique<Volumetric>(); }
size_t VolumetricSettings::estimateBytes(const FrameSettings& fs) { return Volumetric::estimateBytes(fs); }

std::vector<DebugView> Volumetric::debugViews() const {
    std::vector<DebugView> v;
    if (!mActive) return v;
    v.push_back({"volumetricRaw", mMarch.id(), GL_TEXTURE_2D, kViewColor, mWidth, mHeight});
    v.push_back({"volumetric", mBlurred.id(), GL_TEXTURE_2D, kViewColor, mWidth, mHeight});
    return v;
}

bool Volumetric::reloadShaders(std::string& log) {
    bool ok = true;
    for (gl::Program* p : {&mMarchProg, &mBlurProg, &mCompositeProg})
        if (!p->reload()) {
            ok = false;
            log += p->log() + "\n";
        }
    return ok;
}

}  // namespace gi
