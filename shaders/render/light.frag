// Direct light of one light of the frame's light buffer (common/light.h), added to the HDR image
// (additive blend). Shadows: directional and spot lights use a 2D depth map, point lights a cube
// map of distance / far; both are filtered with a grid of hardware-compared taps (PCF) and offset
// along the normal by the bias (in shadow-map texels, so the bias follows the map's resolution).
#include "render/gbuffer_common.glsl"
#include "common/brdf.glsl"
#include "common/light.h"

layout(binding = kUnitShadow2D) uniform sampler2DShadow uShadow2D;
layout(binding = kUnitShadowCube) uniform samplerCubeShadow uShadowCube;

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

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    Surface s;
    if (!readSurface(px, vUV, s)) discard;

    GPULight l = uLights[uRender.lightIndex];
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
    if (l.info.y != 0) vis = l.info.x == kLightPoint ? shadowCube(l, s.P, s.N, L, dist) : shadow2D(l, s.P, s.N, L, dist);
    oColor = vec4(f * E * vis, 1.0);
}
