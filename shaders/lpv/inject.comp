// Injection: every RSM texel is a virtual point light with intensity flux / pi * max(n.w, 0),
// moved `nudge` cells along its normal, added to its cell's SH (float atomic adds,
// exact under contention). The flux is the texel's exitance times its surfel's
// area (rsm.frag), counted in units of the cell's face area: the volumes then hold intensity per
// cell face, whose size does not grow or shrink with the scene's units (half floats hold it), and
// shading reads radiance from them without dividing by the cell's area.
#include "common/atomic_float.glsl"
#include "lpv/common.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup2D, local_size_y = kGroup2D) in;
layout(binding = kLPVImageFlux, rgba16f) uniform readonly image2D uFlux;
layout(binding = kLPVImageNormal, rgba16f) uniform readonly image2D uNormal;
layout(binding = kLPVImagePosition, rgba32f) uniform readonly image2D uPosition;
layout(std430, binding = kLPVBufferInject) buffer Grid { GI_ATOMIC_FLOAT grid[]; };

void atomicAddFloat(int i, float v) { GI_ATOMIC_ADD_FLOAT(grid[i], v); }

void main() {
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(t, ivec2(uLPV.width, uLPV.height)))) return;
    vec4 pos = imageLoad(uPosition, t);
    float cellSize = uLPV.gridMinCell.w;
    vec3 flux = imageLoad(uFlux, t).rgb * (pos.w / (cellSize * cellSize));
    if (pos.w <= 0.0 || max(flux.r, max(flux.g, flux.b)) <= 0.0) return;
    vec3 n = normalize(imageLoad(uNormal, t).xyz);
    vec3 p = pos.xyz + n * uLPV.nudge * cellSize;
    ivec3 c = ivec3(floor((p - uLPV.gridMinCell.xyz) / cellSize));
    if (!insideGrid(c)) return;
    vec4 lobe = shCosLobe(n) / kPi;
    int base = cellIndex(c) * 12;
    for (int k = 0; k < 4; ++k) {
        atomicAddFloat(base + k, lobe[k] * flux.r);
        atomicAddFloat(base + 4 + k, lobe[k] * flux.g);
        atomicAddFloat(base + 8 + k, lobe[k] * flux.b);
    }
}
