// Shared by the VCT compute passes: the voxel grid (uVCT's grid fields) and the packed RGBA8 volumes.
#include "common/shared.h"
#include "common/sh.h"
#include "vct/vct_shared.h"

bool insideGrid(ivec3 c) { return all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(uVCT.resolution))); }
ivec3 texelOf(ivec3 voxel) { return (voxel + uVCT.wrapOffset.xyz) % uVCT.resolution; }
vec3 voxelCentre(ivec3 voxel) { return uVCT.gridMin.xyz + (vec3(voxel) + 0.5) * uVCT.cellSize; }
#include "vct/voxel_encoding.glsl"
