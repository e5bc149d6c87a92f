// The split-sum BRDF table (Karis 2013): for (N.V, perceptual roughness) at texel centres, the
// GGX lobe's directional albedo as F0 * A + B -> (A, B), by importance sampling the same D and
// height-correlated Smith visibility the direct light uses (common/ggx.h).
#include "envmap/envmap.glsl"
#include "common/ggx.h"

#include "common/shared.h"
layout(local_size_x = kGroup2D, local_size_y = kGroup2D) in;
layout(binding = kEnvImageTarget, rg16f) uniform writeonly image2D uLUT;

void main() {
    ivec2 id = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(id, ivec2(uEnv.size)))) return;
    float NoV = (float(id.x) + 0.5) / float(uEnv.size);
    float roughness = (float(id.y) + 0.5) / float(uEnv.size);
    float a = max(roughness * roughness, 0.002);
    vec3 V = vec3(sqrt(1.0 - NoV * NoV), 0.0, NoV);
    float A = 0.0, B = 0.0;
    uint n = uint(uEnv.samples);
    for (uint i = 0u; i < n; ++i) {
        vec3 H = sampleGGX(hammersley(i, n), a);
        vec3 L = reflect(-V, H);
        float NoL = L.z, NoH = H.z, VoH = max(dot(V, H), 0.0);
        if (NoL <= 0.0) continue;
        // f cos / pdf with pdf = D NoH / (4 VoH): 4 V NoL VoH / NoH.
        float w = 4.0 * V_SmithGGXCorrelated(NoV, NoL, a) * NoL * VoH / max(NoH, 1e-6);
        float Fc = pow(1.0 - VoH, 5.0);
        A += (1.0 - Fc) * w;
        B += Fc * w;
    }
    imageStore(uLUT, id, vec4(A / float(n), B / float(n), 0.0, 1.0));
}
