// The surface voxels' encoding (gi/vct/surface_voxels.h writes it): r32ui volumes holding RGBA8
// running averages, rgb the mean, a the sample count. Read by VCT's passes and the diffusion
// technique's; no uniform block, so any pass may include it.

// rgb of an RGBA8-in-r32ui running average, and whether anything was written there.
vec4 unpackVoxel(uint v) { return unpackUnorm4x8(v); }
bool occupied(uint v) { return (v >> 24) != 0u; }
// The mean normal of a normal volume's texel (stored as n * 0.5 + 0.5; not normalised, and short
// where the fragments' normals disagree).
vec3 voxelNormal(uint v) { return unpackVoxel(v).xyz * 2.0 - 1.0; }
