#include "gi/vct/vct_views.h"

#include "gi/render/strokes.h"
#include "gi/scene/camera.h"
#include "gi/util/error.h"
#include "vct/vct_shared.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace gi {

namespace {

glm::ivec3 wrapOf(const glm::ivec3& origin, int res) { return ((origin % res) + res) % res; }

}  // namespace

std::vector<VoxelGridView> voxelGrids(const VCT& vct, VCTMode mode) {
    std::vector<VoxelGridView> grids;
    int res = vct.resolution();
    for (const VCT::Level& l : vct.levels()) {
        VoxelGridView g;
        g.albedo = l.surface.albedo.id();
        g.normal = l.surface.normal.id();
        g.radiance = l.radiance.id();
        g.mipCount = vctMipCount(res);
        g.resolution = res;
        g.box = l.box;
        g.wrap = mode == VCTMode::Clipmap ? wrapOf(l.box.origin, res) : glm::ivec3(0);
        grids.push_back(g);
    }
    return grids;
}

std::vector<VoxelGridView> voxelGrids(const std::vector<DebugView>& views, const FrameSettings& fs, const Bounds& sceneBounds) {
    std::vector<VoxelGridView> grids;
    if (fs.technique != "vct" || !sceneBounds.valid()) return grids;
    auto find = [&](const std::string& name) -> const DebugView* {
        for (const DebugView& v : views)
            if (v.name == name) return &v;
        return nullptr;
    };
    std::vector<VoxelBox> boxes = vctLevels(fs.vct, sceneBounds.min, sceneBounds.max, fs.camera.eye);
    for (size_t k = 0; k < boxes.size(); ++k) {
        // VCT::debugViews numbers the views only when there are several levels.
        std::string suffix = boxes.size() > 1 ? std::to_string(k) : "";
        const DebugView* albedo = find("vct.albedo" + suffix);
        const DebugView* normal = find("vct.normal" + suffix);
        const DebugView* radiance = find("vct.radiance" + suffix);
        if (!albedo || !normal || !radiance) return {};
        VoxelGridView g;
        g.albedo = albedo->texture;
        g.normal = normal->texture;
        g.radiance = radiance->texture;
        g.resolution = radiance->width;
        g.mipCount = vctMipCount(g.resolution);
        g.box = boxes[k];
        g.wrap = fs.vct.mode == VCTMode::Clipmap ? wrapOf(boxes[k].origin, g.resolution) : glm::ivec3(0);
        grids.push_back(g);
    }
    return grids;
}

int finestLevelHolding(const std::vector<VoxelGridView>& grids, const glm::vec3& p) {
    for (size_t k = 0; k < grids.size(); ++k) {
        glm::vec3 lo = grids[k].box.min, hi = lo + glm::vec3(grids[k].box.extent(grids[k].resolution));
        if (glm::all(glm::greaterThanEqual(p, lo)) && glm::all(glm::lessThanEqual(p, hi))) return int(k);
    }
    return std::max(int(grids.size()) - 1, 0);
}

VoxelView::VoxelView()
    : mProgram(gl::fullscreenProgram("vct.voxelView", "vct/voxel_view.frag")), mBlock(vct::kVCTBlockName, vct::kVCTBlockBinding) {
    mBlock.requireIn(mProgram);
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    mVAO = gl::VertexArray(vao);
    mNearest = gl::createSampler({GL_NEAREST_MIPMAP_NEAREST, GL_NEAREST, GL_REPEAT});
}

