#include "gi/render/renderer.h"

#include "render/render_shared.h"
#include "gi/preset/reflect.h"
#include "gi/util/error.h"
#include "gi/util/hash.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace gi {

using namespace shared;

namespace {

gl::Sampler makeSampler(GLenum minFilter, GLenum magFilter, GLenum wrap, bool compare = false) {
    return gl::createSampler({minFilter, magFilter, wrap, 0, 0, compare});
}

// Technique none: the indirect term is the constant ambient radiance (render.ambient), unless an
// effect (the environment) filled it already.
class AmbientPass final : public Pass {
public:
    void indirect(FrameContext& ctx) override {
        if (ctx.indirectWritten) return;
        auto pass = ctx.timer.scope("indirect");
        const glm::vec4 ambient(ctx.settings.render.ambient, 1.0f);
        glClearTexImage(ctx.indirect, 0, GL_RGBA, GL_FLOAT, &ambient[0]);
        ctx.indirectWritten = true;
    }
    size_t passMemory(const std::string&) const override { return 0; }
    size_t memoryBytes() const override { return 0; }
    std::vector<std::string> passNames(const FrameSettings&) const override { return {"indirect"}; }
    bool reloadShaders(std::string&) override { return true; }
};

// The lights as the passes see a change to them: a light added, removed or changed.
uint8_t lightChanges(const FrameSettings& before, const FrameSettings& after) {
    if (before.lights.size() != after.lights.size()) return uint8_t(Cost::Reallocate);
    uint8_t c = 0;
    for (size_t i = 0; i < after.lights.size(); ++i) c |= diff(before.lights[i], after.lights[i]);
    return c;
}

constexpr uint8_t kEverything = 0xff;

constexpr size_t kGBufferBytesPerPixel = 4 + 8 + 4 + 8 + 4;  // albedo, normal, material, emissive, depth
constexpr size_t kTargetBytesPerPixel = 8 + 8 + 8 + 4;        // indirect, indirect specular, HDR, LDR

// The light pass's program for a light (LIGHT_KIND in render/light.frag): 0 a 2D shadow map
// (directional, spot), 1 a cube map (point), 2 an area light.
int lightProgram(LightType type) {
    if (type == LightType::Area) return 2;
    return light::cubeShadow(int(type)) ? 1 : 0;
}

}  // namespace

gl::Program Renderer::lightPassProgram(int kind) {
    static const char* const kNames[kLightKinds] = {"light2D", "lightPoint", "lightArea"};
    GI_ASSERT(kind >= 0 && kind < kLightKinds, "LIGHT_KIND is 0, 1 or 2");
    return gl::fullscreenProgram(kNames[kind], "render/light.frag", {"LIGHT_KIND=" + std::to_string(kind)});
}

Renderer::Renderer()
    : mDepthProg("depthPrepass", {{GL_VERTEX_SHADER, "render/gbuffer.vert"}, {GL_FRAGMENT_SHADER, "render/depth.frag"}}),
      mShadowProg("shadow", {{GL_VERTEX_SHADER, "render/shadow.vert"}, {GL_FRAGMENT_SHADER, "render/shadow.frag"}},
                  {"LINEAR_DEPTH=0"}),
      mShadowOpaqueProg("shadowOpaque", {{GL_VERTEX_SHADER, "render/shadow.vert"}, {GL_FRAGMENT_SHADER, "render/shadow.frag"}},
                        {"LINEAR_DEPTH=0", "ALPHA_CUT=0"}),
      mShadowPointProg("shadowPoint", {{GL_VERTEX_SHADER, "render/shadow.vert"}, {GL_FRAGMENT_SHADER, "render/shadow.frag"}},
                       {"LINEAR_DEPTH=1"}),
      mCompositeProg(gl::fullscreenProgram("composite", "render/composite.frag")),
      mToneProg(gl::fullscreenProgram("tonemap", "render/tonemap.frag")),
      mViewProg(gl::fullscreenProgram("view", "render/view.frag")),
      mLightProgs{lightPassProgram(0), lightPassProgram(1), lightPassProgram(2)},
      mBlock(kRenderBlockName, kRenderBlockBinding),
      mLightBlock(kLightPassBlockName, kLightPassBlockBinding),
      mGBufferProgs("gbuffer", {{GL_VERTEX_SHADER, "render/gbuffer.vert"}, {GL_FRAGMENT_SHADER, "render/gbuffer.frag"}}, {},
                    mMaterialBinding, [this](gl::Program& p) { mBlock.requireIn(p); }),
      mGBufferOpaqueProgs("gbufferOpaque", {{GL_VERTEX_SHADER, "render/gbuffer.vert"}, {GL_FRAGMENT_SHADER, "render/gbuffer.frag"}},
                          {"ALPHA_CUT=0"}, mMaterialBinding, [this](gl::Program& p) { mBlock.requireIn(p); }) {
    for (gl::Program* p : {&mDepthProg, &mShadowProg, &mShadowOpaqueProg, &mShadowPointProg, &mCompositeProg, &mLightProgs[0], &mLightProgs[1], &mLightProgs[2], &mToneProg, &mViewProg})
        mBlock.requireIn(*p);
    for (gl::Program* p : {&mShadowProg, &mShadowOpaqueProg, &mShadowPointProg}) mMaterialBinding.requireIn(*p);
    for (gl::Program& p : mLightProgs) mLightBlock.requireIn(p);
    // Effects live as long as the renderer; the technique is made when it is chosen.
    for (const PassInfo& info : passRegistry())
        if (info.role == PassRole::Effect) mPasses.push_back({&info, info.create()});
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    mEmptyVAO = gl::VertexArray(vao);
    mLinearSampler = makeSampler(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE);
    mPointSampler = makeSampler(GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE);
    mShadowSampler = makeSampler(GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE, true);
    mMaterialSampler = makeSampler(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_REPEAT);
    mLUTSampler = makeSampler(GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE);
    mMipPointSampler = makeSampler(GL_NEAREST_MIPMAP_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE);
    // No anisotropy of its own: sampleMaterial() filters anisotropically (common/material.glsl).
    // Software rasterisers defer draws: serialise the pass timers there (gi/gl/timer.h).
    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    mTimer.setSerialize(renderer && std::string(renderer).find("llvmpipe") != std::string::npos);
    mWhite = gl::Texture::create2D(GL_RGBA8, 1, 1);
    const uint8_t white[4] = {255, 255, 255, 255};
    glTextureSubImage2D(mWhite.id(), 0, 0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, white);
}

