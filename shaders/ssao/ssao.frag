// Screen-space ambient occlusion, raw pass (seed 000 Sec 3.5.1, after Chapman 2011).
//
// For each pixel: the view-space position from depth through the inverse projection, the
// G-buffer's world normal rotated into view space, and a tangent frame about that normal
// rotated by this pixel's angle from the 4x4 noise tile. Each kernel point (in the +Z
// hemisphere, denser near the origin, built on the host with a fixed seed) is scaled by the
// radius, moved into the frame and projected; it is occluded when the surface stored at its
// pixel lies more than uSSAO.bias in front of it. Output: visibility = 1 - occluded / count.
//
// Choices where Chapman is silent (see gi/ssao/ssao.h for the reasons): a branchless
// orthonormal basis (Duff et al. 2017) rotated by the noise angle instead of Gram-Schmidt on a
// random vector; range check smoothstep(0, 1, radius / |z_pixel - z_stored|) against halos;
// samples off screen or behind the eye count as unoccluded.
//
// Known artefacts: occluders outside the frame or hidden behind the visible surface do not
// count; thin objects occlude as if infinitely thick; at grazing angles flat ground can occlude
// itself when a half-pixel depth slope exceeds uSSAO.bias; the noise tile shows until blurred.
#include "common/shared.h"
#include "ssao/ssao_shared.h"

layout(binding = kUnitDepth) uniform sampler2D uDepth;
layout(binding = kUnitNormal) uniform sampler2D uNormal;

out float oVisibility;

vec3 viewPosition(ivec2 px, vec2 size, float depth) {
    vec2 ndc = (vec2(px) + 0.5) / size * 2.0 - 1.0;
    vec4 v = uSSAO.invProj * vec4(ndc, depth * 2.0 - 1.0, 1.0);
    return v.xyz / v.w;
}

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec2 size = vec2(textureSize(uDepth, 0));
    float depth = texelFetch(uDepth, px, 0).r;
    if (depth >= 1.0) {
        oVisibility = 1.0;  // background
        return;
    }
    vec3 P = viewPosition(px, size, depth);
    vec3 N = normalize(mat3(uSSAO.view) * texelFetch(uNormal, px, 0).xyz);

    // Duff et al. 2017: an orthonormal basis about N with no singular direction.
    float sgn = N.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (sgn + N.z);
    float b = N.x * N.y * a;
    vec3 T0 = vec3(1.0 + sgn * N.x * N.x * a, sgn * b, -sgn * N.x);
    vec3 B0 = vec3(b, sgn + N.y * N.y * a, -N.y);
    vec2 r = uSSAO.noise[(px.y % kSSAONoiseSize) * kSSAONoiseSize + px.x % kSSAONoiseSize].xy;
    vec3 T = r.x * T0 + r.y * B0;
    mat3 TBN = mat3(T, cross(N, T), N);

    float occluded = 0.0;
    for (int i = 0; i < uSSAO.sampleCount; ++i) {
        vec3 S = P + TBN * (uSSAO.kernel[i].xyz * uSSAO.radius);
        vec4 clip = uSSAO.proj * vec4(S, 1.0);
        if (clip.w <= 0.0) continue;  // behind the eye
        vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
        if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) continue;
        ivec2 spx = ivec2(uv * size);
        float storedZ = viewPosition(spx, size, texelFetch(uDepth, spx, 0).r).z;
        // View space looks down -Z: a larger z is nearer the eye.
        float rangeCheck = smoothstep(0.0, 1.0, uSSAO.radius / abs(P.z - storedZ));
        occluded += (storedZ >= S.z + uSSAO.bias ? 1.0 : 0.0) * rangeCheck;
    }
    oVisibility = 1.0 - occluded / float(uSSAO.sampleCount);
}
