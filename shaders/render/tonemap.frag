// HDR to display: exposure (2^EV), tone curve, sRGB encoding into an RGBA8 target.
#include "common/shared.h"
#include "common/color.glsl"

layout(binding = kUnitSource) uniform sampler2D uHDR;
uniform float uExposureScale;
uniform int uToneOp;

in vec2 vUV;
out vec4 oColor;

void main() {
    vec3 c = texelFetch(uHDR, ivec2(gl_FragCoord.xy), 0).rgb * uExposureScale;
    oColor = vec4(linearToSRGB(toneMap(c, uToneOp)), 1.0);
}
