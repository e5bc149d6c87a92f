// Direct light of one light of the frame's light buffer (common/light.h), added to the HDR image
// (additive blend). Area lights (the scene's emissive surfaces) below: exact diffuse irradiance
// of their triangles and soft shadows. Shadows: directional and spot lights use a 2D depth map, point lights a cube
// map of distance / far; both are filtered with a grid of hardware-compared taps (PCF) and offset
// along the normal by the bias (in shadow-map texels, so the bias follows the map's resolution).
// LIGHT_KIND: the kind of light the program is built for (gi/render/renderer.cpp draws each light
// with its own): 0 directional or spot (2D shadow map), 1 point (cube map), 2 area. A CPU
// rasterizer runs every side of a branch, masked, even where no invocation takes it, so one
// program for every kind paid each light the area light's soft shadow and both PCF filters.
#ifndef LIGHT_KIND
#error "LIGHT_KIND: 0 (2D shadow map), 1 (cube map) or 2 (area light), as gi/render/renderer.cpp builds it"
#endif
#include "render/gbuffer_common.glsl"
#include "common/brdf.glsl"
#include "common/light.h"

layout(binding = kUnitShadow2D) uniform sampler2DShadow uShadow2D;
layout(binding = kUnitShadowCube) uniform samplerCubeShadow uShadowCube;
layout(binding = kUnitShadowCubeDepth) uniform samplerCube uShadowCubeDepth;

// The light this draw adds, with its triangles when it is an area light (GPULightWithTriangles).
layout(std140, binding = kLightPassBlockBinding) uniform LightBlock {
    GPULight uLight;
    GPUAreaTriangle uLightTriangles[kAreaMaxExactTriangles];
};

// areaIrradiance (common/light.h) over the block's copy of the light's triangles.
vec3 lightAreaIrradiance(GPULight l, vec3 P, vec3 N) {
    vec3 E = vec3(0.0);
    for (int i = 0; i < l.info.w; ++i) E += areaTriangleIrradiance(l, uLightTriangles[i], P, N);
    return E;
}

in vec2 vUV;
out vec4 oColor;

const int kPCFTaps = 2;  // (2 * kPCFTaps + 1)^2 taps

float shadow2D(GPULight l, vec3 P, vec3 N, vec3 L, float dist) {
    float texel = l.info.x == kLightDirectional ? l.shadow.y : l.shadow.y * dist;
    vec3 Pb = P + N * (uRender.shadowBias * texel) + L * (0.5 * uRender.shadowBias * texel);
    vec4 c = l.shadowViewProj * vec4(Pb, 1.0);
    vec3 ndc = c.xyz / c.w;
    vec3 tc = ndc * 0.5 + 0.5;
    if (any(lessThan(tc.xy, vec2(0.0))) || any(greaterThan(tc.xy, vec2(1.0))) || tc.z > 1.0) return 1.0;
    float step = uRender.pcfRadius / (float(kPCFTaps) * uRender.shadowSize);
    float sum = 0.0;
    for (int y = -kPCFTaps; y <= kPCFTaps; ++y)
        for (int x = -kPCFTaps; x <= kPCFTaps; ++x)
            sum += texture(uShadow2D, vec3(tc.xy + vec2(x, y) * step, tc.z));
    return sum / float((2 * kPCFTaps + 1) * (2 * kPCFTaps + 1));
}

float shadowCube(GPULight l, vec3 P, vec3 N, vec3 L, float dist) {
    float texel = l.shadow.y * dist;
    vec3 Pb = P + N * (uRender.shadowBias * texel) + L * (0.5 * uRender.shadowBias * texel);
    vec3 d = Pb - l.position.xyz;
    float ref = length(d) / l.shadow.x;
    vec3 dn = normalize(d);
    vec3 t = normalize(cross(abs(dn.y) < 0.99 ? vec3(0, 1, 0) : vec3(1, 0, 0), dn));
    vec3 b = cross(dn, t);
    float step = 2.0 * uRender.pcfRadius / (float(kPCFTaps) * uRender.shadowSize);
    float sum = 0.0;
    for (int y = -kPCFTaps; y <= kPCFTaps; ++y)
        for (int x = -kPCFTaps; x <= kPCFTaps; ++x)
            sum += texture(uShadowCube, vec4(dn + (t * float(x) + b * float(y)) * step, ref));
    return sum / float((2 * kPCFTaps + 1) * (2 * kPCFTaps + 1));
}

