#include "gi/render/material_binding.h"

namespace gi {

static_assert(int(kSlotCount) == shared::kMaterialSlotCount && int(kSlotNormal) == shared::kSlotNormalTex &&
                  int(kSlotEmissive) == shared::kSlotEmissiveTex && int(kSlotMetallicRoughness) == shared::kSlotMetallicRoughnessTex &&
                  int(kSlotOcclusion) == shared::kSlotOcclusionTex,
              "gi::TextureSlot and common/material_shared.h list the slots alike");

shared::MaterialParams materialParams(const Material& m) {
    shared::MaterialParams p{};
    p.baseColor = m.baseColor;
    p.emissive = glm::vec4(m.emissive, 0.0f);
    for (int s = 0; s < kSlotCount; ++s) {
        const TextureTransform& t = m.uvTransform[s];
        p.uvTransform[2 * s] = glm::vec4(t.row(0), float(t.texCoord));
        p.uvTransform[2 * s + 1] = glm::vec4(t.row(1), 0.0f);
    }
    p.textureMask = materialTextureMask(m);
    p.alphaCutoff = m.alphaCutoff;
    p.alphaMode = m.alphaMode == AlphaMode::Mask ? shared::kAlphaMask : m.alphaMode == AlphaMode::Blend ? shared::kAlphaBlend : shared::kAlphaOpaque;
    p.roughness = m.roughness;
    p.metallic = m.metallic;
    p.normalScale = m.normalScale;
    p.occlusionStrength = m.occlusionStrength;
    p.doubleSided = m.doubleSided ? 1 : 0;
    return p;
}

int materialTextureMask(const Material& m) {
    int mask = 0;
    for (int s = 0; s < kSlotCount; ++s)
        if (m.texture(s) >= 0) mask |= 1 << s;
    return mask;
}

MaterialBinding::MaterialBinding() : mBlock(shared::kMaterialBlockName, GLuint(shared::kMaterialBlockBinding)) {}

void MaterialBinding::begin(GLuint sampler) const {
    for (int s = 0; s < kSlotCount; ++s) glBindSampler(GLuint(shared::kUnitBaseColor + s), sampler);
}

void MaterialBinding::bind(const GPUScene& scene, const Material& m) const {
    mBlock.set(materialParams(m));
    for (int s = 0; s < kSlotCount; ++s)
        if (m.texture(s) >= 0) glBindTextureUnit(GLuint(shared::kUnitBaseColor + s), scene.texture(m.texture(s)));
}

void MaterialBinding::end() const {
    for (int s = 0; s < kSlotCount; ++s) glBindSampler(GLuint(shared::kUnitBaseColor + s), 0);
}

}  // namespace gi
