// The environment as the sky: pixels with no surface get the map's radiance (mip 0) along the
// view ray.
#include "envmap/envmap.glsl"
#include "common/shared.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = kUnitDepth) uniform sampler2D uDepth;
layout(binding = 0) uniform samplerCube uPrefiltered;
layout(binding = 0, rgba16f) uniform image2D uHDR;

uniform ivec2 uSize;
uniform mat4 uInvViewProj;
uniform vec3 uEye;
uniform float uIntensity;
uniform float uRotation;

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, uSize))) return;
    if (texelFetch(uDepth, px, 0).r < 1.0) return;
    vec2 uv = (vec2(px) + 0.5) / vec2(uSize);
    vec4 w = uInvViewProj * vec4(uv * 2.0 - 1.0, 1.0, 1.0);
    vec3 d = normalize(w.xyz / w.w - uEye);
    imageStore(uHDR, px, vec4(uIntensity * textureLod(uPrefiltered, envRotateY(d, -uRotation), 0.0).rgb, 1.0));
}
