// Bounces (KD09 section 5 mentions them; seed 000 does not implement them). After a bounce's
// propagation, per cell: the total shade reads gains the bounce's injection and its propagated
// light P; then the geometry volume's surfels reflect P as the next bounce's injection.
//
// A corner of the geometry volume holds its surfels' summed lobes GV = sum (A / cell face) *
// cosLobe(n) and their albedo. Lit by irradiance E = kLPVRadianceScale * dot(P, cosLobe(-n)) (P
// holds intensity per cell face, inject.comp; shade's convention), they reflect flux albedo * E * A,
// injected as inject.comp does, flux per cell face / pi * cosLobe(n): albedo / pi *
// kLPVRadianceScale * dot(P, cosLobe(-n)) * GV. n is the
// direction of GV's band 1 (a corner with surfels facing opposite ways reflects along their
// mean). As first-bounce VPLs move half a cell along their normal, a corner's surfels (the cube of
// one cell around it) move half a cell along n, and each cell takes the share of that cube it
// overlaps (box-filter weights that sum to one, so no energy is made or lost). E is read from the
// cell the light lands in, after it has crossed no blocking face of the surface. Of the two
// geometry volumes (RSM and G-buffer surfels, which often see the same surface) a corner uses the
// one with the larger coverage, so a surface both see reflects once.
#include "lpv/common.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup3DX, local_size_y = kGroup3DY, local_size_z = kGroup3DZ) in;
// Buffer views of the grids (propagate.comp says why not shader storage).
layout(binding = kLPVUnitBounceGather) uniform samplerBuffer uGathered;  // 3 texels (R, G, B) per cell
layout(binding = kLPVUnitBounceGeometryRSM) uniform samplerBuffer uFromRSM;  // one per corner
layout(binding = kLPVUnitBounceGeometryGBuffer) uniform samplerBuffer uFromGBuffer;
layout(binding = kLPVUnitBounceAlbedo) uniform samplerBuffer uAlbedo;  // RGB x coverage, coverage
layout(binding = kLPVImageBounceInject, rgba32f) uniform imageBuffer uInjected;
layout(binding = kLPVImageBounceTotal, rgba32f) uniform imageBuffer uTotal;

void main() {
    const int res = uLPV.resolution;
    ivec3 cell = ivec3(gl_GlobalInvocationID);
    if (!insideGrid(cell, res)) return;
    int base = cellIndex(cell, res) * 3;
    vec4 pR = texelFetch(uGathered, base), pG = texelFetch(uGathered, base + 1), pB = texelFetch(uGathered, base + 2);
    imageStore(uTotal, base, imageLoad(uTotal, base) + imageLoad(uInjected, base) + pR);
    imageStore(uTotal, base + 1, imageLoad(uTotal, base + 1) + imageLoad(uInjected, base + 1) + pG);
    imageStore(uTotal, base + 2, imageLoad(uTotal, base + 2) + imageLoad(uInjected, base + 2) + pB);
    vec4 outR = vec4(0.0), outG = vec4(0.0), outB = vec4(0.0);
    int r1 = res + 1;
    for (int i = 0; i < 8; ++i) {
        ivec3 g = cell + ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
        int gi = (g.z * r1 + g.y) * r1 + g.x;
        vec4 a = texelFetch(uFromRSM, gi), b = texelFetch(uFromGBuffer, gi);
        vec4 gv = a.x >= b.x ? a : b;
        vec4 alb = texelFetch(uAlbedo, gi);
        if (gv.x <= 0.0 || alb.w <= 0.0) continue;
        vec3 dir = vec3(-gv.w, -gv.y, gv.z);  // band 1 of cosLobe(n) is kCosLobe1 * (-n.y, n.z, -n.x)
        float len = length(dir);
        if (len <= 1e-6 * gv.x) continue;
        vec3 n = dir / len;
        // The overlap of the corner's cube, moved half a cell along n, with this cell.
        vec3 overlap = max(1.0 - abs(vec3(g) + 0.5 * n - (vec3(cell) + 0.5)), 0.0);
        float w = overlap.x * overlap.y * overlap.z;
        if (w <= 0.0) continue;
        vec4 lobe = shCosLobe(-n);
        vec3 e = max(vec3(dot(pR, lobe), dot(pG, lobe), dot(pB, lobe)), 0.0) * kLPVRadianceScale;
        vec3 reflected = w * (alb.rgb / alb.w) * e / kPi;
        outR += reflected.r * gv;
        outG += reflected.g * gv;
        outB += reflected.b * gv;
    }
    imageStore(uInjected, base, outR);
    imageStore(uInjected, base + 1, outG);
    imageStore(uInjected, base + 2, outB);
}
