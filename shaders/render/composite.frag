// Base of the HDR image: emission plus the indirect term. The indirect texture holds
// irradiance / pi, so a Lambert surface reflects albedo * indirect; metals have no diffuse.
// Ambient occlusion (SSAO, any technique) scales the indirect term.
#include "render/gbuffer_common.glsl"

layout(binding = kUnitIndirect) uniform sampler2D uIndirect;
layout(binding = kUnitAO) uniform sampler2D uAO;  // 1 everywhere when SSAO is off

in vec2 vUV;
out vec4 oColor;

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    Surface s;
    if (!readSurface(px, vUV, s)) {
        oColor = vec4(0.0, 0.0, 0.0, 1.0);
        return;
    }
    vec3 emissive = texelFetch(uEmissiveTex, px, 0).rgb;
    vec3 indirect = texelFetch(uIndirect, px, 0).rgb * texelFetch(uAO, px, 0).r;
    oColor = vec4(emissive + s.baseColor * (1.0 - s.metallic) * indirect, 1.0);
}
