#include "gi/render/renderer.h"

#include "gi/lpv/lpv.h"
#include "gi/vct/vct.h"

#include "common/shared.h"
#include "gi/util/error.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace gi {

using namespace shared;

// ---------------------------------------------------------------------------------------------

GPUScene::GPUScene(const Scene& scene) : mDraws(scene.draws), mMaterials(scene.materials), mBounds(scene.bounds) {
    static uint64_t sCount = 0;
    mId = ++sCount;
    mVertices = gl::createBuffer(scene.vertices.size() * sizeof(Vertex), scene.vertices.data());
    mIndices = gl::createBuffer(scene.indices.size() * sizeof(uint32_t), scene.indices.data());
    mBytes = scene.vertices.size() * sizeof(Vertex) + scene.indices.size() * sizeof(uint32_t);
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    mVAO = gl::VertexArray(vao);
    glVertexArrayVertexBuffer(vao, 0, mVertices.id(), 0, sizeof(Vertex));
    glVertexArrayElementBuffer(vao, mIndices.id());
    const GLuint offsets[3] = {offsetof(Vertex, position), offsetof(Vertex, normal), offsetof(Vertex, uv)};
    const GLint sizes[3] = {3, 3, 2};
    for (GLuint a = 0; a < 3; ++a) {
        glEnableVertexArrayAttrib(vao, a);
        glVertexArrayAttribFormat(vao, a, sizes[a], GL_FLOAT, GL_FALSE, offsets[a]);
        glVertexArrayAttribBinding(vao, a, 0);
    }
    for (const Texture& t : scene.textures) {
        int levels = 1 + int(std::floor(std::log2(std::max(t.width, t.height))));
        gl::Texture tex = gl::Texture::create2D(GL_SRGB8_ALPHA8, t.width, t.height, levels);
        glTextureSubImage2D(tex.id(), 0, 0, 0, t.width, t.height, GL_RGBA, GL_UNSIGNED_BYTE, t.rgba.data());
        glGenerateTextureMipmap(tex.id());
        mBytes += tex.bytes();
        mTextures.push_back(std::move(tex));
    }
}

size_t GPUScene::estimateBytes(const Scene& scene) {
    size_t bytes = scene.vertices.size() * sizeof(Vertex) + scene.indices.size() * sizeof(uint32_t);
    for (const Texture& t : scene.textures) bytes += t.rgba.size() * 4 / 3;  // the mip chain adds a third
    return bytes;
}

// ---------------------------------------------------------------------------------------------

namespace {

gl::Sampler makeSampler(GLenum minFilter, GLenum magFilter, GLenum wrap, bool compare = false) {
    return gl::createSampler({minFilter, magFilter, wrap, 0, 0, compare});
}

constexpr size_t kGBufferBytesPerPixel = 4 + 8 + 4 + 8 + 4;  // albedo, normal, material, emissive, depth
constexpr size_t kTargetBytesPerPixel = 8 + 8 + 8 + 4;        // indirect, indirect specular, HDR, LDR

}  // namespace

Renderer::Renderer()
    : mGBufferProg("gbuffer", {{GL_VERTEX_SHADER, "render/gbuffer.vert"}, {GL_FRAGMENT_SHADER, "render/gbuffer.frag"}}),
      mShadowProg("shadow", {{GL_VERTEX_SHADER, "render/shadow.vert"}, {GL_FRAGMENT_SHADER, "render/shadow.frag"}},
                  {"LINEAR_DEPTH=0"}),
      mShadowPointProg("shadowPoint", {{GL_VERTEX_SHADER, "render/shadow.vert"}, {GL_FRAGMENT_SHADER, "render/shadow.frag"}},
                       {"LINEAR_DEPTH=1"}),
      mCompositeProg(gl::fullscreenProgram("composite", "render/composite.frag")),
      mLightProg(gl::fullscreenProgram("light", "render/light.frag")),
      mToneProg(gl::fullscreenProgram("tonemap", "render/tonemap.frag")),
      mViewProg(gl::fullscreenProgram("view", "render/view.frag")) {
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    mEmptyVAO = gl::VertexArray(vao);
    mLinearSampler = makeSampler(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE);
    mPointSampler = makeSampler(GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE);
    mShadowSampler = makeSampler(GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE, true);
    mMaterialSampler = makeSampler(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_REPEAT);
    mLUTSampler = makeSampler(GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE);
    mMipPointSampler = makeSampler(GL_NEAREST_MIPMAP_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE);
    glSamplerParameterf(mMaterialSampler.id(), GL_TEXTURE_MAX_ANISOTROPY, 4.0f);
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
    if (fs.technique == TechniqueKind::LPV) return LPV::estimateBytes(fs);
    if (fs.technique == TechniqueKind::VCT) return VCT::estimateBytes(fs);
    return 0;
}
}  // namespace

