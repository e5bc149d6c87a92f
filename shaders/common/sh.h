// Two-band spherical harmonics (4 coefficients, order Y00, Y1-1, Y10, Y11), shared by C++ (tests,
// CPU checks) and GLSL (LPV). Seed 000 section 1 gives these constants; the basis is orthonormal
// over the sphere, so the integral of a product of two functions is the dot product of their
// coefficients.
#ifdef __cplusplus
#pragma once
#include <glm/glm.hpp>
namespace gi::sh {
using glm::dot;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
#define GI_SH_CONST inline constexpr
#define GI_SH_FUNC inline
#else
#define GI_SH_CONST const
#define GI_SH_FUNC
#endif

GI_SH_CONST float kY00 = 0.282094792f;       // 1 / (2 sqrt(pi))
GI_SH_CONST float kY1 = 0.488602512f;        // sqrt(3) / (2 sqrt(pi))
GI_SH_CONST float kCosLobe0 = 0.886226925f;  // sqrt(pi) / 2: projection of max(cos, 0), band 0
GI_SH_CONST float kCosLobe1 = 1.02332671f;   // sqrt(pi / 3): band 1

// The basis evaluated in direction d (unit).
GI_SH_FUNC vec4 shBasis(vec3 d) { return vec4(kY00, -kY1 * d.y, kY1 * d.z, -kY1 * d.x); }
// Coefficients of the clamped cosine lobe max(dot(n, w), 0) around n.
GI_SH_FUNC vec4 shCosLobe(vec3 n) { return vec4(kCosLobe0, -kCosLobe1 * n.y, kCosLobe1 * n.z, -kCosLobe1 * n.x); }
// Radiance 1 over the hemisphere around n and 0 behind (one side of a Lambertian surface, VCT's
// SH voxels): band 0 is 2 pi Y00 = sqrt(pi), band 1 is pi Y1 along n. It evaluates to 1.25 along
// n, 0.5 at grazing and -0.25 behind (clamp where evaluated); its integral is 2 pi.
GI_SH_CONST float kHemisphere0 = 1.77245385f;  // sqrt(pi)
GI_SH_CONST float kHemisphere1 = 1.53499006f;  // pi * kY1
GI_SH_FUNC vec4 shHemisphere(vec3 n) { return vec4(kHemisphere0, -kHemisphere1 * n.y, kHemisphere1 * n.z, -kHemisphere1 * n.x); }
// A function given by coefficients c, evaluated in direction d.
GI_SH_FUNC float shEval(vec4 c, vec3 d) { return dot(c, shBasis(d)); }

#ifdef __cplusplus
}  // namespace gi::sh
#endif
