// Per-draw material state for every pass that rasterizes the scene's materials (G-buffer,
// shadow maps, LPV's RSMs, VCT's voxelization): the MaterialBlock (common/material_shared.h)
// and the material's textures on kUnitBaseColor + slot, read by common/material.glsl.
#pragma once

#include "common/material_shared.h"
#include "gi/gl/handle.h"
#include "gi/gl/uniform_block.h"
#include "gi/render/gpu_scene.h"

namespace gi {

// The block's contents for a material.
shared::MaterialParams materialParams(const Material& m);
// The material's texture slots as MaterialParams::textureMask has them (bit s: slot s).
int materialTextureMask(const Material& m);

class MaterialBinding {
public:
    MaterialBinding();
    // Makes `program` check that it declares the block (throws gi::Error naming the shader).
    void requireIn(gl::Program& program) const { mBlock.requireIn(program); }
    // Binds `sampler` (0 for the textures' own state) on every material texture unit.
    void begin(GLuint sampler) const;
    // Uploads the material's block and binds its textures; call inside GPUScene::draw.
    void bind(const GPUScene& scene, const Material& m) const;
    // Unbinds the samplers begin() bound.
    void end() const;

private:
    gl::UniformBlock<shared::MaterialParams> mBlock;
};

}  // namespace gi
