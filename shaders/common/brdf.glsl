// Lambert diffuse and GGX specular (Trowbridge-Reitz D, height-correlated Smith visibility,
// Schlick Fresnel), as in Filament's and pbrt's standard model. Roughness is perceptual
// (alpha = roughness^2), clamped so a roughness of 0 does not make a delta lobe.
const float kPi = 3.14159265358979;

float D_GGX(float NoH, float a) {
    float a2 = a * a;
    float d = NoH * NoH * (a2 - 1.0) + 1.0;
    return a2 / (kPi * d * d);
}

float V_SmithGGXCorrelated(float NoV, float NoL, float a) {
    float a2 = a * a;
    float gv = NoL * sqrt(NoV * NoV * (1.0 - a2) + a2);
    float gl = NoV * sqrt(NoL * NoL * (1.0 - a2) + a2);
    return 0.5 / max(gv + gl, 1e-7);
}

vec3 F_Schlick(float VoH, vec3 f0) {
    return f0 + (1.0 - f0) * pow(1.0 - VoH, 5.0);
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
