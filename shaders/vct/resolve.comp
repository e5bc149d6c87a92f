// The traced radiance volumes from the radiance each side of a voxel's surface leaves
// (inject.comp, plus traced indirect light after a bounce). Isotropic voxels store the sum of
// both sides, premultiplied by the opacity (1 where anything was voxelized); SH voxels store each
// side as a hemisphere of radiance around its normal (common.glsl shHemisphere), so a cone sees
// the lit side only. Opacity stays in the isotropic volume's alpha in both cases. With face sides
// (uVCT.sides) it also writes the centroid volume: where each occupied voxel's surface lies, in
// voxels (the position volume), times its opacity, and the opacity, whose box-filtered mips give
// the mean position of the surfaces a texel holds (trace.glsl reads it). The voxel's centre
// instead put every surface up to half a voxel off, by where it fell in the grid: the face sides'
// own-plane test and view direction moved with the alignment, and the shift test
// (VCTGL.IndirectLightDoesNotDependOnWhereTheSceneFallsInTheGrid) gave +2.9 / +8.2 / +5.6 % with
// face sides, the tail and three bounces, +3.5 / +6.2 / +5.3 % at the surface.
#include "vct/common.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup3DX, local_size_y = kGroup3DY, local_size_z = kGroup3DZ) in;
// After a bounce the host binds the bounced volumes at the exit bindings.
layout(binding = kVCTImageAlbedo, r32ui) uniform readonly uimage3D uAlbedoVox;
layout(binding = kVCTImageNormal, r32ui) uniform readonly uimage3D uNormalVox;
layout(binding = kVCTImageExitFront, r11f_g11f_b10f) uniform readonly image3D uExitFront;
layout(binding = kVCTImageExitBack, r11f_g11f_b10f) uniform readonly image3D uExitBack;
layout(binding = kVCTImageRadiance, rgba16f) uniform writeonly image3D uRadiance;
layout(binding = kVCTImageSHR, rgba16f) uniform writeonly image3D uSHR;
layout(binding = kVCTImageSHG, rgba16f) uniform writeonly image3D uSHG;
layout(binding = kVCTImageSHB, rgba16f) uniform writeonly image3D uSHB;
layout(binding = kVCTImageCentroid, rgba16f) uniform writeonly image3D uCentroid;
layout(binding = kVCTImagePosition, r32ui) uniform readonly uimage3D uPositionVox;

void main() {
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (!insideGrid(v)) return;
    ivec3 t = texelOf(v);
    vec3 front = vec3(0.0), back = vec3(0.0), n = vec3(0.0, 1.0, 0.0);
    float alpha = 0.0;
    if (occupied(imageLoad(uAlbedoVox, t).r)) {
        vec3 nn = voxelNormal(imageLoad(uNormalVox, t).r);
        if (length(nn) > 1e-3) n = normalize(nn);
        front = imageLoad(uExitFront, t).rgb;
        back = imageLoad(uExitBack, t).rgb;
        alpha = 1.0;
    }
    imageStore(uRadiance, t, vec4(front + back, alpha));
    if (uVCT.sides != 0) imageStore(uCentroid, t, vec4(voxelSurfaceCell(v, imageLoad(uPositionVox, t).r) * alpha, alpha));
    if (uVCT.sh != 0) {
        vec4 hf = shHemisphere(n), hb = shHemisphere(-n);
        imageStore(uSHR, t, front.r * hf + back.r * hb);
        imageStore(uSHG, t, front.g * hf + back.g * hb);
        imageStore(uSHB, t, front.b * hf + back.b * hb);
    }
}
