// Constants shared by C++ and GLSL: texture units, light types, tone mappers, view modes.
// Written once here; C++ includes it as "common/shared.h", GLSL through the #include expander.
// In C++ the GLSL vector and matrix types are glm's, so a parameter block's struct
// (<technique>/<technique>_shared.h) reads the same in both languages.
#ifdef __cplusplus
#pragma once
#include <glm/glm.hpp>
#include <algorithm>
#include <cstddef>
#define GI_CONST inline constexpr
#define GI_FUNC inline
namespace gi::shared {
using vec2 = glm::vec2;
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using mat4 = glm::mat4;
inline float clamp(float x, float lo, float hi) { return std::min(std::max(x, lo), hi); }
#else
#define GI_CONST const
#define GI_FUNC
#endif

// The constants of the maths, once: every shader and the host code use these.
GI_CONST float kPi = 3.14159265358979f;
GI_CONST float kSqrt3 = 1.7320508f;  // the diagonal of a unit cube

// Mips of the environment's prefiltered chain at most (EnvParams::mipRoughness, VCTParams::skyMipRoughness).
GI_CONST int kSkyMaxMips = 32;

// Workgroup sizes of the compute passes, declared by the shaders and divided by by the host:
// image passes run 8x8 tiles, volume passes 16x2x2 rows (gl::dispatch3D), list passes 64 entries.
// A volume group lies along x, the fastest axis of every grid's memory, so each SIMD vector of
// llvmpipe's (8 lanes) covers 8 consecutive cells of a row and its fetches and stores touch
// contiguous memory: a 32^3 LPV propagation step took 2.17 ms in 4x4x4 bricks, 1.27 ms in rows
// (tests/bench/lpv_bench.sh, medians of 3 on llvmpipe, 2 cores; the same pixels).
GI_CONST int kGroup2D = 8;
GI_CONST int kGroup3DX = 16;
GI_CONST int kGroup3DY = 2;
GI_CONST int kGroup3DZ = 2;
GI_CONST int kGroup1D = 64;

// Texture units of the lighting and composite passes.
GI_CONST int kUnitAlbedo = 0;
GI_CONST int kUnitNormal = 1;
GI_CONST int kUnitMaterial = 2;
GI_CONST int kUnitEmissive = 3;
GI_CONST int kUnitDepth = 4;
GI_CONST int kUnitIndirect = 5;
GI_CONST int kUnitShadow2D = 6;
GI_CONST int kUnitShadowCube = 7;
GI_CONST int kUnitAO = 8;  // ambient occlusion (gi/ssao), multiplies the indirect term
GI_CONST int kUnitIndirectSpecular = 9;  // specular radiance from the technique (VCT's cone), or 0
GI_CONST int kUnitBRDFLUT = 10;  // the split-sum table (gi/envmap/environment.h), (A, B) by (N.V, roughness)
GI_CONST int kUnitShadowCubeDepth = 11;  // the light pass: the cube shadow map's distances, uncompared (soft shadows)
// Material base colour texture in the G-buffer and shadow passes.
GI_CONST int kUnitBaseColor = 0;
// Source texture of the view and tone-map passes.
GI_CONST int kUnitSource = 0;
GI_CONST int kUnitSourceCube = 1;

// LightSettings::type as an int.
GI_CONST int kLightDirectional = 0;
GI_CONST int kLightPoint = 1;
GI_CONST int kLightSpot = 2;
GI_CONST int kLightArea = 3;  // an emitter of the scene (gi/scene/scene.h Emitter): its triangles in the area buffer

// ToneMapper as an int.
GI_CONST int kToneLinear = 0;
GI_CONST int kToneReinhard = 1;
GI_CONST int kToneACES = 2;

// One channel through a tone curve. C++ (reference images) and GLSL (the tone-map pass) share
// this code, so a reference and a render are tone mapped alike. ACES is Narkowicz's 2015 fit.
GI_FUNC float giToneChannel(float x, int op) {
    if (op == kToneReinhard) return x / (1.0f + x);
    if (op == kToneACES) return clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
    return clamp(x, 0.0f, 1.0f);
}

// The view-space depth of an OpenGL depth-buffer value under a perspective projection with these
// clip planes (the debug views' linear depth, the buffer previewer's readout, VCT's upsampling weights).
GI_FUNC float viewDepthOf(float depth, float nearPlane, float farPlane) {
    float z = depth * 2.0f - 1.0f;
    return 2.0f * nearPlane * farPlane / (farPlane + nearPlane - z * (farPlane - nearPlane));
}

// Debug view modes (view.frag).
GI_CONST int kViewColor = 0;        // RGB as stored (linear HDR shown with exposure, sRGB encoded)
GI_CONST int kViewNormal = 1;       // xyz * 0.5 + 0.5
GI_CONST int kViewLinearDepth = 2;  // hyperbolic depth buffer turned into view distance / far
GI_CONST int kViewRawDepth = 3;     // stored depth as grey
GI_CONST int kViewCubeCross = 4;    // a cube map unfolded as a cross
GI_CONST int kViewDisplay = 5;      // already display-encoded (LDR output): no transfer curve
GI_CONST int kViewPosition = 6;     // world positions: fract(p) as colour, so structure shows at any scale
GI_CONST int kViewSHVolume = 7;     // a slice of three RGB SH volumes: irradiance or one coefficient
GI_CONST int kViewVolume = 8;       // a slice of one SH volume (the geometry volume): blocking or a coefficient
GI_CONST int kUnitSource3D = 2;     // view.frag: R (or the only) volume; G and B on the next two units
GI_CONST int kViewVoxelColor = 9;   // a slice of an RGBA volume at mip `level` (VCT radiance): rgb with exposure
GI_CONST int kViewVoxelAlpha = 10;  // the same, alpha (opacity) as grey
GI_CONST int kViewVoxelPacked = 11; // a slice of an r32ui volume of packed RGBA8 (VCT albedo): rgb
GI_CONST int kViewVoxelPackedNormal = 12;  // the same holding n * 0.5 + 0.5: shown as stored, empty black
GI_CONST int kUnitSourceU3D = 5;    // view.frag: unsigned integer volumes
GI_CONST int kViewCubeLatLong = 13; // a cube map (mip `level`) as an equirectangular image, gi/envmap/envmap_image.h's convention

#ifdef __cplusplus
}  // namespace gi::shared
#endif
