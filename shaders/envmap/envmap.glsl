// Environment map helpers shared by the environment passes: the latlong convention of
// gi/envmap/envmap_image.h (latLongUV), GL cube face directions, the Hammersley sequence and
// GGX importance sampling (Karis 2013); the rotation and the mip for a roughness are in
// common/sky.glsl, shared with the techniques that read the sky.
// Through envmap/envmap_shared.h every pass has the constants and the parameter block uEnv.
#include "common/shared.h"
#include "envmap/envmap_shared.h"
#include "common/sky.glsl"

vec2 latLongUV(vec3 dir, float rotationDeg) {
    vec3 d = envRotateY(dir, -rotationDeg);
    return vec2(0.5 + atan(d.x, -d.z) / (2.0 * kPi), acos(clamp(d.y, -1.0, 1.0)) / kPi);
}

// GL's direction through texel (x, y) of cube face f (+X -X +Y -Y +Z -Z) of size n.
vec3 cubeDirection(int f, ivec2 xy, int n) {
    vec2 st = (vec2(xy) + 0.5) / float(n) * 2.0 - 1.0;
    float s = st.x, t = st.y;
    vec3 d;
    if (f == 0) d = vec3(1.0, -t, -s);
    else if (f == 1) d = vec3(-1.0, -t, s);
    else if (f == 2) d = vec3(s, 1.0, t);
    else if (f == 3) d = vec3(s, -1.0, -t);
    else if (f == 4) d = vec3(s, -t, 1.0);
    else d = vec3(-s, -t, -1.0);
    return normalize(d);
}

vec2 hammersley(uint i, uint n) {
    uint b = i;
    b = (b << 16u) | (b >> 16u);
    b = ((b & 0x55555555u) << 1u) | ((b & 0xAAAAAAAAu) >> 1u);
    b = ((b & 0x33333333u) << 2u) | ((b & 0xCCCCCCCCu) >> 2u);
    b = ((b & 0x0F0F0F0Fu) << 4u) | ((b & 0xF0F0F0F0u) >> 4u);
    b = ((b & 0x00FF00FFu) << 8u) | ((b & 0xFF00FF00u) >> 8u);
    return vec2(float(i) / float(n), float(b) * 2.3283064365386963e-10);
}

// Columns: tangent, bitangent, n (Frisvad with Duff et al.'s fix).
mat3 envFrame(vec3 n) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float b = n.x * n.y * a;
    return mat3(vec3(1.0 + s * n.x * n.x * a, s * b, -s * n.x), vec3(b, s + n.y * n.y * a, -n.y), n);
}

// A GGX half vector about +z for alpha = roughness^2.
vec3 sampleGGX(vec2 xi, float a) {
    float phi = 2.0 * kPi * xi.x;
    float cosTheta = sqrt((1.0 - xi.y) / (1.0 + (a * a - 1.0) * xi.y));
    float sinTheta = sqrt(1.0 - cosTheta * cosTheta);
    return vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
}
