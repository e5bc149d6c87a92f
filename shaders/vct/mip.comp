// One mip level of a voxel volume from the level below. Isotropic (uVCT.direction < 0): the mean of
// the 8 children, premultiplied RGBA (or SH coefficients), as a box filter. Anisotropic (seed 003
// section 1.6, after Crassin 2011): one volume per marching direction (+X, -X, +Y, -Y, +Z, -Z);
// along that direction the two children of each of the 4 pairs are composited front to back
// (front + (1 - front.a) * back), then the 4 pairs are averaged, so a cone marching that way sees
// the near side of the block first.
//
// The atlas's mip 0 is level 0 at full resolution as each direction sees it: the isotropic volume
// copied into every slab (by glCopyImageSubData), so a cone reads lod 0 to 1 from the atlas
// alone, with one texture call per direction (reading level 0 from its own volume beside the atlas
// was a fourth call per sample, and the anisotropic trace took 1.24x the time it takes now on
// llvmpipe: 1881 against 1522 ms, gi/vct/vct.h). Mip 1 and up composite the mip below as above.
//
// With vct.faceSides the atlas holds what faces back along its direction: its mip 0 is level 0's
// sides (inject.comp), where a voxel marched along +X shows its -x side, the fragments whose
// normals face the cone: rgb the radiance times that side's coverage, a the voxel's opacity, and
// beside it, in the coverage atlas, the coverage, composited like the radiance in the mips above
// (this mip 0 is written here, uVCT.level0 1).
// A cone divides the first by the second over its three directions (trace.glsl), so it sees the
// mean radiance of the surfaces that face it, and nothing of a surface that faces away: the dark
// face of a thin wall no longer shows the lit face's light, which the mean of all its fragments
// did. Without it the coverage equals the opacity at every mip and no coverage atlas is kept
// (uVCT.sides 0): the atlas holds the premultiplied radiance.
#include "vct/vct_shared.h"

#include "common/shared.h"
layout(local_size_x = kGroup3DX, local_size_y = kGroup3DY, local_size_z = kGroup3DZ) in;
layout(binding = kVCTUnitMipSource) uniform sampler3D uSource;
layout(binding = kVCTUnitMipSourceCoverage) uniform sampler3D uSourceCoverage;
layout(binding = kVCTUnitMipSides) uniform sampler3D uSides;
layout(binding = kVCTImageMipDest, rgba16f) uniform writeonly image3D uDest;
layout(binding = kVCTImageMipDestCoverage, r16f) uniform writeonly image3D uDestCoverage;

// The atlas's mip below at c, as a cone marching along the direction sees it: (radiance x
// coverage, opacity) and the coverage.
vec4 fetch(ivec3 c, out float coverage) {
    vec4 s = texelFetch(uSource, c, uVCT.sourceLevel);
    coverage = uVCT.sides != 0 ? texelFetch(uSourceCoverage, c, uVCT.sourceLevel).r : s.a;
    return s;
}

void main() {
    ivec3 d = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(d, uVCT.destSize.xyz))) return;
    ivec3 base = d * 2 + ivec3(uVCT.sourceOffsetX, 0, 0);
    if (uVCT.direction < 0) {
        vec4 sum = vec4(0.0);
        for (int i = 0; i < 8; ++i) sum += texelFetch(uSource, base + ivec3(i & 1, (i >> 1) & 1, i >> 2), uVCT.sourceLevel);
        imageStore(uDest, d, sum * 0.125);
        return;
    }
    int axis = uVCT.direction / 2;
    bool positive = (uVCT.direction & 1) == 0;
    if (uVCT.level0 != 0) {  // face sides, the atlas's mip 0: level 0's side facing back along the march
        float alpha = texelFetch(uSource, d, 0).a;
        int side = 2 * axis + (positive ? 1 : 0);
        vec4 f = texelFetch(uSides, d + ivec3(side * uVCT.resolution, 0, 0), 0);
        ivec3 dest = d + ivec3(uVCT.destOffsetX, 0, 0);
        imageStore(uDest, dest, vec4(alpha > 0.0 ? f.rgb : vec3(0.0), alpha));
        imageStore(uDestCoverage, dest, vec4(alpha > 0.0 ? f.a : 0.0));
        return;
    }
    ivec3 along = ivec3(0);
    along[axis] = 1;
    ivec3 u = ivec3(0), w = ivec3(0);
    u[(axis + 1) % 3] = 1;
    w[(axis + 2) % 3] = 1;
    vec4 sum = vec4(0.0);
    float sumCoverage = 0.0;
    for (int i = 0; i < 4; ++i) {
        ivec3 c = base + u * (i & 1) + w * (i >> 1);
        float nearCoverage, farCoverage;
        vec4 near = fetch(c, nearCoverage);
        vec4 far = fetch(c + along, farCoverage);
        if (!positive) {
            vec4 t = near;
            near = far;
            far = t;
            float tc = nearCoverage;
            nearCoverage = farCoverage;
            farCoverage = tc;
        }
        sum += near + (1.0 - near.a) * far;
        sumCoverage += nearCoverage + (1.0 - near.a) * farCoverage;
    }
    imageStore(uDest, d + ivec3(uVCT.destOffsetX, 0, 0), sum * 0.25);
    if (uVCT.sides != 0) imageStore(uDestCoverage, d + ivec3(uVCT.destOffsetX, 0, 0), vec4(sumCoverage * 0.25));
}
