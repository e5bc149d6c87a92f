// Lambert diffuse and GGX specular (common/ggx.h, shared with the path tracer), as in
// Filament's and pbrt's standard model. Roughness is perceptual
// (alpha = roughness^2), clamped so a roughness of 0 does not make a delta lobe.
#include "common/shared.h"
#include "common/ggx.h"

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
