#include "gi/render/material_programs.h"

#include "gi/util/error.h"

namespace gi {

MaterialPrograms::MaterialPrograms(std::string name, std::vector<gl::StageSource> stages, std::vector<std::string> defines,
                                   const MaterialBinding& binding, std::function<void(gl::Program&)> requireBlocks)
    : mName(std::move(name)),
      mStages(std::move(stages)),
      mDefines(std::move(defines)),
      mBinding(binding),
      mRequireBlocks(std::move(requireBlocks)),
      mGeneral(mName, mStages, mDefines) {
    prepare(mGeneral);
}

void MaterialPrograms::prepare(gl::Program& p) const {
    mBinding.requireIn(p);
    mRequireBlocks(p);
}

const gl::Program& MaterialPrograms::of(const Material& m, bool specialise) {
    if (!specialise) return mGeneral;
    const int mask = materialTextureMask(m) | (m.emissive != glm::vec3(0.0f) ? shared::kMaterialVariantEmits : 0);
    auto it = mVariants.find(mask);
    if (it == mVariants.end()) {
        std::unique_ptr<gl::Program> p;
        try {
            std::vector<std::string> defines = mDefines;
            defines.push_back("MATERIAL_TEXTURES=" + std::to_string(mask));
            p = std::make_unique<gl::Program>(mName + "[textures " + std::to_string(mask) + "]", mStages, defines);
            prepare(*p);
        } catch (const Error&) {
            p.reset();  // the general program draws it
        }
        it = mVariants.emplace(mask, std::move(p)).first;
    }
    return it->second ? *it->second : mGeneral;
}

bool MaterialPrograms::reload(std::string& log) {
    if (!mGeneral.reload()) {
        log += mGeneral.log() + "\n";
        return false;
    }
    mVariants.clear();
    return true;
}

}  // namespace gi
