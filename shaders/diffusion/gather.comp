// Propagation, second half of a step: each cell gathers the flux its six neighbours sent through
// the faces they share (seed 001 eq. 3.2.3: six reads, one write). Flux s arriving along axis d
// is the beam s * faceLobe(d) / solid angle (its flux is s).
//   - An empty cell passes the light on: the next step's light in flight is what it gathered.
//   - An occupied cell takes it: it adds it to its accumulation (what shading reads) and
//     reflects it as the next step's light, the flux each side of its surface received
//     (light along d reaches the front, the side the mean normal faces, when d . n < 0; half each
//     way at d . n = 0) times the albedo, as a clamped cosine lobe from that side (the source
//     reflects along its mean normal only, which throws away light reaching a one-voxel wall's
//     back). The albedo is the voxel's, or 0.5 with albedoMode 1 (the source's constant).
// So bounces come from steps: light reflected at step k travels on at step k + 1.
// Bounce orders ride along: the light arriving has the flux-weighted mean of its senders'
// orders (outgoing .w); an empty cell passes that on, an occupied cell adds it, times the flux,
// to its accumulated order and reflects the light one order higher.
#include "diffusion/common.glsl"

layout(local_size_x = kGroup3DX, local_size_y = kGroup3DY, local_size_z = kGroup3DZ) in;
layout(binding = kDiffusionImageAlbedo, r32ui) uniform readonly uimage3D uAlbedo;
layout(binding = kDiffusionImageNormal, r32ui) uniform readonly uimage3D uNormal;
layout(binding = kDiffusionUnitStepSource) uniform samplerBuffer uOutgoing;  // 6 texels per cell, from emit.comp
layout(binding = kDiffusionImageStepDestination, rgba32f) uniform writeonly imageBuffer uDestination;
layout(binding = kDiffusionImageStepAccum, rgba32f) uniform imageBuffer uAccum;
layout(binding = kDiffusionImageStepOrderDestination, r32f) uniform writeonly imageBuffer uOrderDestination;
layout(binding = kDiffusionImageStepOrderAccum, r32f) uniform imageBuffer uOrderAccum;

void main() {
    ivec3 cell = ivec3(gl_GlobalInvocationID);
    if (!insideGrid(cell)) return;
    int i = cellIndex(cell);
    vec3 arriving[6];
    bool arrived = false;
    float flux = 0.0, order = 0.0;
    for (int d = 0; d < 6; ++d) {
        ivec3 from = cell - kDirections[d];
        vec4 o = insideGrid(from) ? texelFetch(uOutgoing, 6 * cellIndex(from) + d) : vec4(0.0);
        arriving[d] = o.rgb;
        arrived = arrived || arriving[d] != vec3(0.0);
        float f = o.r + o.g + o.b;
        flux += f;
        order += f * o.w;
    }
    order = flux > 0.0 ? order / flux : 0.0;
    vec4 r = vec4(0.0), g = vec4(0.0), b = vec4(0.0);
    for (int d = 0; d < 6; ++d) {
        vec4 beam = faceLobe(vec3(kDirections[d])) / kFaceSolidAngle;
        r += arriving[d].r * beam;
        g += arriving[d].g * beam;
        b += arriving[d].b * beam;
    }
    uint packedAlbedo = imageLoad(uAlbedo, cell).r;
    if (occupied(packedAlbedo)) {
        if (arrived) {
            imageStore(uAccum, 3 * i, imageLoad(uAccum, 3 * i) + r);
            imageStore(uAccum, 3 * i + 1, imageLoad(uAccum, 3 * i + 1) + g);
            imageStore(uAccum, 3 * i + 2, imageLoad(uAccum, 3 * i + 2) + b);
            imageStore(uOrderAccum, i, imageLoad(uOrderAccum, i) + flux * order);
        }
        vec3 n = meanNormal(imageLoad(uNormal, cell).r);
        vec3 front = vec3(0.0), back = vec3(0.0);
        for (int d = 0; d < 6; ++d) {
            float c = dot(vec3(kDirections[d]), n);
            float toFront = c < -1e-3 ? 1.0 : c > 1e-3 ? 0.0 : 0.5;
            front += toFront * arriving[d];
            back += (1.0 - toFront) * arriving[d];
        }
        vec3 albedo = uDiffusion.albedoMode == 1 ? vec3(0.5) : unpackVoxel(packedAlbedo).rgb;
        // A lobe of flux F: F / pi * shCosLobe (its flux is pi times band 0's weight).
        vec4 lf = shCosLobe(n) / kPi, lb = shCosLobe(-n) / kPi;
        front *= albedo;
        back *= albedo;
        r = front.r * lf + back.r * lb;
        g = front.g * lf + back.g * lb;
        b = front.b * lf + back.b * lb;
        order = arrived ? order + 1.0 : 0.0;
    }
    imageStore(uOrderDestination, i, vec4(order));
    imageStore(uDestination, 3 * i, r);
    imageStore(uDestination, 3 * i + 1, g);
    imageStore(uDestination, 3 * i + 2, b);
}
