// Shadow pass fragment: Mask and Blend materials cut holes (common/material.glsl). With
// LINEAR_DEPTH (point and area lights) it stores distance / far so the six cube faces share one
// linear depth scale, and an area light's own surface is left out of its map; without it the
// depth is left to fixed function, which keeps early depth testing on.
// ALPHA_CUT 0: the variant for Opaque materials, without discard (gbuffer.frag says why).
#ifndef ALPHA_CUT
#define ALPHA_CUT 1
#endif
#include "render/render_shared.h"
#include "common/material.glsl"
#include "common/light.h"

in vec3 vWorld;
in vec2 vUV;
in vec2 vUV1;

void main() {
#if ALPHA_CUT
    if (uMaterialParams.alphaMode != kAlphaOpaque && materialCut(materialBaseColor(vUV, vUV1).a)) discard;
#endif
#if LINEAR_DEPTH
    if (uRender.skipEmitter >= 0 && uTriangleEmitter[uRender.firstTriangle + gl_PrimitiveID] == uRender.skipEmitter) discard;
    gl_FragDepth = length(vWorld - uRender.lightPos.xyz) / uRender.shadowFar;
#endif
}
