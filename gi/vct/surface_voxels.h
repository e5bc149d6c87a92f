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

namespace gi {

class SurfaceVoxelizer {
public:
    // The exit radiance's format: positive HDR colour, no alpha, half RGBA16F's size.
    static constexpr GLenum kExitFormat = GL_R11F_G11F_B10F;
    static constexpr size_t kBytesPerVoxel = 3 * 4 + 2 * 4;  // albedo, normal, position (r32ui); exit front, back

    SurfaceVoxelizer();

    // Clears [clipMin, clipMax) of the grid (in its toroidal place), then voxelizes the scene
    // into albedo, normal and position (GL_R32UI volumes of grid.resolution^3; position: where
    // the surface lies in its voxel) there: one conservative draw, or with `slicing` seed 001's
    // three draws, one along each axis, into the same volumes.
    void voxelize(const FrameContext& ctx, const vct::VCTParams& grid, GLuint albedo, GLuint normal, GLuint position,
                  glm::ivec3 clipMin, glm::ivec3 clipMax, bool slicing = false, GLuint sides = 0);
    // The direct light each side of every occupied voxel leaves, into exitFront and exitBack
    // (kExitFormat volumes of the grid's size), evaluated where its surface lies (position);
    // lights in batches of kVCTMaxLights.
    // With `sides` (an r32ui volume six grids wide along x, voxelize() filled it) also the
    // radiance of each side into sidesRadiance (RGBA16F, as wide), as inject.comp describes.
    void inject(const FrameContext& ctx, const vct::VCTParams& grid, GLuint albedo, GLuint normal, GLuint position,
                GLuint exitFront, GLuint exitBack, GLuint sides = 0, GLuint sidesRadiance = 0);
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
