// Shadow pass fragment: alpha-masked materials cut holes; point lights store distance / far so
// the six cube faces share one linear depth scale.
#include "common/shared.h"

layout(binding = kUnitBaseColor) uniform sampler2D uBaseColorTex;
uniform bool uHasTexture;
uniform float uAlphaCutoff;
uniform float uBaseAlpha;
uniform bool uLinearDepth;
uniform vec3 uLightPos;
uniform float uFar;

in vec3 vWorld;
in vec2 vUV;

void main() {
    if (uAlphaCutoff >= 0.0) {
        float a = uBaseAlpha * (uHasTexture ? texture(uBaseColorTex, vUV).a : 1.0);
        if (a < uAlphaCutoff) discard;
    }
    gl_FragDepth = uLinearDepth ? length(vWorld - uLightPos) / uFar : gl_FragCoord.z;
}
