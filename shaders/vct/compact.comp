// Lists the occupied voxels of a grid for the bounce pass, so its cone traces run on full
// invocation groups instead of grids where most lanes are empty space (10x faster on llvmpipe).
// Entry: x | y << 10 | z << 20. The first invocation of every 64 entries also counts a group of
// the indirect dispatch that follows.
#include "vct/common.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup3DX, local_size_y = kGroup3DY, local_size_z = kGroup3DZ) in;
layout(binding = kVCTImageAlbedo, r32ui) uniform readonly uimage3D uAlbedoVox;
layout(std430, binding = kVCTBufferDispatch) buffer Dispatch { uint groupsX, groupsY, groupsZ, count; };
layout(std430, binding = kVCTBufferVoxels) writeonly buffer Voxels { uint voxels[]; };

void main() {
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (!insideGrid(v) || !occupied(imageLoad(uAlbedoVox, texelOf(v)).r)) return;
    uint i = atomicAdd(count, 1u);
    voxels[i] = uint(v.x) | (uint(v.y) << 10) | (uint(v.z) << 20);
    if (i % uint(kGroup1D) == 0u) atomicAdd(groupsX, 1u);
}
