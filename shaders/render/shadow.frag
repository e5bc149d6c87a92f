// Shadow pass fragment: alpha-masked materials cut holes. With LINEAR_DEPTH (point lights) it
// stores distance / far so the six cube faces share one linear depth scale; without it the
// depth is left to fixed function, which keeps early depth testing on.
#include "common/shared.h"
#include "common/material.glsl"

layout(binding = kUnitBaseColor) uniform sampler2D uBaseColorTex;
uniform bool uHasTexture;
uniform float uAlphaCutoff;
uniform float uBaseAlpha;
#if LINEAR_DEPTH
uniform vec3 uLightPos;
uniform float uFar;
#endif

in vec3 vWorld;
in vec2 vUV;

void main() {
    if (uAlphaCutoff >= 0.0) {
        float a = uBaseAlpha * (uHasTexture ? sampleMaterial(uBaseColorTex, vUV).a : 1.0);
        if (a < uAlphaCutoff) discard;
    }
#if LINEAR_DEPTH
    gl_FragDepth = length(vWorld - uLightPos) / uFar;
#endif
}
