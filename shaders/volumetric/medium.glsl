// The medium of volumetric lighting, the GLSL twin of gi/volumetric/medium.{h,cpp} (see there
// for the model): a homogeneous box (the scene's bounds), lights clipped to their cone and range.
// The box and the coefficients come from VolumeBlock (volumetric_shared.h).
#include "common/light.h"
#include "volumetric/volumetric_shared.h"

// [t0, t1] of o + t d (0 <= t <= tMax) inside the box.
bool clipRayToBox(vec3 o, vec3 d, float tMax, out float t0, out float t1) {
    vec3 inv = 1.0 / d;  // +-inf on an axis-parallel ray: the slab test still works (IEEE)
    vec3 n = (uVolume.boxMin.xyz - o) * inv, f = (uVolume.boxMax.xyz - o) * inv;
    vec3 lo = min(n, f), hi = max(n, f);
    t0 = max(0.0, max(lo.x, max(lo.y, lo.z)));
    t1 = min(tMax, min(hi.x, min(hi.y, hi.z)));
    return t0 < t1;
}

// Narrows [t0, t1] to the light's reach: the range sphere and a spot's convex cone (the outer
// cone is at most 90 degrees).
bool clipRayToLight(GPULight l, vec3 o, vec3 d, inout float t0, inout float t1) {
    if (l.info.x == kLightDirectional) return t0 < t1;
    vec3 axis = l.direction.xyz;
    float range = l.position.w, cosOuter = l.spot.y;
    vec3 v = o - l.position.xyz;
    if (range > 0.0) {
        float b = dot(v, d), c = dot(v, v) - range * range;
        float disc = b * b - c;
        if (disc <= 0.0) return false;
        float s = sqrt(disc);
        t0 = max(t0, -b - s);
        t1 = min(t1, -b + s);
        if (t0 >= t1) return false;
    }
    if (l.info.x != kLightSpot) return true;
    float c2 = cosOuter * cosOuter;
    float ad = dot(axis, d), av = dot(axis, v);
    float A = ad * ad - c2, B = ad * av - c2 * dot(d, v), C = av * av - c2 * dot(v, v);
    float r0 = t1, r1 = t1;  // roots inside (t0, t1), else t1
    if (abs(A) < 1e-9) {
        if (abs(B) > 1e-12) r0 = -C / (2.0 * B);
    } else {
        float disc = B * B - A * C;
        if (disc >= 0.0) {
            float s = sqrt(disc);
            r0 = (-B - s) / A;
            r1 = (-B + s) / A;
            if (r0 > r1) { float t = r0; r0 = r1; r1 = t; }
        }
    }
    if (!(r0 > t0 && r0 < t1)) r0 = t1;
    if (!(r1 > t0 && r1 < t1)) r1 = t1;
    if (r1 < r0) { float t = r0; r0 = r1; r1 = t; }
    // Pieces [t0, r0], [r0, r1], [r1, t1]: the cone holds one run of them.
    float edges[4] = float[4](t0, r0, r1, t1);
    float lo = 0.0, hi = -1.0;
    for (int i = 0; i < 3; ++i) {
        if (edges[i + 1] <= edges[i]) continue;
        float mid = 0.5 * (edges[i] + edges[i + 1]);
        vec3 x = v + mid * d;
        float along = dot(axis, x);
        if (along < 0.0 || along * along < c2 * dot(x, x)) continue;
        if (hi < lo) lo = edges[i];
        hi = edges[i + 1];
    }
    if (hi <= lo) return false;
    t0 = lo;
    t1 = hi;
    return true;
}

// Distance from x towards the light inside the box (to the light, or out of the box for a directional light).
float lightPathInBox(vec3 x, vec3 toLight, float lightDistance) {
    float t0, t1;
    return clipRayToBox(x, toLight, lightDistance, t0, t1) ? t1 - t0 : 0.0;
}
