// The glTF metallic-roughness material of a draw (common/material_shared.h), evaluated the same
// way by every pass that rasterizes the scene: the G-buffer, the shadow maps, LPV's RSMs and VCT's
// voxelization. The path tracer (gi/reference/path_tracer.cpp) follows the same steps on the CPU.
//
// Material textures are read through sampleMaterial(), which filters anisotropically itself:
// up to kMaxAnisotropy trilinear probes spread along the pixel footprint's major axis, each
// filtering major / N of it (N = min(ceil(major / minor), kMaxAnisotropy), the model of
// EXT_texture_filter_anisotropic), and the material sampler has no anisotropy of its own.
// Mesa 22.3 llvmpipe's anisotropic filter sums an elliptical footprint of texels: the G-buffer
// of Sponza at 800x600 took 433 ms with it against 159 ms trilinear, and one sliver triangle of
// its curtains took 2.2 s at 530x750; a file whose texture coordinates reach 1e5 stalled the
// shadow pass for over 300 s. The probes bound the cost at N trilinear reads.
// A quad whose coordinates change by more than kMaxUVPerPixel repeats per pixel samples with
// derivatives bounded to that, and coordinates wrapped into [0, 1) (every material sampler
// repeats): its footprint covers the texture many times over, and the last mips are read either
// way. The test is on coarse (per-quad) derivatives, so a quad never mixes the two paths.
#include "common/material_shared.h"

const float kMaxUVPerPixel = 8.0;

layout(binding = kUnitBaseColor + kSlotBaseColorTex) uniform sampler2D uBaseColorTex;
layout(binding = kUnitBaseColor + kSlotMetallicRoughnessTex) uniform sampler2D uMetallicRoughnessTex;
layout(binding = kUnitBaseColor + kSlotNormalTex) uniform sampler2D uNormalTex;
layout(binding = kUnitBaseColor + kSlotOcclusionTex) uniform sampler2D uOcclusionTex;
layout(binding = kUnitBaseColor + kSlotEmissiveTex) uniform sampler2D uEmissiveMapTex;

const float kMaxAnisotropy = 4.0;

vec4 sampleMaterial(sampler2D tex, vec2 uv) {
    vec2 dx = dFdx(uv), dy = dFdy(uv);
    vec2 cx = dFdxCoarse(uv), cy = dFdyCoarse(uv);
    if (!(max(max(abs(cx.x), abs(cx.y)), max(abs(cy.x), abs(cy.y))) <= kMaxUVPerPixel)) {
        vec2 bound = vec2(kMaxUVPerPixel);
        uv = fract(uv);
        dx = clamp(dx, -bound, bound);
        dy = clamp(dy, -bound, bound);
    }
    vec2 size = vec2(textureSize(tex, 0));
    float lx = length(dx * size), ly = length(dy * size);
    vec2 major = lx > ly ? dx : dy, minor = lx > ly ? dy : dx;
    float n = clamp(ceil(max(lx, ly) / max(min(lx, ly), 1e-8)), 1.0, kMaxAnisotropy);
    vec4 sum = vec4(0.0);
    for (float i = 0.0; i < n; i += 1.0) sum += textureGrad(tex, uv + major * ((i + 0.5) / n - 0.5), major / n, minor);
    return sum / n;
}

// MATERIAL_TEXTURES: the texture slots a program is built for (gi/render/material_programs.h),
// and kMaterialVariantEmits where the material's emissive factor is not zero; slots outside it
// are left out at compile time, since a CPU rasterizer executes a branch that no invocation
// takes (masked) and paid for every absent texture's read. Without kMaterialVariantEmits the
// emission is 0 at compile time, and with it the G-buffer's lookup of the fragment's emitter.
#ifndef MATERIAL_TEXTURES
#define MATERIAL_TEXTURES 63  // the general program: every slot and the emission tested at run time
#endif
bool materialHas(int slot) { return (MATERIAL_TEXTURES & (1 << slot)) != 0 && (uMaterialParams.textureMask & (1 << slot)) != 0; }

