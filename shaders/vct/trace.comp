// Voxel cone tracing, per pixel (seed 000 section 1): the diffuse cone set around the G-buffer
// normal gives E / pi = sum of weight * cone radiance (weights sum to one, gi/vct/cone_set.h);
// the specular cone along the reflected view direction, its aperture lerped from
// specularApertureMin to specularApertureMax by roughness (seed 000: 1 to 80 degrees), gives the
// radiance the composite pass weighs with the split-sum approximation. VAO: the diffuse cones'
// opacity within vaoDistance, weighted like their radiance, scales the indirect light.
// Sky: a cone that leaves the grid, or reaches its length, with transparency 1 - a left sees the
// environment through it: it adds (1 - a) times the prefiltered map along its axis, at the
// roughness whose GGX lobe is as wide as the cone (the diffuse cones: uVCT.sky.w, the inverse of
// the specular aperture's roughness ramp; the specular cone: the pixel's roughness).
#include "vct/trace.glsl"
#include "common/sky.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup2D, local_size_y = kGroup2D) in;
layout(binding = kUnitNormal) uniform sampler2D uNormal;
layout(binding = kUnitMaterial) uniform sampler2D uMaterial;
layout(binding = kUnitDepth) uniform sampler2D uDepth;
layout(binding = kVCTImageIndirect, rgba16f) uniform writeonly image2D uIndirect;
layout(binding = kVCTImageSpecular, rgba16f) uniform writeonly image2D uSpecular;
layout(binding = kVCTImageGuide, rgba32f) uniform writeonly image2D uGuide;
layout(binding = kVCTUnitSky) uniform samplerCube uSky;
layout(std430, binding = kVCTBufferWork) buffer Work { uint uWork[2 * kVCTWorkCount]; };  // (low, high) pairs

// The workgroup's counts, added to the 64-bit totals once per group.
shared uint sWork[kVCTWorkCount];

void countWork(int counter, uint n) { atomicAdd(sWork[counter], n); }

// The environment's radiance seen through a cone's leftover transparency.
vec3 skyRadiance(vec3 dir, float roughness) {
    if (uVCT.sky.x <= 0.0) return vec3(0.0);
    float lod = mipForRoughness(roughness, uVCT.skyMipRoughness, int(uVCT.sky.z));
    return uVCT.sky.x * textureLod(uSky, envRotateY(dir, -uVCT.sky.y), lod).rgb;
}

void trace(ivec2 q) {
    // The traced pixel stands for the full-resolution pixel under its centre (upsample.comp reads the same).
    ivec2 px = min(ivec2((vec2(q) + 0.5) * uVCT.toFull.xy), uVCT.imageSize.zw - 1);
    float depth = texelFetch(uDepth, px, 0).r;
    vec3 indirect = vec3(0.0), specular = vec3(0.0);
    // What the upsampling filter weighs this traced pixel by: its normal and view depth (w < 0: no surface).
    vec4 guide = vec4(0.0, 0.0, 0.0, -1.0);
    if (depth < 1.0) {
        vec2 uv = (vec2(px) + 0.5) / vec2(uVCT.imageSize.zw);
        vec4 w = uVCT.invViewProj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
        vec3 p = w.xyz / w.w;
        vec3 n = normalize(texelFetch(uNormal, px, 0).xyz);
        guide = vec4(n, viewDepthOf(depth, uVCT.nearPlane, uVCT.farPlane));
        mat3 frame = tangentFrame(n);
        // With face sides, the 2 x 2 ordered pattern of the cones' sample phases (trace.glsl
        // traceCone): 1/8, 5/8, 7/8, 3/8.
        ivec2 b = q & 1;
        float phase = VCT_SIDES != 0 ? (float(2 * (b.x ^ b.y) + b.y) + 0.5) * 0.25 : kVCTPhaseUnstaggered;
        float visibility = 0.0;
        countWork(kVCTWorkPixels, 1u);
        countWork(kVCTWorkCones, uint(uVCT.coneCount + (uVCT.specularCone != 0 ? 1 : 0)));
        for (int i = 0; i < uVCT.coneCount; ++i) {
            float occlusion;
            vec3 dir = frame * uVCT.cones[i].xyz;
            vec4 c = traceCone(p, n, dir, uVCT.tanHalf, uVCT.maxDistance, uVCT.occlusionDistance, phase, occlusion);
            indirect += uVCT.cones[i].w * (c.rgb + (1.0 - c.a) * skyRadiance(dir, uVCT.sky.w));
            visibility += uVCT.cones[i].w * (1.0 - occlusion);
        }
        if (uVCT.vao != 0) indirect *= mix(1.0, visibility, uVCT.vaoStrength);
        indirect *= uVCT.intensity;
        if (uVCT.specularCone != 0) {
            vec3 v = normalize(uVCT.cameraPos.xyz - p);
            vec3 r = reflect(-v, n);
            float roughness = texelFetch(uMaterial, px, 0).r;
            float aperture = mix(uVCT.specularAperture.x, uVCT.specularAperture.y, roughness);
            float occlusion;
            vec4 c = traceCone(p, n, r, tan(0.5 * aperture), uVCT.maxDistance, 0.0, phase, occlusion);
            specular = uVCT.intensity * (c.rgb + (1.0 - c.a) * skyRadiance(r, roughness));
        }
    }
    imageStore(uIndirect, q, vec4(indirect, 1.0));
    imageStore(uSpecular, q, vec4(specular, 1.0));
    imageStore(uGuide, q, guide);
    countWork(kVCTWorkSamples, gVCTSamples);
    countWork(kVCTWorkFetches, gVCTFetches);
}

void main() {
    if (gl_LocalInvocationIndex < uint(kVCTWorkCount)) sWork[gl_LocalInvocationIndex] = 0u;
    barrier();
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    if (all(lessThan(q, uVCT.imageSize.xy))) trace(q);
    barrier();
    if (gl_LocalInvocationIndex < uint(kVCTWorkCount)) {
        uint i = 2u * gl_LocalInvocationIndex, n = sWork[gl_LocalInvocationIndex];
        uint before = atomicAdd(uWork[i], n);
        if (before + n < before) atomicAdd(uWork[i + 1u], 1u);  // the carry into the high word
    }
}
