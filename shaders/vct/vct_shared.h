// Constants shared by the VCT host code (gi/vct) and its shaders: texture units, image bindings,
// limits. C++ includes it as "vct/vct_shared.h", GLSL through the #include expander.
#ifdef __cplusplus
#pragma once
#define GI_CONST inline constexpr
namespace gi::vct {
#else
#define GI_CONST const
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

// Encodings of the voxel volumes (r32ui holding RGBA8: rgb = running average, a = sample count).
GI_CONST float kVCTMaxCount = 255.0;

#ifdef __cplusplus
}  // namespace gi::vct
#endif
