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

namespace {

constexpr int kMaxLights = 4;          // march.comp's kVolumeMaxLights
constexpr GLuint kUnitShadow2D = 9;    // march.comp's bindings
constexpr GLuint kUnitShadowCube = 13;

gl::Sampler makeSampler(GLenum filter, bool compare) { return gl::createSampler({filter, filter, GL_CLAMP_TO_EDGE, 0, 0, compare}); }

glm::ivec2 marchSize(const FrameSettings& fs) {
    float s = fs.volumetric.resolutionScale;
    return {std::max(1, int(std::lround(float(fs.width) * s))), std::max(1, int(std::lround(float(fs.height) * s)))};
}

GLuint groups(int n) { return GLuint((n + 7) / 8); }

void setMedium(const gl::Program& p, const Medium& m) {
    p.set("uBoxMin", m.box.min);
    p.set("uBoxMax", m.box.max);
    p.set("uSigmaS", m.sigmaS);
    p.set("uSigmaT", m.sigmaT);
}

}  // namespace

Volumetric::Volumetric()
    : mMarchProg("volumetric.march", {{GL_COMPUTE_SHADER, "volumetric/march.comp"}}),
      mBlurProg("volumetric.blur", {{GL_COMPUTE_SHADER, "volumetric/blur.comp"}}),
      mCompositeProg("volumetric.composite", {{GL_COMPUTE_SHADER, "volumetric/composite.comp"}}) {
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
        setMedium(mMarchProg, medium);
        mMarchProg.set("uInvViewProj", in.invViewProj);
        mMarchProg.set("uEye", fs.camera.eye);
        mMarchProg.set("uSize", glm::ivec2(mWidth, mHeight));
        mMarchProg.set("uFullSize", glm::ivec2(in.width, in.height));
        mMarchProg.set("uToFull", glm::vec2(float(in.width) / float(mWidth), float(in.height) / float(mHeight)));
        mMarchProg.set("uSamples", s.samples);
        mMarchProg.set("uJitter", s.jitter ? 1 : 0);
        mMarchProg.set("uPCF", s.pcf ? 1 : 0);
        mMarchProg.set("uPhase", int(medium.phase.function));
        mMarchProg.set("uG", medium.phase.g);
        mMarchProg.set("uK", medium.phase.k);
        mMarchProg.set("uIntensity", medium.intensity);
        mMarchProg.set("uShadowSize", in.shadowSize);
        glBindTextureUnit(shared::kUnitDepth, in.depth);
        glBindSampler(shared::kUnitDepth, mPoint.id());
        glBindImageTexture(0, mMarch.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
        for (int u = 0; u < kMaxLights; ++u) {
            glBindSampler(kUnitShadow2D + GLuint(u), mShadowSampler.id());
            glBindSampler(kUnitShadowCube + GLuint(u), mShadowSampler.id());
        }
        size_t lightCount = fs.lights.size();
        for (size_t first = 0; first == 0 || first < lightCount; first += kMaxLights) {
            int n = int(std::min<size_t>(kMaxLights, lightCount - std::min(first, lightCount)));
            mMarchProg.set("uLightFirst", int(first));
            mMarchProg.set("uLightCount", n);
            mMarchProg.set("uAccumulate", first > 0 ? 1 : 0);
            for (int i = 0; i < kMaxLights; ++i) {
                // Units of the unused type still need a texture of the sampler's type: 0 is fine.
                glBindTextureUnit(kUnitShadow2D + GLuint(i), 0);
                glBindTextureUnit(kUnitShadowCube + GLuint(i), 0);
            }
            for (int i = 0; i < n; ++i) bindBatchShadowMap(i, in.shadows[first + size_t(i)], kUnitShadow2D, kUnitShadowCube);
            glDispatchCompute(groups(mWidth), groups(mHeight), 1);
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        }
        for (int u = 0; u < kMaxLights; ++u) {
            glBindSampler(kUnitShadow2D + GLuint(u), 0);
            glBindSampler(kUnitShadowCube + GLuint(u), 0);
        }
    }
    GLuint source = mMarch.id();
    if (s.blur != VolumeBlur::None) {
        auto pass = timer.scope("volumetric.blur");
        mBlurProg.use();
        mBlurProg.set("uSize", glm::ivec2(mWidth, mHeight));
        mBlurProg.set("uDepthAware", s.blur == VolumeBlur::DepthAware ? 1 : 0);
        glBindTextureUnit(0, mMarch.id());
        glBindSampler(0, mPoint.id());
        glBindImageTexture(0, mBlurred.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glDispatchCompute(groups(mWidth), groups(mHeight), 1);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        source = mBlurred.id();
    } else {
        glCopyImageSubData(mMarch.id(), GL_TEXTURE_2D, 0, 0, 0, 0, mBlurred.id(), GL_TEXTURE_2D, 0, 0, 0, 0, mWidth, mHeight, 1);
        source = mBlurred.id();
    }
    {
        auto pass = timer.scope("volumetric.composite");
        mCompositeProg.use();
        setMedium(mCompositeProg, medium);
        mCompositeProg.set("uInvViewProj", in.invViewProj);
        mCompositeProg.set("uEye", fs.camera.eye);
        mCompositeProg.set("uFullSize", glm::ivec2(in.width, in.height));
        mCompositeProg.set("uLowSize", glm::ivec2(mWidth, mHeight));
        mCompositeProg.set("uDepthAware", s.blur == VolumeBlur::DepthAware ? 1 : 0);
        mCompositeProg.set("uAttenuateScene", medium.attenuateScene ? 1 : 0);
        glBindTextureUnit(shared::kUnitDepth, in.depth);
        glBindSampler(shared::kUnitDepth, mPoint.id());
        glBindTextureUnit(0, source);
        glBindSampler(0, mLinear.id());
        glBindImageTexture(0, in.hdr, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
        glDispatchCompute(groups(in.width), groups(in.height), 1);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
        glBindSampler(0, 0);
        glBindSampler(shared::kUnitDepth, 0);
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
    v.push_back({"volumetricRaw", mMarch.id(), GL_TEXTURE_2D, shared::kViewColor, mWidth, mHeight});
    v.push_back({"volumetric", mBlurred.id(), GL_TEXTURE_2D, shared::kViewColor, mWidth, mHeight});
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
