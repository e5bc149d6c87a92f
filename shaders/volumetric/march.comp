// Volumetric lighting, per pixel of the march buffer (seed 004 Alg. 5, with gi/volumetric/medium.h's
// model): the view ray to the surface (or out of the box) is clipped to the medium's box and,
// per light, to the light's cone and range (the seed clips to the spot pyramid; a cone is tighter
// and also covers point lights' range); `samples` points spread evenly over the clipped segment,
// offset by a fixed per-pixel hash; each tested against the light's shadow map (3x3 compared taps
// with PCF); unlit samples skip the rest; lit ones add sigma_s p(theta) Li T_light T_view dt.
// A batch of up to kVolumeMaxLights lights of the frame's light buffer (common/light.h) per
// dispatch; later dispatches add to the buffer.
// Output: rgb in-scattered radiance, a = the view distance to the surface (for the depth-aware blur).
#include "volumetric/medium.glsl"
#include "volumetric/phase.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup2D, local_size_y = kGroup2D) in;
layout(binding = kUnitDepth) uniform sampler2D uDepth;
layout(binding = kVolumeImageTarget, rgba16f) uniform image2D uOut;

// The batch's light i is uLights[uVolume.lightFirst + i], its shadow map at index i.
layout(binding = kVolumeUnitShadow2D) uniform sampler2DShadow uShadow2D[kVolumeMaxLights];
layout(binding = kVolumeUnitShadowCube) uniform samplerCubeShadow uShadowCube[kVolumeMaxLights];

float visibility(int i, GPULight l, vec3 x) {
    if (l.info.y == 0) return 1.0;
    if (cubeShadow(l.info.x)) {
        vec3 d = x - l.position.xyz;
        return texture(uShadowCube[i], vec4(normalize(d), length(d) / l.shadow.x));
    }
    vec4 c = l.shadowViewProj * vec4(x, 1.0);
    vec3 tc = c.xyz / c.w * 0.5 + 0.5;
    if (any(lessThan(tc.xy, vec2(0.0))) || any(greaterThan(tc.xy, vec2(1.0))) || tc.z > 1.0) return 1.0;
    if (uVolume.pcf == 0) return texture(uShadow2D[i], tc);
    float sum = 0.0;
    for (int y = -1; y <= 1; ++y)
        for (int xx = -1; xx <= 1; ++xx) sum += texture(uShadow2D[i], vec3(tc.xy + vec2(xx, y) / uVolume.shadowSize, tc.z));
    return sum / 9.0;
}

void main() {
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(q, ivec2(uVolume.lowWidth, uVolume.lowHeight)))) return;
    ivec2 fullSize = ivec2(uVolume.fullWidth, uVolume.fullHeight);
    vec3 eye = uVolume.eye.xyz;
    float sigmaT = uVolume.sigmaT;
    ivec2 px = min(ivec2((vec2(q) + 0.5) * vec2(uVolume.toFullX, uVolume.toFullY)), fullSize - 1);
    float depth = texelFetch(uDepth, px, 0).r;
    vec2 uv = (vec2(px) + 0.5) / vec2(fullSize);
    vec4 w = uVolume.invViewProj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    vec3 p = w.xyz / w.w;
    vec3 d = normalize(p - eye);
    float tHit = depth < 1.0 ? length(p - eye) : 1e30;
    vec3 L = vec3(0.0);
    float b0, b1;
    if (clipRayToBox(eye, d, tHit, b0, b1)) {
        // Interleaved gradient noise (Jimenez 2014): fixed per pixel, so headless renders repeat.
        float jitter = uVolume.jitter != 0 ? fract(52.9829189 * fract(dot(vec2(q), vec2(0.06711056, 0.00583715)))) : 0.5;
        for (int i = 0; i < uVolume.lightCount; ++i) {
            GPULight l = uLights[uVolume.lightFirst + i];
            float t0 = b0, t1 = b1;
            if (!clipRayToLight(l, eye, d, t0, t1)) continue;
            float dt = (t1 - t0) / float(uVolume.samples);
            vec3 sum = vec3(0.0);
            for (int s = 0; s < uVolume.samples; ++s) {
                float t = t0 + (float(s) + jitter) * dt;
                vec3 x = eye + t * d;
                float vis = visibility(i, l, x);
                if (vis <= 0.0) continue;  // unlit: skip the rest (seed 004 Fig. 3.19)
                vec3 toLight, travel;
                float dist, atten = 1.0;
                if (l.info.x == kLightDirectional) {
                    toLight = -l.direction.xyz;
                    travel = l.direction.xyz;
                    dist = 1e30;
                } else {
                    vec3 v = l.position.xyz - x;
                    dist = length(v);
                    toLight = v / max(dist, 1e-6);
                    travel = -toLight;
                    atten = lightFalloff(l, dist, dot(travel, l.direction.xyz));
                }
                float tLight = exp(-sigmaT * lightPathInBox(x, toLight, dist));
                float tView = exp(-sigmaT * (t - b0));
                sum += vis * atten * tLight * tView * phaseFunction(uVolume.phase, uVolume.g, uVolume.k, dot(travel, -d)) * l.color.rgb;
            }
            L += sum * (uVolume.sigmaS * dt);
        }
    }
    L *= uVolume.intensity;
    float viewDistance = depth < 1.0 ? tHit : 65504.0;
    if (uVolume.accumulate != 0) L += imageLoad(uOut, q).rgb;
    imageStore(uOut, q, vec4(L, viewDistance));
}