// A slot's texture coordinates: its set (TEXCOORD_0 or _1) through KHR_texture_transform.
vec2 materialUV(int slot, vec2 uv0, vec2 uv1) {
    vec4 r0 = uMaterialParams.uvTransform[2 * slot], r1 = uMaterialParams.uvTransform[2 * slot + 1];
    vec3 uv = vec3(r0.w > 0.5 ? uv1 : uv0, 1.0);
    return vec2(dot(r0.xyz, uv), dot(r1.xyz, uv));
}

vec4 materialBaseColor(vec2 uv0, vec2 uv1) {
    vec4 base = uMaterialParams.baseColor;
    if (materialHas(kSlotBaseColorTex)) base *= sampleMaterial(uBaseColorTex, materialUV(kSlotBaseColorTex, uv0, uv1));
    return base;
}

// Interleaved gradient noise (Jimenez 2014): the per-pixel threshold of Blend's dithered mask.
float materialDither() { return fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715)))); }

// True where the fragment is cut out: Mask below its cutoff, Blend below the dither threshold.
bool materialCut(float alpha) {
    if (uMaterialParams.alphaMode == kAlphaMask) return alpha < uMaterialParams.alphaCutoff;
    if (uMaterialParams.alphaMode == kAlphaBlend) return alpha < materialDither() * (1.0 - 1e-3) + 1e-3;
    return false;
}

// The shading normal: the interpolated normal facing the viewer on back faces, bent by the
// normal map through the tangent frame (tangent.w the bitangent's side). A zero tangent (no
// usable mapping) leaves the normal as it is.
vec3 materialNormal(vec3 normal, vec4 tangent, bool frontFacing, vec2 uv0, vec2 uv1) {
    vec3 n = normalize(normal);
    if (!frontFacing) n = -n;
    if (!materialHas(kSlotNormalTex)) return n;
    // Sampled before the per-fragment tests, so its derivatives come from uniform control flow.
    vec3 m = sampleMaterial(uNormalTex, materialUV(kSlotNormalTex, uv0, uv1)).xyz * 2.0 - 1.0;
    m.xy *= uMaterialParams.normalScale;
    vec3 t = tangent.xyz - n * dot(n, tangent.xyz);
    if (dot(t, t) < 1e-12) return n;
    t = normalize(t);
    vec3 b = cross(n, t) * (tangent.w < 0.0 ? -1.0 : 1.0);
    vec3 bent = t * m.x + b * m.y + n * m.z;
    return dot(bent, bent) > 1e-12 ? normalize(bent) : n;
}

// (roughness, metallic): the factors times the texture's G and B.
vec2 materialRoughnessMetallic(vec2 uv0, vec2 uv1) {
    vec2 rm = vec2(uMaterialParams.roughness, uMaterialParams.metallic);
    if (materialHas(kSlotMetallicRoughnessTex))
        rm *= sampleMaterial(uMetallicRoughnessTex, materialUV(kSlotMetallicRoughnessTex, uv0, uv1)).gb;
    return rm;
}

// Scales the indirect term only: 1 + strength * (R - 1).
float materialOcclusion(vec2 uv0, vec2 uv1) {
    if (!materialHas(kSlotOcclusionTex)) return 1.0;
    float r = sampleMaterial(uOcclusionTex, materialUV(kSlotOcclusionTex, uv0, uv1)).r;
    return 1.0 + uMaterialParams.occlusionStrength * (r - 1.0);
}

// Emitted radiance: the factor times the sRGB texture; nothing from a single-sided back face.
vec3 materialEmission(bool frontFacing, vec2 uv0, vec2 uv1) {
    if ((MATERIAL_TEXTURES & kMaterialVariantEmits) == 0) return vec3(0.0);  // the factor is 0
    if (!frontFacing && uMaterialParams.doubleSided == 0) return vec3(0.0);
    vec3 e = uMaterialParams.emissive.rgb;
    if (materialHas(kSlotEmissiveTex) && any(greaterThan(e, vec3(0.0))))
        e *= sampleMaterial(uEmissiveMapTex, materialUV(kSlotEmissiveTex, uv0, uv1)).rgb;
    return e;
}
