// Adds the (blurred) in-scattered light to the HDR image at full resolution, after fading the
// lit scene by the transmittance of the view ray's part inside the medium (attenuateScene).
// Upsampling: bilinear, or with depthAware the 2 x 2 march pixels around each pixel weighted
// bilinearly and by view-distance similarity (as the blur), the best match alone where none match.
#include "volumetric/medium.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup2D, local_size_y = kGroup2D) in;
layout(binding = kUnitDepth) uniform sampler2D uDepth;
layout(binding = kVolumeUnitSource) uniform sampler2D uInscatter;
layout(binding = kVolumeImageTarget, rgba16f) uniform image2D uHDR;

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    ivec2 fullSize = ivec2(uVolume.fullWidth, uVolume.fullHeight);
    ivec2 lowSize = ivec2(uVolume.lowWidth, uVolume.lowHeight);
    vec3 eye = uVolume.eye.xyz;
    if (any(greaterThanEqual(px, fullSize))) return;
    float depth = texelFetch(uDepth, px, 0).r;
    vec2 uv = (vec2(px) + 0.5) / vec2(fullSize);
    vec4 w = uVolume.invViewProj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    vec3 p = w.xyz / w.w;
    float tHit = depth < 1.0 ? length(p - eye) : 1e30;
    float z = depth < 1.0 ? tHit : 65504.0;
    vec3 inscatter;
    if (uVolume.depthAware != 0) {
        vec2 f = uv * vec2(lowSize) - 0.5;
        ivec2 base = ivec2(floor(f));
        vec2 t = f - vec2(base);
        vec3 sum = vec3(0.0), bestValue = vec3(0.0);
        float total = 0.0, best = -1.0;
        for (int i = 0; i < 4; ++i) {
            ivec2 o = ivec2(i & 1, i >> 1);
            vec4 s = texelFetch(uInscatter, clamp(base + o, ivec2(0), lowSize - 1), 0);
            float match = exp(-abs(s.a - z) / (kVolumeDepthSimilarity * z));
            float bilinear = (o.x == 1 ? t.x : 1.0 - t.x) * (o.y == 1 ? t.y : 1.0 - t.y);
            sum += match * bilinear * s.rgb;
            total += match * bilinear;
            if (match > best) {
                best = match;
                bestValue = s.rgb;
            }
        }
        inscatter = total > 1e-4 ? sum / total : bestValue;
    } else {
        inscatter = textureLod(uInscatter, uv, 0.0).rgb;
    }
    vec4 hdr = imageLoad(uHDR, px);
    float t0, t1;
    if (uVolume.attenuateScene != 0 && clipRayToBox(eye, normalize(p - eye), tHit, t0, t1)) hdr.rgb *= exp(-uVolume.sigmaT * (t1 - t0));
    imageStore(uHDR, px, vec4(hdr.rgb + inscatter, hdr.a));
}
