#include "gi/volumetric/medium.h"

#include "common/light.h"

#include <algorithm>
#include <cmath>

namespace gi {

Medium makeMedium(const VolumetricSettings& s, const Bounds& sceneBounds) {
    Medium m;
    m.active = s.enabled && s.density > 0.0f && sceneBounds.valid();
    m.box = sceneBounds;
    m.sigmaS = s.density;
    m.sigmaT = s.attenuation == VolumeAttenuation::Coefficients ? s.density + s.absorption : 1.0f / s.opticalThickness;
    m.phase = phaseParams(s);
    m.intensity = s.intensity;
    m.attenuateScene = s.attenuateScene;
    return m;
}

bool clipRayToBox(const Bounds& box, const glm::vec3& o, const glm::vec3& d, float tMax, float& t0, float& t1) {
    t0 = 0.0f;
    t1 = tMax;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(d[a]) < 1e-12f) {
            if (o[a] < box.min[a] || o[a] > box.max[a]) return false;
            continue;
        }
        float inv = 1.0f / d[a];
        float n = (box.min[a] - o[a]) * inv, f = (box.max[a] - o[a]) * inv;
        if (n > f) std::swap(n, f);
        t0 = std::max(t0, n);
        t1 = std::min(t1, f);
    }
    return t0 < t1;
}

bool clipRayToLight(const LightSettings& l, const glm::vec3& o, const glm::vec3& d, float& t0, float& t1) {
    if (l.type == LightType::Directional) return t0 < t1;
    glm::vec3 v = o - l.position;
    if (l.range > 0.0f) {
        // |v + t d|^2 <= range^2
        float b = glm::dot(v, d), c = glm::dot(v, v) - l.range * l.range;
        float disc = b * b - c;
        if (disc <= 0.0f) return false;
        float s = std::sqrt(disc);
        t0 = std::max(t0, -b - s);
        t1 = std::min(t1, -b + s);
        if (t0 >= t1) return false;
    }
    if (l.type != LightType::Spot) return true;
    // Inside the cone: a . (v + t d) >= cos |v + t d|, with a the spot's axis. Squared, with the
    // sign condition a . (v + t d) >= 0: A t^2 + 2 B t + C >= 0.
    glm::vec3 a = light::lightDirection(l.direction);
    float cosOuter = light::spotCosines(l.innerConeDeg, l.outerConeDeg).y;
    float c2 = cosOuter * cosOuter;
    float ad = glm::dot(a, d), av = glm::dot(a, v);
    float A = ad * ad - c2, B = ad * av - c2 * glm::dot(d, v), C = av * av - c2 * glm::dot(v, v);
    auto inside = [&](float t) {
        float along = av + t * ad;
        return along >= 0.0f && along * along >= c2 * glm::dot(v + t * d, v + t * d);
    };
    // The roots split the ray into at most three pieces; the cone holds a single interval of it.
    float roots[2];
    int n = 0;
    if (std::abs(A) < 1e-9f) {
        if (std::abs(B) > 1e-12f) roots[n++] = -C / (2.0f * B);
    } else {
        float disc = B * B - A * C;
        if (disc >= 0.0f) {
            float s = std::sqrt(disc);
            roots[n++] = (-B - s) / A;
            roots[n++] = (-B + s) / A;
            if (roots[0] > roots[1]) std::swap(roots[0], roots[1]);
        }
    }
    float edges[4] = {t0, 0.0f, 0.0f, t1};
    int count = 1;
    for (int i = 0; i < n; ++i)
        if (roots[i] > t0 && roots[i] < t1) edges[count++] = roots[i];
    edges[count++] = t1;
    float lo = 0.0f, hi = -1.0f;
    for (int i = 0; i + 1 < count; ++i) {
        float mid = 0.5f * (edges[i] + edges[i + 1]);
        if (!inside(mid)) continue;
        if (hi < lo) lo = edges[i];
        hi = edges[i + 1];
    }
    if (hi <= lo) return false;
    t0 = lo;
    t1 = hi;
    return true;
}

float lightPathInBox(const Bounds& box, const LightSettings& l, const glm::vec3& x) {
    glm::vec3 dir;
    float length;
    if (l.type == LightType::Directional) {
        dir = -light::lightDirection(l.direction);
        length = 1e30f;
    } else {
        glm::vec3 toLight = l.position - x;
        length = glm::length(toLight);
        if (length < 1e-8f) return 0.0f;
        dir = toLight / length;
    }
    float t0, t1;
    if (!clipRayToBox(box, x, dir, length, t0, t1)) return 0.0f;
    return t1 - t0;
}

}  // namespace gi
