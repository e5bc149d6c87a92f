// Joint bilateral upsampling of the cone trace: each full-resolution pixel takes the 4 x 4 traced
// pixels around it, weighted by a tent two traced pixels wide each way and by how well each one's
// surface matches its own: relative view depth (exp(-|dz| / (z * depthTolerance))) and normal
// (max(n . n_q, 0)^8). Where no neighbour matches (thin objects, silhouettes) the best match
// alone is used. The traced pixel q stands for the full pixel under its centre, as in trace.comp,
// which writes that pixel's normal and view depth to a guide image beside its light, so a tap
// reads one low-resolution texel for them instead of the full-resolution depth and normal at
// scattered places.
// Why the wide tent: the trace staggers its cones' samples by a 2 x 2 pattern (trace.glsl
// traceCone), and along each axis a tent of half-width 2 gives the even and the odd traced pixels
// the same total weight wherever the full pixel lies (t + 2 - t against 1 - t + 1 + t), so the
// pattern cancels on any surface the weights do not cut; a bilinear 2 x 2 left it as a
// checkerboard. It runs at traceScale 1 too, where it is a 1-2-1 filter.
#include "vct/vct_shared.h"

#include "common/shared.h"
layout(local_size_x = kGroup2D, local_size_y = kGroup2D) in;
layout(binding = kUnitNormal) uniform sampler2D uNormal;
layout(binding = kUnitDepth) uniform sampler2D uDepth;
layout(binding = kVCTUnitLowIndirect) uniform sampler2D uLowIndirect;
layout(binding = kVCTUnitLowSpecular) uniform sampler2D uLowSpecular;
layout(binding = kVCTUnitLowGuide) uniform sampler2D uLowGuide;  // the traced pixels' normal and view depth (trace.comp)
layout(binding = kVCTImageIndirect, rgba16f) uniform writeonly image2D uIndirect;
layout(binding = kVCTImageSpecular, rgba16f) uniform writeonly image2D uSpecular;

const float kDepthTolerance = 0.05;

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, uVCT.imageSize.zw))) return;
    float d = texelFetch(uDepth, px, 0).r;
    if (d >= 1.0) {
        imageStore(uIndirect, px, vec4(0.0, 0.0, 0.0, 1.0));
        imageStore(uSpecular, px, vec4(0.0, 0.0, 0.0, 1.0));
        return;
    }
    float z = viewDepthOf(d, uVCT.nearPlane, uVCT.farPlane);
    vec3 n = normalize(texelFetch(uNormal, px, 0).xyz);
    vec2 f = (vec2(px) + 0.5) / uVCT.toFull.xy - 0.5;
    ivec2 base = ivec2(floor(f));
    vec2 t = f - vec2(base);
    vec3 indirect = vec3(0.0), specular = vec3(0.0);
    float total = 0.0, best = -1.0;
    vec3 bestIndirect = vec3(0.0), bestSpecular = vec3(0.0);
    for (int i = 0; i < 16; ++i) {
        ivec2 o = ivec2(i & 3, i >> 2) - 1;
        ivec2 q = clamp(base + o, ivec2(0), uVCT.imageSize.xy - 1);
        vec4 g = texelFetch(uLowGuide, q, 0);
        if (g.w < 0.0) continue;
        float c = max(dot(n, g.xyz), 0.0);
        c *= c;
        c *= c;
        float match = exp(-abs(g.w - z) / (z * kDepthTolerance)) * (c * c);
        vec2 tent = max(2.0 - abs(vec2(o) - t), 0.0);
        float w = match * max(tent.x * tent.y, 1e-3);
        vec3 li = texelFetch(uLowIndirect, q, 0).rgb, ls = texelFetch(uLowSpecular, q, 0).rgb;
        indirect += w * li;
        specular += w * ls;
        total += w;
        if (match > best) {
            best = match;
            bestIndirect = li;
            bestSpecular = ls;
        }
    }
    if (total > 1e-4) {
        indirect /= total;
        specular /= total;
    } else {
        indirect = bestIndirect;
        specular = bestSpecular;
    }
    imageStore(uIndirect, px, vec4(indirect, 1.0));
    imageStore(uSpecular, px, vec4(specular, 1.0));
}
