// The accumulation shading reads (setting smoothing): each occupied cell that light can reach
// takes the mean of its own accumulation and those of the occupied cells among its 26 neighbours
// whose mean normal lies within 18 degrees of its own (kDiffusionSmoothMinCosine), i.e. the cells
// of the same surface, and that light reaches from the side that normal faces (reachableFrom, as
// shade.comp reads them: mixing in cells open only behind the surface took 6 % off a tilted
// panel's light in DiffusionGL.ATiltedFaceShadesWithoutVoxelStripes). A plane voxelized as a staircase holds cells open on one
// face beside cells open on two, which take light through both, so the raw accumulation
// alternates from cell to cell and a tilted face shaded from it shows stripes one cell wide
// (the rotated boxes of every Cornell box); the mean over the surface's cells evens them out.
// Where two surfaces meet (a box's edge, a room's corner) the normals differ and nothing mixes,
// and cells of the other side of a wall face the other way. Empty cells, and occupied cells no
// light reaches, are copied as they are (shade reads neither). Runs once per solve, or per frame
// of a spread solve, not per frame held.
#include "diffusion/common.glsl"

layout(local_size_x = kGroup3DX, local_size_y = kGroup3DY, local_size_z = kGroup3DZ) in;
layout(binding = kDiffusionImageAlbedo, r32ui) uniform readonly uimage3D uAlbedo;
layout(binding = kDiffusionImageNormal, r32ui) uniform readonly uimage3D uNormal;
layout(binding = kDiffusionUnitSmoothSource) uniform samplerBuffer uAccum;  // 3 texels (R, G, B) per cell
layout(binding = kDiffusionImageSmoothDestination, rgba32f) uniform writeonly imageBuffer uSmoothed;

#include "diffusion/reachable.glsl"

void main() {
    ivec3 cell = ivec3(gl_GlobalInvocationID);
    if (!insideGrid(cell)) return;
    int i = 3 * cellIndex(cell);
    vec4 r = texelFetch(uAccum, i), g = texelFetch(uAccum, i + 1), b = texelFetch(uAccum, i + 2);
    if (occupied(imageLoad(uAlbedo, cell).r) && reachable(cell)) {
        vec3 n = meanNormal(imageLoad(uNormal, cell).r);
        float count = 1.0;
        for (int k = 0; k < 27; ++k) {
            ivec3 o = ivec3(k % 3, (k / 3) % 3, k / 9) - 1;
            ivec3 c = cell + o;
            if (o == ivec3(0) || !insideGrid(c) || !occupied(imageLoad(uAlbedo, c).r)) continue;
            if (dot(meanNormal(imageLoad(uNormal, c).r), n) < kDiffusionSmoothMinCosine || !reachableFrom(c, n)) continue;
            int j = 3 * cellIndex(c);
            r += texelFetch(uAccum, j);
            g += texelFetch(uAccum, j + 1);
            b += texelFetch(uAccum, j + 2);
            count += 1.0;
        }
        r /= count;
        g /= count;
        b /= count;
    }
    imageStore(uSmoothed, i, r);
    imageStore(uSmoothed, i + 1, g);
    imageStore(uSmoothed, i + 2, b);
}
