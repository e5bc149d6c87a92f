// Geometry volume: surfels (RSM texels, or subsampled G-buffer pixels) add their blocking
// potential (area / cell face area) * SH(max(n.w, 0)) to the grid sample nearest to them; the
// samples sit on the LPV cell corners, half a cell off the LPV's cell centres. Each also adds its
// diffuse albedo times its coverage, and its coverage, to the corner's albedo (bounce.comp reads
// the ratio: the coverage-weighted mean albedo of the corner's surfels, both sources together).
#include "common/atomic_float.glsl"
#include "lpv/common.glsl"

#include "common/shared.h"
layout(local_size_x = kGroup2D, local_size_y = kGroup2D) in;
layout(binding = kLPVImageNormal, rgba16f) uniform readonly image2D uRSMNormal;
layout(binding = kLPVImagePosition, rgba32f) uniform readonly image2D uRSMPosition;
layout(binding = kLPVImageAlbedo, rgba8) uniform readonly image2D uRSMAlbedo;
layout(binding = kUnitAlbedo) uniform sampler2D uGAlbedo;
layout(binding = kUnitNormal) uniform sampler2D uGNormal;
layout(binding = kUnitMaterial) uniform sampler2D uGMaterial;
layout(binding = kUnitDepth) uniform sampler2D uGDepth;
layout(std430, binding = kLPVBufferGeometry) buffer Geometry { GI_ATOMIC_FLOAT geometry[]; };
layout(std430, binding = kLPVBufferGeometryAlbedo) buffer GeometryAlbedo { GI_ATOMIC_FLOAT geometryAlbedo[]; };

void atomicAddFloat(int i, float v) { GI_ATOMIC_ADD_FLOAT(geometry[i], v); }
void atomicAddAlbedo(int i, float v) { GI_ATOMIC_ADD_FLOAT(geometryAlbedo[i], v); }

void main() {
    vec3 p, n, albedo;
    float area;
    ivec2 sourceSize = ivec2(uLPV.width, uLPV.height);
    float cellSize = uLPV.gridMinCell.w;
    if (uLPV.fromGBuffer != 0) {
        ivec2 px = ivec2(gl_GlobalInvocationID.xy) * uLPV.stride;
        if (any(greaterThanEqual(px, sourceSize))) return;
        float depth = texelFetch(uGDepth, px, 0).r;
        if (depth >= 1.0) return;
        vec2 uv = (vec2(px) + 0.5) / vec2(sourceSize);
        vec4 w = uLPV.invViewProj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
        p = w.xyz / w.w;
        n = normalize(texelFetch(uGNormal, px, 0).xyz);
        vec3 camera = uLPV.cameraPos.xyz;
        float d = length(p - camera);
        float side = d * uLPV.pixelAngle * float(uLPV.stride);
        area = side * side / max(abs(dot(n, (p - camera) / d)), kLPVMinSurfelCosine);
        // Diffuse albedo as the composite reads it: base colour times 1 - metallic.
        albedo = texelFetch(uGAlbedo, px, 0).rgb * (1.0 - texelFetch(uGMaterial, px, 0).g);
    } else {
        ivec2 t = ivec2(gl_GlobalInvocationID.xy);
        if (any(greaterThanEqual(t, sourceSize))) return;
        vec4 pos = imageLoad(uRSMPosition, t);
        if (pos.w <= 0.0) return;
        p = pos.xyz;
        n = normalize(imageLoad(uRSMNormal, t).xyz);
        area = pos.w;
        albedo = imageLoad(uRSMAlbedo, t).rgb;
    }
    ivec3 c = ivec3(floor((p - uLPV.gridMinCell.xyz) / cellSize + 0.5));
    if (any(lessThan(c, ivec3(0))) || any(greaterThan(c, ivec3(uLPV.resolution)))) return;
    int r1 = uLPV.resolution + 1;
    int base = ((c.z * r1 + c.y) * r1 + c.x) * 4;
    float coverage = min(area / (cellSize * cellSize), 1.0);
    vec4 b = shCosLobe(n) * coverage;
    for (int k = 0; k < 4; ++k) atomicAddFloat(base + k, b[k]);
    for (int k = 0; k < 3; ++k) atomicAddAlbedo(base + k, albedo[k] * coverage);
    atomicAddAlbedo(base + 3, coverage);
}
