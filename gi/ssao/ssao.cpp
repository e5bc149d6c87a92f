#include "gi/ssao/ssao.h"

#include "gi/render/gpu_scene.h"
#include "gi/util/error.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <random>

namespace gi {

using namespace shared;

namespace {

// Uniform floats in [0, 1) from mt19937's raw output, whose sequence the standard fixes; the
// std distributions are implementation-defined and would differ between standard libraries.
class Random {
public:
    explicit Random(uint32_t seed) : mEngine(seed) {}
    float uniform() { return float(mEngine() >> 8) * 0x1p-24f; }
    uint32_t below(uint32_t n) { return uint32_t(mEngine() % n); }

private:
    std::mt19937 mEngine;
};

// Both targets are R8: visibility needs no more than 8 bits once blurred.
constexpr GLenum kFormat = GL_R8;

}  // namespace

std::vector<glm::vec3> ssaoKernel(int count, uint32_t seed) {
    GI_ASSERT(count > 0, "ssaoKernel needs at least one sample");
    Random rng(seed);
    std::vector<glm::vec3> kernel;
    kernel.reserve(size_t(count));
    for (int i = 0; i < count; ++i) {
        glm::vec3 d;
        do {
            d = glm::vec3(rng.uniform() * 2.0f - 1.0f, rng.uniform() * 2.0f - 1.0f, rng.uniform());
        } while (glm::dot(d, d) < 1e-8f);
        // Chapman's accelerating scale lerp(0.1, 1, t^2) as the length, with t stratified and
        // jittered: more samples near the pixel, where occluders matter most, yet some reach the
        // full radius. (Chapman multiplies by a further random length, which leaves a mean reach
        // of 0.2 radius and barely darkens creases.)
        float t = (float(i) + rng.uniform()) / float(count);
        d = glm::normalize(d) * (0.1f + 0.9f * t * t);
        kernel.push_back(d);
    }
    return kernel;
}

std::array<glm::vec2, 16> ssaoNoise(uint32_t seed) {
    static_assert(kSSAONoiseSize * kSSAONoiseSize == 16, "the noise tile is 4x4");
    // Second stream of the same seed, so the tile does not repeat the kernel's first numbers.
    Random rng(seed ^ 0x9e3779b9u);
    std::array<float, 16> angles;
    for (int k = 0; k < 16; ++k) angles[k] = (float(k) + rng.uniform()) / 16.0f * glm::two_pi<float>();
    for (uint32_t k = 15; k > 0; --k) std::swap(angles[k], angles[rng.below(k + 1)]);  // Fisher-Yates
    std::array<glm::vec2, 16> noise;
    for (int k = 0; k < 16; ++k) noise[k] = glm::vec2(std::cos(angles[k]), std::sin(angles[k]));
    return noise;
}

SSAO::SSAO()
    : mSSAOProg(gl::fullscreenProgram("ssao", "ssao/ssao.frag")),
      mBlurProg(gl::fullscreenProgram("ssaoBlur", "ssao/ssao_blur.frag")),
      mBlock(kSSAOBlockName, kSSAOBlockBinding) {
    mBlock.requireIn(mSSAOProg);
    mBlock.requireIn(mBlurProg);
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    mEmptyVAO = gl::VertexArray(vao);
    mPointSampler = gl::createSampler({GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE});
}

size_t SSAO::estimateBytes(int width, int height) {
    return 2 * gl::bytesPerTexel(kFormat) * size_t(std::max(width, 0)) * size_t(std::max(height, 0));
}

void SSAO::resize(int width, int height) {
    if (width == mWidth && height == mHeight) return;
    mWidth = width;
    mHeight = height;
    // Grey swizzle: previewers and composites that read .rgb see the AO, not a red image.
    const GLint swizzle[4] = {GL_RED, GL_RED, GL_RED, GL_ONE};
    mRaw = gl::Texture::create2D(kFormat, width, height);
    mAO = gl::Texture::create2D(kFormat, width, height);
    for (GLuint t : {mRaw.id(), mAO.id()}) glTextureParameteriv(t, GL_TEXTURE_SWIZZLE_RGBA, swizzle);
    mRawFBO = gl::createFramebuffer();
    glNamedFramebufferTexture(mRawFBO.id(), GL_COLOR_ATTACHMENT0, mRaw.id(), 0);
    gl::checkFramebuffer(mRawFBO.id(), "SSAO raw framebuffer incomplete");
    mAOFBO = gl::createFramebuffer();
    glNamedFramebufferTexture(mAOFBO.id(), GL_COLOR_ATTACHMENT0, mAO.id(), 0);
    gl::checkFramebuffer(mAOFBO.id(), "SSAO framebuffer incomplete");
}

float ssaoSceneDiagonal(const Bounds& sceneBounds) {
    if (!sceneBounds.valid()) return 1.0f;
    float d = glm::length(sceneBounds.extent());
    return std::isfinite(d) && d > 0.0f ? d : 1.0f;
}

void SSAO::buildKernel(int count) {
    std::vector<glm::vec3> kernel = ssaoKernel(count);
    for (int i = 0; i < count; ++i) mParams.kernel[i] = glm::vec4(kernel[size_t(i)], 0.0f);
    std::array<glm::vec2, 16> noise = ssaoNoise();
    for (int k = 0; k < 16; ++k) mParams.noise[k] = glm::vec4(noise[size_t(k)], 0.0f, 0.0f);
    mKernelCount = count;
}

void SSAO::execute(const SSAOSettings& s, GLuint depthTexture, GLuint normalTexture, int width, int height,
                   const glm::mat4& view, const glm::mat4& proj, float sceneDiagonal, gl::GpuTimer& timer) {
    GI_ASSERT(width > 0 && height > 0, "SSAO::execute needs a non-empty G-buffer");
    GI_ASSERT(std::isfinite(sceneDiagonal) && sceneDiagonal > 0.0f, "SSAO::execute needs the scene's size");
    resize(width, height);
    const float one = 1.0f;
    if (!s.enabled) {
        auto pass = timer.scope("ssao");
        glClearTexImage(mRaw.id(), 0, GL_RED, GL_FLOAT, &one);
        glClearTexImage(mAO.id(), 0, GL_RED, GL_FLOAT, &one);
        return;
    }
    // Settings come validated from presets; the clamp only guards the kernel array's bound.
    int count = std::clamp(s.sampleCount, 1, kSSAOMaxSamples);
    if (count != mKernelCount) buildKernel(count);
    mParams.sampleCount = count;
    // The settings are fractions of the scene's diagonal; the shader works in world units.
    mParams.radius = s.radius * sceneDiagonal;
    mParams.bias = s.bias * sceneDiagonal;
    mParams.blurRadius = std::max(s.blurRadius, 0);
    mParams.strength = std::max(s.strength, 0.0f);
    mParams.view = view;
    mParams.proj = proj;
    mParams.invProj = glm::inverse(proj);
    mBlock.set(mParams);

    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glBindVertexArray(mEmptyVAO.id());
    glBindTextureUnit(kUnitDepth, depthTexture);
    glBindSampler(kUnitDepth, mPointSampler.id());

    {
        auto pass = timer.scope("ssao");
        glBindFramebuffer(GL_FRAMEBUFFER, mRawFBO.id());
        glBindTextureUnit(kUnitNormal, normalTexture);
        glBindSampler(kUnitNormal, mPointSampler.id());
        mSSAOProg.use();
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glBindSampler(kUnitNormal, 0);
    }
    {
        auto pass = timer.scope("ssaoBlur");
        glBindFramebuffer(GL_FRAMEBUFFER, mAOFBO.id());
        glBindTextureUnit(kUnitSource, mRaw.id());
        glBindSampler(kUnitSource, mPointSampler.id());
        mBlurProg.use();
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glBindSampler(kUnitSource, 0);
    }
    glBindSampler(kUnitDepth, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

std::vector<DebugView> SSAO::debugViews() const {
    std::vector<DebugView> v;
    if (!mWidth) return v;
    // AO is a factor, not a colour: shown as stored, without the sRGB curve.
    v.push_back({"ssaoRaw", mRaw.id(), GL_TEXTURE_2D, kViewDisplay, mWidth, mHeight});
    v.push_back({"ssao", mAO.id(), GL_TEXTURE_2D, kViewDisplay, mWidth, mHeight});
    return v;
}

void SSAO::beforeLighting(FrameContext& ctx) {
    execute(ctx.settings.ssao, ctx.depth, ctx.normal, ctx.width, ctx.height, ctx.view, ctx.proj,
            ssaoSceneDiagonal(ctx.scene.bounds()), ctx.timer);
    ctx.ambientOcclusion = aoTexture();
}

std::vector<std::string> SSAO::passNames(const FrameSettings& fs) const {
    if (!fs.ssao.enabled) return {"ssao"};
    return {"ssao", "ssaoBlur"};
}

std::unique_ptr<Pass> SSAOSettings::createPass() { return std::make_unique<SSAO>(); }
size_t SSAOSettings::estimateBytes(const FrameSettings& fs) { return SSAO::estimateBytes(fs.width, fs.height); }

bool SSAO::reloadShaders(std::string& log) {
    bool ok = true;
    for (gl::Program* p : {&mSSAOProg, &mBlurProg}) {
        if (!p->reload()) {
            ok = false;
            log += p->log() + "\n";
        }
    }
    return ok;
}

}  // namespace gi
