// The accumulated SH of each cell into three RGBA16F volumes (R, G, B) for trilinear lookups.
#include "lpv/common.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup3D, local_size_y = kGroup3D, local_size_z = kGroup3D) in;
layout(std430, binding = kLPVBufferAccum) readonly buffer Accumulated { float accum[]; };
layout(binding = kLPVImageSHR, rgba16f) uniform writeonly image3D uR;
layout(binding = kLPVImageSHG, rgba16f) uniform writeonly image3D uG;
layout(binding = kLPVImageSHB, rgba16f) uniform writeonly image3D uB;

void main() {
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (!insideGrid(c)) return;
    int b = cellIndex(c) * 12;
    imageStore(uR, c, vec4(accum[b], accum[b + 1], accum[b + 2], accum[b + 3]));
    imageStore(uG, c, vec4(accum[b + 4], accum[b + 5], accum[b + 6], accum[b + 7]));
    imageStore(uB, c, vec4(accum[b + 8], accum[b + 9], accum[b + 10], accum[b + 11]));
}