Renderer::~Renderer() = default;

void Renderer::setScene(const Scene& scene) { mScene = std::make_unique<GPUScene>(scene); }

namespace {
size_t techniqueBytes(const FrameSettings& fs) {
    const PassInfo* info = findPass(fs.technique);
    return info ? info->estimateBytes(fs) : 0;
}
}  // namespace

size_t Renderer::estimateFrameBytes(const FrameSettings& fs) {
    size_t pixels = size_t(std::max(fs.width, 0)) * size_t(std::max(fs.height, 0));
    size_t bytes = pixels * (kGBufferBytesPerPixel + kTargetBytesPerPixel);
    size_t face = size_t(fs.render.shadowMapSize) * size_t(fs.render.shadowMapSize) * 4;
    for (const auto& l : fs.lights)
        if (l.castShadows) bytes += face * (light::cubeShadow(int(l.type)) ? 6 : 1);
    for (const PassInfo& info : passRegistry())
        if (passActive(info, fs)) bytes += info.estimateBytes(fs);
    return bytes;
}

void Renderer::checkBudget(const FrameSettings& fs, size_t sceneBytes) {
    checkMemoryBudget(fs, sceneBytes);
    // Long work (the environment's prefilter) runs only when its inputs change and is checked
    // again then, so work already done is never refused here by a frame.
    for (const PassInfo& info : passRegistry())
        if (info.checkTime && passActive(info, fs)) info.checkTime(fs);
}

void Renderer::checkMemoryBudget(const FrameSettings& fs, size_t sceneBytes) {
    if (fs.width < 1 || fs.height < 1 || fs.width > 16384 || fs.height > 16384)
        throw Error("image size " + std::to_string(fs.width) + "x" + std::to_string(fs.height) +
                    " is outside 1..16384 per side");
    double mb = double(estimateFrameBytes(fs) + sceneBytes) / (1024.0 * 1024.0);
    if (mb > fs.render.memoryBudgetMB) {
        double technique = double(techniqueBytes(fs)) / (1024.0 * 1024.0);
        char buf[320];
        std::snprintf(buf, sizeof buf,
                      "key 'render.memoryBudgetMB': these settings need %.0f MiB of GPU memory (image %dx%d, "
                      "shadow maps %d^2 for %zu lights, technique %s %.0f MiB, scene %.0f MiB), over the budget of %.0f MiB",
                      mb, fs.width, fs.height, fs.render.shadowMapSize, fs.lights.size(), fs.technique.c_str(), technique,
                      double(sceneBytes) / (1024.0 * 1024.0), double(fs.render.memoryBudgetMB));
        throw Error(buf);
    }
}

