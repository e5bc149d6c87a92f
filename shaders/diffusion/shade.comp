// Shading (seed 001 section 3.3): per pixel, the accumulated light of the occupied cells among
// the eight nearest cell centres, trilinear weights renormalised over them (empty cells hold no
// light: averaging them in would darken every surface). Of those, only cells with an empty face
// neighbour on the side the pixel's normal faces count (reachableFrom): light reaches an
// occupied cell through such a face only, so a cell without one (where two walls meet, inside
// thick geometry) holds none, and one open only behind the surface (where a floor meets a wall,
// open below the floor) holds the light of the other side; averaging either in drew a dark line
// along every edge of a room. Reading only the cells open on the pixel's side (and smoothing
// over them, smooth.comp), at 128x96 against the reference: a closed room lit by a point light
// 0.802 -> 0.871 SSIM, one lit by an emissive panel 0.859 -> 0.928, a corridor lit from its far
// end 0.665 -> 0.842, CornellBox-Empty-White 0.837 -> 0.845, an open street 0.864 -> 0.854;
// diffusion_two_rooms 0.701 -> 0.782 (leak fraction 0.125 -> 0.026), the other shipped presets
// -0.008 (cornell_lamp) to +0.004. Where none is left (the point lies in an edge cell, and the
// other seven are empty: a line half a cell wide along every edge of a room), the reachable
// face neighbours of the point's own cell whose mean normal is within 60 degrees of the pixel's
// stand in, alike weighted (the wall's cells beside the edge, not the ceiling's). None of those
// either (a surface the voxelization missed): no indirect light. Irradiance is the clamped cosine lobe against the
// light's travel direction, shCosLobe(-n), times kDiffusionIrradianceScale, written as E / pi
// (the indirect term's convention), times intensity. With nudge > 0 the point read moves that many
// cells along the pixel's normal first (seed 001 has no offset; the occupied-only weights are its
// only leak control).
#include "diffusion/common.glsl"

layout(local_size_x = kGroup2D, local_size_y = kGroup2D) in;
layout(binding = kUnitNormal) uniform sampler2D uNormalG;
layout(binding = kUnitDepth) uniform sampler2D uDepth;
layout(binding = kDiffusionImageAlbedo, r32ui) uniform readonly uimage3D uAlbedo;
layout(binding = kDiffusionImageNormal, r32ui) uniform readonly uimage3D uVoxelNormal;
layout(binding = kDiffusionImageIndirect, rgba16f) uniform writeonly image2D uIndirect;
// A buffer texture over the accumulation (lpv/propagate.comp says why not shader storage).
layout(binding = kDiffusionUnitShadeAccum) uniform samplerBuffer uAccum;  // 3 texels (R, G, B) per cell

#include "diffusion/reachable.glsl"

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(uDiffusion.width, uDiffusion.height);
    if (any(greaterThanEqual(px, size))) return;
    float depth = texelFetch(uDepth, px, 0).r;
    vec3 result = vec3(0.0);
    if (depth < 1.0) {
        vec2 uv = (vec2(px) + 0.5) / vec2(size);
        vec4 w = uDiffusion.invViewProj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
        vec3 p = w.xyz / w.w;
        vec3 n = normalize(texelFetch(uNormalG, px, 0).xyz);
        vec3 g = (p - uDiffusion.gridMin.xyz) / uDiffusion.gridMin.w + n * uDiffusion.nudge - 0.5;
        ivec3 base = ivec3(floor(g));
        vec3 f = g - vec3(base);
        vec4 r = vec4(0.0), gr = vec4(0.0), b = vec4(0.0);
        float total = 0.0;
        for (int k = 0; k < 8; ++k) {
            ivec3 o = ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
            ivec3 c = base + o;
            if (!insideGrid(c) || !occupied(imageLoad(uAlbedo, c).r) || !reachableFrom(c, n)) continue;
            vec3 t = mix(1.0 - f, f, vec3(o));
            float weight = t.x * t.y * t.z;
            int i = 3 * cellIndex(c);
            r += weight * texelFetch(uAccum, i);
            gr += weight * texelFetch(uAccum, i + 1);
            b += weight * texelFetch(uAccum, i + 2);
            total += weight;
        }
        if (total == 0.0) {
            ivec3 own = ivec3(floor(g + 0.5));
            for (int d = 0; d < 6; ++d) {
                ivec3 c = own + kDirections[d];
                if (!insideGrid(c) || !occupied(imageLoad(uAlbedo, c).r) || !reachableFrom(c, n)) continue;
                if (dot(meanNormal(imageLoad(uVoxelNormal, c).r), n) < 0.5) continue;
                int i = 3 * cellIndex(c);
                r += texelFetch(uAccum, i);
                gr += texelFetch(uAccum, i + 1);
                b += texelFetch(uAccum, i + 2);
                total += 1.0;
            }
        }
        if (total > 0.0) {
            vec4 lobe = shCosLobe(-n) / total;
            result = kDiffusionIrradianceScale * max(vec3(dot(r, lobe), dot(gr, lobe), dot(b, lobe)), vec3(0.0));
        }
    }
    imageStore(uIndirect, px, vec4(uDiffusion.intensity * result / kPi, 1.0));
}
