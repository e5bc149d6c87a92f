// The surface voxels' encoding (gi/vct/surface_voxels.h writes it): r32ui volumes holding RGBA8
// running averages, rgb the mean, a the sample count. Read by VCT's passes and the diffusion
// technique's; no uniform block, so any pass may include it.

// rgb of an RGBA8-in-r32ui running average, and whether anything was written there.
vec4 unpackVoxel(uint v) { return unpackUnorm4x8(v); }
bool occupied(uint v) { return (v >> 24) != 0u; }
// The mean normal of a normal volume's texel (stored as n * 0.5 + 0.5; not normalised, and short
// where the fragments' normals disagree).
vec3 voxelNormal(uint v) { return unpackVoxel(v).xyz * 2.0 - 1.0; }
// The mean position of a voxel's surface fragments within it, from a position volume's texel:
// 0 to 1 along each axis of the voxel (voxelize.frag).
vec3 voxelSurfaceOffset(uint v) { return occupied(v) ? unpackVoxel(v).xyz : vec3(0.5); }
// How much of a voxel's back (the side against its mean normal) is a surface: the fragments
// facing against the mean over those facing along it, (1 - m) / (1 + m) from the mean's length m
// (for two opposite faces, fractions f and 1 - f give m = |2f - 1|). 1 for the two faces of a
// thin wall in one voxel, 0 where every fragment faces one way: there the back is the inside of a
// solid (a hollow box's interior, a wall's core) or the outside of a one-sided shell, and light
// that reaches it, or that its cones gather there, would reach the front through the voxel's
// isotropic radiance (a sunlit roof's back lit a room below it).
float backWeight(uint packedNormal) {
    float m = min(length(voxelNormal(packedNormal)), 1.0);
    return (1.0 - m) / (1.0 + m);
}
