// One mip of the prefiltered environment: per texel direction N (with V = R = N, the split-sum's
// assumption), the radiance of the lobe of roughness uEnv.roughness around it.
//   GGX (kEnvPrefilterGGX): importance sampled half vectors, L = reflect(-N, H), weights N.L (Karis 2013),
//     each sample read from the source mip whose texel matches the sample's solid angle
//     (filtered importance sampling, Krivanek and Colbert 2008), so few samples stay smooth.
//   Beckmann cone (kEnvPrefilterBeckmannCone, seed 004 Alg. 6): directions through a uniform
//     disk of radius uEnv.diskRadius (tan of the lobe aperture) on the plane tangent at N, averaged (normalised by
//     the count, where the seed multiplies by pi r^2 and brightens the rough mips).
//   Irradiance (kEnvPrefilterIrradiance): E / pi from the 9 SH coefficients uEnv.sh
//     (gi/envmap/envmap_image.h irradianceSH: projected on the CPU from every texel, exact for
//     the clamped cosine's bands).
// Roughness 0 copies the source.
#include "envmap/envmap.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup2D, local_size_y = kGroup2D, local_size_z = 1) in;
layout(binding = kEnvUnitSource) uniform samplerCube uSource;  // mip 0 = the map, full mip chain
layout(binding = kEnvImageTarget, rgba16f) uniform writeonly imageCube uDest;

float sourceMip(float pdf) {
    float saSample = 1.0 / (float(uEnv.samples) * max(pdf, 1e-8));
    float saTexel = 4.0 * kPi / (6.0 * float(uEnv.sourceSize * uEnv.sourceSize));
    return max(0.5 * log2(saSample / saTexel) + 1.0, 0.0);
}

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID) + ivec3(0, uEnv.rowOffset, 0);
    if (id.x >= uEnv.size || id.y >= uEnv.size) return;
    vec3 N = cubeDirection(id.z, id.xy, uEnv.size);
    if (uEnv.mode == kEnvPrefilterIrradiance) {
        imageStore(uDest, id, vec4(skyIrradiance(uEnv.sh, N), 1.0));
        return;
    }
    if (uEnv.roughness <= 0.0) {
        imageStore(uDest, id, vec4(textureLod(uSource, N, 0.0).rgb, 1.0));
        return;
    }
    mat3 frame = envFrame(N);
    vec3 sum = vec3(0.0);
    float total = 0.0;
    uint n = uint(uEnv.samples);
    for (uint i = 0u; i < n; ++i) {
        vec2 xi = hammersley(i, n);
        if (uEnv.mode == kEnvPrefilterGGX) {
            float a = uEnv.roughness * uEnv.roughness;
            vec3 H = frame * sampleGGX(xi, a);
            vec3 L = reflect(-N, H);
            float NoL = dot(N, L);
            if (NoL <= 0.0) continue;
            float NoH = max(dot(N, H), 0.0);
            float a2 = a * a, d = NoH * NoH * (a2 - 1.0) + 1.0;
            float pdf = a2 / (kPi * d * d) / 4.0;  // D * NoH / (4 VoH) with V = N
            sum += textureLod(uSource, L, sourceMip(pdf)).rgb * NoL;
            total += NoL;
        } else if (uEnv.mode == kEnvPrefilterBeckmannCone) {
            // Uniform disk (concentric would stratify better; Hammersley already does).
            float r = uEnv.diskRadius * sqrt(xi.y), phi = 2.0 * kPi * xi.x;
            vec3 L = normalize(frame * vec3(r * cos(phi), r * sin(phi), 1.0));
            float area = kPi * uEnv.diskRadius * uEnv.diskRadius;
            float cosL = dot(N, L);
            float pdf = cosL * cosL * cosL / area;  // disk density carried onto the sphere
            sum += textureLod(uSource, L, sourceMip(pdf)).rgb;
            total += 1.0;
        } else {
            float r = sqrt(xi.y), phi = 2.0 * kPi * xi.x;
            vec3 L = frame * vec3(r * cos(phi), r * sin(phi), sqrt(max(1.0 - xi.y, 0.0)));
            float pdf = max(dot(N, L), 1e-4) / kPi;
            sum += textureLod(uSource, L, sourceMip(pdf)).rgb;
            total += 1.0;
        }
    }
    imageStore(uDest, id, vec4(sum / max(total, 1e-6), 1.0));
}