size_t Renderer::estimateFrameBytes(const FrameSettings& fs) {
    size_t pixels = size_t(std::max(fs.width, 0)) * size_t(std::max(fs.height, 0));
    size_t bytes = pixels * (kGBufferBytesPerPixel + kTargetBytesPerPixel);
    size_t face = size_t(fs.render.shadowMapSize) * size_t(fs.render.shadowMapSize) * 4;
    for (const auto& l : fs.lights)
        if (l.castShadows) bytes += face * (l.type == LightType::Point ? 6 : 1);
    bytes += techniqueBytes(fs);
    bytes += SSAO::estimateBytes(fs.width, fs.height);
    bytes += Volumetric::estimateBytes(fs);
    bytes += Environment::estimateBytes(fs.environment);
    return bytes;
}

void Renderer::checkBudget(const FrameSettings& fs, size_t sceneBytes) {
    checkMemoryBudget(fs, sceneBytes);
    // The prefilter runs only when the environment's maps change; Environment::prepare checks
    // again then, so a chain already built is never refused here by a frame.
    if (fs.environment.enabled) Environment::checkTimeBudget(fs.environment, fs.render.timeBudgetSeconds);
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
                      mb, fs.width, fs.height, fs.render.shadowMapSize, fs.lights.size(), enumName(fs.technique), technique,
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
    mDepth = gl::Texture::create2D(GL_DEPTH_COMPONENT32F, width, height);
    mIndirect = gl::Texture::create2D(GL_RGBA16F, width, height);
    mIndirectSpecular = gl::Texture::create2D(GL_RGBA16F, width, height);
    mHDR = gl::Texture::create2D(GL_RGBA16F, width, height);
    mLDR = gl::Texture::create2D(GL_RGBA8, width, height);

    mGBufferFBO = gl::createFramebuffer();
    glNamedFramebufferTexture(mGBufferFBO.id(), GL_COLOR_ATTACHMENT0, mAlbedo.id(), 0);
    glNamedFramebufferTexture(mGBufferFBO.id(), GL_COLOR_ATTACHMENT1, mNormal.id(), 0);
    glNamedFramebufferTexture(mGBufferFBO.id(), GL_COLOR_ATTACHMENT2, mMaterial.id(), 0);
    glNamedFramebufferTexture(mGBufferFBO.id(), GL_COLOR_ATTACHMENT3, mEmissive.id(), 0);
    glNamedFramebufferTexture(mGBufferFBO.id(), GL_DEPTH_ATTACHMENT, mDepth.id(), 0);
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
    mShadows.clear();
    for (const auto& l : fs.lights) {
        ShadowMap sm;
        sm.type = l.type;
        if (l.castShadows) {
            if (l.type == LightType::Point) {
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

void Renderer::render(const FrameSettings& fs) {
    GI_ASSERT(mScene, "Renderer::render before setScene");
    checkMemoryBudget(fs, mScene->memoryBytes());
    resize(fs.width, fs.height);
    prepareShadows(fs);
    mLightBuffer.upload(fs.lights, mScene->bounds(), mShadowSize);
    mCamera = fs.camera;

    if (fs.technique != mTechniqueKind || (fs.technique != TechniqueKind::None && !mTechnique)) {
        mTechnique.reset();
        if (fs.technique == TechniqueKind::LPV) mTechnique = std::make_unique<LPV>();
        if (fs.technique == TechniqueKind::VCT) mTechnique = std::make_unique<VCT>();
        mTechniqueKind = fs.technique;
    }
    glm::mat4 view = viewMatrix(fs.camera);
    glm::mat4 proj = projectionMatrix(fs.camera, float(fs.width) / float(fs.height));
    glm::mat4 viewProj = proj * view;

    mTimer.beginFrame();
    mEnvironment.prepare(fs.environment, mTimer, fs.render, mProgress);
    renderShadows(fs);
    renderGBuffer(viewProj);
    renderIndirect(fs, view, proj);
    mSSAO.execute(fs.ssao, mDepth.id(), mNormal.id(), mWidth, mHeight, view, proj, mTimer);
    renderLighting(fs, viewProj);
    if (fs.environment.enabled && fs.environment.skybox && mEnvironment.ready())
        mEnvironment.sky(fs.environment, mDepth.id(), mHDR.id(), mWidth, mHeight, glm::inverse(viewProj), fs.camera.eye, mTimer);
    mVolumetric.execute({fs, mScene->bounds(), mShadowViews, mDepth.id(), mHDR.id(), mWidth, mHeight, glm::inverse(viewProj),
                         float(mShadowSize)},
                        mTimer);
    renderToneMap(fs);
    mTimer.endFrame();
    mTimer.resolve(false);
}

void Renderer::renderShadows(const FrameSettings& fs) {
    auto pass = mTimer.scope("shadows");
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glViewport(0, 0, mShadowSize, mShadowSize);
    glBindSampler(kUnitBaseColor, mMaterialSampler.id());

    auto drawScene = [&](const gl::Program& prog) {
        mScene->draw([&](const Material& m, int) {
            bool mask = m.alphaMode == AlphaMode::Mask;
            prog.set("uAlphaCutoff", mask ? m.alphaCutoff : -1.0f);
            prog.set("uBaseAlpha", m.baseColor.a);
            prog.set("uHasTexture", mask && m.baseColorTexture >= 0 ? 1 : 0);
            glBindTextureUnit(kUnitBaseColor, m.baseColorTexture >= 0 ? mScene->texture(m.baseColorTexture) : mWhite.id());
        });
    };

    for (size_t i = 0; i < fs.lights.size(); ++i) {
        const LightSettings& l = fs.lights[i];
        ShadowMap& sm = mShadows[i];
        if (!l.castShadows) continue;
        // The projection the light buffer holds, so the passes that read the map agree with it.
        sm.viewProj = mLightBuffer[i].shadowViewProj;
        sm.far = mLightBuffer[i].shadow.x;
        if (l.type == LightType::Point) {
            mShadowPointProg.use();
            mShadowPointProg.set("uLightPos", l.position);
            mShadowPointProg.set("uFar", sm.far);
            // Cube face orientations as GL defines them (+X, -X, +Y, -Y, +Z, -Z).
            const glm::vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
            const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
            glm::mat4 proj = glm::perspective(glm::radians(90.0f), 1.0f, sm.far * light::kShadowNearRatio, sm.far);
            for (int face = 0; face < 6; ++face) {
                glBindFramebuffer(GL_FRAMEBUFFER, sm.fbos[face].id());
                glClear(GL_DEPTH_BUFFER_BIT);
                mShadowPointProg.set("uLightViewProj", proj * glm::lookAt(l.position, l.position + dirs[face], ups[face]));
                drawScene(mShadowPointProg);
            }
        } else {
            mShadowProg.use();
            glBindFramebuffer(GL_FRAMEBUFFER, sm.fbos[0].id());
            glClear(GL_DEPTH_BUFFER_BIT);
            mShadowProg.set("uLightViewProj", sm.viewProj);
            drawScene(mShadowProg);
        }
    }
    glBindSampler(kUnitBaseColor, 0);
}

void Renderer::renderGBuffer(const glm::mat4& viewProj) {
    auto pass = mTimer.scope("gbuffer");
    glBindFramebuffer(GL_FRAMEBUFFER, mGBufferFBO.id());
    glViewport(0, 0, mWidth, mHeight);
    const float zero[4] = {0, 0, 0, 0};
    for (int i = 0; i < 4; ++i) glClearNamedFramebufferfv(mGBufferFBO.id(), GL_COLOR, i, zero);
    const float one = 1.0f;
    glClearNamedFramebufferfv(mGBufferFBO.id(), GL_DEPTH, 0, &one);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    mGBufferProg.use();
    mGBufferProg.set("uViewProj", viewProj);
    glBindSampler(kUnitBaseColor, mMaterialSampler.id());
    mScene->draw([&](const Material& m, int) {
        mGBufferProg.set("uBaseColor", m.baseColor);
        mGBufferProg.set("uHasTexture", m.baseColorTexture >= 0 ? 1 : 0);
        mGBufferProg.set("uAlphaCutoff", m.alphaMode == AlphaMode::Mask ? m.alphaCutoff : -1.0f);
        mGBufferProg.set("uRoughness", m.roughness);
        mGBufferProg.set("uMetallic", m.metallic);
        mGBufferProg.set("uEmissive", m.emissive);
        glBindTextureUnit(kUnitBaseColor, m.baseColorTexture >= 0 ? mScene->texture(m.baseColorTexture) : mWhite.id());
    });
    glBindSampler(kUnitBaseColor, 0);
}

void Renderer::renderIndirect(const FrameSettings& fs, const glm::mat4& view, const glm::mat4& proj) {
    const glm::vec4 zero(0.0f);
    glClearTexImage(mIndirectSpecular.id(), 0, GL_RGBA, GL_FLOAT, &zero[0]);
    // The shadow maps as the technique and the volumetric pass read them.
    mShadowViews.assign(fs.lights.size(), ShadowMapView{});
    for (size_t i = 0; i < fs.lights.size(); ++i)
        if (fs.lights[i].castShadows)
            mShadowViews[i] = {mShadows[i].depth.id(), fs.lights[i].type == LightType::Point, mShadows[i].viewProj, mShadows[i].far};
    if (mTechnique) {
        FrameContext ctx{fs,         *mScene,      view,           proj,          proj * view,
                         glm::inverse(proj * view), mAlbedo.id(), mNormal.id(), mMaterial.id(), mDepth.id(),
                         mIndirect.id(),            mIndirectSpecular.id(),     mShadowViews,  mWidth,
                         mHeight,                   mTimer};
        mTechnique->execute(ctx);
        return;
    }
    if (fs.environment.enabled && mEnvironment.ready()) {
        // Technique none with an environment: it gives the indirect diffuse and specular terms.
        mEnvironment.shade(fs.environment, mNormal.id(), mMaterial.id(), mDepth.id(), mIndirect.id(), mIndirectSpecular.id(), mWidth,
                           mHeight, glm::inverse(proj * view), fs.camera.eye, mTimer);
        return;
    }
    auto pass = mTimer.scope("indirect");
    // Technique none: the indirect term is the constant ambient radiance.
    const glm::vec4 ambient(fs.render.ambient, 1.0f);
    glClearTexImage(mIndirect.id(), 0, GL_RGBA, GL_FLOAT, &ambient[0]);
}

void Renderer::renderLighting(const FrameSettings& fs, const glm::mat4& viewProj) {
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
    glBindTextureUnit(kUnitAO, mSSAO.aoTexture());
    glBindSampler(kUnitAO, mPointSampler.id());
    glBindTextureUnit(kUnitIndirectSpecular, mIndirectSpecular.id());
    glBindSampler(kUnitIndirectSpecular, mPointSampler.id());
    glBindTextureUnit(kUnitBRDFLUT, mEnvironment.brdfLUT());
    glBindSampler(kUnitBRDFLUT, mLUTSampler.id());
    glm::mat4 inv = glm::inverse(viewProj);

    glDisable(GL_BLEND);
    mCompositeProg.use();
    mCompositeProg.set("uInvViewProj", inv);
    mCompositeProg.set("uCameraPos", fs.camera.eye);
    glDrawArrays(GL_TRIANGLES, 0, 3);

    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    mLightProg.use();
    mLightProg.set("uInvViewProj", inv);
    mLightProg.set("uCameraPos", fs.camera.eye);
    mLightProg.set("uSpecular", fs.render.specular ? 1 : 0);
    mLightProg.set("uPCFRadius", fs.render.pcfRadius);
    mLightProg.set("uShadowBias", fs.render.shadowBias);
    mLightProg.set("uShadowSize", float(mShadowSize));
    glBindSampler(kUnitShadow2D, mShadowSampler.id());
    glBindSampler(kUnitShadowCube, mShadowSampler.id());
    // Units of the other shadow type must still hold a texture of the sampler's type.
    glBindTextureUnit(kUnitShadow2D, 0);
    glBindTextureUnit(kUnitShadowCube, 0);
    for (size_t i = 0; i < fs.lights.size(); ++i) {
        const LightSettings& l = fs.lights[i];
        const ShadowMap& sm = mShadows[i];
        mLightProg.set("uLightIndex", int(i));
        if (l.castShadows) glBindTextureUnit(l.type == LightType::Point ? kUnitShadowCube : kUnitShadow2D, sm.depth.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        if (l.castShadows) glBindTextureUnit(l.type == LightType::Point ? kUnitShadowCube : kUnitShadow2D, 0);
    }
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
    mToneProg.set("uExposureScale", std::exp2(fs.toneMap.exposure));
    mToneProg.set("uToneOp", int(fs.toneMap.op));
    glBindTextureUnit(kUnitSource, mHDR.id());
    glBindSampler(kUnitSource, mPointSampler.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindSampler(kUnitSource, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

bool Renderer::reloadShaders(std::string& log) {
    bool ok = true;
    log.clear();
    if (mTechnique && !mTechnique->reloadShaders(log)) ok = false;
    if (!mSSAO.reloadShaders(log)) ok = false;
    if (!mVolumetric.reloadShaders(log)) ok = false;
    if (!mEnvironment.reloadShaders(log)) ok = false;
    for (gl::Program* p : {&mGBufferProg, &mShadowProg, &mShadowPointProg, &mCompositeProg, &mLightProg, &mToneProg, &mViewProg}) {
        if (!p->reload()) {
            ok = false;
            log += p->log() + "\n";
        }
    }
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
    if (mTechnique)
        for (DebugView& tv : mTechnique->debugViews()) v.push_back(tv);
    for (DebugView& sv : mSSAO.debugViews()) v.push_back(sv);
    for (DebugView& vv : mVolumetric.debugViews()) v.push_back(vv);
    for (DebugView& ev : mEnvironment.debugViews()) v.push_back(ev);
    for (size_t i = 0; i < mShadows.size(); ++i) {
        if (!mShadows[i].depth) continue;
        std::string name = "shadow" + std::to_string(i);
        bool cube = mShadows[i].type == LightType::Point;
        // Spot maps hold perspective depth: linearise it so the picture shows shapes, not white.
        const ShadowMap& sm = mShadows[i];
        int mode = cube ? kViewCubeCross : sm.type == LightType::Spot ? kViewLinearDepth : kViewRawDepth;
        v.push_back({name, sm.depth.id(), sm.depth.target(), mode, cube ? mShadowSize * 4 / 3 : mShadowSize, mShadowSize,
                     sm.far * 1e-3f, sm.far, sm.far});
    }
    return v;
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
        else if (r.name == "ssao") bytes = mSSAO.memoryBytes();  // both AO targets; the blur pass holds none
        else if (r.name == "volumetric.march") bytes = mVolumetric.memoryBytes();  // both buffers
        else if (r.name == "environment.prefilter") bytes = mEnvironment.memoryBytes();
        else if (mTechnique) bytes = mTechnique->passMemory(r.name);
        out.push_back({r.name, r.gpuMs, bytes});
    }
    return out;
}

size_t Renderer::memoryBytes() const {
    size_t total = mScene ? mScene->memoryBytes() : 0;
    if (mTechnique) total += mTechnique->memoryBytes();
    total += mSSAO.memoryBytes();
    total += mVolumetric.memoryBytes();
    total += mEnvironment.memoryBytes();
    for (auto& s : mShadows) total += s.depth.bytes();
    for (const gl::Texture* t : {&mAlbedo, &mNormal, &mMaterial, &mEmissive, &mDepth, &mIndirect, &mIndirectSpecular, &mHDR, &mLDR})
        total += t->bytes();
    return total;
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
    mViewProg.set("uMode", view.mode);
    mViewProg.set("uChannelMask", p.channelMask);
    mViewProg.set("uExposureScale", std::exp2(p.exposure));
    mViewProg.set("uNear", view.near);
    mViewProg.set("uFar", view.far);
    mViewProg.set("uRange", view.range);
    mViewProg.set("uZoom", std::max(p.zoom, 1e-3f));
    mViewProg.set("uPan", p.pan);
    mViewProg.set("uLevel", p.level + float(view.level));
    mViewProg.set("uAxis", p.axis);
    mViewProg.set("uSlice", p.slice);
    mViewProg.set("uSHComponent", p.shComponent);
    mViewProg.set("uDirection", glm::length(p.direction) > 0.0f ? glm::normalize(p.direction) : glm::vec3(0, 1, 0));
    mViewProg.set("uFalseColour", p.falseColour ? 1 : 0);
    mViewProg.set("uScale", view.scale);
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
    mViewProg.set("uDepthCube", depthBits > 0 ? 1 : 0);
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
