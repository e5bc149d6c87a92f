// The participating medium of volumetric lighting, shared by the raster march
// (shaders/volumetric/march.comp mirrors these functions) and the path-traced reference so the
// two integrate the same thing:
//   - homogeneous, filling the scene's bounding box (vacuum outside, so a sun shaft enters
//     through the box's faces);
//   - scattering coefficient sigma_s = density, extinction sigma_t = density + absorption, or
//     1 / opticalThickness in the seed's mode (eq. 3.1);
//   - single scattering of the punctual lights along the camera ray only: in-scattered radiance
//     L = intensity * integral over the ray inside the box of T(eye, x) sigma_s p(theta) Li(x) dt,
//     where Li is the light's radiance at x with the raster's falloff (common/light.h: 1/d^2,
//     glTF range window, smoothstep spot cone), its shadow visibility, and T(light, x) over the
//     part of the light's path inside the box; the surface seen through the medium is faded by
//     T(eye, surface) when attenuateScene is on. Light reaching surfaces is not faded by the
//     medium (as the seed: its effect is a post-process), and there is no multiple scattering.
//   - In the seed's opticalThickness mode sigma_t = 1/l does not depend on the density, so a
//     density above 1/l scatters more than the medium removes (not energy conserving: the seed's
//     model, kept for comparison; the coefficients mode always has sigma_t >= sigma_s).
//   - A density of 0 makes the medium inactive in both modes: no in-scattering and no fade.
#pragma once

#include "gi/scene/scene.h"
#include "gi/scene/scene_settings.h"
#include "gi/volumetric/phase.h"

#include <glm/glm.hpp>

#include <cmath>

namespace gi {

struct Medium {
    bool active = false;  // enabled with density > 0 and a valid box
    Bounds box;
    float sigmaS = 0.0f, sigmaT = 0.0f;
    PhaseParams phase;
    float intensity = 1.0f;
    bool attenuateScene = true;

    float transmittance(float distance) const { return std::exp(-sigmaT * distance); }
};

Medium makeMedium(const VolumetricSettings& s, const Bounds& sceneBounds);

// The part [t0, t1] of the ray o + t d (t >= 0, t <= tMax) inside the box; false if none.
bool clipRayToBox(const Bounds& box, const glm::vec3& o, const glm::vec3& d, float tMax, float& t0, float& t1);

// Narrows [t0, t1] to where the light can reach: a spot's cone (outer half-angle, up to 90
// degrees: a convex cone, so one interval) and the range sphere of a point or spot light;
// directional lights reach everywhere. d is a unit vector. False when nothing is left.
bool clipRayToLight(const LightSettings& l, const glm::vec3& o, const glm::vec3& d, float& t0, float& t1);

// Distance a ray from x towards the light travels inside the box before reaching the light (or,
// for a directional light, before leaving the box).
float lightPathInBox(const Bounds& box, const LightSettings& l, const glm::vec3& x);

}  // namespace gi
