// Light injection, per voxel: the direct irradiance E of a batch of up to kVCTMaxLights lights of
// the frame's light buffer (common/light.h) on each side of the voxel's surface (front: along its
// mean normal, back: against it) where the surface lies in the voxel (the position volume,
// voxelize.frag), tested against the renderer's shadow maps at that point moved half a voxel off
// the surface on the lit side, stored as the radiance each side leaves, L = albedo * E / pi
// (Lambertian), the back's times the voxel's backWeight (voxel_encoding.glsl). Evaluated at the
// voxel centre, E and the shadow test moved with the grid's alignment (a point light 0.3 m from a
// wall gives +-17 % across a 5 cm voxel): the shift test's worst case with three bounces fell
// from +5.2 % to +4.2 % at the surface. Later batches (more lights) and bounces add to it. Emissive
// surfaces are area lights here like any other light (their exact irradiance on each voxel below);
// their own emission is not added to their voxels, since the raster's light pass already shades
// their direct light and cones that gathered it would count it twice.
// The test point is not also moved towards the light (as it was before issue 13's leak work): in
// the two-room scene that carried the dark room's floor and wall voxels next to the shared wall
// through it into the lit room's light, and the closed room took 46 % of the lit room's indirect
// light instead of 22 %; the shipped presets moved by at most 0.009 SSIM either way. (Testing at
// the surface rather than the voxel centre lights the dark room's voxel that holds the shared
// wall, which lies on its boundary there, by the wall's lit face: the defaults' two-room leak
// rose from 35 % to 60 %, 57-68 % against 39-61 % at the other alignments; vct_test.cpp.)
// resolve.comp turns the two sides into the traced radiance volumes.
#include "vct/common.glsl"
#include "common/light.h"

#include "common/shared.h"
layout(local_size_x = kGroup3DX, local_size_y = kGroup3DY, local_size_z = kGroup3DZ) in;
layout(binding = kVCTImageAlbedo, r32ui) uniform readonly uimage3D uAlbedoVox;
layout(binding = kVCTImageNormal, r32ui) uniform readonly uimage3D uNormalVox;
layout(binding = kVCTImageExitFront, r11f_g11f_b10f) uniform image3D uExitFront;
layout(binding = kVCTImageExitBack, r11f_g11f_b10f) uniform image3D uExitBack;
layout(binding = kVCTImageSides, r32ui) uniform readonly uimage3D uSidesVox;
layout(binding = kVCTImagePosition, r32ui) uniform readonly uimage3D uPositionVox;
layout(binding = kVCTImageSidesRadiance, rgba16f) uniform image3D uSidesRadiance;
layout(binding = kVCTUnitShadow2D) uniform sampler2DShadow uShadow2D[kVCTMaxLights];
layout(binding = kVCTUnitShadowCube) uniform samplerCubeShadow uShadowCube[kVCTMaxLights];

float visibility(int i, GPULight l, vec3 p) {
    if (l.info.y == 0) return 1.0;
    if (cubeShadow(l.info.x)) {
        vec3 d = p - l.position.xyz;
        return texture(uShadowCube[i], vec4(normalize(d), length(d) / l.shadow.x));
    }
    vec4 c = l.shadowViewProj * vec4(p, 1.0);
    vec3 tc = c.xyz / c.w * 0.5 + 0.5;
    if (any(lessThan(tc.xy, vec2(0.0))) || any(greaterThan(tc.xy, vec2(1.0))) || tc.z > 1.0) return 1.0;
    return texture(uShadow2D[i], tc);
}

// The batch's irradiance on a one-sided surface of normal n at p (the per-side volumes).
vec3 sideIrradiance(vec3 p, vec3 n) {
    vec3 sum = vec3(0.0);
    vec3 probe = p + n * (kVCTSideProbe * uVCT.cellSize);
    for (int i = 0; i < uVCT.lightCount; ++i) {
        GPULight l = uLights[uVCT.lightFirst + i];
        vec3 L;
        vec3 E = l.color.rgb;
        if (l.info.x == kLightDirectional) {
            L = -l.direction.xyz;
        } else {
            vec3 toLight = l.position.xyz - p;
            float dist = length(toLight);
            L = toLight / max(dist, 1e-6);
            E *= lightFalloff(l, dist, dot(-L, l.direction.xyz));
        }
        if (l.info.x == kLightArea && l.info.w <= kAreaMaxExactTriangles) {
            vec3 e = areaIrradiance(l, p, n);
            if (any(greaterThan(e, vec3(0.0)))) sum += e * visibility(i, l, probe);
            continue;
        }
        float c = dot(n, L);
        if (c <= 0.0 || all(equal(E, vec3(0.0)))) continue;
        sum += E * c * visibility(i, l, probe);
    }
    return sum;
}

