// Parameters of the frame pipeline's raster passes, shared by C++ (gi/render/renderer.cpp) and
// GLSL (shaders/render/): gbuffer, shadow (2D and point), composite, light, tonemap and view.
// Their texture units stay in common/shared.h: the G-buffer units are read by the techniques'
// passes too, and kUnitBaseColor and kUnitSource by the RSM, VCT voxelisation and SSAO blur.
//
// One uniform block, RenderBlock, for the seven programs: RenderParams is the union of their
// fields, grouped by the passes that read them (as envmap/envmap_shared.h does, for the same
// reason: std140 blocks are active even where unread). Each pass uploads the whole struct, built
// afresh, so no pass reads a field another left behind. The material fields change per draw and
// the light index per light: the pass uploads the struct again before each of those draws, which
// GL orders after the draws before it.
// Layout as in ssao/ssao_shared.h: mat4, vec4 and scalars in groups of four (one vec2 on an
// 8-byte boundary), so std140 and C++ agree.
#ifdef __cplusplus
#pragma once
#endif
#include "common/shared.h"
#ifdef __cplusplus
namespace gi::shared {
#endif

// Uniform-buffer binding of RenderBlock.
GI_CONST int kRenderBlockBinding = 0;
// Uniform-buffer binding of the light pass's LightBlock: the one light it draws (a copy of
// uLights[i] and its area triangles, common/light.h GPULightWithTriangles). Read per pixel, a
// uniform block costs llvmpipe half what the storage buffers do (the light pass on vct_cornell
// 1280x720: 145 -> 75 ms). 1 is kMaterialBlockBinding.
GI_CONST int kLightPassBlockBinding = 2;

struct RenderParams {
    // gbuffer, shadow
    mat4 viewProj;       // world to clip: the camera's (gbuffer), the light's or a cube face's (shadow)
    // composite, light
    mat4 invViewProj;    // clip to world of the camera
    vec4 cameraPos;      // xyz: the camera position, w unused
    // (the draw's material is MaterialBlock's, common/material_shared.h)
    // shadow with LINEAR_DEPTH (point lights)
    vec4 lightPos;       // xyz: the light's position, w unused
    float shadowFar;     // the cube map stores distance / shadowFar
    int pad0;            // std140 alignment
    // light
    float shadowSize;    // shadow-map texels per side
    float pcfRadius;     // texels
    float shadowBias;    // texels
    int specular;        // 0: diffuse only
    // tonemap, view
    float exposureScale; // 2^EV
    // tonemap
    int toneOp;          // kToneLinear, kToneReinhard or kToneACES
    // view
    vec4 channelMask;    // (1,1,1,0) shows RGB; a single 1 shows that channel as grey
    vec4 direction;      // xyz: unit normal of the surface whose irradiance a volume view shows
    vec2 pan;            // texture-space offset of the view centre
    float zoom;          // 1 shows the whole texture
    float level;         // mip level
    int mode;            // kView* of common/shared.h
    int axis;            // volume views: slice normal axis, 0 x, 1 y, 2 z
    float slice;         // volume views: slice position 0..1
    int shComponent;     // -1: irradiance / blocking towards direction; else that coefficient
    float depthNear;     // linear depth views: the projection's near and far planes
    float depthFar;
    float range;         // distance shown as black in linear depth views
    float scale;         // stored value to radiance (SH volumes)
    int falseColour;     // 1: magnitudes as a colour ramp
    int depthCube;       // cube views: 1 for a depth cube (point shadow map), shown as grey
    // gbuffer, shadow
    int firstTriangle;   // the draw's first triangle in the scene (uTriangleEmitter's index of gl_PrimitiveID 0)
    int skipEmitter;     // shadow: the emitter whose own triangles cast no shadow (its area light's map), -1 none
};

#ifdef __cplusplus
inline constexpr const char* kRenderBlockName = "RenderBlock";
inline constexpr const char* kLightPassBlockName = "LightBlock";  // render/light.frag
static_assert(offsetof(RenderParams, cameraPos) == 128 && offsetof(RenderParams, lightPos) == 144);
static_assert(offsetof(RenderParams, toneOp) == 188 && offsetof(RenderParams, channelMask) == 192);
static_assert(offsetof(RenderParams, pan) == 224 && offsetof(RenderParams, depthNear) == 256);
static_assert(sizeof(RenderParams) == 288);
}  // namespace gi::shared
#else
layout(std140, binding = kRenderBlockBinding) uniform RenderBlock {
    RenderParams uRender;
};
#endif
