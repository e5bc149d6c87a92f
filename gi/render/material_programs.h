// Programs that rasterize the scene's materials, one per set of texture slots a material has and
// whether it emits (MATERIAL_TEXTURES in common/material.glsl), built when a material first needs it.
//
// Why: a CPU rasterizer runs both sides of a branch, masked, even where the condition is the
// same for every invocation, so the general program (which tests the material's textureMask at
// run time) read all five material textures for every fragment, present or not. Used by the
// G-buffer, LPV's RSMs and the surface voxelizer (VCT, diffusion). Sponza's materials have a base
// colour texture only; its G-buffer at 800x600 on llvmpipe took 187 ms before and 136 ms with the
// variants (technique none, three alternating rounds of the two binaries). A variant leaves out
// only the reads the run-time test would skip, so the pixels are the same.
#pragma once

#include "gi/gl/shader.h"
#include "gi/render/material_binding.h"

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace gi {

class MaterialPrograms {
public:
    // Every program built must declare `binding`'s material block, and what `requireBlocks`
    // requires of it (the pass's own uniform block). `binding` must outlive this.
    MaterialPrograms(std::string name, std::vector<gl::StageSource> stages, std::vector<std::string> defines,
                     const MaterialBinding& binding, std::function<void(gl::Program&)> requireBlocks);

    // The program for this material's texture slots and emission. A variant that does not build (its shader
    // edited on disk into an error since the last reload) falls back to the general program,
    // which draws the same pixels; reload() tries again.
    // With `specialise` false: the general program for every material.
    const gl::Program& of(const Material& m, bool specialise = true);
    // Rebuilds the general program from disk, keeping the last good one on failure (the log says
    // why); on success the variants are dropped, to be built again from the new source.
    bool reload(std::string& log);

private:
    void prepare(gl::Program& p) const;  // the block requirements

    std::string mName;
    std::vector<gl::StageSource> mStages;
    std::vector<std::string> mDefines;
    const MaterialBinding& mBinding;
    std::function<void(gl::Program&)> mRequireBlocks;
    gl::Program mGeneral;  // every texture slot tested at run time
    std::map<int, std::unique_ptr<gl::Program>> mVariants;  // by texture mask; null: did not build
};

}  // namespace gi
