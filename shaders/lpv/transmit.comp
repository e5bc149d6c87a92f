// Face transmittance, once per frame: for each cell and each of the 6 directions light can enter
// it, 1 - blocking sampled from the geometry volumes at the centre of the face it enters through.
// Propagation steps then read 6 numbers instead of sampling the volume 6 times per step.
#include "lpv/common.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup3DX, local_size_y = kGroup3DY, local_size_z = kGroup3DZ) in;
layout(binding = kLPVUnitGeometryRSM) uniform sampler3D uGeometryRSM;
layout(binding = kLPVUnitGeometryGBuffer) uniform sampler3D uGeometryGBuffer;
layout(std430, binding = kLPVBufferTransmit) writeonly buffer Transmit { vec4 transmit[]; };  // 2 per cell: +x -x +y -y, +z -z


// Blocking of light flowing along d by surfels whose summed lobes are gv. The 2-band lobe of area a
// is a * (0.25 + 0.5 cos): evaluated as it is, it would block 25 % of the light running parallel
// to a wall on every step. Only the band-1 part, doubled, is kept: a * cos, for fronts facing
// the flow.
float oneSided(vec4 gv, vec3 d) { return max(2.0 * (shEval(gv, -d) - gv.x * kY00), 0.0); }

void main() {
    ivec3 cell = ivec3(gl_GlobalInvocationID);
    if (!insideGrid(cell)) return;
    float t[6];
    for (int d = 0; d < 6; ++d) {
        vec3 fd = vec3(kDirections[d]);
        // Geometry samples sit on cell corners: grid point x is texture coordinate (x + 0.5) / (res + 1).
        vec3 face = vec3(cell) + 0.5 - 0.5 * fd;
        vec3 tc = (face + 0.5) / float(uLPV.resolution + 1);
        float blocking = max(oneSided(texture(uGeometryRSM, tc), fd), oneSided(texture(uGeometryGBuffer, tc), fd));
        t[d] = 1.0 - clamp(uLPV.occlusionStrength * blocking, 0.0, 1.0);
    }
    int i = cellIndex(cell) * 2;
    transmit[i] = vec4(t[0], t[1], t[2], t[3]);
    transmit[i + 1] = vec4(t[4], t[5], 1.0, 1.0);
}