// The six sides of an anisotropic grid's voxel: side 2a + (0: +, 1: -) holds the fragments whose
// normal faces that way along axis a; it leaves albedo * E / pi under its own mean normal, stored
// times its coverage (the mean over all the voxel's fragments of max(0, n . side)) with the
// coverage in alpha, so a cone weighs the sides it sees by how much of the voxel faces it.
void injectSides(ivec3 v, ivec3 t, uint packedAlbedo, uint packedNormal) {
    vec4 albedo = unpackVoxel(packedAlbedo);
    vec3 meanNormal = voxelNormal(packedNormal);
    float back = backWeight(packedNormal);
    float total = max(round(albedo.a * kVCTMaxCount), 1.0);
    vec3 p = voxelSurface(v, imageLoad(uPositionVox, t).r);
    for (int s = 0; s < 6; ++s) {
        ivec3 ts = t + ivec3(s * uVCT.resolution, 0, 0);
        vec4 result = vec4(0.0);
        uint packedSide = imageLoad(uSidesVox, ts).r;
        if (occupied(packedSide) && occupied(packedAlbedo)) {
            vec4 u = unpackVoxel(packedSide);
            vec3 n = voxelNormal(packedSide);
            vec3 axis = vec3(0.0);
            axis[s / 2] = (s & 1) == 0 ? 1.0 : -1.0;
            float coverage = clamp(round(u.a * kVCTMaxCount) / total * max(dot(n, axis), 0.0), 0.0, 1.0);
            float len = length(n);
            // The back of a one-sided voxel (the side against its fragments' mean normal) is
            // weighed as in the voxel's own injection (backWeight).
            float weight = dot(n, meanNormal) < 0.0 ? back : 1.0;
            if (len > 1e-3 && coverage > 0.0) result = vec4(albedo.rgb / kPi * sideIrradiance(p, n / len) * coverage * weight, coverage);
        }
        if (uVCT.accumulate != 0) result.rgb += imageLoad(uSidesRadiance, ts).rgb;
        imageStore(uSidesRadiance, ts, result);
    }
}

void main() {
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (!insideGrid(v)) return;
    ivec3 t = texelOf(v);
    vec3 front = vec3(0.0), back = vec3(0.0);
    uint packedNormal = imageLoad(uNormalVox, t).r;
    uint packedAlbedo = imageLoad(uAlbedoVox, t).r;
    if (uVCT.sides != 0) injectSides(v, t, packedAlbedo, packedNormal);
    if (occupied(packedAlbedo)) {
        vec3 n = voxelNormal(packedNormal);
        float len = length(n);
        n = len > 1e-3 ? n / len : vec3(0.0, 1.0, 0.0);
        vec3 p = voxelSurface(v, imageLoad(uPositionVox, t).r);
        for (int i = 0; i < uVCT.lightCount; ++i) {
            GPULight l = uLights[uVCT.lightFirst + i];
            vec3 L;
            vec3 E = l.color.rgb;
            if (l.info.x == kLightDirectional) {
                L = -l.direction.xyz;
            } else {
                vec3 toLight = l.position.xyz - p;
                float dist = length(toLight);
                L = toLight / max(dist, 1e-6);
                E *= lightFalloff(l, dist, dot(-L, l.direction.xyz));
            }
            float c = dot(n, L);
            if (l.info.x == kLightArea && len > 1e-3 && l.info.w <= kAreaMaxExactTriangles) {
                // An area light near the voxel: the exact irradiance of its triangles on each side.
                vec3 ef = areaIrradiance(l, p, n), eb = areaIrradiance(l, p, -n);
                float vis = all(equal(ef + eb, vec3(0.0))) ? 0.0 : visibility(i, l, p + (c >= 0.0 ? n : -n) * (0.5 * uVCT.cellSize));
                front += ef * vis;
                back += eb * vis;
                continue;
            }
            if (all(equal(E, vec3(0.0))) || (len > 1e-3 && abs(c) < 1e-4)) continue;
            vec3 side = c >= 0.0 ? n : -n;
            float vis = visibility(i, l, p + side * (0.5 * uVCT.cellSize));
            // A voxel whose normals cancelled (two faces of a thin slab) takes the light unweighted.
            vec3 e = E * vis * (len > 1e-3 ? abs(c) : 1.0);
            if (c >= 0.0) front += e;
            else back += e;
        }
    }
    vec3 albedo = unpackVoxel(packedAlbedo).rgb / kPi;
    front *= albedo;
    back *= albedo * backWeight(packedNormal);
    if (uVCT.accumulate != 0) {
        front += imageLoad(uExitFront, t).rgb;
        back += imageLoad(uExitBack, t).rgb;
    }
    imageStore(uExitFront, t, vec4(front, 1.0));
    imageStore(uExitBack, t, vec4(back, 1.0));
}
