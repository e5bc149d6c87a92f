// Clears the voxel volumes over a region of logical voxels (the whole grid, or a clipmap slab at
// its toroidal place) before it is voxelized.
#include "vct/common.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup3DX, local_size_y = kGroup3DY, local_size_z = kGroup3DZ) in;
layout(binding = kVCTImageAlbedo, r32ui) uniform writeonly uimage3D uAlbedoVox;
layout(binding = kVCTImageNormal, r32ui) uniform writeonly uimage3D uNormalVox;
layout(binding = kVCTImageSides, r32ui) uniform writeonly uimage3D uSidesVox;
layout(binding = kVCTImagePosition, r32ui) uniform writeonly uimage3D uPositionVox;

void main() {
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (!insideGrid(v) || any(lessThan(v, uVCT.clipMin.xyz)) || any(greaterThanEqual(v, uVCT.clipMax.xyz))) return;
    ivec3 t = texelOf(v);
    imageStore(uAlbedoVox, t, uvec4(0u));
    imageStore(uNormalVox, t, uvec4(0u));
    imageStore(uPositionVox, t, uvec4(0u));
    if (uVCT.sides != 0)
        for (int s = 0; s < 6; ++s) imageStore(uSidesVox, t + ivec3(s * uVCT.resolution, 0, 0), uvec4(0u));
}
