// Shading: per pixel, irradiance from the finest cascade that holds the point, blended towards
// the next cascade over the outer tenth of its extent (LH04), written as E / pi (the indirect
// term's convention). Radiance in a cell is its SH intensity over the cell's face area (the
// volumes hold it so, inject.comp), times kLPVRadianceScale (the accumulation's calibration,
// lpv_shared.h).
// Lookups are taken half a cell in front of the surface. Self-illumination damping compares the irradiance half a cell in front of the surface with
// half a cell behind it: where it grows behind, the light comes from the surface's own VPLs.
#include "lpv/common.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup2D, local_size_y = kGroup2D) in;
layout(binding = kUnitNormal) uniform sampler2D uNormal;
layout(binding = kUnitDepth) uniform sampler2D uDepth;
layout(binding = kLPVImageIndirect, rgba16f) uniform writeonly image2D uIndirect;
// Channel c (kSHR, kSHG, kSHB) of cascade k at uSH[kLPVSHChannels * k + c].
layout(binding = kLPVUnitSH) uniform sampler3D uSH[kLPVSHChannels * kLPVMaxCascades];
const int kSHR = 0, kSHG = 1, kSHB = 2;

// Channel c of cascade k at tc. GLSL indexes an array of samplers only by a dynamically uniform
// expression (undefined otherwise), and the cascade differs between neighbouring pixels, so each
// cascade's lookup has its own constant index; a CPU rasterizer runs only the cascades some
// invocation executed together needs (the rest are skipped whole).
vec4 lookup(int k, int c, vec3 tc) {
    vec4 r = vec4(0.0);
    for (int i = 0; i < kLPVMaxCascades; ++i)
        if (i == k) r = texture(uSH[kLPVSHChannels * i + c], tc);
    return r;
}

vec3 irradiance(int k, vec3 p, vec3 n) {
    vec3 g = (p - uLPV.cascadeMinCell[k].xyz) / uLPV.cascadeMinCell[k].w;
    vec3 tc = g / float(uLPV.resolution);
    vec4 lobe = shCosLobe(-n);
    vec3 e = vec3(dot(lookup(k, kSHR, tc), lobe), dot(lookup(k, kSHG, tc), lobe), dot(lookup(k, kSHB, tc), lobe));
    return max(e, 0.0) * kLPVRadianceScale;
}

// Irradiance from the green SH alone: damping needs a brightness ratio, not colour, and one
// lookup instead of three keeps the pass cheap.
float greenIrradiance(int k, vec3 p, vec3 n) {
    vec3 tc = (p - uLPV.cascadeMinCell[k].xyz) / (uLPV.cascadeMinCell[k].w * float(uLPV.resolution));
    return max(dot(lookup(k, kSHG, tc), shCosLobe(-n)), 0.0);
}

vec3 dampedIrradiance(int k, vec3 p, vec3 n) {
    float h = 0.5 * uLPV.cascadeMinCell[k].w;
    // Shade from half a cell in front of the surface: the surface's own blocking sits on the
    // cell corners around it and would otherwise hold back the light that reaches it.
    vec3 e = irradiance(k, p + n * h, n);
    if (uLPV.damping <= 0.0) return e;
    float front = e.g / kLPVRadianceScale;
    float back = greenIrradiance(k, p - n * h, n);
    float ratio = back > front && back > 0.0 ? front / back : 1.0;
    return e * mix(1.0, ratio, uLPV.damping);
}

// How far p is into the outer blending band of cascade k: 0 inside, 1 at the edge.
float blendWeight(int k, vec3 p) {
    float extent = uLPV.cascadeMinCell[k].w * float(uLPV.resolution);
    vec3 centre = uLPV.cascadeMinCell[k].xyz + 0.5 * extent;
    float w = kLPVCascadeBlend * extent;
    vec3 a = clamp((abs(p - centre) - (0.5 * extent - w)) / w, 0.0, 1.0);
    return max(a.x, max(a.y, a.z));
}

bool inside(int k, vec3 p) {
    vec3 g = (p - uLPV.cascadeMinCell[k].xyz) / uLPV.cascadeMinCell[k].w;
    return all(greaterThanEqual(g, vec3(0.0))) && all(lessThanEqual(g, vec3(float(uLPV.resolution))));
}

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(uLPV.width, uLPV.height);
    if (any(greaterThanEqual(px, size))) return;
    float depth = texelFetch(uDepth, px, 0).r;
    vec3 result = vec3(0.0);
    if (depth < 1.0) {
        vec2 uv = (vec2(px) + 0.5) / vec2(size);
        vec4 w = uLPV.invViewProj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
        vec3 p = w.xyz / w.w;
        vec3 n = normalize(texelFetch(uNormal, px, 0).xyz);
        // The cascade first, then its lookups: a CPU rasterizer runs a loop until every
        // invocation it executes together has left it, and the lookups inside a loop over the
        // cascades ran (masked) once per cascade tried. Sponza 800x600, 3 cascades of 32^3, steady
        // state, three alternating rounds of the two binaries: 116 -> 63 ms, the same pixels.
        int k = 0;
        while (k + 1 < uLPV.cascadeCount && !inside(k, p)) ++k;
        if (inside(k, p)) {
            vec3 e = dampedIrradiance(k, p, n);
            float a = blendWeight(k, p);
            if (a > 0.0 && k + 1 < uLPV.cascadeCount) e = mix(e, dampedIrradiance(k + 1, p, n), a);
            result = e;
        }
    }
    imageStore(uIndirect, px, vec4(uLPV.intensity * result / kPi, 1.0));
}
