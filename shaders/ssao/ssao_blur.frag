// SSAO blur (seed 000 Sec 3.5.1: "banding is later removed in a separate blur pass"): a box
// 2 * uSSAO.blurRadius pixels wide, offsets -r..r-1, so radius 2 covers the 4x4 noise tile
// exactly and every window averages all 16 rotations. Background pixels are left out of the
// average and stay 1. Then AO = pow(visibility, uSSAO.strength), strength 0 meaning no occlusion.
#include "common/shared.h"
#include "ssao/ssao_shared.h"

layout(binding = kUnitSource) uniform sampler2D uRaw;
layout(binding = kUnitDepth) uniform sampler2D uDepth;

out float oAO;

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(uRaw, 0);
    if (texelFetch(uDepth, px, 0).r >= 1.0) {
        oAO = 1.0;
        return;
    }
    int lo = uSSAO.blurRadius > 0 ? -uSSAO.blurRadius : 0;
    int hi = uSSAO.blurRadius > 0 ? uSSAO.blurRadius - 1 : 0;
    float sum = 0.0;
    float count = 0.0;
    for (int y = lo; y <= hi; ++y) {
        for (int x = lo; x <= hi; ++x) {
            ivec2 q = px + ivec2(x, y);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
            if (texelFetch(uDepth, q, 0).r >= 1.0) continue;
            sum += texelFetch(uRaw, q, 0).r;
            count += 1.0;
        }
    }
    // The pixel itself is always in its window, so count >= 1.
    float visibility = sum / count;
    // pow(0, 0) is undefined in GLSL: strength 0 is handled apart.
    oAO = uSSAO.strength > 0.0 ? pow(visibility, uSSAO.strength) : 1.0;
}
