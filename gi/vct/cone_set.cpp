#include "gi/vct/cone_set.h"

#include "common/shared.h"

#include <algorithm>
#include <cmath>

namespace gi {

namespace {

using shared::kPi;

glm::vec3 fromPolar(float cosTheta, float phi) {
    float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
    return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

}  // namespace

ConeSet makeConeSet(ConeSetKind kind, int customCount, float apertureDeg, ConeWeighting weighting) {
    ConeSet set;
    set.aperture = glm::radians(apertureDeg);
    std::vector<glm::vec3> axes;
    if (kind == ConeSetKind::Six) {
        axes.push_back({0, 0, 1});
        for (int k = 0; k < 5; ++k) axes.push_back(fromPolar(0.5f, float(k) * 2.0f * kPi / 5.0f + 0.5f * kPi));
    } else if (kind == ConeSetKind::Nine) {
        axes.push_back({0, 0, 1});
        for (int sx : {-1, 1})
            for (int sy : {-1, 1}) axes.push_back(glm::normalize(glm::vec3(float(sx), float(sy), 1.0f)));
        for (int k = 0; k < 4; ++k) {
            float phi = float(k) * 0.5f * kPi;
            axes.push_back(glm::normalize(glm::vec3(std::cos(phi), std::sin(phi), 1.0f)));
        }
    } else {
        int n = std::clamp(customCount, 1, kMaxCones);
        const float golden = kPi * (3.0f - std::sqrt(5.0f));
        for (int i = 0; i < n; ++i) axes.push_back(fromPolar(1.0f - (float(i) + 0.5f) / float(n), float(i) * golden));
    }
    float total = 0.0f;
    for (const glm::vec3& a : axes) {
        float w = weighting == ConeWeighting::Cosine ? a.z : 1.0f;
        set.cones.push_back({a, w});
        total += w;
    }
    for (Cone& c : set.cones) c.weight /= total;
    return set;
}

double coneSetCoverage(const ConeSet& set, int samples) {
    // Uniform hemisphere directions on a stratified grid in (z, phi): z = cos(theta) is uniform in
    // solid angle on the hemisphere.
    int side = std::max(1, int(std::sqrt(double(samples))));
    float cosHalf = std::cos(0.5f * set.aperture);
    int inside = 0;
    for (int i = 0; i < side; ++i)
        for (int j = 0; j < side; ++j) {
            glm::vec3 d = fromPolar((float(i) + 0.5f) / float(side), 2.0f * kPi * (float(j) + 0.5f) / float(side));
            for (const Cone& c : set.cones)
                if (glm::dot(d, c.direction) >= cosHalf) {
                    ++inside;
                    break;
                }
        }
    return double(inside) / double(side * side);
}

}  // namespace gi
