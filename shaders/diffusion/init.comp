// Injection (seed 001 section 3.1): every occupied cell becomes a VPL, the light its surface
// reflects on each side (VCT's exit radiance, albedo E / pi, shaders/vct/inject.comp) as a
// clamped cosine lobe around its mean normal and one around the opposite. In flux units per unit
// of surface area: a side leaving radiance L emits pi L, the flux of L * shCosLobe(n). The cell
// size cancels between injection and shading, so the buffers carry no area. The accumulation
// starts at zero: it sums the light that arrives, the indirect term only. The injected light is
// bounce order 1 (gather.comp counts the orders on).
#include "diffusion/common.glsl"

layout(local_size_x = kGroup3DX, local_size_y = kGroup3DY, local_size_z = kGroup3DZ) in;
layout(binding = kDiffusionImageAlbedo, r32ui) uniform readonly uimage3D uAlbedo;
layout(binding = kDiffusionImageNormal, r32ui) uniform readonly uimage3D uNormal;
layout(binding = kDiffusionImageExitFront, r11f_g11f_b10f) uniform readonly image3D uExitFront;
layout(binding = kDiffusionImageExitBack, r11f_g11f_b10f) uniform readonly image3D uExitBack;
layout(std430, binding = kDiffusionBufferDestination) writeonly buffer Destination { vec4 dst[]; };
layout(std430, binding = kDiffusionBufferAccum) writeonly buffer Accumulated { vec4 accum[]; };
layout(std430, binding = kDiffusionBufferOrderDestination) writeonly buffer OrderDestination { float orderDst[]; };
layout(std430, binding = kDiffusionBufferOrderAccum) writeonly buffer OrderAccumulated { float orderAccum[]; };

void main() {
    ivec3 cell = ivec3(gl_GlobalInvocationID);
    if (!insideGrid(cell)) return;
    int i = 3 * cellIndex(cell);
    vec4 r = vec4(0.0), g = vec4(0.0), b = vec4(0.0);
    float order = 0.0;
    if (occupied(imageLoad(uAlbedo, cell).r)) {
        vec3 n = meanNormal(imageLoad(uNormal, cell).r);
        vec3 front = imageLoad(uExitFront, cell).rgb, back = imageLoad(uExitBack, cell).rgb;
        vec4 lf = shCosLobe(n), lb = shCosLobe(-n);
        r = front.r * lf + back.r * lb;
        g = front.g * lf + back.g * lb;
        b = front.b * lf + back.b * lb;
        order = any(greaterThan(front + back, vec3(0.0))) ? 1.0 : 0.0;  // reflected direct light: the first bounce
    }
    dst[i] = r;
    dst[i + 1] = g;
    dst[i + 2] = b;
    accum[i] = vec4(0.0);
    accum[i + 1] = vec4(0.0);
    accum[i + 2] = vec4(0.0);
    orderDst[cellIndex(cell)] = order;
    orderAccum[cellIndex(cell)] = 0.0;
}
