// One propagation step, as a gather (KD09; seed 000 section 1). A cell receives from each of its
// 6 neighbours the flux through 5 of its faces: the face it shares with the neighbour (solid
// angle 0.4006696846 seen from the neighbour's centre) and the 4 faces beside it (0.4234413544),
// each re-emitted as a clamped cosine lobe towards that face. The lobes carry the weights solid
// angle / pi: flux = solid angle * intensity, and a lobe of flux F has intensity F / pi * cos.
// The loops have constant bounds so the compiler folds each face's basis and lobe into constants
// (a table of uniforms measured slower on llvmpipe).
// Blocking scales the flux through a face by its transmittance, computed once per frame from the
// geometry volume (transmit.comp).
// The grids are read through buffer textures and written through buffer images that view the
// same storage as the other passes' shader storage buffers: on llvmpipe a shader storage load
// at a per-invocation address runs a loop over the SIMD lanes, one scalar load each, and the 18
// vec4 loads of a cell's neighbours took 10 of a step's 11 ms at 32^3; texelFetch gathers all
// lanes at once (a step 3.8 ms, same pixels).
#include "lpv/common.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup3DX, local_size_y = kGroup3DY, local_size_z = kGroup3DZ) in;
layout(binding = kLPVUnitPropagateSource) uniform samplerBuffer uSource;  // 3 texels (R, G, B) per cell
layout(binding = kLPVUnitPropagateTransmit) uniform samplerBuffer uTransmit;  // 2 texels per cell, from transmit.comp
layout(binding = kLPVImagePropagateDestination, rgba32f) uniform writeonly imageBuffer uDestination;
layout(binding = kLPVImagePropagateAccum, rgba32f) uniform imageBuffer uAccum;

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
        t0 = texelFetch(uTransmit, cellIndex(cell, res) * 2);
        t1 = texelFetch(uTransmit, cellIndex(cell, res) * 2 + 1);
    }
    float faceTransmit[6] = float[6](t0.x, t0.y, t0.z, t0.w, t1.x, t1.y);
    for (int d = 0; d < 6; ++d) {
        ivec3 dir = kDirections[d];
        ivec3 neighbour = cell - dir;  // light flows from the neighbour along dir
        if (!insideGrid(neighbour, res)) continue;
        int ni = cellIndex(neighbour, res) * 3;
        vec4 r = texelFetch(uSource, ni), g = texelFetch(uSource, ni + 1), b = texelFetch(uSource, ni + 2);
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
    imageStore(uDestination, base, outR);
    imageStore(uDestination, base + 1, outG);
    imageStore(uDestination, base + 2, outB);
    imageStore(uAccum, base, imageLoad(uAccum, base) + outR);
    imageStore(uAccum, base + 1, imageLoad(uAccum, base + 1) + outG);
    imageStore(uAccum, base + 2, imageLoad(uAccum, base + 2) + outB);
}
