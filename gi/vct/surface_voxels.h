// The scene's surfaces in a voxel grid and the direct light they reflect: VCT's passes 1 and 2
// (gi/vct/vct.h describes them), as one piece that VCT and the diffusion technique
// (gi/diffusion/diffusion.h) both use.
//
//   - voxelize(): clears a region of a grid, then one draw of the scene, each triangle projected
//     along its dominant axis with conservative rasterization, writes diffuse albedo and normal
//     into r32ui volumes as atomic running averages of RGBA8 (a = the count; occupied where a > 0).
//   - inject(): per occupied voxel, the direct light of every light (shadow-mapped, area lights
//     exact) on each side of its mean normal, as the radiance each side leaves: albedo * E / pi,
//     in exitFront (along the mean normal) and exitBack (R11F_G11F_B10F).
// The grid is described by a VCTParams holding its fields (gridMin, cellSize, resolution,
// wrapOffset); the shaders are shaders/vct/{clear.comp, voxelize.*, inject.comp}.
#pragma once

#include "gi/gl/handle.h"
#include "gi/gl/shader.h"
#include "gi/gl/uniform_block.h"
#include "gi/render/material_binding.h"
#include "gi/render/material_programs.h"
#include "gi/render/pass.h"
#include "vct/vct_shared.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace gi {

// One grid's surface voxels: what voxelize() writes (albedo, normal and where the surface lies in
// its voxel: r32ui RGBA8 running averages with their count) and what inject() writes (the
// radiance each side of the mean normal leaves, front and back, R11F_G11F_B10F).
struct SurfaceVolumes {
    static constexpr GLenum kExitFormat = GL_R11F_G11F_B10F;  // positive HDR colour, half RGBA16F's size
    static constexpr size_t kBytesPerVoxel = 3 * 4 + 2 * 4;  // the five volumes below, for estimates before allocation
    gl::Texture albedo, normal, position;
    gl::Texture exitFront, exitBack;

    static SurfaceVolumes create(int resolution);
    size_t bytes() const;
    // Binds albedo, normal and position at their image units (vct_shared.h) with `access`.
    void bindVoxels(GLenum access) const;
    // Their entries for a pass's volumeMemory(), names suffixed (a level's "[k]").
    void describe(std::vector<VolumeMemory>& out, int resolution, const std::string& suffix = "") const;
};

class SurfaceVoxelizer {
public:

    SurfaceVoxelizer();

    // Clears [clipMin, clipMax) of the grid (in its toroidal place), then voxelizes the scene
    // into v's albedo, normal and position there: one conservative draw, or with `slicing` seed
    // 001's three draws, one along each axis, into the same volumes.
    void voxelize(const FrameContext& ctx, const vct::VCTParams& grid, const SurfaceVolumes& v, glm::ivec3 clipMin,
                  glm::ivec3 clipMax, bool slicing = false, GLuint sides = 0);
    // The direct light each side of every occupied voxel leaves, into v's exitFront and exitBack,
    // evaluated where its surface lies (position); lights in batches of kVCTMaxLights.
    // With `sides` (an r32ui volume six grids wide along x, voxelize() filled it) also the
    // radiance of each side into sidesRadiance (RGBA16F, as wide), as inject.comp describes.
    void inject(const FrameContext& ctx, const vct::VCTParams& grid, const SurfaceVolumes& v, GLuint sides = 0,
                GLuint sidesRadiance = 0);
    bool reloadShaders(std::string& log);
    // Voxelizations run since creation (tests: a static grid is not voxelized twice).
    int voxelizationCount() const { return mVoxelizationCount; }

private:
    gl::Program mClearProg, mInjectProg;
    gl::UniformBlock<vct::VCTParams> mBlock;
    MaterialBinding mMaterialBinding;
    MaterialPrograms mVoxelizePrograms;  // one per set of material textures (gi/render/material_programs.h)
    gl::Framebuffer mEmptyFBO;
    gl::Sampler mRepeat, mShadowSampler;
    int mFramebufferSize = 0;
    int mVoxelizationCount = 0;
};

}  // namespace gi
