// The environment as the sky: pixels with no surface get the map's radiance (mip 0) along the
// view ray.
#include "envmap/envmap.glsl"
#include "common/shared.h"

layout(local_size_x = kGroup2D, local_size_y = kGroup2D) in;
layout(binding = kUnitDepth) uniform sampler2D uDepth;
layout(binding = kEnvUnitPrefiltered) uniform samplerCube uPrefiltered;
layout(binding = kEnvImageTarget, rgba16f) uniform image2D uHDR;

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(uEnv.width, uEnv.height);
    if (any(greaterThanEqual(px, size))) return;
    if (texelFetch(uDepth, px, 0).r < 1.0) return;
    vec2 uv = (vec2(px) + 0.5) / vec2(size);
    vec4 w = uEnv.invViewProj * vec4(uv * 2.0 - 1.0, 1.0, 1.0);
    vec3 d = normalize(w.xyz / w.w - uEnv.eye.xyz);
    imageStore(uHDR, px, vec4(uEnv.intensity * textureLod(uPrefiltered, envRotateY(d, -uEnv.rotation), 0.0).rgb, 1.0));
}
