// Shading: per pixel, irradiance from the finest cascade that holds the point, blended towards
// the next cascade over the outer tenth of its extent (LH04), written as E / pi (the indirect
// term's convention). Radiance in a cell is its SH intensity over the cell's face area.
// Lookups are taken half a cell in front of the surface. Self-illumination damping compares the irradiance half a cell in front of the surface with
// half a cell behind it: where it grows behind, the light comes from the surface's own VPLs.
#include "lpv/common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = kUnitNormal) uniform sampler2D uNormal;
layout(binding = kUnitDepth) uniform sampler2D uDepth;
layout(binding = 0, rgba16f) uniform writeonly image2D uIndirect;
layout(binding = 8) uniform sampler3D uSH[12];  // cascade k: units 8 + 3k (R), +1 (G), +2 (B)

uniform mat4 uInvViewProj;
uniform ivec2 uSize;
uniform int uCascadeCount;
uniform vec4 uCascadeMinCell[4];  // xyz: grid minimum, w: cell size
uniform float uIntensity;
uniform float uDamping;


vec3 irradiance(int k, vec3 p, vec3 n) {
    vec3 g = (p - uCascadeMinCell[k].xyz) / uCascadeMinCell[k].w;
    vec3 tc = g / float(uResolution);
    vec4 lobe = shCosLobe(-n);
    vec3 e = vec3(dot(texture(uSH[3 * k], tc), lobe), dot(texture(uSH[3 * k + 1], tc), lobe),
                  dot(texture(uSH[3 * k + 2], tc), lobe));
    return max(e, 0.0) / (uCascadeMinCell[k].w * uCascadeMinCell[k].w);
}

// Irradiance from the green SH alone: damping needs a brightness ratio, not colour, and one
// lookup instead of three keeps the pass cheap.
float greenIrradiance(int k, vec3 p, vec3 n) {
    vec3 tc = (p - uCascadeMinCell[k].xyz) / (uCascadeMinCell[k].w * float(uResolution));
    return max(dot(texture(uSH[3 * k + 1], tc), shCosLobe(-n)), 0.0);
}

vec3 dampedIrradiance(int k, vec3 p, vec3 n) {
    float h = 0.5 * uCascadeMinCell[k].w;
    // Shade from half a cell in front of the surface: the surface's own blocking sits on the
    // cell corners around it and would otherwise hold back the light that reaches it.
    vec3 e = irradiance(k, p + n * h, n);
    if (uDamping <= 0.0) return e;
    float front = e.g * uCascadeMinCell[k].w * uCascadeMinCell[k].w;
    float back = greenIrradiance(k, p - n * h, n);
    float ratio = back > front && back > 0.0 ? front / back : 1.0;
    return e * mix(1.0, ratio, uDamping);
}

// How far p is into the outer blending band of cascade k: 0 inside, 1 at the edge.
float blendWeight(int k, vec3 p) {
    float extent = uCascadeMinCell[k].w * float(uResolution);
    vec3 centre = uCascadeMinCell[k].xyz + 0.5 * extent;
    float w = 0.1 * extent;
    vec3 a = clamp((abs(p - centre) - (0.5 * extent - w)) / w, 0.0, 1.0);
    return max(a.x, max(a.y, a.z));
}

bool inside(int k, vec3 p) {
    vec3 g = (p - uCascadeMinCell[k].xyz) / uCascadeMinCell[k].w;
    return all(greaterThanEqual(g, vec3(0.0))) && all(lessThanEqual(g, vec3(float(uResolution))));
}

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, uSize))) return;
    float depth = texelFetch(uDepth, px, 0).r;
    vec3 result = vec3(0.0);
    if (depth < 1.0) {
        vec2 uv = (vec2(px) + 0.5) / vec2(uSize);
        vec4 w = uInvViewProj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
        vec3 p = w.xyz / w.w;
        vec3 n = normalize(texelFetch(uNormal, px, 0).xyz);
        for (int k = 0; k < uCascadeCount; ++k) {
            if (!inside(k, p)) continue;
            vec3 e = dampedIrradiance(k, p, n);
            float a = blendWeight(k, p);
            if (a > 0.0 && k + 1 < uCascadeCount) e = mix(e, dampedIrradiance(k + 1, p, n), a);
            result = e;
            break;
        }
    }
    imageStore(uIndirect, px, vec4(uIntensity * result / kPi, 1.0));
}
