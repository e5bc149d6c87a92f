// Environment lighting of the G-buffer (technique none): the indirect diffuse term is the
// cosine-convolved map (E / pi, as the composite expects), the indirect specular the
// prefiltered chain at the mip of the pixel's roughness (envmap.glsl mipForRoughness) along the
// reflected view direction; the composite weighs it with the split-sum table.
#include "envmap/envmap.glsl"
#include "common/shared.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = kUnitNormal) uniform sampler2D uNormal;
layout(binding = kUnitMaterial) uniform sampler2D uMaterial;
layout(binding = kUnitDepth) uniform sampler2D uDepth;
layout(binding = 0) uniform samplerCube uPrefiltered;
layout(binding = 3) uniform samplerCube uIrradiance;
layout(binding = 0, rgba16f) uniform writeonly image2D uIndirect;
layout(binding = 1, rgba16f) uniform writeonly image2D uSpecular;

uniform ivec2 uSize;
uniform mat4 uInvViewProj;
uniform vec3 uEye;
uniform float uIntensity;
uniform float uRotation;
uniform float uMipRoughness[32];
uniform int uMipCount;

void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, uSize))) return;
    float depth = texelFetch(uDepth, px, 0).r;
    vec3 diffuse = vec3(0.0), specular = vec3(0.0);
    if (depth < 1.0) {
        vec2 uv = (vec2(px) + 0.5) / vec2(uSize);
        vec4 w = uInvViewProj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
        vec3 P = w.xyz / w.w;
        vec3 N = normalize(texelFetch(uNormal, px, 0).xyz);
        vec3 V = normalize(uEye - P);
        if (dot(N, V) < 0.0) N = -N;  // two-sided, as the direct light
        vec3 R = reflect(-V, N);
        float roughness = texelFetch(uMaterial, px, 0).r;
        diffuse = uIntensity * textureLod(uIrradiance, envRotateY(N, -uRotation), 0.0).rgb;
        float lod = mipForRoughness(roughness, uMipRoughness, uMipCount);
        specular = uIntensity * textureLod(uPrefiltered, envRotateY(R, -uRotation), lod).rgb;
    }
    imageStore(uIndirect, px, vec4(diffuse, 1.0));
    imageStore(uSpecular, px, vec4(specular, 1.0));
}
