// One more bounce in the voxels: every occupied voxel traces the diffuse cone set on both sides
// of its mean normal through the current radiance volumes (direct light plus the bounces so far)
// and leaves its direct radiance plus albedo * E / pi (seed 000 re-injects the traced light; the
// cones start one voxel diagonal out, more with a larger nudge, so a voxel does not light itself).
// The cones start where the voxel's surface lies (the position volume), not at its centre, so the
// gathered light does not depend on where the surface falls in its voxel; the back's light is
// weighted by how much of the voxel faces back (backWeight), and a voxel with no back traces
// nothing there.
// With vct.bounceTail the last bounce also adds the bounces after it (hemisphere() below).
// resolve.comp and the mip pass then rebuild the traced volumes.
#include "vct/trace.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup1D) in;
layout(std430, binding = kVCTBufferDispatch) readonly buffer Dispatch { uint groupsX, groupsY, groupsZ, count; };
layout(std430, binding = kVCTBufferVoxels) readonly buffer Voxels { uint voxels[]; };  // compact.comp's list
layout(binding = kVCTImageAlbedo, r32ui) uniform readonly uimage3D uAlbedoVox;
layout(binding = kVCTImageNormal, r32ui) uniform readonly uimage3D uNormalVox;
layout(binding = kVCTImagePosition, r32ui) uniform readonly uimage3D uPositionVox;
layout(binding = kVCTImageExitFront, r11f_g11f_b10f) uniform readonly image3D uDirectFront;  // inject.comp's result
layout(binding = kVCTImageExitBack, r11f_g11f_b10f) uniform readonly image3D uDirectBack;
layout(binding = kVCTImageBouncedFront, r11f_g11f_b10f) uniform writeonly image3D uExitFront;  // what resolve.comp reads next
layout(binding = kVCTImageBouncedBack, r11f_g11f_b10f) uniform writeonly image3D uExitBack;
#if VCT_SIDES
layout(binding = kVCTImageSides, r32ui) uniform readonly uimage3D uSidesVox;  // each side's mean normal
layout(binding = kVCTImageSidesDirect, rgba16f) uniform readonly image3D uSidesDirect;  // inject.comp's sides
layout(binding = kVCTImageSidesBounced, rgba16f) uniform writeonly image3D uSidesBounced;  // what mip.comp reads next
#endif

// E / pi gathered over the hemisphere around n. On the last bounce with vct.bounceTail
// (uVCT.gridMin.w 1) it also stands for the bounces left out: the cones' opacity says how much
// of the hemisphere surfaces fill (its enclosure e), and if those surfaces reflect like this one
// (albedo rho, the assumption of Jimenez et al. 2016's multi-bounce fit for ambient occlusion)
// and receive light like it, each further bounce multiplies the gathered light by rho e, so all
// of them sum to E / (1 - rho e), capped at 1 / kVCTTailMinRemainder times E. A closed room of
// albedo 0.8 then holds 5x, an open floor (e near 0) its own gathered light.
vec3 hemisphere(vec3 p, vec3 n, float albedo) {
    mat3 frame = tangentFrame(n);
    vec3 e = vec3(0.0);
    float enclosed = 0.0;
    for (int i = 0; i < uVCT.coneCount; ++i) {
        float occlusion;
        vec4 c = traceCone(p, n, frame * uVCT.cones[i].xyz, uVCT.tanHalf, uVCT.maxDistance, 0.0, kVCTPhaseUnstaggered, occlusion);
        e += uVCT.cones[i].w * c.rgb;
        enclosed += uVCT.cones[i].w * c.a;
    }
    if (uVCT.gridMin.w > 0.0) e /= max(1.0 - albedo * enclosed, kVCTTailMinRemainder);
    return e;
}

void main() {
    if (gl_GlobalInvocationID.x >= count) return;
    uint e = voxels[gl_GlobalInvocationID.x];
    ivec3 v = ivec3(e & 1023u, (e >> 10) & 1023u, e >> 20);
    ivec3 t = texelOf(v);
    uint a = imageLoad(uAlbedoVox, t).r;
    vec3 albedo = unpackVoxel(a).rgb;
    uint packedNormal = imageLoad(uNormalVox, t).r;
    vec3 nn = voxelNormal(packedNormal);
    vec3 n = length(nn) > 1e-3 ? normalize(nn) : vec3(0.0, 1.0, 0.0);
    vec3 p = voxelSurface(v, imageLoad(uPositionVox, t).r);
    // E / pi on each side; the surface then leaves albedo * E / pi.
    float rho = dot(albedo, vec3(0.2126, 0.7152, 0.0722));  // Rec. 709 luminance
    float wb = backWeight(packedNormal);
    vec3 front = hemisphere(p, n, rho), back = wb > kVCTBackMinWeight ? wb * hemisphere(p, -n, rho) : vec3(0.0);
    imageStore(uExitFront, t, imageLoad(uDirectFront, t) + vec4(albedo * front, 0.0));
    imageStore(uExitBack, t, imageLoad(uDirectBack, t) + vec4(albedo * back, 0.0));
#if VCT_SIDES
    // Each side leaves its direct light plus the light gathered on the side of the mean normal
    // it faces, times its coverage, as inject.comp stores it (the cones are not traced again per side).
    for (int s = 0; s < 6; ++s) {
        ivec3 ts = t + ivec3(s * uVCT.resolution, 0, 0);
        vec4 direct = imageLoad(uSidesDirect, ts);
        vec3 ns = voxelNormal(imageLoad(uSidesVox, ts).r);
        vec3 gathered = dot(ns, n) >= 0.0 ? front : back;
        imageStore(uSidesBounced, ts, vec4(direct.rgb + albedo * gathered * direct.a, direct.a));
    }
#endif
}
