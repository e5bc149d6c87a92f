// Face sides: the coverage atlas (mip.comp, one R16F slab per marching direction) regrouped by
// octant for the trace, one mip level per dispatch: octant o (bit a set where the march runs
// negative along axis a) holds in rgb the coverage of the three slabs a cone marching into that
// octant reads, x from +X or -X, y from +Y or -Y, z from +Z or -Z. A cone sample then reads its
// three directions' coverage in one texture call (trace.glsl sampleAniso) where it made one per
// direction; each octant's slab is a texel-for-texel copy, so the filtered values are the same.
#include "vct/vct_shared.h"

#include "common/shared.h"
layout(local_size_x = kGroup3DX, local_size_y = kGroup3DY, local_size_z = kGroup3DZ) in;
layout(binding = kVCTUnitMipSourceCoverage) uniform sampler3D uCoverage;
layout(binding = kVCTImageOctants, rgba16f) uniform writeonly image3D uOctants;

void main() {
    ivec3 d = ivec3(gl_GlobalInvocationID);
    int size = uVCT.destSize.x;
    if (any(greaterThanEqual(d, uVCT.destSize.xyz))) return;
    float c[6];
    for (int s = 0; s < 6; ++s) c[s] = texelFetch(uCoverage, d + ivec3(s * size, 0, 0), uVCT.sourceLevel).r;
    for (int o = 0; o < 8; ++o) {
        ivec3 negative = ivec3(o & 1, (o >> 1) & 1, (o >> 2) & 1);
        imageStore(uOctants, d + ivec3(o * size, 0, 0), vec4(c[negative.x], c[2 + negative.y], c[4 + negative.z], 0.0));
    }
}
