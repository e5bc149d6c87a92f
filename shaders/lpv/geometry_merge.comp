// Merges one light's RSM surfels into the RSM geometry volume: each corner keeps the lobe with
// the larger coverage (band 0), as bounce.comp and transmit.comp keep the larger of the RSM and
// G-buffer volumes. Summed, a surface that n lights' RSMs all see blocked and reflected n times:
// two lights at one place, each of half the intensity, gave the room 14 % more light than one,
// and sixteen lights over a room made it 2.9x too bright.
#include "lpv/common.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup3DX, local_size_y = kGroup3DY, local_size_z = kGroup3DZ) in;
layout(std430, binding = kLPVBufferGeometryRSM) buffer Merged { float merged[]; };
layout(std430, binding = kLPVBufferGeometryGBuffer) readonly buffer FromLight { float fromLight[]; };

void main() {
    ivec3 c = ivec3(gl_GlobalInvocationID);
    int r1 = uLPV.resolution + 1;
    if (any(greaterThanEqual(c, ivec3(r1)))) return;
    int base = ((c.z * r1 + c.y) * r1 + c.x) * 4;
    if (fromLight[base] <= merged[base]) return;
    for (int k = 0; k < 4; ++k) merged[base + k] = fromLight[base + k];
}
