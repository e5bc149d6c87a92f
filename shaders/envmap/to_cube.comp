// The latlong environment (uploaded bottom row first) into mip 0 of a cube map (bilinear, u
// wrapping), unrotated: the rotation applies where the cube is read.
#include "envmap/envmap.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup2D, local_size_y = kGroup2D, local_size_z = 1) in;
layout(binding = kEnvUnitSource) uniform sampler2D uLatLong;
layout(binding = kEnvImageTarget, rgba16f) uniform writeonly imageCube uCube;

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (id.x >= uEnv.size || id.y >= uEnv.size) return;
    vec3 d = cubeDirection(id.z, id.xy, uEnv.size);
    vec2 uv = latLongUV(d, 0.0);
    imageStore(uCube, id, vec4(textureLod(uLatLong, vec2(uv.x, 1.0 - uv.y), 0.0).rgb, 1.0));  // stored bottom row first
}