// Soft shadow of an area light (percentage-closer soft shadows, Fernando 2005, on its cube map):
// the mean distance of the blockers in the cone through which the receiver sees the light (as a
// disc of the light's radius at the light's centre) sets the penumbra, and a PCF of that width
// follows. Taps on a Vogel spiral (golden-angle), the same for every pixel.
const int kSoftTaps = 16;
const float kGoldenAngle = 2.39996323;
const float kMaxPenumbra = 0.35;  // radians: wider penumbrae are clamped (their blockers are near the light)

vec3 spiralTap(int i, vec3 dn, vec3 t, vec3 b, float radius) {
    float r = sqrt((float(i) + 0.5) / float(kSoftTaps)) * radius;
    float a = float(i) * kGoldenAngle;
    return dn + (t * cos(a) + b * sin(a)) * r;
}

// The distance / far at which the light's ray along unit w meets the receiver's plane (through
// Pb, normal N): each tap compares against the receiver there, not at the pixel, so a plane never
// shadows itself however wide the filter (receiver-plane depth bias).
float receiverDepth(GPULight l, vec3 Pb, vec3 N, vec3 w, float fallback) {
    float dn = dot(w, N);
    return dn < -1e-3 ? dot(Pb - l.position.xyz, N) / dn / l.shadow.x : fallback;
}

float shadowArea(GPULight l, vec3 P, vec3 N, vec3 L, float dist) {
    float texel = l.shadow.y * dist;
    vec3 Pb = P + N * (uRender.shadowBias * texel) + L * (0.5 * uRender.shadowBias * texel);
    vec3 d = Pb - l.position.xyz;
    float receiver = length(d);
    float ref = receiver / l.shadow.x;
    vec3 dn = d / receiver;
    vec3 t = normalize(cross(abs(dn.y) < 0.99 ? vec3(0, 1, 0) : vec3(1, 0, 0), dn));
    vec3 b = cross(dn, t);
    float radius = l.spot.y;
    // Blockers: within the angle the light's disc covers at the receiver's distance.
    float search = min(radius / receiver, kMaxPenumbra);
    float blockers = 0.0, count = 0.0;
    for (int i = 0; i < kSoftTaps; ++i) {
        vec3 w = normalize(spiralTap(i, dn, t, b, search));
        float z = texture(uShadowCubeDepth, w).r;
        if (z < receiverDepth(l, Pb, N, w, ref)) {
            blockers += z;
            count += 1.0;
        }
    }
    if (count == 0.0) return 1.0;
    float blocker = max(blockers / count * l.shadow.x, 1e-4);
    // The penumbra, as an angle seen from the light: the disc's edge through the blocker.
    float penumbra = clamp(radius * (receiver - blocker) / (receiver * blocker), 0.0, kMaxPenumbra);
    float width = max(penumbra, uRender.pcfRadius * 2.0 / uRender.shadowSize);
    float sum = 0.0;
    for (int i = 0; i < kSoftTaps; ++i) {
        vec3 w = normalize(spiralTap(i, dn, t, b, width));
        sum += texture(uShadowCube, vec4(w, receiverDepth(l, Pb, N, w, ref)));
    }
    return sum / float(kSoftTaps);
}

