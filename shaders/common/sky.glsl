// Reading the environment's prefiltered chain (gi/envmap/environment.h), shared by the
// environment passes and the techniques that gather the sky (FrameContext::sky): the map's
// rotation about +y, the mip that holds a perceptual roughness, and the irradiance (E / pi) from
// the map's 9 SH coefficients (gi/envmap/envmap_image.h irradianceSH; xyz used).
#include "common/shared.h"

vec3 skyIrradiance(vec4 sh[9], vec3 N) {
    float b[9] = float[9](0.282095, 0.488603 * N.y, 0.488603 * N.z, 0.488603 * N.x, 1.092548 * N.x * N.y, 1.092548 * N.y * N.z,
                          0.315392 * (3.0 * N.z * N.z - 1.0), 1.092548 * N.x * N.z, 0.546274 * (N.x * N.x - N.y * N.y));
    vec3 e = vec3(0.0);
    for (int i = 0; i < 9; ++i) e += sh[i].xyz * b[i];
    return max(e, vec3(0.0));
}

vec3 envRotateY(vec3 d, float deg) {
    float a = radians(deg), c = cos(a), s = sin(a);
    return vec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
}

// The mip (fractional) of a chain whose mip m holds roughness table[m / 4][m % 4] (packed as
// EnvParams::mipRoughness), for perceptual roughness r: piecewise linear in the table, as the
// seed's shading (Alg. 8) does.
float mipForRoughness(float r, vec4 table[kSkyMaxMips / 4], int count) {
    if (r <= table[0][0]) return 0.0;
    for (int m = 0; m + 1 < count; ++m) {
        float lo = table[m / 4][m % 4], hi = table[(m + 1) / 4][(m + 1) % 4];
        if (r <= hi) return float(m) + (r - lo) / max(hi - lo, 1e-6);
    }
    return float(count - 1);
}
