// Base of the HDR image: emission plus the indirect term. The indirect texture holds
// irradiance / pi, so a Lambert surface reflects albedo * indirect; metals have no diffuse.
// Ambient occlusion (SSAO, any technique) and the material's occlusion map scale the indirect term. Specular radiance from the
// technique (VCT's specular cone) or the environment map is weighed by the split-sum table of
// the GGX lobe's directional albedo, F0 * A + B (gi/envmap/environment.h).
#include "render/gbuffer_common.glsl"
#include "common/brdf.glsl"

layout(binding = kUnitIndirect) uniform sampler2D uIndirect;
layout(binding = kUnitAO) uniform sampler2D uAO;  // 1 everywhere when SSAO is off
layout(binding = kUnitIndirectSpecular) uniform sampler2D uIndirectSpecular;
layout(binding = kUnitBRDFLUT) uniform sampler2D uBRDFLUT;

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
    // SSAO times the material's occlusion map (stored as 1 - occlusion, gbuffer.frag).
    float ao = texelFetch(uAO, px, 0).r * (1.0 - texelFetch(uMaterial, px, 0).b);
    vec3 indirect = texelFetch(uIndirect, px, 0).rgb * ao;
    vec3 specular = texelFetch(uIndirectSpecular, px, 0).rgb * ao;
    vec3 f0 = mix(vec3(0.04), s.baseColor, s.metallic);
    vec2 ab = textureLod(uBRDFLUT, vec2(max(dot(s.N, s.V), 1e-4), s.roughness), 0.0).rg;
    vec3 weight = f0 * ab.x + ab.y;
    oColor = vec4(emissive + s.baseColor * (1.0 - s.metallic) * indirect + specular * weight, 1.0);
}
