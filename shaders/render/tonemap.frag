// HDR to display: exposure (2^EV), tone curve, sRGB encoding into an RGBA8 target.
#include "render/render_shared.h"
#include "common/color.glsl"

layout(binding = kUnitSource) uniform sampler2D uHDR;

in vec2 vUV;
out vec4 oColor;

void main() {
    vec3 c = texelFetch(uHDR, ivec2(gl_FragCoord.xy), 0).rgb * uRender.exposureScale;
    oColor = vec4(linearToSRGB(toneMap(c, uRender.toneOp)), 1.0);
}
