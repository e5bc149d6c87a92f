// Diffuse cone sets for voxel cone tracing, in tangent space (z along the surface normal).
//
// - six (seed 003, Yeung's set): one cone along the normal and five at 60 degrees from it,
//   72 degrees apart in azimuth (seed 003 writes them with y up: (0, 0.5, 0.866025) rotated
//   about y by k * 2 pi / 5).
// - nine (seed 000): one along the normal and eight towards "the top corners and the sides of
//   the box around the normal": the four top corners (+-1, +-1, 1)/sqrt(3), 54.7 degrees off the
//   normal, and the four side midpoints (+-1, 0, 1)/sqrt(2), (0, +-1, 1)/sqrt(2), 45 degrees off.
// - custom: `count` axes spread evenly over the hemisphere (a spherical Fibonacci lattice with
//   z = 1 - (i + 0.5) / count, golden-angle azimuths), so any count covers it without clumping.
//
// Weights: the seeds do not give them. A cone stands for the radiance over its part of the
// hemisphere, and irradiance weighs radiance by cos(theta); with cones of equal aperture the
// weight is cos(theta) of the axis ("cosine", the default; seed 003 names these weights).
// "equal" gives every cone the same weight. Either is normalised to sum to one, so a uniform
// radiance L gives E / pi = L exactly, and the traced sum is directly the indirect term E / pi.
#pragma once

#include "gi/vct/vct_settings.h"

#include <glm/glm.hpp>

#include <vector>

namespace gi {

inline constexpr int kMaxCones = 32;

struct Cone {
    glm::vec3 direction;  // unit, tangent space, z = normal
    float weight;         // normalised: the weights of a set sum to 1
};

struct ConeSet {
    std::vector<Cone> cones;
    float aperture = 0.0f;  // full aperture of every cone, radians
};

ConeSet makeConeSet(ConeSetKind kind, int customCount, float apertureDeg, ConeWeighting weighting);
inline ConeSet makeConeSet(const VCTSettings& s) {
    return makeConeSet(s.coneSet, s.coneCount, s.coneAperture, s.coneWeighting);
}

// The set's estimate of E / pi for incident radiance L(w) (tangent space), taking each cone's
// radiance as L along its axis: sum of weight * L(axis). Used by the tests.
template <class F>
double coneSetIrradianceOverPi(const ConeSet& set, F&& radiance) {
    double sum = 0.0;
    for (const Cone& c : set.cones) sum += double(c.weight) * radiance(c.direction);
    return sum;
}

// Fraction of the hemisphere's solid angle that lies inside at least one cone (Monte Carlo on a
// deterministic stratified set of `samples` directions).
double coneSetCoverage(const ConeSet& set, int samples = 65536);

}  // namespace gi
