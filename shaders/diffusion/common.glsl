// Shared by the diffusion passes: cell indexing, the mean normal and the face transfer lobe; the
// surface voxels' encoding is VCT's (vct/voxel_encoding.glsl).
#include "diffusion/diffusion_shared.h"
#include "common/sh.h"
#include "vct/voxel_encoding.glsl"

// +x -x +y -y +z -z: the order of the outgoing buffer's six faces.
const ivec3 kDirections[6] = ivec3[6](ivec3(1, 0, 0), ivec3(-1, 0, 0), ivec3(0, 1, 0), ivec3(0, -1, 0), ivec3(0, 0, 1), ivec3(0, 0, -1));

int cellIndex(ivec3 c) { return (c.z * uDiffusion.resolution + c.y) * uDiffusion.resolution + c.x; }
bool insideGrid(ivec3 c) { return all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(uDiffusion.resolution))); }

// The mean normal, unit length; zero where the normals in a cell cancel (the running average is
// shorter than 1e-3), and the cell then reflects to both sides alike.
vec3 meanNormal(uint packedNormal) {
    vec3 n = voxelNormal(packedNormal);
    float l = length(n);
    return l > 1e-3 ? n / l : vec3(0.0);
}

// The face lobe towards axis d (diffusion_shared.h): its dot product with a cell's SH is the
// part of the cell's flux leaving through that face.
vec4 faceLobe(vec3 d) { return vec4(kFaceBand0, -kFaceBand1 * d.y, kFaceBand1 * d.z, -kFaceBand1 * d.x); }
