// G-buffer: albedo (sRGB texture decoded by the sampler), world normal, roughness/metallic,
// emissive (times its area light's scale). Alpha-masked materials discard below the cutoff. Back faces flip their normal so
// single-sheet geometry (curtains, leaves) is lit from both sides.
#include "render/render_shared.h"
#include "common/material.glsl"
#include "common/light.h"

layout(binding = kUnitBaseColor) uniform sampler2D uBaseColorTex;

in vec3 vNormal;
in vec2 vUV;

layout(location = 0) out vec4 oAlbedo;
layout(location = 1) out vec4 oNormal;
layout(location = 2) out vec4 oMaterial;
layout(location = 3) out vec4 oEmissive;

void main() {
    vec4 base = uRender.baseColor;
    if (uRender.hasTexture != 0) base *= sampleMaterial(uBaseColorTex, vUV);
    if (uRender.alphaCutoff >= 0.0 && base.a < uRender.alphaCutoff) discard;
    vec3 n = normalize(vNormal);
    if (!gl_FrontFacing) n = -n;
    oAlbedo = vec4(base.rgb, 1.0);
    oNormal = vec4(n, 1.0);
    oMaterial = vec4(uRender.roughness, uRender.metallic, 0.0, 1.0);
    // Emission belongs to an emitter (an area light), scaled by that light (0 when it is off).
    vec3 emission = uRender.emissive.rgb;
    if (any(greaterThan(emission, vec3(0.0)))) {
        int e = uTriangleEmitter[uRender.firstTriangle + gl_PrimitiveID];
        emission = e >= 0 ? emission * uEmitterScale[e].rgb : vec3(0.0);
    }
    oEmissive = vec4(emission, 1.0);
}
