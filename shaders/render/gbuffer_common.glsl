// Reading the G-buffer back in screen-space passes.
#include "render/render_shared.h"

layout(binding = kUnitAlbedo) uniform sampler2D uAlbedo;
layout(binding = kUnitNormal) uniform sampler2D uNormal;
layout(binding = kUnitMaterial) uniform sampler2D uMaterial;
layout(binding = kUnitEmissive) uniform sampler2D uEmissiveTex;
layout(binding = kUnitDepth) uniform sampler2D uDepth;

struct Surface {
    vec3 P;
    vec3 N;
    vec3 V;
    vec3 baseColor;
    float roughness;
    float metallic;
};

// False for background pixels (depth 1).
bool readSurface(ivec2 px, vec2 uv, out Surface s) {
    float depth = texelFetch(uDepth, px, 0).r;
    if (depth >= 1.0) return false;
    vec4 clip = vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    vec4 world = uRender.invViewProj * clip;
    s.P = world.xyz / world.w;
    s.N = normalize(texelFetch(uNormal, px, 0).xyz);
    s.V = normalize(uRender.cameraPos.xyz - s.P);
    s.baseColor = texelFetch(uAlbedo, px, 0).rgb;
    vec2 rm = texelFetch(uMaterial, px, 0).rg;
    s.roughness = rm.r;
    s.metallic = rm.g;
    return true;
}
