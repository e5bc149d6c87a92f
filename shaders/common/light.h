// The one light model, shared by C++ (the renderer, the RSM setup, the path tracer, the medium's
// CPU clipping) and GLSL (the raster light pass, the RSMs, VCT injection, the volumetric march),
// with glTF KHR_lights_punctual semantics:
//   - direction: the way the light travels; a zero vector falls back to straight down;
//   - point and spot lights fall off with the inverse square of the distance, times a range
//     window that reaches zero at `range` (0: infinite). The window is glTF's recommended
//     clamp(1 - (d / range)^4, 0, 1), squared so it also ends with zero slope (as Filament and
//     Unreal do; the spec's own formula is unsquared);
//   - spot lights: a smoothstep from the outer cone (0) to the inner cone (1), the outer
//     half-angle at most 90 degrees as glTF requires, the inner at most the outer.
// The renderer packs every light into one GPULight array each frame (a std430 buffer at
// kLightBufferBinding) with its shadow projection, so every pass reads the same numbers.
// C++ includes it as "common/light.h", GLSL through the #include expander.
#ifdef __cplusplus
#pragma once
#include <glm/glm.hpp>
#include <algorithm>
#include <cmath>
#include <cstddef>
#endif
#include "common/shared.h"
#ifdef __cplusplus
namespace gi::light {
using namespace gi::shared;
using glm::ivec4;
using glm::length;
using glm::mat4;
using glm::normalize;
using glm::radians;
using glm::vec2;
using glm::vec3;
using glm::vec4;
using glm::cross;
using glm::dot;
using std::abs;
using std::atan2;
using std::cos;
using std::max;
using std::min;
using std::tan;
// GLSL's smoothstep; callers keep edge0 < edge1.
inline float smoothstep(float edge0, float edge1, float x) {
    float t = clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}
#else
float atan2(float y, float x) { return atan(y, x); }
#endif

GI_CONST int kLightBufferBinding = 7;         // shader storage binding of the GPULight array (passes use 0..6)
GI_CONST int kAreaMaxExactTriangles = 16;    // area lights (and emitter parts) up to this many triangles are shaded exactly
GI_CONST float kAreaPlaneTolerance = 1e-3f;  // triangleIrradiance: points this close to the plane (times the size) get nothing
GI_CONST int kAreaTriangleBinding = 8;        // shader storage binding of the area lights' triangles
GI_CONST int kTriangleEmitterBinding = 9;     // int per scene triangle: its emitter, -1 for none (GPUScene)
GI_CONST int kEmitterScaleBinding = 10;       // vec4 per emitter: rgb factor on its emission this frame, 0 when off
GI_CONST float kSpotMaxConeDeg = 90.0f;       // glTF: outerConeAngle <= pi / 2
GI_CONST float kSpotShadowMarginDeg = 1.0f;   // a spot's shadow frustum reaches this far past its outer cone
GI_CONST float kShadowMaxFovDeg = 170.0f;     // wider perspective maps waste their texels at the edges
GI_CONST float kShadowNearRatio = 1e-3f;      // near plane of perspective shadow maps and RSMs, times far

// One light as every pass reads it. vec4-packed so std430 and C++ lay it out alike.
struct GPULight {
    vec4 color;           // rgb: color * intensity
    vec4 position;        // xyz: position (point, spot); w: range (0: infinite)
    vec4 direction;       // xyz: unit direction the light travels (lightDirection)
    vec4 spot;            // x: cos inner, y: cos outer (spotCosines); area: x area, y radius of the equal disc, z 1 when double-sided
    vec4 shadow;          // x: far (cube maps store distance / far), y: texel (world size, at distance 1 for spot and point)
    ivec4 info;           // x: type (kLight*), y: 1 when it casts a shadow (each pass binds the map);
                          // area: z first triangle in the area buffer, w triangle count
    mat4 shadowViewProj;  // directional and spot: world to the shadow map's clip space
};

// One triangle of an area light, wound so that its front (p1 - p0) x (p2 - p0) is the side it
// emits from, with its radiance (emission factor x strength x the texture's mean over it, times the
// light's colour and intensity).
struct GPUAreaTriangle {
    vec4 p0;        // xyz, w unused
    vec4 p1;
    vec4 p2;
    vec4 radiance;  // rgb
};

// One light with its triangles when it is an area light of at most kAreaMaxExactTriangles (the
// rest left zero): what the raster light pass reads per pixel, as a uniform block
// (render/light.frag's LightBlock), where llvmpipe loads each field once per draw; from the
// storage buffers above it loaded them per fragment.
struct GPULightWithTriangles {
    GPULight light;
    GPUAreaTriangle triangles[kAreaMaxExactTriangles];
};

#ifdef __cplusplus
static_assert(sizeof(GPULight) == 160, "GPULight must match its std430 layout");
static_assert(offsetof(GPULight, info) == 80 && offsetof(GPULight, shadowViewProj) == 96, "GPULight must match std430");
static_assert(sizeof(GPUAreaTriangle) == 64, "GPUAreaTriangle must match its std430 layout");
static_assert(sizeof(GPULightWithTriangles) == 160 + 64 * kAreaMaxExactTriangles, "GPULightWithTriangles must match std140");
#else
layout(std430, binding = kLightBufferBinding) readonly buffer LightBuffer { GPULight uLights[]; };
layout(std430, binding = kAreaTriangleBinding) readonly buffer AreaTriangleBuffer { GPUAreaTriangle uAreaTriangles[]; };
layout(std430, binding = kTriangleEmitterBinding) readonly buffer TriangleEmitterBuffer { int uTriangleEmitter[]; };
layout(std430, binding = kEmitterScaleBinding) readonly buffer EmitterScaleBuffer { vec4 uEmitterScale[]; };
#endif

// Lights whose shadow is a cube map around their position: point lights and area lights (whose
// position is the emitter's centroid, nudged off its surface).
GI_FUNC bool cubeShadow(int type) { return type == kLightPoint || type == kLightArea; }

// The direction a light travels, unit length; a zero vector means straight down.
GI_FUNC vec3 lightDirection(vec3 d) { return length(d) > 1e-8f ? normalize(d) : vec3(0.0f, -1.0f, 0.0f); }

// cos of a spot's inner and outer half-angles, the outer at most kSpotMaxConeDeg and the inner at
// most the outer.
GI_FUNC vec2 spotCosines(float innerDeg, float outerDeg) {
    float outer = min(outerDeg, kSpotMaxConeDeg);
    return vec2(cos(radians(min(innerDeg, outer))), cos(radians(outer)));
}

// The range window: 1 at the light, 0 from `range` on; range 0 is infinite.
GI_FUNC float rangeWindow(float dist, float range) {
    if (range <= 0.0f) return 1.0f;
    float r = dist / range;
    float w = clamp(1.0f - r * r * r * r, 0.0f, 1.0f);
    return w * w;
}

// The spot cone at cosAxis, the cosine between the spot's axis and the way the light leaves
// towards the point. Equal cones (inner = outer) give a hard edge.
GI_FUNC float spotCone(float cosAxis, vec2 cosines) {
    return smoothstep(cosines.y, max(cosines.x, cosines.y + 1e-6f), cosAxis);
}

// A point or spot light's falloff at distance dist apart from the inverse square: the range
// window times the spot cone. RSM texels carry the inverse square in their solid angle.
// An area light seen from afar is a point with a cosine lobe about its normal: intensity
// radiance x area x cos (both sides when double-sided).
GI_FUNC float lightProfile(GPULight l, float dist, float cosAxis) {
    float w = rangeWindow(dist, l.position.w);
    if (l.info.x == kLightArea) return w * l.spot.x * (l.spot.z != 0.0f ? abs(cosAxis) : max(cosAxis, 0.0f));
    return l.info.x == kLightSpot ? w * spotCone(cosAxis, vec2(l.spot)) : w;
}

// A point or spot light's full falloff: inverse square, range window and spot cone. Multiply
// color by it for the irradiance normal to the light's path. (Multiplied in this order, the
// order every pass has always used, so images stay the same to the bit.)
GI_FUNC float lightFalloff(GPULight l, float dist, float cosAxis) {
    float atten = 1.0f / max(dist * dist, 1e-8f) * rangeWindow(dist, l.position.w);
    if (l.info.x == kLightSpot) atten *= spotCone(cosAxis, vec2(l.spot));
    if (l.info.x == kLightArea) atten *= l.spot.x * (l.spot.z != 0.0f ? abs(cosAxis) : max(cosAxis, 0.0f));
    return atten;
}

// The irradiance at P (unit normal N) from a triangle of unit radiance: the integral of the
// cosine over the solid angle it covers, clipped to N's hemisphere. Lambert's closed form for a
// polygon (the exact diffuse case of linearly transformed cosines, Heitz et al. 2016): half the
// sum over the edges of the angle each subtends times the cosine of the normal of the plane
// through P and the edge. The triangle is clipped to the plane of N first (at most four
// vertices), so parts below the horizon count nothing. Emits from its front only unless
// doubleSided: its front is (b - a) x (c - a).
GI_FUNC float triangleIrradiance(vec3 a, vec3 b, vec3 c, vec3 P, vec3 N, bool doubleSided) {
    vec3 front = cross(b - a, c - a);
    float twiceArea = length(front);
    if (twiceArea <= 0.0f) return 0.0f;
    // The distance to the triangle's plane; points on the plane (within a small fraction of the
    // triangle's size: positions rebuilt from depth are not exact) see it edge-on and get nothing,
    // where the edge formula would count it whole.
    float side = dot(P - a, front) / twiceArea;
    if (abs(side) <= kAreaPlaneTolerance * sqrt(twiceArea) || (!doubleSided && side < 0.0f)) return 0.0f;
    vec3 v[3];
    v[0] = a - P;
    v[1] = b - P;
    v[2] = c - P;
    float h[3];
    h[0] = dot(v[0], N);
    h[1] = dot(v[1], N);
    h[2] = dot(v[2], N);
    vec3 q[4];
    int n = 0;
    for (int i = 0; i < 3; ++i) {
        int j = i == 2 ? 0 : i + 1;
        if (h[i] >= 0.0f) {
            q[n] = v[i];
            n += 1;
        }
        if ((h[i] >= 0.0f) != (h[j] >= 0.0f)) {
            q[n] = v[i] + (v[j] - v[i]) * (h[i] / (h[i] - h[j]));
            n += 1;
        }
    }
    if (n < 3) return 0.0f;
    float sum = 0.0f;
    for (int i = 0; i < n; ++i) {
        vec3 p = normalize(q[i]);
        vec3 r = normalize(q[i + 1 < n ? i + 1 : 0]);
        vec3 cr = cross(p, r);
        float len = length(cr);
        if (len > 1e-9f) sum += atan2(len, dot(p, r)) * dot(cr, N) / len;
    }
    return 0.5f * abs(sum);
}

#ifndef __cplusplus
// The irradiance at P (unit normal N) of one triangle of area light l: its radiance times
// triangleIrradiance.
vec3 areaTriangleIrradiance(GPULight l, GPUAreaTriangle tri, vec3 P, vec3 N) {
    return tri.radiance.rgb * triangleIrradiance(tri.p0.xyz, tri.p1.xyz, tri.p2.xyz, P, N, l.spot.z != 0.0);
}

// The exact irradiance at P of area light l: its triangles' (the area buffer's) summed. For
// lights of at most kAreaMaxExactTriangles triangles; larger ones are shaded as their point with
// a cosine lobe (lightFalloff).
vec3 areaIrradiance(GPULight l, vec3 P, vec3 N) {
    vec3 E = vec3(0.0);
    for (int i = 0; i < l.info.w; ++i) E += areaTriangleIrradiance(l, uAreaTriangles[l.info.z + i], P, N);
    return E;
}
#endif


// Full field of view of a spot's shadow map (and RSM): the outer cone and a margin.
GI_FUNC float spotShadowFovDeg(float outerConeDeg) {
    return min(2.0f * min(outerConeDeg, kSpotMaxConeDeg) + 2.0f * kSpotShadowMarginDeg, kShadowMaxFovDeg);
}

// Far plane of a point or spot light's shadow map: where the scene ends seen from the light
// (`reach`), or the range when nearer, since nothing is lit past it.
GI_FUNC float shadowFar(float reach, float range) { return range > 0.0f ? min(range, reach) : reach; }

// World size of one texel at distance 1 of a square perspective map `size` texels wide.
GI_FUNC float perspectiveTexel(float fovDeg, int size) { return 2.0f * tan(radians(fovDeg) * 0.5f) / float(size); }

// World size of one texel of a square orthographic map `size` texels wide spanning 2 halfWidth.
GI_FUNC float orthoTexel(float halfWidth, int size) { return 2.0f * halfWidth / float(size); }

// perspectiveTexel of a cube map face (90 degrees: tan 45 = 1).
GI_FUNC float cubeTexel(int size) { return 2.0f / float(size); }

// Up vector of a light's view: world up unless the light travels nearly along it.
GI_FUNC vec3 shadowUp(vec3 dir) { return abs(dir.y) > 0.99f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f); }

#ifdef __cplusplus
}  // namespace gi::light
#endif
