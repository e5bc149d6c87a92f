// The blur of the march buffer: seed 004's single-pass 5x5 Gaussian (Alg. 3: the outer product
// of [0.06136, 0.24477, 0.38774, 0.24477, 0.06136]), or the same weights times a depth
// similarity exp(-|z_q - z| / (0.05 z)) on the view distance the march stores in alpha, so light
// does not bleed across depth edges (normalised by the weights kept).
#include "volumetric/volumetric_shared.h"

#include "common/shared.h"
layout(local_size_x = kGroup2D, local_size_y = kGroup2D) in;
layout(binding = kVolumeUnitSource) uniform sampler2D uSource;
layout(binding = kVolumeImageTarget, rgba16f) uniform writeonly image2D uOut;

const float kWeights[5] = float[5](0.06136, 0.24477, 0.38774, 0.24477, 0.06136);

void main() {
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(uVolume.lowWidth, uVolume.lowHeight);
    if (any(greaterThanEqual(q, size))) return;
    vec4 centre = texelFetch(uSource, q, 0);
    vec3 sum = vec3(0.0);
    float total = 0.0;
    for (int y = -2; y <= 2; ++y)
        for (int x = -2; x <= 2; ++x) {
            vec4 s = texelFetch(uSource, clamp(q + ivec2(x, y), ivec2(0), size - 1), 0);
            float w = kWeights[x + 2] * kWeights[y + 2];
            if (uVolume.depthAware != 0) w *= exp(-abs(s.a - centre.a) / (kVolumeDepthSimilarity * centre.a));
            sum += w * s.rgb;
            total += w;
        }
    imageStore(uOut, q, vec4(sum / total, centre.a));
}
