// One mip level of a voxel volume from the level below. Isotropic (uVCT.direction < 0): the mean of
// the 8 children, premultiplied RGBA (or SH coefficients), as a box filter. Anisotropic (seed 003
// section 1.6, after Crassin 2011): one volume per marching direction (+X, -X, +Y, -Y, +Z, -Z);
// along that direction the two children of each of the 4 pairs are composited front to back
// (front + (1 - front.a) * back), then the 4 pairs are averaged, so a cone marching that way sees
// the near side of the block first.
//
// With vct.faceSides the anisotropic atlas holds what faces back along its direction: its first mip is built from
// level 0's sides (inject.comp), where a voxel marched along +X shows its -x side, the fragments
// whose normals face the cone: rgb the radiance times that side's coverage, a the voxel's opacity,
// and beside it, in the coverage atlas, the coverage composited the same way. A cone divides the
// first by the second over its three directions (trace.glsl), so it sees the mean radiance of the
// surfaces that face it, and nothing of a surface that faces away: the dark face of a thin wall
// no longer shows the lit face's light, which the mean of all its fragments did. Without it the
// first mip comes from the isotropic level 0, the coverage equals the opacity at every mip and
// no coverage atlas is kept (uVCT.sides 0): the atlas holds the premultiplied radiance as before.
#include "vct/vct_shared.h"

#include "common/shared.h"
layout(local_size_x = kGroup3DX, local_size_y = kGroup3DY, local_size_z = kGroup3DZ) in;
layout(binding = kVCTUnitMipSource) uniform sampler3D uSource;
layout(binding = kVCTUnitMipSourceCoverage) uniform sampler3D uSourceCoverage;
layout(binding = kVCTUnitMipSides) uniform sampler3D uSides;
layout(binding = kVCTImageMipDest, rgba16f) uniform writeonly image3D uDest;
layout(binding = kVCTImageMipDestCoverage, r16f) uniform writeonly image3D uDestCoverage;

// The source at c as a cone marching along the direction sees it: (radiance x coverage, opacity)
// and the coverage.
vec4 fetch(ivec3 c, int side, out float coverage) {
    if (uVCT.fromSides != 1) {  // the atlas's mip below, or the isotropic level 0 (every face faces every way)
        vec4 s = texelFetch(uSource, c, uVCT.sourceLevel);
        coverage = uVCT.sides != 0 ? texelFetch(uSourceCoverage, c, uVCT.sourceLevel).r : s.a;
        return s;
    }
    vec4 s = texelFetch(uSides, c + ivec3(side * uVCT.resolution, 0, 0), 0);
    float alpha = texelFetch(uSource, c, 0).a;
    coverage = alpha > 0.0 ? s.a : 0.0;
    return vec4(alpha > 0.0 ? s.rgb : vec3(0.0), alpha);
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
    int side = 2 * axis + (positive ? 1 : 0);  // the side facing back along the march
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
        vec4 near = fetch(c, side, nearCoverage);
        vec4 far = fetch(c + along, side, farCoverage);
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