// An area light: the exact diffuse irradiance of its triangles (areaIrradiance), or, for a
// light of more than kAreaMaxExactTriangles, its point-with-a-cosine-lobe approximation from the
// centroid; GGX specular evaluated towards the point of the light nearest the mirror direction
// (Karis 2013's representative point) times the same irradiance, its lobe widened by the
// light's size so the energy does not grow as the highlight spreads.
vec3 areaLight(GPULight l, Surface s, out vec3 L, out float dist) {
    vec3 toLight = l.position.xyz - s.P;
    dist = max(length(toLight), 1e-6);
    L = toLight / dist;
    vec3 E = l.info.w <= kAreaMaxExactTriangles
                 ? lightAreaIrradiance(l, s.P, s.N)
                 : l.color.rgb * lightFalloff(l, dist, dot(-L, l.direction.xyz)) * max(dot(s.N, L), 0.0);
    if (all(equal(E, vec3(0.0)))) return vec3(0.0);
    vec3 result = s.baseColor * (1.0 - s.metallic) / kPi * E;
    if (uRender.specular != 0) {
        // The mirror ray meets the light's plane; the point is pulled into the light's disc.
        vec3 R = reflect(-s.V, s.N);
        vec3 n = l.direction.xyz;
        float denom = dot(R, n);
        vec3 onPlane = l.position.xyz;
        if (abs(denom) > 1e-4) {
            float tHit = dot(l.position.xyz - s.P, n) / denom;
            if (tHit > 0.0) onPlane = s.P + R * tHit;
        }
        vec3 offset = onPlane - l.position.xyz;
        float off = length(offset);
        vec3 closest = l.position.xyz + (off > l.spot.y ? offset * (l.spot.y / off) : offset);
        vec3 Ls = normalize(closest - s.P);
        float NoL = dot(s.N, Ls);
        if (NoL > 0.0) {
            vec3 H = normalize(s.V + Ls);
            float NoV = max(dot(s.N, s.V), 1e-4);
            float a = max(s.roughness * s.roughness, 0.002);
            float a2 = clamp(a + l.spot.y / (2.0 * dist), 0.0, 1.0);
            vec3 f0 = mix(vec3(0.04), s.baseColor, s.metallic);
            float norm = (a / a2) * (a / a2);
            result += D_GGX(max(dot(s.N, H), 0.0), a) * V_SmithGGXCorrelated(NoV, NoL, a) *
                      F_Schlick(max(dot(s.V, H), 0.0), f0) * norm * E;
        }
    }
    return result;
}

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    Surface s;
    if (!readSurface(px, vUV, s)) discard;

    GPULight l = uLight;
#if LIGHT_KIND == 2
    if (l.info.x == kLightArea) {
        vec3 L;
        float dist;
        vec3 c = areaLight(l, s, L, dist);
        if (all(equal(c, vec3(0.0)))) discard;
        float vis = l.info.y != 0 ? shadowArea(l, s.P, s.N, L, dist) : 1.0;
        oColor = vec4(c * vis, 1.0);
        return;
    }
#endif
#if LIGHT_KIND != 2
    // Normalised once more, as this pass always did: the GPU's normalize rounds unlike the CPU's,
    // and leaving it out would move pixels.
    vec3 axis = normalize(l.direction.xyz);
    vec3 L;
    vec3 E = l.color.rgb;
    float dist = 1.0;
    if (l.info.x == kLightDirectional) {
        L = -axis;
    } else {
        vec3 toLight = l.position.xyz - s.P;
        dist = length(toLight);
        L = toLight / max(dist, 1e-6);
        E *= lightFalloff(l, dist, dot(-L, axis));
    }
    vec3 f = evalBRDFCos(s.N, s.V, L, s.baseColor, s.metallic, s.roughness, uRender.specular != 0);
    if (all(equal(f, vec3(0.0))) || all(equal(E, vec3(0.0)))) discard;
    float vis = 1.0;
#if LIGHT_KIND == 0
    if (l.info.y != 0) vis = shadow2D(l, s.P, s.N, L, dist);
#else
    if (l.info.y != 0) vis = shadowCube(l, s.P, s.N, L, dist);
#endif
    oColor = vec4(f * E * vis, 1.0);
#endif
}