void Renderer::resize(int width, int height) {
    if (width == mWidth && height == mHeight) return;
    mWidth = width;
    mHeight = height;
    mAlbedo = gl::Texture::create2D(GL_RGBA8, width, height);
    mNormal = gl::Texture::create2D(GL_RGBA16F, width, height);
    mMaterial = gl::Texture::create2D(GL_RGBA8, width, height);
    mEmissive = gl::Texture::create2D(GL_RGBA16F, width, height);
    // Stencil beside the depth: the G-buffer pass keeps the first surface drawn at a pixel (renderGBuffer).
    mDepth = gl::Texture::create2D(GL_DEPTH32F_STENCIL8, width, height);
    mIndirect = gl::Texture::create2D(GL_RGBA16F, width, height);
    mIndirectSpecular = gl::Texture::create2D(GL_RGBA16F, width, height);
    mHDR = gl::Texture::create2D(GL_RGBA16F, width, height);
    mLDR = gl::Texture::create2D(GL_RGBA8, width, height);

    mGBufferFBO = gl::createFramebuffer();
    glNamedFramebufferTexture(mGBufferFBO.id(), GL_COLOR_ATTACHMENT0, mAlbedo.id(), 0);
    glNamedFramebufferTexture(mGBufferFBO.id(), GL_COLOR_ATTACHMENT1, mNormal.id(), 0);
    glNamedFramebufferTexture(mGBufferFBO.id(), GL_COLOR_ATTACHMENT2, mMaterial.id(), 0);
    glNamedFramebufferTexture(mGBufferFBO.id(), GL_COLOR_ATTACHMENT3, mEmissive.id(), 0);
    glNamedFramebufferTexture(mGBufferFBO.id(), GL_DEPTH_STENCIL_ATTACHMENT, mDepth.id(), 0);
    const GLenum bufs[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};
    glNamedFramebufferDrawBuffers(mGBufferFBO.id(), 4, bufs);
    gl::checkFramebuffer(mGBufferFBO.id(), "G-buffer framebuffer incomplete");

    mHDRFBO = gl::createFramebuffer();
    glNamedFramebufferTexture(mHDRFBO.id(), GL_COLOR_ATTACHMENT0, mHDR.id(), 0);
    gl::checkFramebuffer(mHDRFBO.id(), "HDR framebuffer incomplete");
    mLDRFBO = gl::createFramebuffer();
    glNamedFramebufferTexture(mLDRFBO.id(), GL_COLOR_ATTACHMENT0, mLDR.id(), 0);
    gl::checkFramebuffer(mLDRFBO.id(), "LDR framebuffer incomplete");
}

void Renderer::prepareShadows(const FrameSettings& fs) {
    std::vector<LightType> types;
    std::vector<bool> cast;
    for (const auto& l : fs.lights) {
        types.push_back(l.type);
        cast.push_back(l.castShadows);
    }
    if (types == mShadowTypes && cast == mShadowCast && fs.render.shadowMapSize == mShadowSize) return;
    mShadowTypes = types;
    mShadowCast = cast;
    mShadowSize = fs.render.shadowMapSize;
    mShadowKey = 0;
    mShadows.clear();
    for (const auto& l : fs.lights) {
        ShadowMap sm;
        sm.type = l.type;
        if (l.castShadows) {
            if (light::cubeShadow(int(l.type))) {
                sm.depth = gl::Texture::createCube(GL_DEPTH_COMPONENT32F, mShadowSize);
                for (int face = 0; face < 6; ++face) {
                    gl::Framebuffer fbo = gl::createFramebuffer();
                    glNamedFramebufferTextureLayer(fbo.id(), GL_DEPTH_ATTACHMENT, sm.depth.id(), 0, face);
                    glNamedFramebufferDrawBuffer(fbo.id(), GL_NONE);
                    gl::checkFramebuffer(fbo.id(), "cube shadow framebuffer incomplete");
                    sm.fbos.push_back(std::move(fbo));
                }
            } else {
                sm.depth = gl::Texture::create2D(GL_DEPTH_COMPONENT32F, mShadowSize, mShadowSize);
                gl::Framebuffer fbo = gl::createFramebuffer();
                glNamedFramebufferTexture(fbo.id(), GL_DEPTH_ATTACHMENT, sm.depth.id(), 0);
                glNamedFramebufferDrawBuffer(fbo.id(), GL_NONE);
                gl::checkFramebuffer(fbo.id(), "shadow framebuffer incomplete");
                sm.fbos.push_back(std::move(fbo));
            }
        }
        mShadows.push_back(std::move(sm));
    }
}

void Renderer::selectPasses(const FrameSettings& fs) {
    if (fs.technique == mTechniqueName && !mPasses.empty() && mPasses.back().pass) return;
    std::erase_if(mPasses, [](const ActivePass& p) { return !p.info || p.info->role == PassRole::Technique; });
    if (const PassInfo* info = findPass(fs.technique); info && info->role == PassRole::Technique) {
        // In registry order among the effects, so the stages run in the order the list gives.
        auto at = std::find_if(mPasses.begin(), mPasses.end(), [&](const ActivePass& p) { return p.info > info; });
        mPasses.insert(at, {info, info->create()});
    } else {
        mPasses.push_back({nullptr, std::make_unique<AmbientPass>()});
    }
    mTechniqueName = fs.technique;
}

template <class F>
void Renderer::runStage(FrameContext& ctx, F&& stage) {
    for (ActivePass& p : mPasses) {
        const FrameSettings& fs = ctx.settings;
        if (!p.completed) {
            ctx.changes = kEverything;
        } else {
            const FrameSettings& before = *p.completed;
            ctx.changes = lightChanges(before, fs);
            if (before.width != fs.width || before.height != fs.height) ctx.changes |= uint8_t(Cost::Reallocate);
            if (p.info) ctx.changes |= p.info->changes(before, fs);
        }
        stage(*p.pass, ctx);
        gl::unbindTextureUnits();
    }
}

