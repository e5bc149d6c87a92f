// G-buffer: albedo (sRGB texture decoded by the sampler), world normal, roughness/metallic,
// emissive. Alpha-masked materials discard below the cutoff. Back faces flip their normal so
// single-sheet geometry (curtains, leaves) is lit from both sides.
#include "common/shared.h"
#include "common/material.glsl"

layout(binding = kUnitBaseColor) uniform sampler2D uBaseColorTex;
uniform vec4 uBaseColor;
uniform bool uHasTexture;
uniform float uAlphaCutoff;  // < 0: opaque
uniform float uRoughness;
uniform float uMetallic;
uniform vec3 uEmissive;

in vec3 vNormal;
in vec2 vUV;

layout(location = 0) out vec4 oAlbedo;
layout(location = 1) out vec4 oNormal;
layout(location = 2) out vec4 oMaterial;
layout(location = 3) out vec4 oEmissive;

void main() {
    vec4 base = uBaseColor;
    if (uHasTexture) base *= sampleMaterial(uBaseColorTex, vUV);
    if (uAlphaCutoff >= 0.0 && base.a < uAlphaCutoff) discard;
    vec3 n = normalize(vNormal);
    if (!gl_FrontFacing) n = -n;
    oAlbedo = vec4(base.rgb, 1.0);
    oNormal = vec4(n, 1.0);
    oMaterial = vec4(uRoughness, uMetallic, 0.0, 1.0);
    oEmissive = vec4(uEmissive, 1.0);
}
