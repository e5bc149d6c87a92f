// The accumulation as a volume to look at (the diffusion.accumulated debug view): per occupied
// cell, the flux per area that arrived over all steps (band 0 times 2 sqrt(pi), per colour), as
// irradiance over pi like the indirect term; alpha 1 where occupied.
#include "diffusion/common.glsl"

layout(local_size_x = kGroup3D, local_size_y = kGroup3D, local_size_z = kGroup3D) in;
layout(binding = kDiffusionImageAlbedo, r32ui) uniform readonly uimage3D uAlbedo;
layout(binding = kDiffusionImageView, rgba16f) uniform writeonly image3D uView;
layout(std430, binding = kDiffusionBufferAccum) readonly buffer Accumulated { vec4 accum[]; };

void main() {
    ivec3 cell = ivec3(gl_GlobalInvocationID);
    if (!insideGrid(cell)) return;
    int i = 3 * cellIndex(cell);
    bool solid = occupied(imageLoad(uAlbedo, cell).r);
    vec3 arrived = 2.0 * sqrt(kPi) * vec3(accum[i].x, accum[i + 1].x, accum[i + 2].x);
    imageStore(uView, cell, solid ? vec4(uDiffusion.intensity * max(arrived, vec3(0.0)) / kPi, 1.0) : vec4(0.0));
}
