// Shared by the VCT compute passes: the voxel grid (uVCT's grid fields) and the packed RGBA8 volumes.
#include "common/shared.h"
#include "common/sh.h"
#include "vct/vct_shared.h"

bool insideGrid(ivec3 c) { return all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(uVCT.resolution))); }
ivec3 texelOf(ivec3 voxel) { return (voxel + uVCT.wrapOffset.xyz) % uVCT.resolution; }
#include "vct/voxel_encoding.glsl"
// The mean position of the surface in voxel v (a position volume's texel, voxelize.frag), in
// voxels from the grid's corner; the voxel's centre where the grid keeps no positions (wrapOffset.w 0).
vec3 voxelSurfaceCell(ivec3 voxel, uint packedPosition) { return vec3(voxel) + (uVCT.wrapOffset.w != 0 ? voxelSurfaceOffset(packedPosition) : vec3(0.5)); }
// The same in world space.
vec3 voxelSurface(ivec3 voxel, uint packedPosition) { return uVCT.gridMin.xyz + voxelSurfaceCell(voxel, packedPosition) * uVCT.cellSize; }
