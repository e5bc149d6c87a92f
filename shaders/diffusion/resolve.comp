// The volumes the debug views show, per cell:
//   - diffusion.accumulated: per occupied cell, the flux per area that arrived over all steps
//     (band 0 times 2 sqrt(pi), per colour), as irradiance over pi like the indirect term;
//     alpha 1 where occupied.
//   - diffusion.inFlight: the light in flight after the last step (the propagation buffer), in
//     every cell, the same units; alpha 1 where any is.
//   - diffusion.bounces: per occupied cell that received light, the flux-weighted mean bounce
//     order of what it received (1: light straight from a directly lit surface), as a colour
//     ramp from blue (1) through green (2) and yellow (3) to red (4 and more).
#include "diffusion/common.glsl"

layout(local_size_x = kGroup3DX, local_size_y = kGroup3DY, local_size_z = kGroup3DZ) in;
layout(binding = kDiffusionImageAlbedo, r32ui) uniform readonly uimage3D uAlbedo;
layout(binding = kDiffusionImageView, rgba16f) uniform writeonly image3D uView;
layout(binding = kDiffusionImageViewInFlight, rgba16f) uniform writeonly image3D uViewInFlight;
layout(binding = kDiffusionImageViewBounces, rgba16f) uniform writeonly image3D uViewBounces;
layout(std430, binding = kDiffusionBufferAccum) readonly buffer Accumulated { vec4 accum[]; };
layout(std430, binding = kDiffusionBufferSource) readonly buffer Source { vec4 src[]; };
layout(std430, binding = kDiffusionBufferOrderAccum) readonly buffer OrderAccumulated { float orderAccum[]; };

// Blue, green, yellow, red over t in [0, 1].
vec3 ramp(float t) { return clamp(vec3(1.5 - abs(4.0 * t - 3.0), 1.5 - abs(4.0 * t - 2.0), 1.5 - abs(4.0 * t - 1.0)), 0.0, 1.0); }

void main() {
    ivec3 cell = ivec3(gl_GlobalInvocationID);
    if (!insideGrid(cell)) return;
    int c = cellIndex(cell), i = 3 * c;
    bool solid = occupied(imageLoad(uAlbedo, cell).r);
    vec3 arrived = 2.0 * sqrt(kPi) * vec3(accum[i].x, accum[i + 1].x, accum[i + 2].x);
    imageStore(uView, cell, solid ? vec4(uDiffusion.intensity * max(arrived, vec3(0.0)) / kPi, 1.0) : vec4(0.0));
    vec3 flight = max(2.0 * sqrt(kPi) * vec3(src[i].x, src[i + 1].x, src[i + 2].x), vec3(0.0));
    imageStore(uViewInFlight, cell, vec4(uDiffusion.intensity * flight / kPi, any(greaterThan(flight, vec3(0.0))) ? 1.0 : 0.0));
    float flux = arrived.r + arrived.g + arrived.b;
    vec4 bounces = vec4(0.0);
    if (solid && flux > 0.0) bounces = vec4(ramp(clamp((orderAccum[c] / flux - 1.0) / 3.0, 0.0, 1.0)), 1.0);
    imageStore(uViewBounces, cell, bounces);
}
