// The sky (FrameContext::sky), after shade.comp: the environment's irradiance at the normal (its 9
// SH coefficients, as the irradiance cube is built from) times the sky's visibility is added to the
// indirect term, and the prefiltered map along the reflection, at the pixel's roughness, times the
// visibility around the reflection is the indirect specular (LPV has no other). Visibility is marched from the cell half a cell in front of the surface along
// each of the six axes that face the normal's hemisphere, multiplying the face transmittances the
// propagation uses (transmit.comp: 1 - the geometry volume's blocking), for surfaces facing either
// way, until the ray leaves the cascade, and the six are weighted by their cosine to the normal. A
// closed room's walls block every axis; an open floor sees the sky along +y. Only six directions:
// an overhang open to the side reads as covered (the +y ray is blocked). Sky light does not bounce,
// and what no RSM and not the camera have seen is not in the geometry volume and blocks nothing.
// (A cube map read in shade.comp, beside its twelve SH samplers, returned half the map's value on
// Mesa 22 llvmpipe; this pass declares four samplers.)
#include "lpv/common.glsl"
#include "common/sky.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup2D, local_size_y = kGroup2D) in;
layout(binding = kUnitNormal) uniform sampler2D uNormal;
layout(binding = kUnitMaterial) uniform sampler2D uMaterial;
layout(binding = kUnitDepth) uniform sampler2D uDepth;
layout(binding = kLPVUnitSky) uniform samplerCube uSky;  // the prefiltered chain
layout(binding = kLPVImageIndirect, rgba16f) uniform image2D uIndirect;
layout(binding = kLPVImageSpecular, rgba16f) uniform writeonly image2D uSpecular;
layout(std430, binding = kLPVBufferTransmit) readonly buffer Transmit { vec4 transmit[]; };  // 2 per cell: +x -x +y -y, +z -z

// The transmittance of the sky along axis d from cell c, to the cascade's edge. Each face the ray
// crosses blocks with surfaces facing either way: the light flowing along d into the next cell
// (surfaces facing the ray) and the light flowing back through the same face into this one
// (surfaces facing away, which the propagation does not count but which stand in the sky's way).
float axisVisibility(ivec3 c, int d) {
    const int res = uLPV.resolution;
    int back = d ^ 1;  // the opposite axis: +x <-> -x, +y <-> -y, +z <-> -z
    float v = 1.0;
    for (ivec3 x = c + kDirections[d]; insideGrid(x, res) && v > 1e-3; x += kDirections[d]) {
        v *= transmit[cellIndex(x, res) * 2 + d / 4][d % 4];
        // The first face is the receiver's own (its surfels face away from the ray).
        if (x != c + kDirections[d]) v *= transmit[cellIndex(x - kDirections[d], res) * 2 + back / 4][back % 4];
    }
    return v;
}

float skyVisibility(vec3 p, vec3 n) {
    int k = uLPV.skyCascade;
    if (k < 0) return 1.0;
    vec3 g = (p - uLPV.cascadeMinCell[k].xyz) / uLPV.cascadeMinCell[k].w + 0.5 * n;
    ivec3 c = ivec3(floor(g));
    if (!insideGrid(c, uLPV.resolution)) return 1.0;
    float sum = 0.0, weight = 0.0;
    for (int d = 0; d < 6; ++d) {
        float w = dot(n, vec3(kDirections[d]));
        if (w <= 0.0) continue;
        sum += w * axisVisibility(c, d);
        weight += w;
    }
    return weight > 0.0 ? sum / weight : 1.0;
}

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, ivec2(uLPV.width, uLPV.height)))) return;
    float depth = texelFetch(uDepth, px, 0).r;
    if (depth >= 1.0) return;
    vec2 uv = (vec2(px) + 0.5) / vec2(uLPV.width, uLPV.height);
    vec4 w = uLPV.invViewProj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    vec3 p = w.xyz / w.w;
    vec3 n = normalize(texelFetch(uNormal, px, 0).xyz);
    // skyIrradiance gives E / pi, the indirect term's convention.
    vec3 diffuse = uLPV.skyIntensity * skyIrradiance(uLPV.skySH, envRotateY(n, -uLPV.skyRotation)) * skyVisibility(p, n);
    imageStore(uIndirect, px, imageLoad(uIndirect, px) + vec4(uLPV.intensity * diffuse, 0.0));
    vec3 v = normalize(uLPV.cameraPos.xyz - p);
    if (dot(n, v) < 0.0) n = -n;  // two-sided, as the direct light
    vec3 r = reflect(-v, n);
    float roughness = texelFetch(uMaterial, px, 0).r;
    float lod = mipForRoughness(roughness, uLPV.skyMipRoughness, uLPV.skyMipCount);
    vec3 specular = uLPV.skyIntensity * textureLod(uSky, envRotateY(r, -uLPV.skyRotation), lod).rgb * skyVisibility(p, r);
    imageStore(uSpecular, px, vec4(uLPV.intensity * specular, 1.0));
}