void Renderer::render(const FrameSettings& fs) {
    GI_ASSERT(mScene, "Renderer::render before setScene");
    checkMemoryBudget(fs, mScene->memoryBytes());
    resize(fs.width, fs.height);
    prepareShadows(fs);
    selectPasses(fs);
    mLightBuffer.upload(fs.lights, mScene->emitters(), mScene->bounds(), mShadowSize);
    mScene->bindTriangleEmitters();
    mCamera = rasterCamera(fs.camera, mScene->bounds().center(), mScene->bounds().radius());

    glm::mat4 view = viewMatrix(mCamera);
    glm::mat4 proj = projectionMatrix(mCamera, float(fs.width) / float(fs.height));
    glm::mat4 viewProj = proj * view;
    // The shadow maps as the passes read them (their matrices are set when they are drawn).
    mShadowViews.assign(fs.lights.size(), ShadowMapView{});
    FrameContext ctx{fs,
                     *mScene,
                     view,
                     proj,
                     viewProj,
                     glm::inverse(viewProj),
                     mAlbedo.id(),
                     mNormal.id(),
                     mMaterial.id(),
                     mEmissive.id(),
                     mDepth.id(),
                     mIndirect.id(),
                     mIndirectSpecular.id(),
                     mHDR.id(),
                     mShadowViews,
                     mShadowSize,
                     mWidth,
                     mHeight,
                     mTimer,
                     mProgress};
    ctx.ambientOcclusion = mWhite.id();

    gl::unbindTextureUnits();
    mTimer.beginFrame();
    runStage(ctx, [](Pass& p, FrameContext& c) { p.prepare(c); });
    // What the shadow maps depend on: the scene, the map size and each light's packed entry
    // (position, direction, cone, shadow projection) with its type and castShadows.
    Hasher shadowKey;
    shadowKey.value(mScene->id());
    shadowKey.value(mShadowSize);
    for (size_t i = 0; i < fs.lights.size(); ++i) {
        shadowKey.value(fs.lights[i].type);
        shadowKey.value(fs.lights[i].castShadows);
        shadowKey.value(mLightBuffer[i]);
    }
    renderShadows(fs, shadowKey.result() | 1);
    for (size_t i = 0; i < fs.lights.size(); ++i)
        if (fs.lights[i].castShadows)
            mShadowViews[i] = {mShadows[i].depth.id(), light::cubeShadow(int(fs.lights[i].type)), mLightBuffer[i].shadowViewProj,
                               mLightBuffer[i].shadow.x};
    renderGBuffer(viewProj, fs.render);
    const glm::vec4 zero(0.0f);
    glClearTexImage(mIndirectSpecular.id(), 0, GL_RGBA, GL_FLOAT, &zero[0]);
    runStage(ctx, [](Pass& p, FrameContext& c) { p.indirect(c); });
    runStage(ctx, [](Pass& p, FrameContext& c) { p.beforeLighting(c); });
    renderLighting(fs, viewProj, ctx);
    runStage(ctx, [](Pass& p, FrameContext& c) { p.afterLighting(c); });
    renderToneMap(fs);
    mTimer.endFrame();
    mTimer.resolve(false);
    for (ActivePass& p : mPasses) p.completed = fs;
}

void Renderer::renderShadows(const FrameSettings& fs, uint64_t key) {
    auto pass = mTimer.scope("shadows");
    // The maps already hold this key's shadows (the editor's steady state): nothing to redraw.
    if (fs.render.keepStaticWork && key == mShadowKey) {
        mShadowDrawn = {};
        return;
    }
    mShadowKey = key;
    mScene->resetDrawn();
    ++mShadowDraws;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glViewport(0, 0, mShadowSize, mShadowSize);
    mMaterialBinding.begin(mMaterialSampler.id());

    // `params` holds the face's projection; the material block is uploaded per draw. With
    // `opaque`, Opaque materials first with that program, then the rest with `cut`.
    auto drawScene = [&](RenderParams& params, gl::Program* opaque, gl::Program& cut) {
        // Per draw: the draw's first triangle (an area light's map leaves its own surface out).
        auto bind = [&](const Material& m, int, int firstTriangle) {
            params.firstTriangle = firstTriangle;
            mBlock.set(params);
            mMaterialBinding.bind(*mScene, m);
        };
        // params.viewProj stays put while the draws change only firstTriangle.
        const glm::mat4* cull = fs.render.cullClusters ? &params.viewProj : nullptr;
        if (!opaque) {
            cut.use();
            mScene->draw(bind, cull);
            return;
        }
        opaque->use();
        mScene->drawIf([](const Material& m) { return m.alphaMode == AlphaMode::Opaque; }, bind, cull);
        cut.use();
        mScene->drawIf([](const Material& m) { return m.alphaMode != AlphaMode::Opaque; }, bind, cull);
    };

    for (size_t i = 0; i < fs.lights.size(); ++i) {
        const LightSettings& l = fs.lights[i];
        ShadowMap& sm = mShadows[i];
        if (!l.castShadows) continue;
        // The projection the light buffer holds, so the passes that read the map agree with it.
        const light::GPULight& g = mLightBuffer[i];
        const float far = g.shadow.x;
        if (light::cubeShadow(int(l.type))) {
            RenderParams params{};
            params.lightPos = glm::vec4(l.position, 1.0f);
            params.shadowFar = far;
            // An area light's own surface, through whose middle the map looks, casts no shadow.
            params.skipEmitter = l.type == LightType::Area ? l.emitter : -1;
            for (int face = 0; face < kCubeFaceCount; ++face) {
                glBindFramebuffer(GL_FRAMEBUFFER, sm.fbos[face].id());
                glClear(GL_DEPTH_BUFFER_BIT);
                params.viewProj = cubeFaceViewProj(l.position, face, far);
                drawScene(params, nullptr, mShadowPointProg);
            }
        } else {
            glBindFramebuffer(GL_FRAMEBUFFER, sm.fbos[0].id());
            glClear(GL_DEPTH_BUFFER_BIT);
            RenderParams params{};
            params.skipEmitter = -1;
            params.viewProj = g.shadowViewProj;
            drawScene(params, &mShadowOpaqueProg, mShadowProg);
        }
    }
    mMaterialBinding.end();
    mShadowDrawn = mScene->resetDrawn();
}

