// Parameters and bindings of the diffusion technique's passes (gi/diffusion/diffusion.h), shared
// by C++ and GLSL, as lpv/lpv_shared.h. One block, DiffusionBlock, for every pass; layout in
// groups of four so std140 and C++ agree.
#ifdef __cplusplus
#pragma once
#endif
#include "common/shared.h"
#ifdef __cplusplus
namespace gi::shared {
#endif

GI_CONST int kDiffusionBlockBinding = 0;

// Image bindings of the surface voxels (gi/vct/surface_voxels.h writes them).
GI_CONST int kDiffusionImageAlbedo = 0;     // r32ui RGBA8 running average, a > 0: occupied
GI_CONST int kDiffusionImageNormal = 1;     // r32ui RGBA8 running average of n * 0.5 + 0.5
GI_CONST int kDiffusionImageExitFront = 3;  // R11F_G11F_B10F radiance leaving along the mean normal
GI_CONST int kDiffusionImageExitBack = 4;   // and against it
GI_CONST int kDiffusionImageIndirect = 2;   // shade: E / pi, rgba16f
GI_CONST int kDiffusionImageView = 2;       // resolve: the accumulation as an rgba16f volume
GI_CONST int kDiffusionImageViewInFlight = 3;  // resolve: the light in flight after the last step
GI_CONST int kDiffusionImageViewBounces = 4;   // resolve: the mean bounce order of the accumulated light

// Shader storage bindings (7 to 10 are the frame's light buffers, common/light.h).
GI_CONST int kDiffusionBufferSource = 0;       // 3 vec4 (R, G, B SH) per cell: the light in flight
GI_CONST int kDiffusionBufferDestination = 1;  // the next step's
GI_CONST int kDiffusionBufferAccum = 3;        // 3 vec4 per cell: incoming light summed over the steps (occupied cells)
// Bounce orders (one float per cell): the flux-weighted mean bounce order of the light in flight
// (source and destination, ping-pong beside the light), and of the light accumulated, summed as
// order times flux (the accumulation's band 0 gives the flux to divide by).
GI_CONST int kDiffusionBufferOrderDestination = 5;
GI_CONST int kDiffusionBufferOrderAccum = 6;
// emit and gather read the grids above through buffer textures and write them through buffer
// images over the same storage (lpv/propagate.comp says why not shader storage on llvmpipe).
// The outgoing flux: 6 vec4 per cell, the flux (rgb) leaving through each face, and its order (w).
GI_CONST int kDiffusionUnitStepSource = 0;       // emit: the light in flight; gather: the outgoing flux
GI_CONST int kDiffusionUnitStepOrder = 1;        // emit: the source's bounce orders (r32f)
GI_CONST int kDiffusionImageStepOutgoing = 2;    // emit writes the outgoing flux
GI_CONST int kDiffusionImageStepDestination = 2; // gather: the next step's light
GI_CONST int kDiffusionImageStepAccum = 3;       // gather: the accumulation
GI_CONST int kDiffusionImageStepOrderDestination = 4;  // gather: r32f
GI_CONST int kDiffusionImageStepOrderAccum = 5;        // gather: r32f
// shade reads the accumulation through a buffer texture too (3 texels per cell), beside the
// G-buffer's normal and depth (kUnitNormal, kUnitDepth).
GI_CONST int kDiffusionUnitShadeAccum = 2;
// smooth: the accumulation in (a buffer texture) and the shaded accumulation out (a buffer image).
GI_CONST int kDiffusionUnitSmoothSource = 2;
GI_CONST int kDiffusionImageSmoothDestination = 3;
// smooth: neighbours on the same surface have mean normals within acos(this) (18 degrees) of the cell's.
GI_CONST float kDiffusionSmoothMinCosine = 0.95;

// The face transfer (seed 001 eq. 3.2.1-3.2.3, corrected, see propagate.glsl): the 2-band SH of
// the indicator of the solid angle a cell's face subtends from its centre (2 pi / 3), towards
// axis d: (kFaceBand0, kFaceBand1 * d in the basis's order). kFaceBand0 = (2 pi / 3) * Y00;
// kFaceBand1 = the face's projected solid angle 2 sqrt(2) atan(1 / sqrt(2)) times Y1.
GI_CONST float kFaceSolidAngle = 2.0943951;
GI_CONST float kFaceBand0 = 0.5908180;
GI_CONST float kFaceBand1 = 0.8505786;
// Shading: a beam's lobe (face lobe / solid angle) under the clamped cosine head on gives
// (kFaceBand0 kCosLobe0 + kFaceBand1 kCosLobe1) / kFaceSolidAngle = 0.66560 of its flux; this
// undoes that, so the light arriving head on gives its flux per area as irradiance.
GI_CONST float kDiffusionIrradianceScale = 1.5024209;

struct DiffusionParams {
    vec4 gridMin;      // xyz: world corner of cell 0; w: cell size
    int resolution;
    int albedoMode;    // 0: the voxel's albedo; 1: 0.5 (seed 001's constant)
    float intensity;
    float nudge;       // shade: cells along the pixel's normal
    mat4 invViewProj;  // shade: pixel to world
    int width;
    int height;
    float pad1;
    float pad2;
};

#ifdef __cplusplus
inline constexpr const char* kDiffusionBlockName = "DiffusionBlock";
static_assert(sizeof(DiffusionParams) == 112);
}  // namespace gi::shared
#else
layout(std140, binding = kDiffusionBlockBinding) uniform DiffusionBlock {
    DiffusionParams uDiffusion;
};
#endif
