// The accumulated SH of each cell into three RGBA16F volumes (R, G, B) for trilinear lookups.
#include "lpv/common.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup3DX, local_size_y = kGroup3DY, local_size_z = kGroup3DZ) in;
layout(binding = kLPVUnitResolveAccum) uniform samplerBuffer uAccum;  // 3 texels (R, G, B) per cell
layout(binding = kLPVImageSHR, rgba16f) uniform writeonly image3D uR;
layout(binding = kLPVImageSHG, rgba16f) uniform writeonly image3D uG;
layout(binding = kLPVImageSHB, rgba16f) uniform writeonly image3D uB;

void main() {
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (!insideGrid(c)) return;
    int b = cellIndex(c) * 3;
    imageStore(uR, c, texelFetch(uAccum, b));
    imageStore(uG, c, texelFetch(uAccum, b + 1));
    imageStore(uB, c, texelFetch(uAccum, b + 2));
}
