// Previewers of voxel cone tracing: the voxels seen from a camera, and the cone set at a surface
// point as world-space glyphs (the editor projects them over its viewport).
//
// Voxel view (shaders/vct/voxel_view.frag): per pixel, the camera ray is clipped to one level's
// grid and marched voxel by voxel (Amanatides and Woo's 3D DDA) through the dense volume at a
// chosen mip. The first occupied voxel is drawn as the face of a cube the ray enters: its colour
// is the voxel's albedo, normal or radiance, times a fixed shade per face direction
// (top brightest, bottom darkest) with darkened voxel edges, so cubes read as cubes without a
// light. Rays that hit nothing show the background colour.
//   - Occupancy: the packed sources use the albedo volume's sample count (every voxelized voxel
//     has one); radiance uses opacity >= opacityThreshold, which
//     matters at coarse mips where opacity is fractional. Radiance is shown unpremultiplied.
//   - The packed r32ui volumes have no mips: their view is at mip 0 always.
//   - Clipmap levels are read through their toroidal offset, as the trace reads them.
// Sampler count: three (llvmpipe reads garbage past sixteen).
//
// Cone glyphs: the diffuse set of gi/vct/cone_set.h turned into world space with the tangent
// frame of shaders/vct/trace.glsl (vctTangentFrame mirrors tangentFrame there), and the specular
// cone along the reflected view direction with trace.comp's aperture. Each glyph is an axis from
// the apex, the start of the march after the nudge, and the aperture at a chosen length.
#pragma once

#include "gi/gl/handle.h"
#include "gi/gl/shader.h"
#include "gi/render/pass.h"
#include "gi/scene/scene.h"
#include "gi/vct/vct.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace gi {

// What a voxel view shows. The values are VCTParams::viewSource (shaders/vct/vct_shared.h).
// Emissive surfaces have no voxel volume of their own (they reach VCT as area lights).
enum class VoxelViewSource { Albedo = 0, Normal = 1, Radiance = 2 };
template <>
struct EnumNames<VoxelViewSource> {
    static constexpr std::array<std::pair<VoxelViewSource, const char*>, 3> values{
        {{VoxelViewSource::Albedo, "albedo"}, {VoxelViewSource::Normal, "normal"}, {VoxelViewSource::Radiance, "radiance"}}};
};

// One level's volumes and placement, as the voxel view reads them.
struct VoxelGridView {
    GLuint albedo = 0, normal = 0;  // r32ui packed RGBA8 (rgb mean, a count)
    GLuint radiance = 0;                          // RGBA16F premultiplied radiance + opacity, with mips
    int mipCount = 1;                             // of radiance
    int resolution = 0;                           // voxels per side
    VoxelBox box;
    glm::ivec3 wrap{0};  // clipmap: texel = (voxel + wrap) mod resolution; else 0
};

// The levels of a VCT after its last execute().
std::vector<VoxelGridView> voxelGrids(const VCT& vct, VCTMode mode);
// The same from a renderer's debug views (vct.albedo, vct.radiance, ... or vct.albedo0, ...),
// placed by vctLevels for the frame's settings and the scene's bounds, as VCT::execute placed
// them: for callers that hold a Renderer rather than the technique. Empty when the views are
// not VCT's.
std::vector<VoxelGridView> voxelGrids(const std::vector<DebugView>& views, const FrameSettings& fs, const Bounds& sceneBounds);

// The finest level whose grid holds p (cascaded and clipmap levels are nested around the
// camera, so the finest may hold only empty space in front of it); the coarsest when none does.
int finestLevelHolding(const std::vector<VoxelGridView>& grids, const glm::vec3& p);

struct VoxelViewParams {
    VoxelViewSource source = VoxelViewSource::Albedo;
    int level = 0;                  // grid level (cascaded and clipmap modes), clamped to those there are
    int mip = 0;                    // radiance mip, clamped; the packed sources show mip 0
    float exposure = 0.0f;          // EV, radiance
    float opacityThreshold = 0.25f; // radiance: a voxel is solid from this opacity
    bool edges = true;              // darken voxel edges
    glm::vec3 background{0.08f, 0.08f, 0.09f};  // display-encoded colour where the ray hits nothing
    glm::mat4 viewProj{1.0f};       // the camera (projection * view)
};

class VoxelView {
public:
    VoxelView();  // compiles the program; throws gi::Error on a shader error

    // Draws the view into `framebuffer` over (x, 0, width, height), display-encoded (sRGB).
    void render(const std::vector<VoxelGridView>& grids, const VoxelViewParams& params, GLuint framebuffer, int width,
                int height, int x = 0) const;
    // Renders into a new RGBA8 image, bottom row first.
    std::vector<uint8_t> renderImage(const std::vector<VoxelGridView>& grids, const VoxelViewParams& params, int width,
                                     int height) const;
    bool reloadShaders(std::string& log);

private:
    gl::Program mProgram;
    gl::UniformBlock<vct::VCTParams> mBlock;  // VCT's block, with the view's fields
    gl::VertexArray mVAO;
    gl::Sampler mNearest;  // integer volumes are incomplete under the default linear filters
};

// trace.glsl's tangentFrame: columns tangent, bitangent, n (Frisvad, with Duff et al.'s fix).
glm::mat3 vctTangentFrame(const glm::vec3& n);

struct ConeGlyph {
    glm::vec3 apex{0.0f}, direction{0.0f, 0.0f, 1.0f};  // world space, unit direction
    float start = 0.0f;     // where the march starts (the nudge), world distance from the apex
    float tanHalf = 0.0f;   // tan of half the aperture
    float weight = 1.0f;    // the cone's normalised weight (1 for the specular cone)
    bool specular = false;
};

// The cones trace.comp traces at a surface point p with unit normal n, seen from `eye`, with
// perceptual roughness `roughness`: the diffuse set, then (with s.specularCone) the specular
// cone. `voxelSize` is level 0's voxel, for the nudge.
std::vector<ConeGlyph> vctConeGlyphs(const VCTSettings& s, const glm::vec3& p, const glm::vec3& n, const glm::vec3& eye,
                                     float roughness, float voxelSize);

// The strokes that draw the glyphs drawn `length` long: each cone's axis, the aperture as a
// circle at its end with two silhouette lines to the apex, and a dot where the march starts
// (within the length). Diffuse cones cyan, more opaque the heavier; the specular cone orange.
// The apex itself as a white dot with a dark rim.
std::vector<GlyphLine> coneGlyphLines(const std::vector<ConeGlyph>& glyphs, float length);
// The cone glyphs' default length, in level-0 voxels.
inline constexpr float kConeGlyphVoxels = 12.0f;

}  // namespace gi