void VoxelView::render(const std::vector<VoxelGridView>& grids, const VoxelViewParams& params, GLuint framebuffer, int width,
                       int height, int x) const {
    GI_ASSERT(width > 0 && height > 0, "voxel view of an empty size");
    glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, "vct.voxelView");
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(x, 0, width, height);
    if (grids.empty()) {
        glClearColor(params.background.r, params.background.g, params.background.b, 1.0f);
        glEnable(GL_SCISSOR_TEST);
        glScissor(x, 0, width, height);
        glClear(GL_COLOR_BUFFER_BIT);
        glDisable(GL_SCISSOR_TEST);
    } else {
        const VoxelGridView& g = grids[size_t(std::clamp(params.level, 0, int(grids.size()) - 1))];
        bool radiance = params.source == VoxelViewSource::Radiance;
        int mip = radiance ? std::clamp(params.mip, 0, g.mipCount - 1) : 0;
        GLuint packed = params.source == VoxelViewSource::Normal ? g.normal : g.albedo;
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        glBindVertexArray(mVAO.id());
        vct::VCTParams p{};
        p.invViewProj = glm::inverse(params.viewProj);
        p.gridMin = glm::vec4(g.box.min, 0.0f);
        p.cellSize = g.box.cellSize;
        p.resolution = g.resolution;
        p.wrapOffset = glm::ivec4(g.wrap, 0);
        p.viewMip = mip;
        p.viewSource = int(params.source);
        p.exposureScale = std::exp2(params.exposure);
        p.opacityThreshold = params.opacityThreshold;
        p.edges = params.edges ? 1 : 0;
        p.background = glm::vec4(params.background, 0.0f);
        mProgram.use();
        mBlock.set(p);
        // texelFetch only, but an r32ui volume under a linear filter is incomplete and reads 0.
        glBindTextureUnit(vct::kVCTUnitViewOccupancy, g.albedo);
        glBindTextureUnit(vct::kVCTUnitViewPacked, packed);
        glBindTextureUnit(vct::kVCTUnitViewRadiance, g.radiance);
        const GLuint units[3] = {vct::kVCTUnitViewOccupancy, vct::kVCTUnitViewPacked, vct::kVCTUnitViewRadiance};
        for (GLuint u : units) glBindSampler(u, mNearest.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        for (GLuint u : units) {
            glBindSampler(u, 0);
            glBindTextureUnit(u, 0);
        }
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glPopDebugGroup();
}

std::vector<uint8_t> VoxelView::renderImage(const std::vector<VoxelGridView>& grids, const VoxelViewParams& params, int width,
                                            int height) const {
    gl::Texture image = gl::Texture::create2D(GL_RGBA8, width, height);
    gl::Framebuffer fbo = gl::createFramebuffer();
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, image.id(), 0);
    gl::checkFramebuffer(fbo.id(), "voxel view");
    render(grids, params, fbo.id(), width, height);
    std::vector<uint8_t> pixels(size_t(width) * size_t(height) * 4);
    glGetTextureImage(image.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(pixels.size()), pixels.data());
    return pixels;
}

bool VoxelView::reloadShaders(std::string& log) {
    if (mProgram.reload()) return true;
    log += mProgram.log() + "\n";
    return false;
}

glm::mat3 vctTangentFrame(const glm::vec3& n) {
    float s = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (s + n.z);
    float b = n.x * n.y * a;
    glm::vec3 t(1.0f + s * n.x * n.x * a, s * b, -s * n.x);
    glm::vec3 bt(b, s + n.y * n.y * a, -n.y);
    return glm::mat3(t, bt, n);
}

std::vector<ConeGlyph> vctConeGlyphs(const VCTSettings& s, const glm::vec3& p, const glm::vec3& n, const glm::vec3& eye,
                                     float roughness, float voxelSize) {
    std::vector<ConeGlyph> glyphs;
    glm::mat3 frame = vctTangentFrame(n);
    // Where trace.glsl's traceCone starts its march.
    auto start = [&](const glm::vec3& dir) { return vct::vctConeStart(s.nudge, voxelSize, glm::dot(n, dir), vctFaceSidesOn(s)); };
    ConeSet set = makeConeSet(s);
    for (const Cone& c : set.cones) {
        ConeGlyph g;
        g.apex = p;
        g.direction = glm::normalize(frame * c.direction);
        g.start = start(g.direction);
        g.tanHalf = std::tan(0.5f * set.aperture);
        g.weight = c.weight;
        glyphs.push_back(g);
    }
    if (s.specularCone) {
        // trace.comp: the reflected view direction, the aperture lerped by roughness.
        ConeGlyph g;
        g.apex = p;
        g.direction = glm::normalize(glm::reflect(glm::normalize(p - eye), n));
        g.start = start(g.direction);
        float aperture = glm::radians(s.specularApertureMin + (s.specularApertureMax - s.specularApertureMin) * roughness);
        g.tanHalf = std::tan(0.5f * aperture);
        g.specular = true;
        glyphs.push_back(g);
    }
    return glyphs;
}

