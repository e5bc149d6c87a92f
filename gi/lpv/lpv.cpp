#include "gi/lpv/lpv.h"

#include "common/light.h"
#include "common/shared.h"
#include "gi/gl/buffer_texture.h"
#include "gi/gl/extensions.h"
#include "gi/render/gpu_scene.h"
#include "gi/render/lights.h"
#include "gi/scene/camera.h"
#include "gi/util/error.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

namespace gi {

using namespace shared;

namespace {

constexpr int kCoefficients = 12;  // 4 SH coefficients x RGB per cell
constexpr size_t kRSMBytesPerTexel = 8 + 8 + 16 + 4 + 4;  // flux, normal, position, depth, albedo

size_t cells(int res) { return size_t(res) * res * res; }
size_t corners(int res) { return size_t(res + 1) * (res + 1) * (res + 1); }

gl::Buffer zeroBuffer(size_t bytes) {
    return gl::createBuffer(bytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
}

void clearBuffer(const gl::Buffer& b) { glClearNamedBufferData(b.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr); }


// Lights seen through a cube RSM: six 90-degree faces around the light, one cube shared by every
// cascade. A kind that emits from a point, whatever its intensity profile, belongs here: area
// lights are seen from their centroid with their cosine lobe (light::lightProfile).
bool cubeRSM(const LightSettings& l) { return l.type == LightType::Point || l.type == LightType::Area; }
// Lights the LPV injects: directional and spot lights through one map per cascade, the rest
// through a cube.
bool hasRSM(const LightSettings& l) { return l.type == LightType::Directional || l.type == LightType::Spot || cubeRSM(l); }
// The maps light l needs: 6 cube faces, or one per cascade.
size_t rsmMaps(const LightSettings& l, int cascadeCount) {
    return !hasRSM(l) ? 0 : cubeRSM(l) ? size_t(kCubeFaceCount) : size_t(cascadeCount);
}

}  // namespace

std::string lpvIgnoredLights(const std::vector<LightSettings>& lights) {
    int ignored = 0;
    std::string kinds;
    for (const auto& l : lights) {
        if (hasRSM(l)) continue;
        ++ignored;
        std::string kind = enumName(l.type);
        if (kinds.find(kind) == std::string::npos) kinds += (kinds.empty() ? "" : ", ") + kind;
    }
    if (ignored == 0) return "";
    return std::to_string(ignored) + " light" + (ignored > 1 ? "s add" : " adds") + " no indirect light: the LPV has no RSM for " +
           kinds + " lights";
}

std::vector<CascadeBox> lpvCascades(const LPVSettings& s, const glm::vec3& sceneMin, const glm::vec3& sceneMax,
                                    const glm::vec3& camera) {
    std::vector<CascadeBox> boxes;
    glm::vec3 size = sceneMax - sceneMin;
    float sceneSize = std::max(std::max(size.x, size.y), std::max(size.z, 1e-3f));
    if (s.cascadeCount == 1 && s.cascadeExtent <= 0.0f) {
        // One grid: the scene's grid cube.
        const Bounds bounds{sceneMin, sceneMax};
        CascadeBox b;
        b.extent = bounds.gridCubeSize();
        b.cellSize = b.extent / float(s.gridResolution);
        b.min = bounds.gridCubeMin();
        boxes.push_back(b);
        return boxes;
    }
    float finest = s.cascadeExtent > 0.0f ? s.cascadeExtent : sceneSize / float(1 << (s.cascadeCount - 1));
    for (int k = 0; k < s.cascadeCount; ++k) {
        CascadeBox b;
        b.extent = finest * float(1 << k);
        b.cellSize = b.extent / float(s.gridResolution);
        // Snapped to whole cells of this cascade, so moving the camera never shifts the lattice.
        b.min = glm::floor(camera / b.cellSize - glm::vec3(0.5f * float(s.gridResolution))) * b.cellSize;
        boxes.push_back(b);
    }
    return boxes;
}

LPV::LPV()
    : mInjectProg("lpv.inject", {{GL_COMPUTE_SHADER, "lpv/inject.comp"}}, {gl::floatAtomicsDefine()}),
      mGeometryProg("lpv.geometry", {{GL_COMPUTE_SHADER, "lpv/geometry.comp"}}, {gl::floatAtomicsDefine()}),
      mGeometryResolveProg("lpv.geometryResolve", {{GL_COMPUTE_SHADER, "lpv/geometry_resolve.comp"}}),
      mGeometryMergeProg("lpv.geometryMerge", {{GL_COMPUTE_SHADER, "lpv/geometry_merge.comp"}}),
      mTransmitProg("lpv.transmit", {{GL_COMPUTE_SHADER, "lpv/transmit.comp"}}),
      mPropagateProg("lpv.propagate", {{GL_COMPUTE_SHADER, "lpv/propagate.comp"}}),
      mBounceProg("lpv.bounce", {{GL_COMPUTE_SHADER, "lpv/bounce.comp"}}),
      mResolveProg("lpv.resolve", {{GL_COMPUTE_SHADER, "lpv/resolve.comp"}}),
      mShadeProg("lpv.shade", {{GL_COMPUTE_SHADER, "lpv/shade.comp"}}),
      mSkyProg("lpv.sky", {{GL_COMPUTE_SHADER, "lpv/sky.comp"}}),
      mBlock(kLPVBlockName, kLPVBlockBinding),
      mRSMProgs("lpv.rsm", {{GL_VERTEX_SHADER, "lpv/rsm.vert"}, {GL_FRAGMENT_SHADER, "lpv/rsm.frag"}}, {},
                mMaterialBinding, [this](gl::Program& p) { mBlock.requireIn(p); }),
      mRSMOpaqueProgs("lpv.rsmOpaque", {{GL_VERTEX_SHADER, "lpv/rsm.vert"}, {GL_FRAGMENT_SHADER, "lpv/rsm.frag"}}, {"ALPHA_CUT=0"},
                      mMaterialBinding, [this](gl::Program& p) { mBlock.requireIn(p); }) {
    for (gl::Program* p : {&mInjectProg, &mGeometryProg, &mGeometryResolveProg, &mGeometryMergeProg, &mTransmitProg, &mPropagateProg, &mBounceProg, &mResolveProg,
                           &mShadeProg, &mSkyProg})
        mBlock.requireIn(*p);
    mLinear = gl::createSampler({GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE});
}

LPV::~LPV() = default;

size_t LPV::estimateBytes(const FrameSettings& fs) {
    const LPVSettings& s = fs.lpv;
    size_t perCascade = 6 * cells(s.gridResolution) * kCoefficients * 4  // inject, its kept copy, ping, pong, gather, accum
                        + 5 * corners(s.gridResolution) * 4 * 4           // geometry from RSMs and G-buffer, albedo, the RSMs' kept
                        + 3 * cells(s.gridResolution) * 8                 // SH textures
                        + 2 * corners(s.gridResolution) * 8               // geometry textures
                        + cells(s.gridResolution) * 32;                   // face transmittance
    size_t maps = 0;
    for (const auto& l : fs.lights) maps += rsmMaps(l, s.cascadeCount);
    size_t rsm = maps * size_t(s.rsmResolution) * s.rsmResolution * kRSMBytesPerTexel;
    return perCascade * size_t(s.cascadeCount) + rsm;
}

bool lpvFitsGrid(const LPVSettings& s) { return s.fitGrid && s.cascadeCount == 1 && s.cascadeExtent <= 0.0f; }

int lpvGridResolution(const LPVSettings& s, const FreePath& path) {
    if (!lpvFitsGrid(s) || !(path.meanHitDistance > 0.0f)) return s.gridResolution;
    const float cells = kLPVFitCellsPerGap * path.cubeSize / path.meanHitDistance;
    if (!(cells < float(s.gridResolution))) return s.gridResolution;
    const int rounded = int(std::ceil(cells / float(kLPVFitStep))) * kLPVFitStep;
    return std::clamp(rounded, std::min(kLPVFitMinCells, s.gridResolution), s.gridResolution);
}

void LPV::allocate(const FrameSettings& fs, uint8_t changes, int resolution) {
    // The volumes and RSMs follow the Reallocate fields (grid, cascades, RSM size, the lights),
    // and a fitted grid the scene.
    if (!any(Cost(changes), Cost::Reallocate) && resolution == mResolution) return;
    const LPVSettings& s = fs.lpv;
    size_t rsmCount = 0;
    for (const auto& l : fs.lights) rsmCount += rsmMaps(l, s.cascadeCount);
    {
        mResolution = resolution;
        // propagate.comp views a grid as a buffer texture of 3 texels per cell.
        gl::requireBufferTexels(cells(mResolution) * kCoefficients / 4, "lpv.gridResolution");
        mCascadeData.clear();
        mInjectedBoxes.clear();  // nothing injected or added up is kept in the new buffers
        mGeometryBoxes.clear();
        mVolumeBytes = mGeometryBytes = 0;
        int r = mResolution;
        for (int k = 0; k < s.cascadeCount; ++k) {
            Cascade c;
            size_t shBytes = cells(r) * kCoefficients * 4;
            c.inject = zeroBuffer(shBytes);
            c.injected = zeroBuffer(shBytes);
            c.ping = zeroBuffer(shBytes);
            c.pong = zeroBuffer(shBytes);
            c.accum = zeroBuffer(shBytes);
            c.gather = zeroBuffer(shBytes);
            c.geometryRSM = zeroBuffer(corners(r) * 16);
            c.albedo = zeroBuffer(corners(r) * 16);
            c.geometryGBuffer = zeroBuffer(corners(r) * 16);
            c.geometryRSMKept = zeroBuffer(corners(r) * 16);
            c.albedoKept = zeroBuffer(corners(r) * 16);
            c.transmit = zeroBuffer(cells(r) * 32);
            c.shR = gl::Texture::create3D(GL_RGBA16F, r, r, r);
            c.shG = gl::Texture::create3D(GL_RGBA16F, r, r, r);
            c.shB = gl::Texture::create3D(GL_RGBA16F, r, r, r);
            c.geometryRSMVolume = gl::Texture::create3D(GL_RGBA16F, r + 1, r + 1, r + 1);
            c.geometryGBufferVolume = gl::Texture::create3D(GL_RGBA16F, r + 1, r + 1, r + 1);
            mVolumeBytes += 6 * shBytes + c.shR.bytes() * 3;
            mGeometryBytes += 5 * corners(r) * 16 + 2 * c.geometryRSMVolume.bytes() + cells(r) * 32;
            mCascadeData.push_back(std::move(c));
        }
    }
    {
        mRSMResolution = s.rsmResolution;
        mRSMs.clear();
        mRSMBytes = 0;
        int n = mRSMResolution;
        for (size_t i = 0; i < rsmCount; ++i) {
            RSM m;
            m.flux = gl::Texture::create2D(GL_RGBA16F, n, n);
            m.normal = gl::Texture::create2D(GL_RGBA16F, n, n);
            m.position = gl::Texture::create2D(GL_RGBA32F, n, n);
            m.depth = gl::Texture::create2D(GL_DEPTH_COMPONENT32F, n, n);
            m.albedo = gl::Texture::create2D(GL_RGBA8, n, n);
            m.fbo = gl::createFramebuffer();
            glNamedFramebufferTexture(m.fbo.id(), GL_COLOR_ATTACHMENT0, m.flux.id(), 0);
            glNamedFramebufferTexture(m.fbo.id(), GL_COLOR_ATTACHMENT1, m.normal.id(), 0);
            glNamedFramebufferTexture(m.fbo.id(), GL_COLOR_ATTACHMENT2, m.position.id(), 0);
            glNamedFramebufferTexture(m.fbo.id(), GL_COLOR_ATTACHMENT3, m.albedo.id(), 0);
            glNamedFramebufferTexture(m.fbo.id(), GL_DEPTH_ATTACHMENT, m.depth.id(), 0);
            const GLenum bufs[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};
            glNamedFramebufferDrawBuffers(m.fbo.id(), 4, bufs);
            gl::checkFramebuffer(m.fbo.id(), "RSM framebuffer incomplete");
            mRSMBytes += m.flux.bytes() + m.normal.bytes() + m.position.bytes() + m.depth.bytes() + m.albedo.bytes();
            mRSMs.push_back(std::move(m));
        }
    }
}

void LPV::indirect(FrameContext& ctx) {
    mFreePath = ctx.scene.freePath();
    LPVSettings grid = ctx.settings.lpv;
    grid.gridResolution = lpvGridResolution(grid, mFreePath);
    allocate(ctx.settings, ctx.changes, grid.gridResolution);
    const Bounds& b = ctx.scene.bounds();
    mBoxes = lpvCascades(grid, b.min, b.max, ctx.settings.camera.eye);
    renderRSMs(ctx);
    inject(ctx);
    buildGeometry(ctx);
    propagate(ctx);
    shade(ctx);
    ctx.indirectWritten = true;
}

void LPV::renderRSMs(const FrameContext& ctx) {
    auto pass = ctx.timer.scope("lpv.rsm");
    const FrameSettings& fs = ctx.settings;
    const Bounds& bounds = ctx.scene.bounds();
    const float sceneRadius = bounds.radius();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glViewport(0, 0, mRSMResolution, mRSMResolution);
    // A map is kept while what it shows stays (issue 17 item 4, render.keepStaticWork): the
    // scene, every light and LPV setting (ctx.changes: any light field; the RSM size
    // reallocates) and its own projection (a directional light's follows its cascade).
    const bool redrawAll = !fs.render.keepStaticWork || ctx.changes != 0 || ctx.scene.id() != mRSMSceneId;
    const int drawsBefore = mRSMDraws;
    mRSMSceneId = ctx.scene.id();
    // Draws the scene into map m, with the light's entry li in the light buffer.
    auto draw = [&](RSM& m, size_t li) {
        if (!redrawAll && m.drawn && m.drawnViewProj == m.viewProj) return;
        m.drawn = true;
        m.drawnViewProj = m.viewProj;
        ++mRSMDraws;
        glBindFramebuffer(GL_FRAMEBUFFER, m.fbo.id());
        const float zero[4] = {0, 0, 0, 0};
        for (int i = 0; i < 4; ++i) glClearNamedFramebufferfv(m.fbo.id(), GL_COLOR, i, zero);
        const float one = 1.0f;
        glClearNamedFramebufferfv(m.fbo.id(), GL_DEPTH, 0, &one);
        LPVParams p{};
        p.lightViewProj = m.viewProj;
        p.lightIndex = int(li);
        p.texelArea = m.texelArea;
        p.texelSolidAngle = m.texelSolidAngle;
        p.cubeFace = m.face >= 0 ? 1 : 0;
        mBlock.set(p);
        // The material changes per draw: its own block (common/material_shared.h).
        mMaterialBinding.begin(0);
        // Opaque materials first, with the variant that tests depth before shading, then the rest.
        MaterialPrograms* programs = &mRSMOpaqueProgs;
        auto bind = [&](const Material& mat, int) {
            programs->of(mat, fs.render.materialPrograms).use();
            mMaterialBinding.bind(ctx.scene, mat);
        };
        // Clusters outside the map's frustum are left out (render.cullClusters; a directional
        // light's map covers only its cascade, so the finer cascades draw a part of the scene).
        const glm::mat4* cull = fs.render.cullClusters ? &m.viewProj : nullptr;
        ctx.scene.drawIf([](const Material& mat) { return mat.alphaMode == AlphaMode::Opaque; }, bind, cull);
        programs = &mRSMProgs;
        ctx.scene.drawIf([](const Material& mat) { return mat.alphaMode != AlphaMode::Opaque; }, bind, cull);
        mMaterialBinding.end();
    };
    size_t index = 0;
    for (size_t li = 0; li < fs.lights.size(); ++li) {
        const LightSettings& l = fs.lights[li];
        if (!hasRSM(l)) continue;
        if (cubeRSM(l)) {
            // One cube for every cascade: its faces depend on the light and the scene, not on the
            // cascade box. Not cut at the range, like the spot's frustum below.
            float far = glm::length(l.position - bounds.center()) + sceneRadius;
            float t = light::cubeTexel(mRSMResolution);
            for (int face = 0; face < kCubeFaceCount; ++face, ++index) {
                RSM& m = mRSMs[index];
                m.light = int(li);
                m.cascade = -1;
                m.face = face;
                m.viewProj = cubeFaceViewProj(l.position, face, far);
                m.texelArea = 0.0f;
                m.texelSolidAngle = t * t;
                draw(m, li);
            }
            continue;
        }
        glm::vec3 dir = light::lightDirection(l.direction);
        for (size_t k = 0; k < mBoxes.size(); ++k, ++index) {
            RSM& m = mRSMs[index];
            m.light = int(li);
            m.cascade = int(k);
            m.face = -1;
            const CascadeBox& box = mBoxes[k];
            if (l.type == LightType::Directional) {
                // The seed's fit: the extent of the cascade's corners projected on the light's plane.
                glm::vec3 c = box.center();
                float back = glm::length(bounds.center() - c) + sceneRadius + box.extent;
                glm::mat4 view = glm::lookAt(c - dir * back, c, light::shadowUp(dir));
                float half = 0.0f;
                for (int i = 0; i < 8; ++i) {
                    glm::vec3 corner = box.min + box.extent * glm::vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
                    glm::vec4 v = view * glm::vec4(corner, 1.0f);
                    half = std::max(half, std::max(std::abs(v.x), std::abs(v.y)));
                }
                m.viewProj = glm::ortho(-half, half, -half, half, back * 0.01f, back * 2.0f + box.extent) * view;
                float texel = light::orthoTexel(half, mRSMResolution);
                m.texelArea = texel * texel;
                m.texelSolidAngle = 0.0f;
            } else {
                // The shadow map's frustum, but not cut at the range: texels past it light nothing
                // yet still block light in the geometry volume.
                float fov = light::spotShadowFovDeg(l.outerConeDeg);
                float far = glm::length(l.position - bounds.center()) + sceneRadius;
                m.viewProj = spotViewProj(l.position, dir, fov, far);
                float t = light::perspectiveTexel(fov, mRSMResolution);
                m.texelArea = 0.0f;
                m.texelSolidAngle = t * t;
            }
            draw(m, li);
        }
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    mRSMsChanged = redrawAll || mRSMDraws != drawsBefore;
}

bool LPV::keepsRSMWork(const FrameContext& ctx, const std::vector<CascadeBox>& keptFor) const {
    if (!ctx.settings.render.keepStaticWork || mRSMsChanged || keptFor.size() != mBoxes.size()) return false;
    for (size_t k = 0; k < mBoxes.size(); ++k)
        if (keptFor[k].min != mBoxes[k].min || keptFor[k].cellSize != mBoxes[k].cellSize) return false;
    return true;
}

void LPV::dispatchPerTexel(const RSM& m, LPVParams p, const std::function<void(const Cascade&)>& bindTargets) {
    p.resolution = mResolution;
    p.width = p.height = mRSMResolution;
    for (size_t k = 0; k < mBoxes.size(); ++k) {
        if (!m.feeds(k)) continue;
        p.gridMinCell = glm::vec4(mBoxes[k].min, mBoxes[k].cellSize);
        mBlock.set(p);
        bindTargets(mCascadeData[k]);
        glDispatchCompute(gl::groupCount(mRSMResolution, shared::kGroup2D), gl::groupCount(mRSMResolution, shared::kGroup2D), 1);
    }
}

void LPV::inject(const FrameContext& ctx) {
    auto pass = ctx.timer.scope("lpv.inject");
    const LPVSettings& s = ctx.settings.lpv;
    // The injection depends on the RSMs, the cascades' boxes and the LPV settings (which redraw
    // the RSMs): with none of them changed, the copy kept from the last injection is restored
    // (propagation overwrites `inject` with each bounce's light, so it cannot simply stay).
    const GLsizeiptr shBytes = GLsizeiptr(cells(mResolution) * kCoefficients * 4);
    if (keepsRSMWork(ctx, mInjectedBoxes)) {
        for (auto& c : mCascadeData) glCopyNamedBufferSubData(c.injected.id(), c.inject.id(), 0, 0, shBytes);
        return;
    }
    ++mInjects;
    for (auto& c : mCascadeData) clearBuffer(c.inject);
    mInjectProg.use();
    LPVParams p{};
    p.nudge = s.nudge;
    for (const RSM& m : mRSMs) {
        glBindImageTexture(kLPVImageFlux, m.flux.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA16F);
        glBindImageTexture(kLPVImageNormal, m.normal.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA16F);
        glBindImageTexture(kLPVImagePosition, m.position.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
        dispatchPerTexel(m, p, [](const Cascade& c) { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLPVBufferInject, c.inject.id()); });
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    for (auto& c : mCascadeData) glCopyNamedBufferSubData(c.inject.id(), c.injected.id(), 0, 0, shBytes);
    mInjectedBoxes = mBoxes;
}

void LPV::buildGeometry(const FrameContext& ctx) {
    auto pass = ctx.timer.scope("lpv.geometry");
    // The RSMs' surfels depend on what the injection does (keepsRSMWork): with nothing changed,
    // their sums (blocking and albedo) are restored from the copies kept after the last run, and
    // only the G-buffer's, which follow the camera, are added again.
    const bool keepRSM = keepsRSMWork(ctx, mGeometryBoxes);
    const GLsizeiptr cornerBytes = GLsizeiptr(corners(mResolution) * 16);
    for (auto& c : mCascadeData) {
        if (keepRSM) {
            glCopyNamedBufferSubData(c.geometryRSMKept.id(), c.geometryRSM.id(), 0, 0, cornerBytes);
            glCopyNamedBufferSubData(c.albedoKept.id(), c.albedo.id(), 0, 0, cornerBytes);
        } else {
            clearBuffer(c.geometryRSM);
            clearBuffer(c.albedo);
        }
        clearBuffer(c.geometryGBuffer);
    }
    // Bounces past the first reflect light at the geometry volume, occlusion or not.
    if (!ctx.settings.lpv.occlusion && ctx.settings.lpv.bounces <= 1) {
        mGeometryBoxes.clear();
        const float zero[4] = {0, 0, 0, 0};
        for (auto& c : mCascadeData) {
            glClearTexImage(c.geometryRSMVolume.id(), 0, GL_RGBA, GL_FLOAT, zero);
            glClearTexImage(c.geometryGBufferVolume.id(), 0, GL_RGBA, GL_FLOAT, zero);
        }
        return;
    }
    mGeometryProg.use();
    // Surfels from the RSMs. Each light's are summed apart (in the G-buffer's buffer, cleared
    // again below) and merged corner by corner, the larger coverage kept (geometry_merge.comp):
    // the lights see the same surfaces, which should block and reflect once. The albedo sums
    // are the coverage-weighted mean, which the repeats leave as it is.
    if (!keepRSM) {
        LPVParams p{};
        p.fromGBuffer = 0;
        auto mergeLight = [&] {
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
            mGeometryMergeProg.use();
            LPVParams merged{};
            merged.resolution = mResolution;
            mBlock.set(merged);
            for (auto& c : mCascadeData) {
                glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLPVBufferGeometryRSM, c.geometryRSM.id());
                glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLPVBufferGeometryGBuffer, c.geometryGBuffer.id());
                gl::dispatch3D(mResolution + 1);
            }
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        };
        for (size_t i = 0; i < mRSMs.size(); ++i) {
            const RSM& m = mRSMs[i];
            if (i == 0 || m.light != mRSMs[i - 1].light) {  // a light's first RSM
                for (auto& c : mCascadeData) clearBuffer(c.geometryGBuffer);
                mGeometryProg.use();
            }
            glBindImageTexture(kLPVImageNormal, m.normal.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA16F);
            glBindImageTexture(kLPVImagePosition, m.position.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
            glBindImageTexture(kLPVImageAlbedo, m.albedo.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA8);
            dispatchPerTexel(m, p, [](const Cascade& c) {
                glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLPVBufferGeometry, c.geometryGBuffer.id());
                glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLPVBufferGeometryAlbedo, c.albedo.id());
            });
            if (i + 1 == mRSMs.size() || mRSMs[i + 1].light != m.light) mergeLight();  // its last
        }
        for (auto& c : mCascadeData) clearBuffer(c.geometryGBuffer);
        mGeometryProg.use();
        // The sums so far are the RSMs' alone: kept for the frames that change none of their inputs.
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        for (auto& c : mCascadeData) {
            glCopyNamedBufferSubData(c.geometryRSM.id(), c.geometryRSMKept.id(), 0, 0, cornerBytes);
            glCopyNamedBufferSubData(c.albedo.id(), c.albedoKept.id(), 0, 0, cornerBytes);
        }
        mGeometryBoxes = mBoxes;
    }
    // Surfels from the camera's G-buffer, subsampled to about 128 x 128 samples.
    int stride = std::max(1, std::max(ctx.width, ctx.height) / 128);
    glBindTextureUnit(kUnitAlbedo, ctx.albedo);
    glBindTextureUnit(kUnitNormal, ctx.normal);
    glBindTextureUnit(kUnitMaterial, ctx.material);
    glBindTextureUnit(kUnitDepth, ctx.depth);
    for (size_t k = 0; k < mCascadeData.size(); ++k) {
        LPVParams p{};
        p.resolution = mResolution;
        p.fromGBuffer = 1;
        p.stride = stride;
        p.width = ctx.width;
        p.height = ctx.height;
        p.invViewProj = ctx.invViewProj;
        p.cameraPos = glm::vec4(ctx.settings.camera.eye, 1.0f);
        p.pixelAngle = 2.0f * std::tan(glm::radians(ctx.settings.camera.fovY) * 0.5f) / float(ctx.height);
        p.gridMinCell = glm::vec4(mBoxes[k].min, mBoxes[k].cellSize);
        mBlock.set(p);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLPVBufferGeometry, mCascadeData[k].geometryGBuffer.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLPVBufferGeometryAlbedo, mCascadeData[k].albedo.id());
        // One invocation per `stride`-th G-buffer pixel.
        const int samplesX = (ctx.width + stride - 1) / stride, samplesY = (ctx.height + stride - 1) / stride;
        glDispatchCompute(gl::groupCount(samplesX, shared::kGroup2D), gl::groupCount(samplesY, shared::kGroup2D), 1);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    mGeometryResolveProg.use();
    LPVParams resolve{};
    resolve.resolution = mResolution;
    mBlock.set(resolve);
    for (auto& c : mCascadeData) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLPVBufferGeometryRSM, c.geometryRSM.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLPVBufferGeometryGBuffer, c.geometryGBuffer.id());
        glBindImageTexture(kLPVImageGeometryRSM, c.geometryRSMVolume.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glBindImageTexture(kLPVImageGeometryGBuffer, c.geometryGBufferVolume.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        gl::dispatch3D(mResolution + 1);
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void LPV::propagateStep(GLuint src, GLuint dst, GLuint accum, GLuint transmit, int resolution, bool blocking) {
    mPropagateProg.use();
    LPVParams p{};
    p.resolution = resolution;
    p.blocking = blocking ? 1 : 0;
    mBlock.set(p);
    // Buffer views of the grids (propagate.comp): re-pointed each step, as ping and pong swap.
    glTextureBuffer(mSourceView.id(), GL_RGBA32F, src);
    glTextureBuffer(mTransmitView.id(), GL_RGBA32F, transmit);
    glTextureBuffer(mDestinationView.id(), GL_RGBA32F, dst);
    glTextureBuffer(mAccumView.id(), GL_RGBA32F, accum);
    glBindTextureUnit(kLPVUnitPropagateSource, mSourceView.id());
    glBindTextureUnit(kLPVUnitPropagateTransmit, mTransmitView.id());
    glBindImageTexture(kLPVImagePropagateDestination, mDestinationView.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glBindImageTexture(kLPVImagePropagateAccum, mAccumView.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    gl::dispatch3D(resolution);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void LPV::propagate(const FrameContext& ctx) {
    auto pass = ctx.timer.scope("lpv.propagate");
    const LPVSettings& s = ctx.settings.lpv;
    if (s.occlusion) {
        mTransmitProg.use();
        LPVParams p{};
        p.resolution = mResolution;
        p.occlusionStrength = s.occlusionStrength;
        mBlock.set(p);
        glBindSampler(kLPVUnitGeometryRSM, mLinear.id());
        glBindSampler(kLPVUnitGeometryGBuffer, mLinear.id());
        for (auto& c : mCascadeData) {
            glBindTextureUnit(kLPVUnitGeometryRSM, c.geometryRSMVolume.id());
            glBindTextureUnit(kLPVUnitGeometryGBuffer, c.geometryGBufferVolume.id());
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLPVBufferTransmit, c.transmit.id());
            gl::dispatch3D(mResolution);
        }
        glBindSampler(kLPVUnitGeometryRSM, 0);
        glBindSampler(kLPVUnitGeometryGBuffer, 0);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    for (auto& c : mCascadeData) {
        clearBuffer(c.accum);
        for (int bounce = 0; bounce < s.bounces; ++bounce) {
            // The bounce's injection propagates into `gather`; bounce.comp adds both to the total
            // and replaces the injection with the light the geometry volume reflects.
            clearBuffer(c.gather);
            GLuint src = c.inject.id(), dst = c.ping.id();
            for (int step = 0; step < s.propagationSteps; ++step) {
                propagateStep(src, dst, c.gather.id(), c.transmit.id(), mResolution, s.occlusion && step > 0);
                src = dst;
                dst = dst == c.ping.id() ? c.pong.id() : c.ping.id();
            }
            mBounceProg.use();
            LPVParams p{};
            p.resolution = mResolution;
            mBlock.set(p);
            // Buffer views (bounce.comp); the propagation's views are re-pointed here.
            glTextureBuffer(mSourceView.id(), GL_RGBA32F, c.gather.id());
            glTextureBuffer(mGeometryRSMView.id(), GL_RGBA32F, c.geometryRSM.id());
            glTextureBuffer(mGeometryGBufferView.id(), GL_RGBA32F, c.geometryGBuffer.id());
            glTextureBuffer(mAlbedoView.id(), GL_RGBA32F, c.albedo.id());
            glTextureBuffer(mDestinationView.id(), GL_RGBA32F, c.inject.id());
            glTextureBuffer(mAccumView.id(), GL_RGBA32F, c.accum.id());
            glBindTextureUnit(kLPVUnitBounceGather, mSourceView.id());
            glBindTextureUnit(kLPVUnitBounceGeometryRSM, mGeometryRSMView.id());
            glBindTextureUnit(kLPVUnitBounceGeometryGBuffer, mGeometryGBufferView.id());
            glBindTextureUnit(kLPVUnitBounceAlbedo, mAlbedoView.id());
            glBindImageTexture(kLPVImageBounceInject, mDestinationView.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
            glBindImageTexture(kLPVImageBounceTotal, mAccumView.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
            gl::dispatch3D(mResolution);
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        }
    }
    mResolveProg.use();
    LPVParams p{};
    p.resolution = mResolution;
    mBlock.set(p);
    for (auto& c : mCascadeData) {
        glTextureBuffer(mAccumView.id(), GL_RGBA32F, c.accum.id());
        glBindTextureUnit(kLPVUnitResolveAccum, mAccumView.id());
        glBindImageTexture(kLPVImageSHR, c.shR.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glBindImageTexture(kLPVImageSHG, c.shG.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glBindImageTexture(kLPVImageSHB, c.shB.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        gl::dispatch3D(mResolution);
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

void LPV::shade(const FrameContext& ctx) {
    auto pass = ctx.timer.scope("lpv.shade");
    const LPVSettings& s = ctx.settings.lpv;
    GI_ASSERT(mBoxes.size() <= size_t(kLPVMaxCascades), "LPVParams holds kLPVMaxCascades cascades");
    mShadeProg.use();
    LPVParams p{};
    p.invViewProj = ctx.invViewProj;
    p.cascadeCount = int(mBoxes.size());
    p.intensity = s.intensity;
    p.damping = s.damping;
    p.width = ctx.width;
    p.height = ctx.height;
    p.resolution = mResolution;
    for (size_t k = 0; k < mBoxes.size(); ++k) {
        p.cascadeMinCell[k] = glm::vec4(mBoxes[k].min, mBoxes[k].cellSize);
        const Cascade& c = mCascadeData[k];
        const GLuint volumes[kLPVSHChannels] = {c.shR.id(), c.shG.id(), c.shB.id()};
        for (int ch = 0; ch < kLPVSHChannels; ++ch) {
            GLuint unit = GLuint(kLPVUnitSH + kLPVSHChannels * int(k) + ch);
            glBindTextureUnit(unit, volumes[ch]);
            glBindSampler(unit, mLinear.id());
        }
    }
    mBlock.set(p);
    glBindTextureUnit(kUnitNormal, ctx.normal);
    glBindTextureUnit(kUnitDepth, ctx.depth);
    glBindImageTexture(kLPVImageIndirect, ctx.indirect, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute(gl::groupCount(ctx.width, shared::kGroup2D), gl::groupCount(ctx.height, shared::kGroup2D), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    for (int unit = kLPVUnitSH; unit < kLPVUnitSH + kLPVSHChannels * kLPVMaxCascades; ++unit) glBindSampler(GLuint(unit), 0);
    if (ctx.sky.prefiltered == 0) return;
    // The sky (sky.comp): its irradiance and its prefiltered chain, times its visibility marched
    // through the coarsest cascade's face transmittances (computed with occlusion on; without it
    // the sky is unoccluded).
    mSkyProg.use();
    p.skyIntensity = ctx.sky.intensity;
    p.skyRotation = ctx.sky.rotation;
    p.skyCascade = s.occlusion ? int(mBoxes.size()) - 1 : -1;
    p.cameraPos = glm::vec4(ctx.settings.camera.eye, 0.0f);
    for (int i = 0; i < 9; ++i) p.skySH[i] = glm::vec4(ctx.sky.irradianceSH[size_t(i)], 0.0f);
    p.skyMipCount = std::min(int(ctx.sky.mipRoughness.size()), shared::kSkyMaxMips);
    for (int m = 0; m < shared::kSkyMaxMips; ++m)
        p.skyMipRoughness[m / 4][m % 4] = m < p.skyMipCount ? ctx.sky.mipRoughness[size_t(m)] : 1.0f;
    mBlock.set(p);
    glBindTextureUnit(kUnitMaterial, ctx.material);
    glBindTextureUnit(kLPVUnitSky, ctx.sky.prefiltered);
    glBindSampler(kLPVUnitSky, ctx.sky.sampler);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLPVBufferTransmit, mCascadeData.back().transmit.id());
    glBindImageTexture(kLPVImageIndirect, ctx.indirect, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
    glBindImageTexture(kLPVImageSpecular, ctx.indirectSpecular, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute(gl::groupCount(ctx.width, shared::kGroup2D), gl::groupCount(ctx.height, shared::kGroup2D), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glBindSampler(kLPVUnitSky, 0);
}

std::vector<DebugView> LPV::debugViews() const {
    std::vector<DebugView> v;
    for (const RSM& m : mRSMs) {
        // lpv.rsmFlux<light>c<cascade>, or lpv.rsmFlux<light>f<face> for a cube's faces.
        std::string suffix = std::to_string(m.light) + (m.face >= 0 ? "f" + std::to_string(m.face) : "c" + std::to_string(m.cascade));
        int n = mRSMResolution;
        v.push_back({"lpv.rsmFlux" + suffix, m.flux.id(), GL_TEXTURE_2D, kViewColor, n, n, 0, 1, 1});
        v.push_back({"lpv.rsmNormal" + suffix, m.normal.id(), GL_TEXTURE_2D, kViewNormal, n, n, 0, 1, 1});
        v.push_back({"lpv.rsmPosition" + suffix, m.position.id(), GL_TEXTURE_2D, kViewPosition, n, n, 0, 1, 1});
    }
    for (size_t k = 0; k < mCascadeData.size(); ++k) {
        const Cascade& c = mCascadeData[k];
        DebugView sh{"lpv.volume" + std::to_string(k), c.shR.id(), GL_TEXTURE_3D, kViewSHVolume, 512, 512, 0, 1, 1};
        sh.extra[0] = c.shG.id();
        sh.extra[1] = c.shB.id();
        // sh.scale stays 1: the volumes hold intensity per cell face (inject.comp), read as radiance.
        v.push_back(sh);
        v.push_back({"lpv.geometryRSM" + std::to_string(k), c.geometryRSMVolume.id(), GL_TEXTURE_3D, kViewVolume, 512, 512, 0, 1, 1});
        v.push_back({"lpv.geometryGBuffer" + std::to_string(k), c.geometryGBufferVolume.id(), GL_TEXTURE_3D, kViewVolume, 512,
                     512, 0, 1, 1});
    }
    return v;
}

size_t LPV::passMemory(const std::string& pass) const {
    if (pass == "lpv.rsm") return mRSMBytes;
    if (pass == "lpv.geometry") return mGeometryBytes;
    if (pass == "lpv.propagate") return mVolumeBytes;
    return 0;
}

size_t LPV::memoryBytes() const { return mRSMBytes + mVolumeBytes + mGeometryBytes; }

PassReport LPV::report(const FrameSettings& fs) const {
    PassReport r;
    if (!mResolution) return r;
    r.numbers = {{"gridResolution", double(mResolution)}};
    if (lpvFitsGrid(fs.lpv) && mFreePath.rays > 0) {
        r.numbers.push_back({"meanSurfaceGap", double(mFreePath.meanHitDistance)});
        r.numbers.push_back({"surfaceGapRays", double(mFreePath.rays)});
        r.numbers.push_back({"surfaceGapHitFraction", double(mFreePath.hitFraction)});
        r.numbers.push_back({"surfaceGapPoints", double(mFreePath.points)});
        char line[160];
        std::snprintf(line, sizeof line, "%d^3, fitted: surfaces %.3g apart on average (%.1f cells), at most %d^3", mResolution,
                      double(mFreePath.meanHitDistance), double(mFreePath.meanHitDistance / mFreePath.cubeSize * float(mResolution)),
                      fs.lpv.gridResolution);
        r.texts = {{"grid", line}};
    }
    return r;
}

std::vector<std::string> LPV::passNames(const FrameSettings&) const {
    return {"lpv.rsm", "lpv.inject", "lpv.geometry", "lpv.propagate", "lpv.shade"};
}

std::vector<Previewer> LPV::previewers(const FrameSettings& fs) const {
    auto boxes = [](const PreviewContext& ctx) {
        std::vector<GlyphLine> lines;
        if (!ctx.sceneBounds.valid()) return lines;
        const glm::vec4 colours[4] = {{1.0f, 0.86f, 0.24f, 0.8f}, {0.31f, 0.86f, 1.0f, 0.8f}, {1.0f, 0.43f, 0.78f, 0.8f},
                                      {0.59f, 1.0f, 0.47f, 0.8f}};
        std::vector<CascadeBox> cascades =
            lpvCascades(ctx.settings.lpv, ctx.sceneBounds.min, ctx.sceneBounds.max, ctx.settings.camera.eye);
        for (size_t k = 0; k < cascades.size(); ++k) {
            auto corner = [&](int i) { return cascades[k].min + cascades[k].extent * glm::vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1); };
            // The 12 edges: corners that differ in one bit.
            for (int a = 0; a < 8; ++a)
                for (int bit = 1; bit < 8; bit <<= 1)
                    if (!(a & bit)) lines.push_back({corner(a), corner(a | bit), colours[k % 4], 1.5f * ctx.overlayScale});
        }
        return lines;
    };
    std::vector<Previewer> out{{"lpv.cascades", "The cascades' boxes: each grid's extent in the scene", {}, boxes}};
    for (size_t li = 0; li < fs.lights.size(); ++li) {
        if (!cubeRSM(fs.lights[li])) continue;
        // The six flux faces of light li's cube RSM as the cross the cube views use (view.frag's
        // cubeCross): -X +Z +X -Z in the middle row, +Y above +Z, -Y below, each face with s to
        // the right and t downwards.
        auto cross = [li](const PreviewContext& ctx) {
            constexpr int n = 128;
            const int cells[kCubeFaceCount][2] = {{2, 1}, {0, 1}, {1, 0}, {1, 2}, {1, 1}, {3, 1}};  // column, row from the top
            PreviewImage img;
            for (int face = 0; face < kCubeFaceCount; ++face) {
                std::string name = "lpv.rsmFlux" + std::to_string(li) + "f" + std::to_string(face);
                auto it = std::find_if(ctx.views.begin(), ctx.views.end(), [&](const DebugView& v) { return v.name == name; });
                if (it == ctx.views.end() || !ctx.renderView) return PreviewImage{};
                if (img.width == 0) {
                    img.width = 4 * n;
                    img.height = 3 * n;
                    img.rgba.assign(size_t(img.width) * img.height * 4, 0);
                    for (size_t i = 3; i < img.rgba.size(); i += 4) img.rgba[i] = 255;
                }
                std::vector<uint8_t> faceImage = ctx.renderView(*it, n, n);
                // Face row r (bottom row first) holds t = r / n, which the cross shows r rows below the cell's top.
                for (int r = 0; r < n; ++r) {
                    int row = img.height - 1 - (cells[face][1] * n + r);
                    std::copy_n(faceImage.begin() + size_t(r) * n * 4, size_t(n) * 4,
                                img.rgba.begin() + (size_t(row) * img.width + size_t(cells[face][0]) * n) * 4);
                }
            }
            return img;
        };
        out.push_back({"lpv.rsmCube" + std::to_string(li), "Light " + std::to_string(li) +
                       "'s cube RSM: the flux of its six faces as a cross", cross, {}});
    }
    return out;
}

std::unique_ptr<Pass> LPVSettings::createPass() { return std::make_unique<LPV>(); }
size_t LPVSettings::estimateBytes(const FrameSettings& fs) { return LPV::estimateBytes(fs); }
std::string LPVSettings::notes(const FrameSettings& fs) { return lpvIgnoredLights(fs.lights); }

bool LPV::reloadShaders(std::string& log) {
    for (RSM& m : mRSMs) m.drawn = false;  // the edited shaders draw them afresh
    bool ok = true;
    for (gl::Program* p : {&mInjectProg, &mGeometryProg, &mGeometryResolveProg, &mGeometryMergeProg, &mTransmitProg, &mPropagateProg, &mBounceProg, &mResolveProg,
                           &mShadeProg, &mSkyProg})
        if (!p->reload()) {
            ok = false;
            log += p->log() + "\n";
        }
    for (MaterialPrograms* p : {&mRSMProgs, &mRSMOpaqueProgs})
        if (!p->reload(log)) ok = false;
    return ok;
}

}  // namespace gi
