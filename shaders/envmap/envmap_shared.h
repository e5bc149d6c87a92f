// Parameters, texture units and image bindings of the environment's passes, shared by C++
// (gi/envmap/environment.cpp) and GLSL (shaders/envmap/). The shade and sky passes read the
// G-buffer on the lighting pass's units (kUnitNormal, kUnitMaterial, kUnitDepth, common/shared.h).
//
// One uniform block, EnvBlock, for the five passes: EnvParams is the union of their fields,
// grouped by the passes that read them. A block per pass would fit each pass more closely, but
// std140 blocks are active even where unread, so every program including this header would hold
// all of them, most left unbound; one block keeps one buffer and one binding per technique. Each
// pass uploads the whole struct, built afresh, so no pass reads a field another left behind.
// Layout as in ssao/ssao_shared.h: mat4, vec4 and scalars in groups of four, so std140 and C++
// agree.
#ifdef __cplusplus
#pragma once
#endif
#include "common/shared.h"
#ifdef __cplusplus
namespace gi::shared {
#endif

// Mips of the prefiltered chain at most: the length of EnvParams::mipRoughness.
GI_CONST int kEnvMaxMips = kSkyMaxMips;

// EnvParams::mode of the prefilter.
GI_CONST int kEnvPrefilterGGX = 0;
GI_CONST int kEnvPrefilterBeckmannCone = 1;
GI_CONST int kEnvPrefilterIrradiance = 2;

// Uniform-buffer binding of EnvBlock.
GI_CONST int kEnvBlockBinding = 0;

// Texture units. The source is the latlong (to_cube) or the source cube (prefilter); the
// irradiance cube sits apart from the G-buffer's units, which shade reads at the same time.
GI_CONST int kEnvUnitSource = 0;
GI_CONST int kEnvUnitPrefiltered = 0;
GI_CONST int kEnvUnitIrradiance = 3;
// Image bindings: the one image a pass writes (a cube level, the BRDF table, the sky's HDR
// target), or shade's two.
GI_CONST int kEnvImageTarget = 0;
GI_CONST int kEnvImageIndirect = 0;
GI_CONST int kEnvImageSpecular = 1;

struct EnvParams {
    // shade, sky
    mat4 invViewProj;
    vec4 eye;         // xyz: the camera position, w unused
    int width;        // of the image written, in pixels
    int height;
    float intensity;  // radiance scale
    float rotation;   // degrees about +y
    // shade
    int mipCount;     // mips in the chain
    float pad0;
    float pad1;
    float pad2;
    vec4 mipRoughness[kEnvMaxMips / 4];  // roughness of mip m at [m / 4][m % 4]
    // to_cube, prefilter, brdf_lut
    int size;         // face size of the level written (to_cube, prefilter), the table's side (brdf_lut)
    int rowOffset;    // prefilter: first row of this dispatch's band (a large mip is cut into bands)
    int sourceSize;   // prefilter: the source's mip-0 face size
    int mode;         // prefilter: kEnvPrefilterGGX, kEnvPrefilterBeckmannCone or kEnvPrefilterIrradiance
    float roughness;  // prefilter: the lobe's perceptual roughness; 0 copies the source
    float diskRadius; // prefilter, Beckmann cone: tan of the lobe's aperture
    int samples;      // prefilter and brdf_lut: per texel
    float pad3;
    vec4 sh[9];       // prefilter, irradiance: xyz, the map's 9 SH coefficients of E (w unused)
};

#ifdef __cplusplus
inline constexpr const char* kEnvBlockName = "EnvBlock";
static_assert(offsetof(EnvParams, eye) == 64 && offsetof(EnvParams, rotation) == 92);
static_assert(offsetof(EnvParams, mipRoughness) == 112 && offsetof(EnvParams, size) == 112 + kEnvMaxMips * 4);
static_assert(offsetof(EnvParams, sh) == 144 + kEnvMaxMips * 4 && sizeof(EnvParams) == 288 + kEnvMaxMips * 4);
}  // namespace gi::shared
#else
layout(std140, binding = kEnvBlockBinding) uniform EnvBlock {
    EnvParams uEnv;
};
#endif
