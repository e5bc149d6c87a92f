// Propagation, first half of a step: the flux each cell sends through each of its six faces
// (seed 001 eq. 3.2.2, corrected). The source's transfer, written as it stands, multiplies the
// flux by the face's solid angle (2.09) at every step: the integral it calls an average is never
// divided by the solid angle. Here the part leaving through face d is dot(L, faceLobe(d)), the
// integral of the cell's intensity over the face's solid angle, exact for 2-band SH.
//
// Two choices where the source is silent:
//   - Occupancy: a face between two occupied cells is closed (light moves through empty cells,
//     "from one voxel boundary to the next"); so is nothing else. A face at the grid's edge is
//     open: the light leaves the grid and is lost.
//   - Non-negative, flux-conserving: 2-band lobes are negative behind, and clamping the negative
//     faces alone adds light (x1.11 at the first step); the clamped parts of the open faces are
//     scaled to the cell's whole flux (2 sqrt(pi) times band 0), per colour. A cell with no open
//     face (inside thick geometry) sends nothing.
#include "diffusion/common.glsl"

layout(local_size_x = kGroup3DX, local_size_y = kGroup3DY, local_size_z = kGroup3DZ) in;
layout(binding = kDiffusionImageAlbedo, r32ui) uniform readonly uimage3D uAlbedo;
layout(binding = kDiffusionUnitStepSource) uniform samplerBuffer uSource;  // 3 texels (R, G, B SH) per cell
layout(binding = kDiffusionUnitStepOrder) uniform samplerBuffer uOrderSource;
layout(binding = kDiffusionImageStepOutgoing, rgba32f) uniform writeonly imageBuffer uOutgoing;  // 6 per cell

void main() {
    ivec3 cell = ivec3(gl_GlobalInvocationID);
    if (!insideGrid(cell)) return;
    int i = cellIndex(cell);
    vec4 r = texelFetch(uSource, 3 * i), g = texelFetch(uSource, 3 * i + 1), b = texelFetch(uSource, 3 * i + 2);
    vec3 parts[6];
    vec3 total = vec3(0.0);
    if (r.x > 0.0 || g.x > 0.0 || b.x > 0.0) {
        bool solid = occupied(imageLoad(uAlbedo, cell).r);
        for (int d = 0; d < 6; ++d) {
            ivec3 next = cell + kDirections[d];
            bool open = !solid || !insideGrid(next) || !occupied(imageLoad(uAlbedo, next).r);
            vec4 lobe = faceLobe(vec3(kDirections[d]));
            parts[d] = open ? max(vec3(dot(r, lobe), dot(g, lobe), dot(b, lobe)), vec3(0.0)) : vec3(0.0);
            total += parts[d];
        }
    } else {
        for (int d = 0; d < 6; ++d) parts[d] = vec3(0.0);
    }
    vec3 flux = 2.0 * sqrt(kPi) * max(vec3(r.x, g.x, b.x), vec3(0.0));
    vec3 scale = mix(vec3(0.0), flux / max(total, vec3(1e-30)), greaterThan(total, vec3(0.0)));
    // w: the bounce order of the light leaving (gather.comp).
    float order = texelFetch(uOrderSource, i).r;
    for (int d = 0; d < 6; ++d) imageStore(uOutgoing, 6 * i + d, vec4(parts[d] * scale, order));
}
