// Adds the (blurred) in-scattered light to the HDR image at full resolution, after fading the
// lit scene by the transmittance of the view ray's part inside the medium (attenuateScene).
// Upsampling: bilinear, or with depthAware the 2 x 2 march pixels around each pixel weighted
// bilinearly and by view-distance similarity (as the blur), the best match alone where none match.
#include "volumetric/medium.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = kUnitDepth) uniform sampler2D uDepth;
layout(binding = 0) uniform sampler2D uVolume;
layout(binding = 0, rgba16f) uniform image2D uHDR;

uniform mat4 uInvViewProj;
uniform vec3 uEye;
uniform ivec2 uFullSize;
uniform ivec2 uLowSize;
uniform bool uDepthAware;
uniform bool uAttenuateScene;

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, uFullSize))) return;
    float depth = texelFetch(uDepth, px, 0).r;
    vec2 uv = (vec2(px) + 0.5) / vec2(uFullSize);
    vec4 w = uInvViewProj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    vec3 p = w.xyz / w.w;
    float tHit = depth < 1.0 ? length(p - uEye) : 1e30;
    float z = depth < 1.0 ? tHit : 65504.0;
    vec3 inscatter;
    if (uDepthAware) {
        vec2 f = uv * vec2(uLowSize) - 0.5;
        ivec2 base = ivec2(floor(f));
        vec2 t = f - vec2(base);
        vec3 sum = vec3(0.0), bestValue = vec3(0.0);
        float total = 0.0, best = -1.0;
        for (int i = 0; i < 4; ++i) {
            ivec2 o = ivec2(i & 1, i >> 1);
            vec4 s = texelFetch(uVolume, clamp(base + o, ivec2(0), uLowSize - 1), 0);
            float match = exp(-abs(s.a - z) / (0.05 * z));
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
        inscatter = textureLod(uVolume, uv, 0.0).rgb;
    }
    vec4 hdr = imageLoad(uHDR, px);
    float t0, t1;
    if (uAttenuateScene && clipRayToBox(uEye, normalize(p - uEye), tHit, t0, t1)) hdr.rgb *= exp(-uSigmaT * (t1 - t0));
    imageStore(uHDR, px, vec4(hdr.rgb + inscatter, hdr.a));
}
