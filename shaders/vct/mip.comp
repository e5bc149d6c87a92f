// One mip level of a voxel volume from the level below. Isotropic (uVCT.direction < 0): the mean of
// the 8 children, premultiplied RGBA (or SH coefficients), as a box filter. Anisotropic (seed 003
// section 1.6, after Crassin 2011): one volume per marching direction (+X, -X, +Y, -Y, +Z, -Z);
// along that direction the two children of each of the 4 pairs are composited front to back
// (front + (1 - front.a) * back), then the 4 pairs are averaged, so a cone marching that way sees
// the near side of the block first.
#include "vct/vct_shared.h"

#include "common/shared.h"
layout(local_size_x = kGroup3D, local_size_y = kGroup3D, local_size_z = kGroup3D) in;
layout(binding = kVCTUnitMipSource) uniform sampler3D uSource;
layout(binding = kVCTImageMipDest, rgba16f) uniform writeonly image3D uDest;

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
    ivec3 along = ivec3(0);
    along[axis] = 1;
    ivec3 u = ivec3(0), w = ivec3(0);
    u[(axis + 1) % 3] = 1;
    w[(axis + 2) % 3] = 1;
    vec4 sum = vec4(0.0);
    for (int i = 0; i < 4; ++i) {
        ivec3 c = base + u * (i & 1) + w * (i >> 1);
        vec4 near = texelFetch(uSource, c, uVCT.sourceLevel);
        vec4 far = texelFetch(uSource, c + along, uVCT.sourceLevel);
        if (!positive) {
            vec4 t = near;
            near = far;
            far = t;
        }
        sum += near + (1.0 - near.a) * far;
    }
    imageStore(uDest, d + ivec3(uVCT.destOffsetX, 0, 0), sum * 0.25);
}
