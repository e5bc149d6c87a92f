// One propagation step, as a gather (KD09; seed 000 section 1). A cell receives from each of its
// 6 neighbours the flux through 5 of its faces: the face it shares with the neighbour (solid
// angle 0.4006696846 seen from the neighbour's centre) and the 4 faces beside it (0.4234413544),
// each re-emitted as a clamped cosine lobe towards that face. The lobes carry the weights solid
// angle / pi: flux = solid angle * intensity, and a lobe of flux F has intensity F / pi * cos.
// The loops have constant bounds so the compiler folds each face's basis and lobe into constants
// (a table of uniforms measured slower on llvmpipe).
// Blocking scales the flux through a face by its transmittance, computed once per frame from the
// geometry volume (transmit.comp).
#include "lpv/common.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup3D, local_size_y = kGroup3D, local_size_z = kGroup3D) in;
layout(std430, binding = kLPVBufferSource) readonly buffer Source { vec4 src[]; };  // 3 vec4 (R, G, B) per cell
layout(std430, binding = kLPVBufferDestination) writeonly buffer Destination { vec4 dst[]; };
layout(std430, binding = kLPVBufferAccum) buffer Accumulated { vec4 accum[]; };
layout(std430, binding = kLPVBufferTransmit) readonly buffer Transmit { vec4 transmit[]; };  // from transmit.comp

const float kMainFace = 0.12753712;  // 0.4006696846 / pi
const float kSideFace = 0.13478556;  // 0.4234413544 / pi


void main() {
    // Read once: llvmpipe reloads a block member at every use inside the neighbour loop.
    const int res = uLPV.resolution;
    ivec3 cell = ivec3(gl_GlobalInvocationID);
    if (!insideGrid(cell, res)) return;
    vec4 outR = vec4(0.0), outG = vec4(0.0), outB = vec4(0.0);
    vec4 t0 = vec4(1.0), t1 = vec4(1.0);
    if (uLPV.blocking != 0) {
        t0 = transmit[cellIndex(cell, res) * 2];
        t1 = transmit[cellIndex(cell, res) * 2 + 1];
    }
    float faceTransmit[6] = float[6](t0.x, t0.y, t0.z, t0.w, t1.x, t1.y);
    for (int d = 0; d < 6; ++d) {
        ivec3 dir = kDirections[d];
        ivec3 neighbour = cell - dir;  // light flows from the neighbour along dir
        if (!insideGrid(neighbour, res)) continue;
        int ni = cellIndex(neighbour, res) * 3;
        vec4 r = src[ni], g = src[ni + 1], b = src[ni + 2];
        float transmit = faceTransmit[d];
        vec3 fd = vec3(dir);
        vec4 e = shBasis(fd);
        vec4 lobe = shCosLobe(fd) * (kMainFace * transmit);
        outR += max(dot(r, e), 0.0) * lobe;
        outG += max(dot(g, e), 0.0) * lobe;
        outB += max(dot(b, e), 0.0) * lobe;
        for (int s = 0; s < 6; ++s) {
            vec3 side = vec3(kDirections[s]);
            if (abs(dot(side, fd)) > 0.5) continue;
            e = shBasis(0.894427191 * fd + 0.447213595 * side);
            lobe = shCosLobe(side) * (kSideFace * transmit);
            outR += max(dot(r, e), 0.0) * lobe;
            outG += max(dot(g, e), 0.0) * lobe;
            outB += max(dot(b, e), 0.0) * lobe;
        }
    }
    int base = cellIndex(cell, res) * 3;
    dst[base] = outR;
    dst[base + 1] = outG;
    dst[base + 2] = outB;
    accum[base] += outR;
    accum[base + 1] += outG;
    accum[base + 2] += outB;
}