void Renderer::renderGBuffer(const glm::mat4& viewProj, const RenderSettings& settings) {
    const glm::mat4* cull = settings.cullClusters ? &viewProj : nullptr;
    auto pass = mTimer.scope("gbuffer");
    glBindFramebuffer(GL_FRAMEBUFFER, mGBufferFBO.id());
    glViewport(0, 0, mWidth, mHeight);
    const float zero[4] = {0, 0, 0, 0};
    for (int i = 0; i < 4; ++i) glClearNamedFramebufferfv(mGBufferFBO.id(), GL_COLOR, i, zero);
    // Clears obey the write masks: the lighting pass leaves depth writes off, and until the
    // shadow maps were kept between frames the shadow pass turned them back on before this.
    glDepthMask(GL_TRUE);
    glStencilMask(0xff);
    glClearNamedFramebufferfi(mGBufferFBO.id(), GL_DEPTH_STENCIL, 0, 1.0f, 0);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    RenderParams params{};
    params.viewProj = viewProj;
    mScene->resetDrawn();
    mMaterialBinding.begin(mMaterialSampler.id());
    // Per draw: the draw's first triangle (to find each triangle's emitter) and the material.
    // Opaque materials first, with the program that tests depth before shading (gbuffer.frag).
    MaterialPrograms* programs = &mGBufferOpaqueProgs;
    auto bind = [&](const Material& m, int, int firstTriangle) {
        programs->of(m, settings.materialPrograms).use();
        params.firstTriangle = firstTriangle;
        mBlock.set(params);
        mMaterialBinding.bind(*mScene, m);
    };
    auto opaque = [](const Material& m) { return m.alphaMode == AlphaMode::Opaque; };
    // Depth first (depth.frag), then the G-buffer where the depth is equal: each pixel's
    // nearest opaque surface is shaded once.
    mDepthProg.use();
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    mBlock.set(params);
    mScene->drawIf(opaque, [](const Material&, int) {}, cull);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
    // Where two surfaces lie at the same depth (coincident faces), the first drawn wins, as it
    // did with a single GL_LESS pass: the stencil counts the writes and admits only the first.
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_EQUAL, 0, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
    mScene->drawIf(opaque, bind, cull);
    glDisable(GL_STENCIL_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    programs = &mGBufferProgs;
    mScene->drawIf([](const Material& m) { return m.alphaMode != AlphaMode::Opaque; }, bind, cull);
    mMaterialBinding.end();
    mGBufferDrawn = mScene->resetDrawn();
}

void Renderer::renderLighting(const FrameSettings& fs, const glm::mat4& viewProj, const FrameContext& ctx) {
    auto pass = mTimer.scope("lighting");
    glBindFramebuffer(GL_FRAMEBUFFER, mHDRFBO.id());
    glViewport(0, 0, mWidth, mHeight);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    glBindVertexArray(mEmptyVAO.id());

    const GLuint gbuffer[5] = {mAlbedo.id(), mNormal.id(), mMaterial.id(), mEmissive.id(), mDepth.id()};
    for (int i = 0; i < 5; ++i) {
        glBindTextureUnit(kUnitAlbedo + i, gbuffer[i]);
        glBindSampler(kUnitAlbedo + i, mPointSampler.id());
    }
    glBindTextureUnit(kUnitIndirect, mIndirect.id());
    glBindSampler(kUnitIndirect, mPointSampler.id());
    glBindTextureUnit(kUnitAO, ctx.ambientOcclusion);
    glBindSampler(kUnitAO, mPointSampler.id());
    glBindTextureUnit(kUnitIndirectSpecular, mIndirectSpecular.id());
    glBindSampler(kUnitIndirectSpecular, mPointSampler.id());
    glBindTextureUnit(kUnitBRDFLUT, ctx.brdfLUT);
    glBindSampler(kUnitBRDFLUT, mLUTSampler.id());
    RenderParams params{};
    params.invViewProj = glm::inverse(viewProj);
    params.cameraPos = glm::vec4(fs.camera.eye, 1.0f);

    glDisable(GL_BLEND);
    mCompositeProg.use();
    mBlock.set(params);
    glDrawArrays(GL_TRIANGLES, 0, 3);

    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    params.specular = fs.render.specular ? 1 : 0;
    params.pcfRadius = fs.render.pcfRadius;
    params.shadowBias = fs.render.shadowBias;
    params.shadowSize = float(mShadowSize);
    glBindSampler(kUnitShadow2D, mShadowSampler.id());
    glBindSampler(kUnitShadowCube, mShadowSampler.id());
    glBindSampler(kUnitShadowCubeDepth, mPointSampler.id());
    // Units of the other shadow type must still hold a texture of the sampler's type.
    glBindTextureUnit(kUnitShadow2D, 0);
    glBindTextureUnit(kUnitShadowCube, 0);
    glBindTextureUnit(kUnitShadowCubeDepth, 0);
    mBlock.set(params);  // the same for every light: each light's own fields are in LightBlock
    for (size_t i = 0; i < fs.lights.size(); ++i) {
        const LightSettings& l = fs.lights[i];
        const ShadowMap& sm = mShadows[i];
        mLightBlock.set(mLightBuffer.withTriangles(i));
        const bool cube = light::cubeShadow(int(l.type));
        mLightProgs[lightProgram(l.type)].use();
        if (l.castShadows) glBindTextureUnit(cube ? kUnitShadowCube : kUnitShadow2D, sm.depth.id());
        // The area lights' soft shadows search the same map's distances for blockers.
        if (l.castShadows && cube) glBindTextureUnit(kUnitShadowCubeDepth, sm.depth.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        if (l.castShadows) glBindTextureUnit(cube ? kUnitShadowCube : kUnitShadow2D, 0);
        if (l.castShadows && cube) glBindTextureUnit(kUnitShadowCubeDepth, 0);
    }
    glBindSampler(kUnitShadowCubeDepth, 0);
    glDisable(GL_BLEND);
    for (int u = kUnitAlbedo; u <= kUnitIndirectSpecular; ++u) glBindSampler(u, 0);
}

void Renderer::renderToneMap(const FrameSettings& fs) {
    auto pass = mTimer.scope("tonemap");
    glBindFramebuffer(GL_FRAMEBUFFER, mLDRFBO.id());
    glViewport(0, 0, mWidth, mHeight);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glBindVertexArray(mEmptyVAO.id());
    mToneProg.use();
    RenderParams params{};
    params.exposureScale = std::exp2(fs.toneMap.exposure);
    params.toneOp = int(fs.toneMap.op);
    mBlock.set(params);
    glBindTextureUnit(kUnitSource, mHDR.id());
    glBindSampler(kUnitSource, mPointSampler.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindSampler(kUnitSource, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

bool Renderer::reloadShaders(std::string& log) {
    bool ok = true;
    log.clear();
    for (ActivePass& p : mPasses)
        if (!p.pass->reloadShaders(log)) ok = false;
    for (gl::Program* p : {&mDepthProg, &mShadowProg, &mShadowOpaqueProg, &mShadowPointProg, &mCompositeProg, &mLightProgs[0], &mLightProgs[1], &mLightProgs[2], &mToneProg, &mViewProg}) {
        if (!p->reload()) {
            ok = false;
            log += p->log() + "\n";
        }
    }
    for (MaterialPrograms* p : {&mGBufferProgs, &mGBufferOpaqueProgs})
        if (!p->reload(log)) ok = false;
    return ok;
}

std::vector<DebugView> Renderer::debugViews() const {
    std::vector<DebugView> v;
    if (!mWidth) return v;
    float range = mScene ? glm::length(mScene->bounds().extent()) + glm::length(mCamera.eye - mScene->bounds().center()) : mCamera.far;
    auto add = [&](const char* name, const gl::Texture& t, int mode) {
        v.push_back({name, t.id(), t.target(), mode, t.width(), t.height(), mCamera.near, mCamera.far, range});
    };
    add("final", mLDR, kViewDisplay);
    add("hdr", mHDR, kViewColor);
    add("albedo", mAlbedo, kViewColor);
    add("normal", mNormal, kViewNormal);
    add("depth", mDepth, kViewLinearDepth);
    add("roughnessMetallic", mMaterial, kViewDisplay);
    add("emissive", mEmissive, kViewColor);
    add("indirect", mIndirect, kViewColor);
    add("indirectSpecular", mIndirectSpecular, kViewColor);
    for (const ActivePass& p : mPasses)
        for (DebugView& pv : p.pass->debugViews()) v.push_back(std::move(pv));
    for (size_t i = 0; i < mShadows.size(); ++i) {
        if (!mShadows[i].depth) continue;
        std::string name = "shadow" + std::to_string(i);
        bool cube = light::cubeShadow(int(mShadows[i].type));
        // Spot maps hold perspective depth: linearise it so the picture shows shapes, not white.
        const ShadowMap& sm = mShadows[i];
        int mode = cube ? kViewCubeCross : sm.type == LightType::Spot ? kViewLinearDepth : kViewRawDepth;
        const float far = mLightBuffer[i].shadow.x;
        v.push_back({name, sm.depth.id(), sm.depth.target(), mode, cube ? mShadowSize * 4 / 3 : mShadowSize, mShadowSize,
                     far * light::kShadowNearRatio, far, far});
    }
    return v;
}

bool Renderer::pickSurface(glm::ivec2 px, SurfacePick& out) const {
    GLuint depth = mDepth.id(), normal = mNormal.id(), material = mMaterial.id();
    glm::ivec2 size(mWidth, mHeight);
    if (!depth || size.x <= 0 || size.y <= 0) return false;
    px = glm::clamp(px, glm::ivec2(0), size - 1);
    float d = 1.0f, n[4] = {}, m[4] = {};
    glGetTextureSubImage(depth, 0, px.x, px.y, 0, 1, 1, 1, GL_DEPTH_COMPONENT, GL_FLOAT, sizeof d, &d);
    glGetTextureSubImage(normal, 0, px.x, px.y, 0, 1, 1, 1, GL_RGBA, GL_FLOAT, sizeof n, n);
    glGetTextureSubImage(material, 0, px.x, px.y, 0, 1, 1, 1, GL_RGBA, GL_FLOAT, sizeof m, m);
    glm::vec3 nn(n[0], n[1], n[2]);
    if (d >= 1.0f || glm::length(nn) < 1e-3f) return false;
    glm::mat4 inv = glm::inverse(projectionMatrix(mCamera, float(size.x) / float(size.y)) * viewMatrix(mCamera));
    glm::vec2 uv = (glm::vec2(px) + 0.5f) / glm::vec2(size);
    glm::vec4 w = inv * glm::vec4(uv * 2.0f - 1.0f, d * 2.0f - 1.0f, 1.0f);
    out.position = glm::vec3(w) / w.w;
    out.normal = glm::normalize(nn);
    out.roughness = m[0];
    return true;
}

std::vector<Previewer> Renderer::previewers(const FrameSettings& fs) const {
    std::vector<Previewer> out;
    for (const ActivePass& p : mPasses)
        for (Previewer& pv : p.pass->previewers(fs)) out.push_back(std::move(pv));
    return out;
}

PreviewContext Renderer::previewContext(const FrameSettings& fs, std::optional<glm::ivec2> focus) const {
    PreviewContext ctx{fs};
    ctx.sceneBounds = mScene ? mScene->bounds() : Bounds{};
    ctx.views = debugViews();
    ctx.width = mWidth;
    ctx.height = mHeight;
    if (mWidth > 0) ctx.viewProj = projectionMatrix(mCamera, float(mWidth) / float(mHeight)) * viewMatrix(mCamera);
    SurfacePick pick;
    if (focus && pickSurface(*focus, pick)) ctx.focus = pick;
    ctx.renderView = [this](const DebugView& v, int w, int h) { return renderViewImage(v, w, h); };
    return ctx;
}

std::vector<PassStats> Renderer::passStats() const {
    size_t shadowBytes = 0;
    for (auto& s : mShadows) shadowBytes += s.depth.bytes();
    size_t gbuffer = mAlbedo.bytes() + mNormal.bytes() + mMaterial.bytes() + mEmissive.bytes() + mDepth.bytes();
    std::vector<PassStats> out;
    for (const auto& r : mTimer.results()) {
        size_t bytes = 0;
        if (r.name == "shadows") bytes = shadowBytes;
        else if (r.name == "gbuffer") bytes = gbuffer;
        else if (r.name == "indirect") bytes = mIndirect.bytes() + mIndirectSpecular.bytes();
        else if (r.name == "lighting") bytes = mHDR.bytes();
        else if (r.name == "tonemap") bytes = mLDR.bytes();
        else
            for (const ActivePass& p : mPasses) bytes += p.pass->passMemory(r.name);
        PassStats st{r.name, r.gpuMs, bytes};
        if (r.name == "shadows" || r.name == "gbuffer") {
            const GPUScene::Drawn& d = r.name == "shadows" ? mShadowDrawn : mGBufferDrawn;
            st.countsDraws = true;
            st.draws = d.draws;
            st.triangles = d.triangles;
        }
        out.push_back(st);
    }
    return out;
}

size_t Renderer::memoryBytes() const {
    size_t total = mScene ? mScene->memoryBytes() : 0;
    for (const ActivePass& p : mPasses) total += p.pass->memoryBytes();
    for (auto& s : mShadows) total += s.depth.bytes();
    for (const gl::Texture* t : {&mAlbedo, &mNormal, &mMaterial, &mEmissive, &mDepth, &mIndirect, &mIndirectSpecular, &mHDR, &mLDR})
        total += t->bytes();
    return total;
}

const Pass* Renderer::technique() const {
    for (const ActivePass& p : mPasses)
        if (!p.info || p.info->role == PassRole::Technique) return p.pass.get();
    return nullptr;
}

std::vector<std::pair<std::string, PassReport>> Renderer::passReports(const FrameSettings& fs) const {
    std::vector<std::pair<std::string, PassReport>> out;
    for (const ActivePass& p : mPasses)
        if (p.info)
            if (PassReport r = p.pass->report(fs); !r.empty()) out.emplace_back(std::string(p.info->name), std::move(r));
    return out;
}

std::vector<VolumeMemory> Renderer::volumeMemory() const {
    std::vector<VolumeMemory> out;
    for (const ActivePass& p : mPasses)
        for (VolumeMemory& v : p.pass->volumeMemory()) out.push_back(std::move(v));
    return out;
}

std::vector<uint8_t> Renderer::readLDR() const {
    std::vector<uint8_t> px(size_t(mWidth) * mHeight * 4);
    glGetTextureImage(mLDR.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(px.size()), px.data());
    return px;
}

std::vector<float> Renderer::readHDR() const {
    std::vector<float> px(size_t(mWidth) * mHeight * 4);
    glGetTextureImage(mHDR.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(px.size() * sizeof(float)), px.data());
    return px;
}

std::vector<float> Renderer::readIndirectRadiance() const {
    size_t n = size_t(mWidth) * mHeight * 4;
    std::vector<float> albedo(n), material(n), indirect(n);
    GLsizei bytes = GLsizei(n * sizeof(float));
    glGetTextureImage(mAlbedo.id(), 0, GL_RGBA, GL_FLOAT, bytes, albedo.data());
    glGetTextureImage(mMaterial.id(), 0, GL_RGBA, GL_FLOAT, bytes, material.data());
    glGetTextureImage(mIndirect.id(), 0, GL_RGBA, GL_FLOAT, bytes, indirect.data());
    for (size_t i = 0; i < n; i += 4) {
        float diffuse = 1.0f - material[i + 1];
        for (int c = 0; c < 3; ++c) indirect[i + c] *= albedo[i + c] * diffuse;
    }
    return indirect;
}

void Renderer::drawView(const DebugView& view, const ViewParams& p) const {
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glBindVertexArray(mEmptyVAO.id());
    mViewProg.use();
    RenderParams params{};
    params.mode = view.mode;
    params.channelMask = p.channelMask;
    params.exposureScale = std::exp2(p.exposure);
    params.depthNear = view.near;
    params.depthFar = view.far;
    params.range = view.range;
    params.zoom = std::max(p.zoom, 1e-3f);
    params.pan = p.pan;
    params.level = p.level + float(view.level);
    params.axis = p.axis;
    params.slice = p.slice;
    params.shComponent = p.shComponent;
    params.direction = glm::vec4(glm::length(p.direction) > 0.0f ? glm::normalize(p.direction) : glm::vec3(0, 1, 0), 0.0f);
    params.falseColour = p.falseColour ? 1 : 0;
    params.scale = view.scale;
    GLuint units[3] = {GLuint(kUnitSource), 0, 0};
    int count = 1;
    GLuint sampler = mPointSampler.id();
    GLint depthBits = 0;
    if (view.target == GL_TEXTURE_CUBE_MAP) {
        units[0] = kUnitSourceCube;
        // Cube views show one mip (`level`), nearest texels: the point sampler has no mips.
        sampler = mMipPointSampler.id();
        if (view.texture) glGetTextureLevelParameteriv(view.texture, 0, GL_TEXTURE_DEPTH_SIZE, &depthBits);
    } else if (view.target == GL_TEXTURE_3D && (view.mode == kViewVoxelPacked || view.mode == kViewVoxelPackedNormal)) {
        units[0] = kUnitSourceU3D;
    } else if (view.target == GL_TEXTURE_3D) {
        units[0] = kUnitSource3D;
        units[1] = kUnitSource3D + 1;
        units[2] = kUnitSource3D + 2;
        count = view.extra[0] ? 3 : 1;
    }
    params.depthCube = depthBits > 0 ? 1 : 0;
    mBlock.set(params);
    const GLuint textures[3] = {view.texture, view.extra[0], view.extra[1]};
    for (int i = 0; i < count; ++i) {
        glBindTextureUnit(units[i], textures[i]);
        glBindSampler(units[i], sampler);
    }
    glDrawArrays(GL_TRIANGLES, 0, 3);
    for (int i = 0; i < count; ++i) {
        glBindTextureUnit(units[i], 0);
        glBindSampler(units[i], 0);
    }
}

std::vector<uint8_t> Renderer::renderViewImage(const DebugView& view, int width, int height) const {
    gl::Texture target = gl::Texture::create2D(GL_RGBA8, width, height);
    gl::Framebuffer fbo = gl::createFramebuffer();
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, target.id(), 0);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glViewport(0, 0, width, height);
    drawView(view, ViewParams{});
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    std::vector<uint8_t> px(size_t(width) * height * 4);
    glGetTextureImage(target.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(px.size()), px.data());
    return px;
}

}  // namespace gi
