// The VCT voxels seen from the camera (gi/vct/vct_views.h describes the view): each pixel's ray
// is clipped to one level's grid and marched voxel by voxel (Amanatides and Woo's 3D DDA) at mip
// uVCT.viewMip; the first occupied voxel is drawn as the cube face the ray enters, shaded by the face's
// direction, with darkened edges.
#include "common/shared.h"
#include "common/color.glsl"
#include "vct/vct_shared.h"

layout(binding = kVCTUnitViewOccupancy) uniform usampler3D uOccupancy;
layout(binding = kVCTUnitViewPacked) uniform usampler3D uPacked;
layout(binding = kVCTUnitViewRadiance) uniform sampler3D uRadiance;


in vec2 vUV;
out vec4 oColor;

// The texel holding logical voxel `cell` of a grid of `size` voxels per side (GL_REPEAT placement).
ivec3 texelOf(ivec3 cell, int size) {
    vec3 tc = (vec3(cell) + 0.5) / float(size) + vec3(uVCT.wrapOffset.xyz) / float(uVCT.resolution);
    return clamp(ivec3(floor(fract(tc) * float(size))), ivec3(0), ivec3(size - 1));
}

// Colour of an occupied voxel (linear for the packed sources, unpremultiplied radiance), or a < 0.
vec4 voxelColour(ivec3 cell, int size) {
    ivec3 t = texelOf(cell, size);
    if (uVCT.viewSource == 2) {
        vec4 r = texelFetch(uRadiance, t, uVCT.viewMip);
        if (r.a < uVCT.opacityThreshold) return vec4(-1.0);
        return vec4(r.rgb / r.a * uVCT.exposureScale, 1.0);
    }
    if ((texelFetch(uOccupancy, t, 0).r >> 24) == 0u) return vec4(-1.0);
    vec3 c = unpackUnorm4x8(texelFetch(uPacked, t, 0).r).rgb;
    return vec4(c, 1.0);
}

void main() {
    vec4 nearH = uVCT.invViewProj * vec4(vUV * 2.0 - 1.0, -1.0, 1.0);
    vec4 farH = uVCT.invViewProj * vec4(vUV * 2.0 - 1.0, 1.0, 1.0);
    vec3 origin = nearH.xyz / nearH.w;
    vec3 dir = normalize(farH.xyz / farH.w - origin);
    // No zero components: the DDA divides by them and steps by their sign.
    dir = mix(dir, vec3(1e-7), lessThan(abs(dir), vec3(1e-7)));

    // Grid units of the marched mip: the level spans [0, size]^3.
    int size = max(uVCT.resolution >> uVCT.viewMip, 1);
    float cell = uVCT.cellSize * float(uVCT.resolution) / float(size);
    vec3 o = (origin - uVCT.gridMin.xyz) / cell;
    vec3 inv = 1.0 / dir;
    vec3 t0 = (vec3(0.0) - o) * inv, t1 = (vec3(float(size)) - o) * inv;
    vec3 tNear = min(t0, t1), tFar = max(t0, t1);
    float tEnter = max(max(tNear.x, tNear.y), max(tNear.z, 0.0));
    float tExit = min(tFar.x, min(tFar.y, tFar.z));
    oColor = vec4(uVCT.background.xyz, 1.0);
    if (tEnter >= tExit) return;

    // The face entered first: the axis whose slab was entered last (none when the eye is inside).
    int axis = tEnter <= 0.0 ? -1 : tNear.x >= max(tNear.y, tNear.z) ? 0 : tNear.y >= tNear.z ? 1 : 2;
    vec3 p = o + dir * tEnter;
    ivec3 c = clamp(ivec3(floor(p + dir * 1e-4)), ivec3(0), ivec3(size - 1));
    ivec3 stepDir = ivec3(sign(dir));
    vec3 tDelta = abs(inv);
    vec3 tMax = (vec3(c) + max(vec3(stepDir), vec3(0.0)) - o) * inv;
    float t = tEnter;
    for (int i = 0; i < 3 * size + 3; ++i) {
        vec4 v = voxelColour(c, size);
        if (v.a >= 0.0) {
            // Fixed shades per face direction: top 1, sides 0.8 and 0.65, bottom 0.5.
            float shade = 0.9;
            if (axis == 0) shade = 0.8;
            else if (axis == 1) shade = stepDir.y < 0 ? 1.0 : 0.5;
            else if (axis == 2) shade = 0.65;
            vec3 colour = v.rgb * shade;
            if (uVCT.edges != 0 && axis >= 0) {
                vec3 f = fract(o + dir * t);
                vec2 uv = axis == 0 ? f.yz : axis == 1 ? f.xz : f.xy;
                vec2 edge = min(uv, 1.0 - uv);
                if (min(edge.x, edge.y) < 0.06) colour *= 0.7;
            }
            oColor = vec4(uVCT.viewSource == 1 ? colour : linearToSRGB(colour), 1.0);
            return;
        }
        // Step into the neighbour across the nearest face.
        if (tMax.x <= tMax.y && tMax.x <= tMax.z) {
            c.x += stepDir.x;
            t = tMax.x;
            tMax.x += tDelta.x;
            axis = 0;
        } else if (tMax.y <= tMax.z) {
            c.y += stepDir.y;
            t = tMax.y;
            tMax.y += tDelta.y;
            axis = 1;
        } else {
            c.z += stepDir.z;
            t = tMax.z;
            tMax.z += tDelta.z;
            axis = 2;
        }
        if (any(lessThan(c, ivec3(0))) || any(greaterThanEqual(c, ivec3(size)))) return;
    }
}
