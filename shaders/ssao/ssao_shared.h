// Constants and parameters of the SSAO pass shared by C++ (gi/ssao/ssao.cpp) and GLSL
// (shaders/ssao/). The passes read the G-buffer on the lighting pass's units (kUnitDepth,
// kUnitNormal) and the blur reads the raw AO on kUnitSource, all from common/shared.h.
//
// SSAOParams is the uniform block of both passes (gl::UniformBlock): one struct, written once
// here, laid out by std140 in GLSL and by the same rules in C++ because every member is a
// mat4, a vec4 or a scalar in a group of four (a bare vec3 or vec2 array is padded differently).
#ifdef __cplusplus
#pragma once
#endif
#include "common/shared.h"
#ifdef __cplusplus
namespace gi::shared {
#endif

// Size of the kernel array: SSAOSettings::sampleCount is at most this.
GI_CONST int kSSAOMaxSamples = 64;
// Side of the tiled rotation-noise pattern; a box blur 2 * 2 pixels wide covers one tile.
GI_CONST int kSSAONoiseSize = 4;

// Uniform-buffer binding of SSAOBlock.
GI_CONST int kSSAOBlockBinding = 0;

struct SSAOParams {
    int sampleCount;  // kernel points used, 1 .. kSSAOMaxSamples
    float radius;     // view and world units agree: the view matrix is rigid
    float bias;
    int blurRadius;   // ssao_blur: box half-width in pixels, >= 0
    float strength;   // ssao_blur: AO = visibility^strength, >= 0
    float pad0;
    float pad1;
    float pad2;
    mat4 view;        // world to view; its rotation takes normals into view space
    mat4 proj;
    mat4 invProj;
    vec4 kernel[kSSAOMaxSamples];                // xyz: hemisphere point about +Z, w unused
    vec4 noise[kSSAONoiseSize * kSSAONoiseSize];  // xy: (cos, sin) of the rotation about N
};

#ifdef __cplusplus
inline constexpr const char* kSSAOBlockName = "SSAOBlock";
static_assert(offsetof(SSAOParams, strength) == 16 && offsetof(SSAOParams, view) == 32);
static_assert(offsetof(SSAOParams, kernel) == 224 && offsetof(SSAOParams, noise) == 224 + 16 * kSSAOMaxSamples);
static_assert(sizeof(SSAOParams) == 224 + 16 * (kSSAOMaxSamples + kSSAONoiseSize * kSSAONoiseSize));
}  // namespace gi::shared
#else
layout(std140, binding = kSSAOBlockBinding) uniform SSAOBlock {
    SSAOParams uSSAO;
};
#endif
