// Constants shared by the VCT host code (gi/vct) and its shaders: texture units, image bindings,
// limits. C++ includes it as "vct/vct_shared.h", GLSL through the #include expander.
#include "common/shared.h"
#ifdef __cplusplus
#pragma once
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

// The cone march (trace.glsl; the editor's cone glyphs start where it starts).
GI_CONST float kVCTMinStartCosine = 0.25;  // n.w clamp of the start offset: grazing cones would start far away
GI_CONST int kVCTMaxConeSteps = 512;       // a cone stops after this many samples whatever its length
GI_CONST float kVCTOpaque = 0.99;          // a cone stops once its gathered opacity reaches this
GI_CONST float kVCTLevelBlend = 0.1;       // fraction of a level's extent over which it blends into the next

// Where a cone's march starts: nudge voxel diagonals out from the surface (seed 000 eq. 3.4),
// divided by n.w so a cone leaving at a grazing angle still clears the surface's voxels.
GI_FUNC float vctConeStart(float nudge, float voxel, float nDotDir) {
    return nudge * voxel * kSqrt3 / (nDotDir > kVCTMinStartCosine ? nDotDir : kVCTMinStartCosine);
}

// Encodings of the voxel volumes (r32ui holding RGBA8: rgb = running average, a = sample count).
GI_CONST float kVCTMaxCount = 255.0;

#ifdef __cplusplus
}  // namespace gi::vct
#endif
