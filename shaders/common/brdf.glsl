// Lambert diffuse and GGX specular (common/ggx.h, shared with the path tracer), as in
// Filament's and pbrt's standard model. Roughness is perceptual
// (alpha = roughness^2), clamped so a roughness of 0 does not make a delta lobe.
const float kPi = 3.14159265358979;

#include "common/ggx.h"

// The split-sum's directional albedo of the GGX lobe, F0 * A + B, from Karis's analytic fit
// ("Physically Based Shading on Mobile", 2014): weighs prefiltered specular radiance (VCT's
// specular cone) without a lookup table.
vec3 envBRDFApprox(vec3 f0, float roughness, float NoV) {
    const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
    const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
    vec4 r = roughness * c0 + c1;
    float a004 = min(r.x * r.x, exp2(-9.28 * NoV)) * r.x + r.y;
    vec2 ab = vec2(-1.04, 1.04) * a004 + r.zw;
    return f0 * ab.x + ab.y;
}

// BRDF times cos(theta_l) for one light direction. Returns radiance per unit irradiance.
vec3 evalBRDFCos(vec3 N, vec3 V, vec3 L, vec3 baseColor, float metallic, float roughness, bool specular) {
    float NoL = dot(N, L);
    if (NoL <= 0.0) return vec3(0.0);
    vec3 diffuse = baseColor * (1.0 - metallic) / kPi;
    vec3 result = diffuse;
    if (specular) {
        vec3 H = normalize(V + L);
        float NoV = max(dot(N, V), 1e-4);
        float NoH = max(dot(N, H), 0.0);
        float VoH = max(dot(V, H), 0.0);
        float a = max(roughness * roughness, 0.002);
        vec3 f0 = mix(vec3(0.04), baseColor, metallic);
        result += D_GGX(NoH, a) * V_SmithGGXCorrelated(NoV, NoL, a) * F_Schlick(VoH, f0);
    }
    return result * NoL;
}
