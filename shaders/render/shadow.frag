// Shadow pass fragment: alpha-masked materials cut holes. With LINEAR_DEPTH (point and area
// lights) it stores distance / far so the six cube faces share one linear depth scale, and an
// area light's own surface is left out of its map; without it the depth is left to fixed
// function, which keeps early depth testing on.
#include "render/render_shared.h"
#include "common/material.glsl"
#include "common/light.h"

layout(binding = kUnitBaseColor) uniform sampler2D uBaseColorTex;

in vec3 vWorld;
in vec2 vUV;

void main() {
    if (uRender.alphaCutoff >= 0.0) {
        float a = uRender.baseColor.a * (uRender.hasTexture != 0 ? sampleMaterial(uBaseColorTex, vUV).a : 1.0);
        if (a < uRender.alphaCutoff) discard;
    }
#if LINEAR_DEPTH
    if (uRender.skipEmitter >= 0 && uTriangleEmitter[uRender.firstTriangle + gl_PrimitiveID] == uRender.skipEmitter) discard;
    gl_FragDepth = length(vWorld - uRender.lightPos.xyz) / uRender.shadowFar;
#endif
}
