// G-buffer: albedo (sRGB texture decoded by the sampler), world shading normal (normal-mapped),
// roughness/metallic and 1 - occlusion (the material texture's G, B and the occlusion map's R),
// emission (factor times the emissive texture, times its area light's scale: 0 when the light is
// off). Mask and Blend materials cut fragments (common/material.glsl). Back faces flip their
// normal so single-sheet geometry (curtains, leaves) is lit from both sides; a single-sided
// material's back faces emit nothing. Occlusion is stored as 1 - occlusion so surfaces without
// the map keep 0 there.
// ALPHA_CUT 0 (the renderer's variant for Opaque materials) has no discard at all: on llvmpipe a
// shader that may discard tests depth after shading, so every hidden fragment paid for its five
// texture reads; without one the depth test runs first.
#ifndef ALPHA_CUT
#define ALPHA_CUT 1
#endif
#include "render/render_shared.h"
#include "common/material.glsl"
#include "common/light.h"

in vec3 vNormal;
in vec4 vTangent;
in vec2 vUV;
in vec2 vUV1;

layout(location = 0) out vec4 oAlbedo;
layout(location = 1) out vec4 oNormal;
layout(location = 2) out vec4 oMaterial;
layout(location = 3) out vec4 oEmissive;

void main() {
    vec4 base = materialBaseColor(vUV, vUV1);
    vec3 n = materialNormal(vNormal, vTangent, gl_FrontFacing, vUV, vUV1);
    vec2 rm = materialRoughnessMetallic(vUV, vUV1);
    float occlusion = materialOcclusion(vUV, vUV1);
    vec3 emission = materialEmission(gl_FrontFacing, vUV, vUV1);
#if ALPHA_CUT
    if (materialCut(base.a)) discard;
#endif
    oAlbedo = vec4(base.rgb, 1.0);
    oNormal = vec4(n, 1.0);
    oMaterial = vec4(rm, 1.0 - occlusion, 1.0);
    // Emission belongs to an emitter (an area light), scaled by that light (0 when it is off).
    if (any(greaterThan(emission, vec3(0.0)))) {
        int e = uTriangleEmitter[uRender.firstTriangle + gl_PrimitiveID];
        emission = e >= 0 ? emission * uEmitterScale[e].rgb : vec3(0.0);
    }
    oEmissive = vec4(emission, 1.0);
}
