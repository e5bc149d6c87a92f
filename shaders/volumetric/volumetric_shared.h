// Parameters, texture units and image bindings of volumetric lighting's passes, shared by C++
// (gi/volumetric/volumetric.cpp) and GLSL (shaders/volumetric/). The march and the composite
// read the G-buffer's depth on the lighting pass's unit (kUnitDepth, common/shared.h) and the
// march reads the light buffer (common/light.h).
//
// One uniform block, VolumeBlock, for the three passes: VolumeParams is the union of their
// fields, grouped by the passes that read them, as in envmap/envmap_shared.h. Each pass uploads
// the whole struct, built afresh. Layout as in ssao/ssao_shared.h: mat4, vec4 and scalars in
// groups of four, so std140 and C++ agree.
#ifdef __cplusplus
#pragma once
#endif
#include "common/shared.h"
#ifdef __cplusplus
namespace gi::shared {
#endif

// Lights per march dispatch: one shadow map of each type per light on the units below.
GI_CONST int kVolumeMaxLights = 4;
// blur (depth-aware) and composite: samples weigh exp(-|z_q - z| / (this z)) by their stored view
// distance, so light does not bleed across depth edges.
GI_CONST float kVolumeDepthSimilarity = 0.05;

// Uniform-buffer binding of VolumeBlock.
GI_CONST int kVolumeBlockBinding = 0;

// Texture units. Light i of a batch has its 2D map on kVolumeUnitShadow2D + i, its cube map on
// kVolumeUnitShadowCube + i, past the G-buffer's units.
GI_CONST int kVolumeUnitShadow2D = 9;
GI_CONST int kVolumeUnitShadowCube = kVolumeUnitShadow2D + kVolumeMaxLights;
// The march buffer the blur and the composite read.
GI_CONST int kVolumeUnitSource = 0;
// Image bindings: the one image a pass writes (the march buffer, the blurred one, the HDR image).
GI_CONST int kVolumeImageTarget = 0;

struct VolumeParams {
    // march, composite
    mat4 invViewProj;
    vec4 eye;          // xyz: the camera position, w unused
    // the medium (medium.glsl): march, composite
    vec4 boxMin;       // xyz, w unused
    vec4 boxMax;       // xyz, w unused
    float sigmaS;      // scattering coefficient
    float sigmaT;      // extinction coefficient
    // march, composite: the depth buffer's size
    int fullWidth;
    int fullHeight;
    // every pass: the march buffer's size
    int lowWidth;
    int lowHeight;
    // march
    float toFullX;     // full-size pixels per march pixel
    float toFullY;
    int samples;       // per light along the clipped ray
    int jitter;        // 1: per-pixel offset of the samples, 0: at the middle of each step
    int pcf;           // 1: 3x3 compared taps, 0: one
    int phase;         // phase function, kPhase* (volumetric/phase.glsl)
    float g;           // Henyey-Greenstein asymmetry
    float k;           // Schlick's k
    float intensity;   // in-scattered radiance scale
    float shadowSize;  // texels per side of the 2D shadow maps
    int lightFirst;    // the batch: light buffer entries lightFirst .. lightFirst + lightCount - 1
    int lightCount;
    int accumulate;    // 1: add to the march buffer (a later batch), 0: overwrite it
    // blur, composite
    int depthAware;    // 1: weight by view-distance similarity
    // composite
    int attenuateScene;  // 1: fade the lit scene by the view ray's transmittance in the medium
    float pad0;
    float pad1;
    float pad2;
};

#ifdef __cplusplus
inline constexpr const char* kVolumeBlockName = "VolumeBlock";
static_assert(offsetof(VolumeParams, eye) == 64 && offsetof(VolumeParams, sigmaS) == 112);
static_assert(offsetof(VolumeParams, toFullX) == 136 && offsetof(VolumeParams, lightFirst) == 176);
static_assert(offsetof(VolumeParams, attenuateScene) == 192 && sizeof(VolumeParams) == 208);
}  // namespace gi::shared
#else
layout(std140, binding = kVolumeBlockBinding) uniform VolumeBlock {
    VolumeParams uVolume;
};
#endif
