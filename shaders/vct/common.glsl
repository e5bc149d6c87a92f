// Shared by the VCT compute passes: the voxel grid's uniforms and the packed RGBA8 volumes.
#include "common/shared.h"
#include "common/sh.h"
#include "vct/vct_shared.h"

uniform int uResolution;    // voxels per side
uniform vec3 uGridMin;      // world position of the grid's corner (logical voxel 0)
uniform float uCellSize;    // world size of a voxel
uniform ivec3 uWrapOffset;  // clipmap: texel = (voxel + offset) mod resolution

bool insideGrid(ivec3 c) { return all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(uResolution))); }
ivec3 texelOf(ivec3 voxel) { return (voxel + uWrapOffset) % uResolution; }
vec3 voxelCentre(ivec3 voxel) { return uGridMin + (vec3(voxel) + 0.5) * uCellSize; }

// rgb of an RGBA8-in-r32ui running average, and whether anything was written there.
vec4 unpackVoxel(uint v) { return unpackUnorm4x8(v); }
bool occupied(uint v) { return (v >> 24) != 0u; }
