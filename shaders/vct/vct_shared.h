// Constants shared by the VCT host code (gi/vct) and its shaders: texture units, image and
// buffer bindings, limits, and the parameters of every VCT pass. C++ includes it as
// "vct/vct_shared.h", GLSL through the #include expander.
//
// One uniform block, VCTBlock, for all the passes (as envmap/envmap_shared.h explains): VCTParams
// is the union of their fields, grouped by the passes that read them, and each pass uploads the
// whole struct, built afresh. Its layout does not depend on the VCT_LEVELS, VCT_ANISO and VCT_SH
// variants: the per-level arrays have kVCTMaxLevels entries in every one. Layout as in
// ssao/ssao_shared.h: mat4, vec4, ivec4 and scalars in groups of four, so std140 and C++ agree.
#ifdef __cplusplus
#pragma once
#endif
#include "common/shared.h"
#ifdef __cplusplus
namespace gi::vct {
using namespace gi::shared;
#endif

GI_CONST int kVCTMaxCones = 32;        // diffuse cones per set (gi/vct/cone_set.h kMaxCones)
GI_CONST int kVCTMaxLights = 4;        // lights injected per dispatch (more run in further dispatches)
GI_CONST int kVCTMaxLevels = 6;        // cascaded / clipmap levels
GI_CONST int kVCTAtomicTries = 256;    // cap of the running-average compare-and-swap loop (seed 000 caps at 1000)

// Texture units of the trace, bounce and inject passes (above the G-buffer units 0..8).
GI_CONST int kVCTUnitRadiance = 9;     // premultiplied radiance + opacity, with mips (one per level: 9 + level)
GI_CONST int kVCTUnitAniso = 16;       // the six directional volumes +X -X +Y -Y +Z -Z side by side along x
GI_CONST int kVCTUnitSH = 22;          // R, G, B SH coefficient volumes (22..24)
GI_CONST int kVCTUnitShadow2D = 9;     // inject: 2D shadow maps, one per light of the batch (9..12)
GI_CONST int kVCTUnitShadowCube = 13;  // inject: cube shadow maps (13..16)
GI_CONST int kVCTUnitSky = 25;         // trace: the environment's prefiltered cube (FrameContext::sky)
GI_CONST int kVCTUnitMipSource = 0;    // mip: the volume read
GI_CONST int kVCTUnitMipSourceCoverage = 1;  // mip (anisotropic): the coverage atlas read
GI_CONST int kVCTUnitMipSides = 2;     // mip (anisotropic, the atlas's mip 0): level 0's sides
GI_CONST int kVCTUnitCoverageOctants = 18;  // trace: the facing coverage by octant (octants.comp)
GI_CONST int kVCTUnitCentroid = 17;    // trace, bounce (faceSides): the centroid volume, with mips (resolve.comp)
GI_CONST int kVCTUnitLowIndirect = 0;  // upsample: the traced images (beside the G-buffer's normal and depth)
GI_CONST int kVCTUnitLowSpecular = 3;
GI_CONST int kVCTUnitLowGuide = 2;     // upsample: each traced pixel's normal and view depth (trace.comp writes them)
GI_CONST int kVCTUnitViewOccupancy = 0;  // voxel view (gi/vct/vct_views.h): packed albedo, a > 0 where voxelized
GI_CONST int kVCTUnitViewPacked = 1;     // the packed source shown (albedo or normal)
GI_CONST int kVCTUnitViewRadiance = 2;   // premultiplied radiance + opacity, with mips

// Image bindings. The voxel volumes keep one binding in every pass that reads or writes them;
// the volumes a pass writes besides take the bindings that pass leaves free.
GI_CONST int kVCTImageAlbedo = 0;      // r32ui running averages (clear, voxelize, inject, resolve, compact, bounce)
GI_CONST int kVCTImageNormal = 1;
GI_CONST int kVCTImageExitFront = 3;   // radiance each side leaves (inject writes, resolve and bounce read)
GI_CONST int kVCTImageExitBack = 4;
GI_CONST int kVCTImageRadiance = 5;    // resolve: the traced radiance volume
GI_CONST int kVCTImageSHR = 6;         // resolve: the SH volumes; B takes binding 2, free there
GI_CONST int kVCTImageSHG = 7;
GI_CONST int kVCTImageSHB = 2;
GI_CONST int kVCTImageCentroid = 8;   // resolve (faceSides): the centroid volume written (voxel centre times opacity, opacity)
GI_CONST int kVCTImageBouncedFront = 5;  // bounce: direct plus gathered light, which resolve reads next
GI_CONST int kVCTImageBouncedBack = 6;
GI_CONST int kVCTImagePosition = 9;   // r32ui running average of where the surface lies in its voxel (clear, voxelize; inject, bounce read)
GI_CONST int kVCTImageSides = 2;       // voxelize, clear, inject: r32ui per-side normals, six slabs along x
GI_CONST int kVCTImageSidesRadiance = 5;  // inject: RGBA16F per-side exit radiance times coverage, coverage
GI_CONST int kVCTImageSidesDirect = 7;     // bounce (faceSides): inject's per-side radiance, read
GI_CONST int kVCTImageSidesBounced = 8;    // bounce (faceSides): it plus each side's gathered light, written
GI_CONST int kVCTImageMipDest = 0;     // mip: the level written
GI_CONST int kVCTImageMipDestCoverage = 1;  // mip (anisotropic): the coverage atlas's level written
GI_CONST int kVCTImageOctants = 0;     // octants: the coverage by octant, the level written
GI_CONST int kVCTImageIndirect = 0;    // trace (at traceScale) and upsample (full size): diffuse
GI_CONST int kVCTImageSpecular = 1;    // and specular indirect light
GI_CONST int kVCTImageGuide = 2;       // trace: the traced pixels' normal and view depth (w < 0: no surface), RGBA32F

// Shader storage bindings of compact.comp's occupied-voxel list, which bounce.comp reads.
GI_CONST int kVCTBufferDispatch = 0;   // indirect dispatch arguments and the entry count
GI_CONST int kVCTBufferVoxels = 1;     // the entries
// trace.comp's work counters, each 64-bit as (low, high) uints: kVCTWork* index the pairs.
GI_CONST int kVCTBufferWork = 2;
GI_CONST int kVCTWorkPixels = 0;       // traced pixels that hold a surface
GI_CONST int kVCTWorkCones = 1;        // cones traced
GI_CONST int kVCTWorkSamples = 2;      // cone steps (each samples the level that holds it, two in a level's blend band)
GI_CONST int kVCTWorkFetches = 3;      // texture calls made by those samples
GI_CONST int kVCTWorkCount = 4;

// Uniform-buffer binding of VCTBlock.
GI_CONST int kVCTBlockBinding = 0;

// The cone march (trace.glsl; the editor's cone glyphs start where it starts).
GI_CONST float kVCTMinStartCosine = 0.25;  // n.w clamp of the start offset without face sides: grazing cones would start far away
GI_CONST int kVCTMaxConeSteps = 512;       // a cone stops after this many samples whatever its length
GI_CONST float kVCTOpaque = 0.99;          // a cone stops once its gathered opacity reaches this
GI_CONST float kVCTLevelBlend = 0.1;       // fraction of a level's extent over which it blends into the next
// Cone samples read this many mip levels finer than the cone's diameter (trace.glsl explains
// why). Swept on VCTGL.NudgeRemovesSelfOcclusionOnAFlatFloor (share of the analytic value at the
// default nudge 3, the panel lit from below) and
// VCTGL.IndirectLightDoesNotDependOnWhereTheSceneFallsInTheGrid (worst change of the mean over
// the three shifts; the bound is 5 %):
//   0 (the cone's width): 43 %, 4.8 %   1.0: 80 %, 1.6 %   1.25: 89 %, 3.8 %
//   1.5: 95 %, 6.9 %   log2(3): 97 %, 8.3 %   2.0: 97 %, 17.6 % (gaps between samples)
GI_CONST float kVCTFootprintLod = 1.25;
// Face sides (trace.glsl): a sample whose content's centroid lies less than kVCTOwnPlaneStart
// voxels above the plane through the cone's apex (along the receiver's normal) is the receiver's
// own surface and is dropped, fading back in over the next kVCTOwnPlaneRamp voxels. Swept on the
// Cornell presets at 128x96 (start / ramp 0 / 1, 0.5 / 1, 1 / 1, 2 / 2): SSIM within 0.003, and
// the two-room leak 3.5-3.7 %.
GI_CONST float kVCTOwnPlaneStart = 1.0;
GI_CONST float kVCTOwnPlaneRamp = 1.0;
// bounce.comp with vct.bounceTail: the last bounce's gathered light is divided by
// max(1 - albedo * enclosure, this), so the bounces left out add at most 1 / this times it.
GI_CONST float kVCTTailMinRemainder = 0.2;

// Where a cone's march starts: nudge voxel diagonals out from the surface (seed 000 eq. 3.4).
// Without face sides it is divided by n.w, so a cone leaving at a grazing angle still clears the
// surface's voxels. With them every sample drops the receiver's own plane (kVCTOwnPlaneStart), which
// is what the division was for, and it is left out: near a wall it started a grazing cone up to
// 4x further out, past the wall, in the next room. The two-room leak (VCTGL.TwoRoomLeak, face
// sides, tail, three bounces) 6.1 -> 4.1 %; at the other alignments of the wall 24.5 / 23.8 /
// 23.0 -> 21.2 / 20.3 / 19.5 %. On 21 scenes at 128x96 with no preset against 1024-spp
// references (17 of those of vct_settings.h's faceSides figures, and four never loaded before:
// a gallery with pillars and a point light, a loft under a window's sun, a stair shaft under a
// skylight's sun, a kitchen behind a partition lit by a spot), mean SSIM 0.770 -> 0.777. The floor under a panel (VCTGL.NudgeRemovesSelfOcclusionOnAFlatFloor) reads
// 90 % of the analytic light at nudge 1 to 4 either way.
GI_FUNC float vctConeStart(float nudge, float voxel, float nDotDir, bool faceSides) {
    float cosine = faceSides ? 1.0f : (nDotDir > kVCTMinStartCosine ? nDotDir : kVCTMinStartCosine);
    return nudge * voxel * kSqrt3 / cosine;
}

// Encodings of the voxel volumes (r32ui holding RGBA8: rgb = running average, a = sample count).
GI_CONST float kVCTMaxCount = 255.0;
// A fragment joins the side of axis a its normal faces when |n[a]| exceeds this.
GI_CONST float kVCTSideMinCosine = 0.001;
// inject: a side's shadow test lies this many voxels out from the voxel centre along its normal.
GI_CONST float kVCTSideProbe = 0.5;
// bounce: a voxel whose back weighs less than this (voxel_encoding.glsl backWeight: nearly all its
// fragments face one way) traces no cones on its back.
GI_CONST float kVCTBackMinWeight = 0.02;
// voxelize: how far (voxels) a surface thickens across a voxel boundary, and how far behind a face
// a voxel centre may lie and still hold that face.
GI_CONST float kVCTSideMargin = 0.05;

struct VCTParams {
    // the grid (level) a pass works on: clear, voxelize, inject, resolve, compact, bounce, trace
    vec4 gridMin;        // xyz: world position of the grid's corner (logical voxel 0); w: bounce: 1 adds the
                         // bounces left out to the gathered light (vct.bounceTail, the last bounce), else 0
    ivec4 wrapOffset;    // xyz: clipmap texel = (voxel + offset) mod resolution, else 0; w: inject, bounce: 1
                         // works where the surface lies in its voxel (the position volume), 0 at the voxel
                         // centre (VCT's coarser levels, whose voxels hold surfaces too far apart for their
                         // mean position to lie on any: at it vct_sponza_cascaded fell from 0.827 to 0.797 SSIM)
    ivec4 clipMin;       // clear, voxelize: xyz: voxels outside [clipMin, clipMax) are not written
    ivec4 clipMax;
    int resolution;      // voxels per side
    float cellSize;      // world size of a voxel
    // (voxelize: the material drawn is MaterialBlock's, common/material_shared.h; no emission:
    // emissive surfaces reach VCT as area lights)
    // inject: the batch, uLights[lightFirst + i] with its shadow maps on unit + i
    int lightFirst;
    int lightCount;
    int accumulate;      // adds to the exit radiance of the earlier batches
    int sides;           // voxelize, clear, inject: also the per-side volumes (anisotropic dense grids);
                         // mip: also the coverage atlas; resolve: also the centroid volume
    int sliceAxis;       // voxelize: 0: each triangle along its dominant axis, grown (conservative);
                         // 1, 2, 3: along x, y, z, not grown, one cell per fragment (seed 001's slicing)
    int level0;          // mip (anisotropic with `sides`): 1 writes the atlas's mip 0 from level 0's
                         // sides (kVCTUnitMipSides), 0 a mip from the atlas's mip below
    // mip
    ivec4 destSize;      // xyz: the level written, in voxels; w unused
    int sourceLevel;
    int direction;       // -1: isotropic; 0..5: +X, -X, +Y, -Y, +Z, -Z
    // anisotropic: the six directions lie side by side along x in one atlas; the direction's
    // slab starts at these x in the source (0 for the isotropic base level) and the destination
    int sourceOffsetX;
    int destOffsetX;
    // bounce, trace: the cone set and the march (trace.glsl)
    int coneCount;
    float tanHalf;       // tan of half the diffuse aperture
    float maxDistance;
    float occlusionDistance;  // trace: VAO counts opacity within this
    int levelCount;
    float maxLod;        // mip levels per level - 1
    float nudge;
    float stepMultiplier;
    vec4 cones[kVCTMaxCones];              // xyz: tangent-space axis, w: normalised weight
    vec4 levelMinCell[kVCTMaxLevels];      // xyz: grid minimum, w: voxel size
    ivec4 levelWrap[kVCTMaxLevels];        // xyz: toroidal offsets (clipmap), else 0
    // trace, upsample, voxel view
    mat4 invViewProj;    // trace, voxel view
    vec4 cameraPos;      // trace: xyz, w unused
    ivec4 imageSize;     // xy: the traced image (the G-buffer's size times traceScale), zw: the G-buffer's
    vec4 toFull;         // xy: full-resolution pixels per traced pixel, zw unused
    vec4 specularAperture;  // trace: xy: radians at roughness 0 and 1, zw unused
    int vao;             // trace
    float vaoStrength;
    float intensity;
    int specularCone;
    float nearPlane;     // trace, upsample: the camera's clip planes (viewDepthOf)
    float farPlane;
    float exposureScale;  // voxel view: radiance
    float opacityThreshold;  // voxel view: radiance voxels below it are empty
    int viewSource;      // voxel view: VoxelViewSource, 0 albedo, 1 normal, 2 radiance
    int viewMip;         // voxel view: the radiance mip marched (0 for the packed sources)
    int edges;           // voxel view: darken voxel edges
    int sh;              // resolve: write the SH volumes too
    vec4 background;     // voxel view: xyz, display-encoded; w unused
    // trace: the environment's prefiltered chain on kVCTUnitSky (FrameContext::sky), read where
    // a cone ends with transparency left: x its radiance scale (0: no sky), y its rotation
    // (degrees about +y), z the mips of its chain, w the roughness whose lobe the diffuse cones match
    vec4 sky;
    vec4 skyMipRoughness[kSkyMaxMips / 4];  // roughness of mip m at [m / 4][m % 4], as EnvParams
};

#ifdef __cplusplus
inline constexpr const char* kVCTBlockName = "VCTBlock";
static_assert(offsetof(VCTParams, resolution) == 64 && offsetof(VCTParams, lightFirst) == 72);
static_assert(offsetof(VCTParams, destSize) == 96 && offsetof(VCTParams, coneCount) == 128);
static_assert(offsetof(VCTParams, cones) == 160 && offsetof(VCTParams, levelMinCell) == 160 + 16 * kVCTMaxCones);
static_assert(offsetof(VCTParams, invViewProj) == 160 + 16 * (kVCTMaxCones + 2 * kVCTMaxLevels));
static_assert(offsetof(VCTParams, sh) == 160 + 16 * (kVCTMaxCones + 2 * kVCTMaxLevels) + 64 + 4 * 16 + 44);
static_assert(offsetof(VCTParams, sky) == 160 + 16 * (kVCTMaxCones + 2 * kVCTMaxLevels) + 64 + 4 * 16 + 64);
static_assert(sizeof(VCTParams) == 160 + 16 * (kVCTMaxCones + 2 * kVCTMaxLevels) + 64 + 4 * 16 + 64 + 16 + 4 * kSkyMaxMips);
}  // namespace gi::vct
#else
layout(std140, binding = kVCTBlockBinding) uniform VCTBlock {
    VCTParams uVCT;
};
#endif
