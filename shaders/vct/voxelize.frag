// Voxelization, fragment stage: one fragment is one voxel column of the projected triangle. The
// fragment writes every voxel the triangle's depth crosses within its pixel (the depth slope is
// at most ~1.4 voxels per pixel along the dominant axis, so one or two voxels, three at most),
// which keeps sloped surfaces watertight. Slicing (seed 001) writes only the cell of the depth at
// the pixel's centre, as a slab-clipped scan conversion does; the other axes fill the gaps. Values go in with a running average by atomic
// compare-and-swap on RGBA8 packed in r32ui (seed 000 and 003): rgb the mean, a the count.
// Albedo is the diffuse albedo (base colour times 1 - metallic); normals are stored as
// n * 0.5 + 0.5, and the position volume holds where the surface lies in the voxel (0 to 1 per
// axis: the pixel's centre across the projection, the triangle's depth along it), so injection
// and bounces work at the surface, not at the voxel centre. Emission is not stored: emissive
// surfaces reach VCT as area lights (inject.comp).
#include "common/shared.h"
#include "common/material.glsl"
#include "vct/vct_shared.h"

layout(binding = kVCTImageAlbedo, r32ui) uniform coherent volatile uimage3D uAlbedoVox;
layout(binding = kVCTImageNormal, r32ui) uniform coherent volatile uimage3D uNormalVox;
layout(binding = kVCTImageSides, r32ui) uniform coherent volatile uimage3D uSidesVox;
layout(binding = kVCTImagePosition, r32ui) uniform coherent volatile uimage3D uPositionVox;

in vec3 gGrid;
in vec3 gNormal;
in vec2 gUV;
in vec4 gTangent;
in vec2 gUV1;
flat in vec4 gBox;
flat in vec2 gDepthRange;
flat in int gAxis;

vec3 unswizzle(vec3 s, int axis) { return axis == 0 ? s.zxy : axis == 1 ? s.yzx : s; }

#define GI_RUNNING_AVERAGE(img, c, value)                                                    \
    {                                                                                        \
        uint expected = 0u;                                                                  \
        uint desired = packUnorm4x8(vec4(value, 1.0 / kVCTMaxCount));                        \
        for (int i = 0; i < kVCTAtomicTries; ++i) {                                         \
            uint found = imageAtomicCompSwap(img, c, expected, desired);                     \
            if (found == expected) break;                                                    \
            expected = found;                                                                \
            vec4 old = unpackUnorm4x8(found);                                                \
            float count = round(old.a * kVCTMaxCount);                                       \
            if (count >= kVCTMaxCount) break;                                                \
            desired = packUnorm4x8(vec4((old.rgb * count + value) / (count + 1.0), (count + 1.0) / kVCTMaxCount)); \
        }                                                                                    \
    }

void main() {
    if (any(lessThan(gl_FragCoord.xy, gBox.xy)) || any(greaterThan(gl_FragCoord.xy, gBox.zw))) discard;
    // The material as the G-buffer reads it (common/material.glsl); a voxel has no side, so
    // the normal is the front face's. (Emission reaches VCT as area lights, not voxels.)
    vec4 base = materialBaseColor(gUV, gUV1);
    vec3 normal = materialNormal(gNormal, gTangent, true, gUV, gUV1);
    float metallic = materialRoughnessMetallic(gUV, gUV1).y;
    if (materialCut(base.a)) discard;

    float slope = 0.5 * (abs(dFdx(gGrid.z)) + abs(dFdy(gGrid.z)));
    // With sides, a surface within kVCTSideMargin of a voxel boundary also fills the voxel across
    // it, so each of its two faces has a voxel on its own side (below).
    float margin = uVCT.sides != 0 ? kVCTSideMargin : 0.0;
    float z0 = clamp(gGrid.z - slope - margin, gDepthRange.x - margin, gDepthRange.y + margin);
    float z1 = clamp(gGrid.z + slope + margin, gDepthRange.x - margin, gDepthRange.y + margin);
    int first = int(floor(z0)), last = min(int(floor(z1)), int(floor(z0)) + 2);
    if (uVCT.sliceAxis > 0) first = last = int(floor(gGrid.z));  // slicing: the slice the pixel's centre lies in

    vec3 albedo = clamp(base.rgb * (1.0 - metallic), 0.0, 1.0);
    vec3 n = normal * 0.5 + 0.5;
    vec3 g = unswizzle(vec3(gl_FragCoord.xy, gGrid.z), gAxis);  // the surface at the pixel, in voxels
    for (int z = first; z <= last; ++z) {
        ivec3 c = ivec3(unswizzle(vec3(floor(gl_FragCoord.xy), float(z)), gAxis));
        vec3 offset = vec3(c) + 0.5 - g;  // the voxel centre from the surface
        if (any(lessThan(c, uVCT.clipMin.xyz)) || any(greaterThanEqual(c, uVCT.clipMax.xyz))) continue;
        vec3 inside = clamp(0.5 - offset, 0.0, 1.0);  // where the surface lies in this voxel
        c = (c + uVCT.wrapOffset.xyz) % uVCT.resolution;
        GI_RUNNING_AVERAGE(uAlbedoVox, c, albedo)
        GI_RUNNING_AVERAGE(uNormalVox, c, n)
        GI_RUNNING_AVERAGE(uPositionVox, c, inside)
        if (uVCT.sides != 0)
            for (int a = 0; a < 3; ++a)
                if (abs(normal[a]) > kVCTSideMinCosine) {
                    // Both faces (every surface is two-sided in the raster); a face goes into
                    // this voxel unless the voxel's centre lies more than kVCTSideMargin behind it.
                    vec3 facing = normal[a] < 0.0 ? -normal : normal;
                    float d = dot(offset, facing);
                    float h = 0.5 * (abs(facing.x) + abs(facing.y) + abs(facing.z)) - kVCTSideMargin;
                    if (d > -h) {
                        ivec3 cs = c + ivec3(2 * a * uVCT.resolution, 0, 0);
                        GI_RUNNING_AVERAGE(uSidesVox, cs, facing * 0.5 + 0.5)
                    }
                    if (d < h) {
                        ivec3 cs = c + ivec3((2 * a + 1) * uVCT.resolution, 0, 0);
                        GI_RUNNING_AVERAGE(uSidesVox, cs, -facing * 0.5 + 0.5)
                    }
                }
    }
}
