// Copies the RSM and G-buffer geometry volumes into two textures. They are kept apart because
// each holds one-sided blocking (a surfel blocks light that hits its front): the RSM sees the lit
// side of a thin wall and the camera often the other, so the transmittance pass takes the larger
// blocking of the two for each direction (adding them would count a surface both see twice).
#include "lpv/common.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup3DX, local_size_y = kGroup3DY, local_size_z = kGroup3DZ) in;
layout(std430, binding = kLPVBufferGeometryRSM) readonly buffer FromRSM { float fromRSM[]; };
layout(std430, binding = kLPVBufferGeometryGBuffer) readonly buffer FromGBuffer { float fromGBuffer[]; };
layout(binding = kLPVImageGeometryRSM, rgba16f) uniform writeonly image3D uGeometryRSM;
layout(binding = kLPVImageGeometryGBuffer, rgba16f) uniform writeonly image3D uGeometryGBuffer;

void main() {
    ivec3 c = ivec3(gl_GlobalInvocationID);
    int r1 = uLPV.resolution + 1;
    if (any(greaterThanEqual(c, ivec3(r1)))) return;
    int base = ((c.z * r1 + c.y) * r1 + c.x) * 4;
    imageStore(uGeometryRSM, c, vec4(fromRSM[base], fromRSM[base + 1], fromRSM[base + 2], fromRSM[base + 3]));
    imageStore(uGeometryGBuffer, c,
               vec4(fromGBuffer[base], fromGBuffer[base + 1], fromGBuffer[base + 2], fromGBuffer[base + 3]));
}
