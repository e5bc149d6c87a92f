// The GGX specular terms, shared by C++ (the path tracer) and GLSL (direct light), so the
// reference and the raster pipeline evaluate the very same BRDF: Trowbridge-Reitz D,
// height-correlated Smith visibility, Schlick Fresnel, and Smith G1 for sampling visible normals.
#include "common/shared.h"
#ifdef __cplusplus
#pragma once
#include <glm/glm.hpp>
#include <cmath>
namespace gi::ggx {
using gi::shared::kPi;
using glm::vec3;
using std::pow;
using std::sqrt;
inline float max(float a, float b) { return a > b ? a : b; }
#define GI_GGX_FUNC inline
#else
#define GI_GGX_FUNC
#endif

GI_GGX_FUNC float D_GGX(float NoH, float a) {
    float a2 = a * a;
    float d = NoH * NoH * (a2 - 1.0f) + 1.0f;
    return a2 / (kPi * d * d);
}

GI_GGX_FUNC float V_SmithGGXCorrelated(float NoV, float NoL, float a) {
    float a2 = a * a;
    float gv = NoL * sqrt(NoV * NoV * (1.0f - a2) + a2);
    float gl = NoV * sqrt(NoL * NoL * (1.0f - a2) + a2);
    return 0.5f / max(gv + gl, 1e-7f);
}

GI_GGX_FUNC vec3 F_Schlick(float VoH, vec3 f0) { return f0 + (1.0f - f0) * pow(1.0f - VoH, 5.0f); }

GI_GGX_FUNC float G1_GGX(float NoV, float a) {
    float a2 = a * a;
    return 2.0f * NoV / (NoV + sqrt(a2 + (1.0f - a2) * NoV * NoV));
}

#ifdef __cplusplus
}  // namespace gi::ggx
#endif
