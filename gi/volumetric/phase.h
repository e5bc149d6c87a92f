// Phase functions of seed 004 (eqs. 2.2 to 2.6) and isotropic, as functions of the scattering
// angle theta between the light's direction of travel and the scattered direction (theta = 0:
// the light goes on straight). Each integrates to one over the sphere (tests check it).
// shaders/volumetric/phase.glsl is the GLSL twin; the reference and the editor's polar plot use
// these.
//
// Errors in the seed, fixed here:
//   - Schlick (eq. 2.3) is printed as (1 - k^2) / (4 pi (1 + k cos theta)^2), which with k > 0
//     scatters backwards while the seed's k = 1.55 g - 0.55 g^3 carries g's sign (g > 0 forward).
//     We use (1 - k cos theta)^2, Blasi et al.'s form, so k and g agree.
//   - The Mie murky function (eq. 2.6) is labelled P_HG in the seed; it is Nishita et al.'s
//     murky Mie approximation, (1 / 4 pi) (1/2 + 33/2 ((1 + cos theta) / 2)^32).
//   - k = 1.55 g - 0.55 g^3 exceeds 1 for g between 0.94 and 1 (the lobe then has a pole);
//     schlickKFromG holds k within 0.99.
#pragma once

#include "gi/volumetric/volumetric_settings.h"

namespace gi {

struct PhaseParams {
    PhaseFunction function = PhaseFunction::Isotropic;
    float g = 0.0f;  // Henyey-Greenstein asymmetry
    float k = 0.0f;  // Schlick's parameter
};

// The parameters the settings select (k from g unless schlickFromG is off).
PhaseParams phaseParams(const VolumetricSettings& s);
// Schlick's k that approximates Henyey-Greenstein's g (Blasi et al.; seed 004).
float schlickKFromG(float g);
// p(cos theta), per steradian.
double phase(const PhaseParams& p, double cosTheta);

}  // namespace gi