std::vector<GlyphLine> coneGlyphLines(const std::vector<ConeGlyph>& glyphs, float length) {
    std::vector<GlyphLine> lines;
    float maxWeight = 0.0f;
    for (const ConeGlyph& g : glyphs)
        if (!g.specular) maxWeight = std::max(maxWeight, g.weight);
    for (const ConeGlyph& g : glyphs) {
        float alpha = g.specular ? 0.9f : 0.35f + 0.65f * (maxWeight > 0.0f ? g.weight / maxWeight : 1.0f);
        glm::vec4 colour = g.specular ? glm::vec4(1.0f, 0.59f, 0.16f, alpha) : glm::vec4(0.27f, 0.9f, 1.0f, alpha);
        glm::vec3 end = g.apex + g.direction * length;
        lines.push_back({g.apex, end, colour, 2.0f});
        if (g.start < length) {
            glm::vec3 s = g.apex + g.direction * g.start;
            lines.push_back({s, s, colour, 6.0f});
        }
        glm::mat3 frame = vctTangentFrame(g.direction);
        float radius = length * g.tanHalf;
        constexpr int kSegments = 32;
        glm::vec3 previous = end + frame[0] * radius;
        for (int i = 1; i <= kSegments; ++i) {
            float a = 2.0f * glm::pi<float>() * float(i) / float(kSegments);
            glm::vec3 q = end + (frame[0] * std::cos(a) + frame[1] * std::sin(a)) * radius;
            lines.push_back({previous, q, colour, 1.5f});
            previous = q;
        }
        glm::vec4 faint(glm::vec3(colour), alpha / 3.0f);
        lines.push_back({g.apex, end + frame[0] * radius, faint, 1.0f});
        lines.push_back({g.apex, end - frame[0] * radius, faint, 1.0f});
    }
    if (!glyphs.empty()) {
        lines.push_back({glyphs[0].apex, glyphs[0].apex, glm::vec4(0.0f, 0.0f, 0.0f, 0.9f), 11.0f});
        lines.push_back({glyphs[0].apex, glyphs[0].apex, glm::vec4(1.0f, 1.0f, 1.0f, 0.9f), 8.0f});
    }
    return lines;
}

std::vector<Previewer> VCT::previewers(const FrameSettings&) const {
    // The voxels from the camera, at the finest level holding its target.
    auto voxels = [](VoxelViewSource source) {
        return [source](const PreviewContext& ctx) {
            VoxelViewParams vp;
            vp.viewProj = ctx.viewProj;
            vp.source = source;
            std::vector<VoxelGridView> grids = voxelGrids(ctx.views, ctx.settings, ctx.sceneBounds);
            vp.level = finestLevelHolding(grids, ctx.settings.camera.target);
            return PreviewImage{ctx.width, ctx.height, VoxelView().renderImage(grids, vp, ctx.width, ctx.height)};
        };
    };
    auto cones = [](const PreviewContext& ctx) {
        if (!ctx.focus || !ctx.sceneBounds.valid()) return std::vector<GlyphLine>{};
        const FrameSettings& fs = ctx.settings;
        float voxel = vctLevels(fs.vct, ctx.sceneBounds.min, ctx.sceneBounds.max, fs.camera.eye).front().cellSize;
        const SurfacePick& p = *ctx.focus;
        std::vector<ConeGlyph> glyphs = vctConeGlyphs(fs.vct, p.position, p.normal, fs.camera.eye, p.roughness, voxel);
        return coneGlyphLines(glyphs, kConeGlyphVoxels * ctx.overlayScale * voxel);
    };
    return {{"vct.voxels", "The voxel albedo seen from the camera (the finest level holding its target)", voxels(VoxelViewSource::Albedo), {}},
            {"vct.voxels.radiance", "The voxel radiance the cones trace, seen from the camera", voxels(VoxelViewSource::Radiance), {}},
            {"vct.cones", "The diffuse and specular cones traced at the focus pixel", {}, cones}};
}

}  // namespace gi
