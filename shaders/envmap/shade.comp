// Environment lighting of the G-buffer (technique none): the indirect diffuse term is the
// cosine-convolved map (E / pi, as the composite expects), the indirect specular the
// prefiltered chain at the mip of the pixel's roughness (envmap.glsl mipForRoughness) along the
// reflected view direction; the composite weighs it with the split-sum table.
#include "envmap/envmap.glsl"
#include "common/shared.h"

layout(local_size_x = kGroup2D, local_size_y = kGroup2D) in;
layout(binding = kUnitNormal) uniform sampler2D uNormal;
layout(binding = kUnitMaterial) uniform sampler2D uMaterial;
layout(binding = kUnitDepth) uniform sampler2D uDepth;
layout(binding = kEnvUnitPrefiltered) uniform samplerCube uPrefiltered;
layout(binding = kEnvUnitIrradiance) uniform samplerCube uIrradiance;
layout(binding = kEnvImageIndirect, rgba16f) uniform writeonly image2D uIndirect;
layout(binding = kEnvImageSpecular, rgba16f) uniform writeonly image2D uSpecular;

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(uEnv.width, uEnv.height);
    if (any(greaterThanEqual(px, size))) return;
    float depth = texelFetch(uDepth, px, 0).r;
    vec3 diffuse = vec3(0.0), specular = vec3(0.0);
    if (depth < 1.0) {
        vec2 uv = (vec2(px) + 0.5) / vec2(size);
        vec4 w = uEnv.invViewProj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
        vec3 P = w.xyz / w.w;
        vec3 N = normalize(texelFetch(uNormal, px, 0).xyz);
        vec3 V = normalize(uEnv.eye.xyz - P);
        if (dot(N, V) < 0.0) N = -N;  // two-sided, as the direct light
        vec3 R = reflect(-V, N);
        float roughness = texelFetch(uMaterial, px, 0).r;
        diffuse = uEnv.intensity * textureLod(uIrradiance, envRotateY(N, -uEnv.rotation), 0.0).rgb;
        float lod = mipForRoughness(roughness, uEnv.mipRoughness, uEnv.mipCount);
        specular = uEnv.intensity * textureLod(uPrefiltered, envRotateY(R, -uEnv.rotation), lod).rgb;
    }
    imageStore(uIndirect, px, vec4(diffuse, 1.0));
    imageStore(uSpecular, px, vec4(specular, 1.0));
}
