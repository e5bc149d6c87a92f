// Parameters, buffer bindings, image bindings and texture units of the LPV's passes, shared by
// C++ (gi/lpv/lpv.cpp) and GLSL (shaders/lpv/). The geometry pass and shade read the G-buffer on
// the lighting pass's units (kUnitNormal, kUnitDepth, common/shared.h); the RSM pass reads the
// light buffer (common/light.h) and the material (common/material_shared.h).
//
// One uniform block, LPVBlock, for the eight programs: LPVParams is the union of their fields,
// grouped by the passes that read them, as in envmap/envmap_shared.h (std140 blocks are active
// even where unread, so one block keeps one buffer and one binding). Each pass uploads the whole
// struct, built afresh. Layout as in ssao/ssao_shared.h: mat4, vec4 and scalars in groups of
// four, so std140 and C++ agree.
#ifdef __cplusplus
#pragma once
#endif
#include "common/shared.h"
#ifdef __cplusplus
namespace gi::shared {
#endif

// Cascades at most (LPVSettings::cascadeCount's range): the length of LPVParams::cascadeMinCell.
GI_CONST int kLPVMaxCascades = 4;
// SH volumes per cascade in shade: R, G and B.
GI_CONST int kLPVSHChannels = 3;
// shade: the outer fraction of a cascade's extent over which it blends into the next.
GI_CONST float kLPVCascadeBlend = 0.1;
// geometry: a G-buffer surfel's area grows as 1 / |cos| towards grazing views, up to 1 / this.
GI_CONST float kLPVMinSurfelCosine = 0.2;
// rsm: a texel's area over cos theta is capped at 1 / this for light grazing the surface.
GI_CONST float kLPVMinRSMCosine = 0.05;
// shade, bounce: radiance is the accumulated SH intensity over the cell face area times this.
// Every lobe the LPV propagates starts as a clamped cosine lobe (a VPL, a bounce's re-injection),
// and propagation's first step returns 1.1382 times such a lobe's flux: the 2-band lobe is
// (1/4 + cos/2) / pi per unit flux, negative behind, and the gather clamps that back lobe away
// (+1/8) and samples the rest at the 30 face directions. From the second step on the kernel
// keeps the flux (within 0.1 % over 32 steps). This is 1 / 1.1382, so the propagated light
// carries the flux injected (tests/lpv_propagation_test.cpp measures both). The injection itself,
// summed into the same accumulator, is scaled alike (one factor for the whole volume).
GI_CONST float kLPVRadianceScale = 0.8786;

// Uniform-buffer binding of LPVBlock.
GI_CONST int kLPVBlockBinding = 0;

// Shader storage bindings (the light buffer sits apart, at kLightBufferBinding).
GI_CONST int kLPVBufferInject = 0;           // inject: the SH grid it adds to
GI_CONST int kLPVBufferGeometry = 0;         // geometry: the corner blocking it adds to
GI_CONST int kLPVBufferGeometryRSM = 0;      // geometry_resolve: blocking from the RSMs
GI_CONST int kLPVBufferGeometryGBuffer = 1;  // geometry_resolve: blocking from the G-buffer
GI_CONST int kLPVBufferAccum = 2;            // resolve reads it (propagate adds to it through kLPVImagePropagateAccum)
GI_CONST int kLPVBufferTransmit = 3;         // transmit writes it, sky reads it (propagate through kLPVUnitPropagateTransmit)
GI_CONST int kLPVBufferGeometryAlbedo = 1;   // geometry: the corners' albedo (RGB x coverage, coverage) it adds to
// bounce: a bounce's propagated light, its injection (replaced by the next bounce's), the total
// shade reads, and the corners' blocking (RSM, G-buffer) and albedo.
// (bounce reads and writes its buffers through buffer textures and images, below.)

// Image bindings. The RSM's three images (inject reads all, geometry normal and position).
GI_CONST int kLPVImageFlux = 0;
GI_CONST int kLPVImageNormal = 1;
GI_CONST int kLPVImagePosition = 2;
GI_CONST int kLPVImageAlbedo = 3;  // the RSM's diffuse albedo (geometry reads it)
// geometry_resolve's two volumes.
GI_CONST int kLPVImageGeometryRSM = 0;
GI_CONST int kLPVImageGeometryGBuffer = 1;
// resolve's three SH volumes.
GI_CONST int kLPVImageSHR = 0;
GI_CONST int kLPVImageSHG = 1;
GI_CONST int kLPVImageSHB = 2;
// shade's output.
GI_CONST int kLPVImageIndirect = 0;
GI_CONST int kLPVImageSpecular = 1;  // sky: the indirect specular
// sky: the environment's prefiltered chain (the G-buffer's indirect unit, unused there)
GI_CONST int kLPVUnitSky = 5;

// Texture units. transmit samples the two geometry volumes.
GI_CONST int kLPVUnitGeometryRSM = 0;
GI_CONST int kLPVUnitGeometryGBuffer = 1;
// propagate: buffer textures over the step's input and the transmittances, and buffer images over
// its output and the accumulator (propagate.comp says why not shader storage)
GI_CONST int kLPVUnitPropagateSource = 0;
GI_CONST int kLPVUnitPropagateTransmit = 1;
GI_CONST int kLPVImagePropagateDestination = 0;
GI_CONST int kLPVImagePropagateAccum = 1;
// bounce, likewise: the gathered light, the two geometry volumes and the albedo as buffer
// textures; the injection (replaced) and the total (added to) as buffer images.
GI_CONST int kLPVUnitBounceGather = 0;
GI_CONST int kLPVUnitBounceGeometryRSM = 1;
GI_CONST int kLPVUnitBounceGeometryGBuffer = 2;
GI_CONST int kLPVUnitBounceAlbedo = 3;
GI_CONST int kLPVImageBounceInject = 0;
GI_CONST int kLPVImageBounceTotal = 1;
// resolve: the accumulated SH as a buffer texture
GI_CONST int kLPVUnitResolveAccum = 0;
// shade: channel c of cascade k on kLPVUnitSH + kLPVSHChannels * k + c, past the G-buffer's units.
GI_CONST int kLPVUnitSH = 8;

struct LPVParams {
    // geometry (G-buffer surfels), shade
    mat4 invViewProj;
    // rsm
    mat4 lightViewProj;
    // (the draw's material is MaterialBlock's, common/material_shared.h)
    // inject, geometry
    vec4 gridMinCell;  // the cascade's grid: xyz its minimum corner, w its cell size
    // geometry (G-buffer surfels)
    vec4 cameraPos;    // xyz, w unused
    // shade
    vec4 cascadeMinCell[kLPVMaxCascades];  // cascade k: xyz its minimum corner, w its cell size
    // every pass but rsm
    int resolution;    // cells per side of a cascade
    // inject, geometry: the source image (an RSM or the G-buffer); shade: the image written
    int width;
    int height;
    // rsm
    int lightIndex;    // the light's entry in the light buffer
    float texelArea;   // directional: projected world area of a texel
    float texelSolidAngle;  // spot, cube face: solid angle of the map's centre texel
    // inject
    float nudge;       // cells along the surfel's normal
    // geometry
    int fromGBuffer;   // 1: surfels from the G-buffer, 0: from an RSM
    int stride;        // G-buffer: one sample every `stride` pixels
    float pixelAngle;  // G-buffer: world size of a pixel at distance 1
    // propagate
    int blocking;      // 1: scale each face's flux by its transmittance
    // transmit
    float occlusionStrength;
    // shade
    int cascadeCount;
    float intensity;
    float damping;     // self-illumination damping, 0 .. 1
    // rsm
    int cubeFace;      // 1: a face of a point light's cube RSM (texel solid angles off the face's axis)
    // sky: the environment (FrameContext::sky) times the sky's visibility through cascade
    // skyCascade's face transmittances (sky.comp)
    float skyIntensity;
    float skyRotation; // degrees about +y
    int skyCascade;    // -1: no occlusion (the sky is unoccluded)
    int skyMipCount;   // mips in the prefiltered chain
    vec4 skySH[9];     // E / pi of the map as 9 SH coefficients (xyz)
    vec4 skyMipRoughness[kSkyMaxMips / 4];  // the prefiltered chain: roughness of mip m at [m / 4][m % 4]
};

#ifdef __cplusplus
inline constexpr const char* kLPVBlockName = "LPVBlock";
static_assert(offsetof(LPVParams, gridMinCell) == 128 && offsetof(LPVParams, cascadeMinCell) == 160);
static_assert(offsetof(LPVParams, resolution) == 160 + 16 * kLPVMaxCascades);
static_assert(offsetof(LPVParams, nudge) == 184 + 16 * kLPVMaxCascades && offsetof(LPVParams, cubeFace) == 220 + 16 * kLPVMaxCascades);
static_assert(offsetof(LPVParams, skyIntensity) == 224 + 16 * kLPVMaxCascades && offsetof(LPVParams, skySH) == 240 + 16 * kLPVMaxCascades);
static_assert(sizeof(LPVParams) == 240 + 16 * kLPVMaxCascades + 9 * 16 + 4 * kSkyMaxMips);
}  // namespace gi::shared
#else
layout(std140, binding = kLPVBlockBinding) uniform LPVBlock {
    LPVParams uLPV;
};
#endif
