// The glTF metallic-roughness material of one draw, shared by C++ (gi/render/material_binding.cpp)
// and GLSL (common/material.glsl): every pass that rasterizes the scene's materials (G-buffer,
// shadow maps, LPV's RSMs, VCT's voxelization) uploads it per draw at kMaterialBlockBinding and
// binds the material's textures at kUnitBaseColor + slot, slots in the order of gi::TextureSlot
// (gi/scene/scene.h): base colour, metallic-roughness, normal, occlusion, emissive.
#ifdef __cplusplus
#pragma once
#endif
#include "common/shared.h"
#ifdef __cplusplus
namespace gi::shared {
#endif

GI_CONST int kMaterialBlockBinding = 1;  // the passes' own blocks take binding 0
GI_CONST int kMaterialSlotCount = 5;
GI_CONST int kSlotBaseColorTex = 0;        // sRGB
GI_CONST int kSlotMetallicRoughnessTex = 1;  // linear: G roughness, B metallic
GI_CONST int kSlotNormalTex = 2;           // linear tangent-space normal
GI_CONST int kSlotOcclusionTex = 3;        // linear: R
GI_CONST int kSlotEmissiveTex = 4;         // sRGB
// A program variant's key (MATERIAL_TEXTURES, common/material.glsl) holds a bit per slot with a
// texture and this one where the emissive factor is not zero.
GI_CONST int kMaterialVariantEmits = 1 << kMaterialSlotCount;
GI_CONST int kAlphaOpaque = 0;
GI_CONST int kAlphaMask = 1;
GI_CONST int kAlphaBlend = 2;  // a dithered mask: cut where alpha < a per-pixel threshold

struct MaterialParams {
    vec4 baseColor;        // linear RGBA factor
    vec4 emissive;         // rgb: emissiveFactor times KHR_materials_emissive_strength, w unused
    vec4 uvTransform[10];  // slot s: rows 2s and 2s + 1 of KHR_texture_transform's 2x3 map; row 2s's w is the texCoord set
    float alphaCutoff;     // kAlphaMask: fragments with alpha below it are cut
    int alphaMode;         // kAlpha*
    float roughness;       // perceptual factor, 0..1
    float metallic;        // factor, 0..1
    float normalScale;     // scales the normal map's x and y
    float occlusionStrength;  // 0..1
    int textureMask;       // bit s: slot s has a texture
    int doubleSided;       // 0: back faces emit nothing
};

#ifdef __cplusplus
inline constexpr const char* kMaterialBlockName = "MaterialBlock";
static_assert(sizeof(MaterialParams) == 224 && offsetof(MaterialParams, alphaCutoff) == 192);
}  // namespace gi::shared
#else
layout(std140, binding = kMaterialBlockBinding) uniform MaterialBlock {
    MaterialParams uMaterialParams;
};
#endif
