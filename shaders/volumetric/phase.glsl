// Phase functions of seed 004 and isotropic, p(cos theta) per steradian, theta between the
// light's direction of travel and the scattered direction. The GLSL twin of gi/volumetric/phase.h
// (see it for the seed's errors fixed here); the kPhase* values are EnumNames<PhaseFunction>'s order.
#include "common/shared.h"
const int kPhaseIsotropic = 0;
const int kPhaseHenyeyGreenstein = 1;
const int kPhaseSchlick = 2;
const int kPhaseRayleigh = 3;
const int kPhaseMieHazy = 4;
const int kPhaseMieMurky = 5;
const float kInv4Pi = 0.07957747154594767;

float phaseFunction(int f, float g, float k, float c) {
    if (f == kPhaseHenyeyGreenstein) {
        float d = 1.0 + g * g - 2.0 * g * c;
        return kInv4Pi * (1.0 - g * g) / (d * sqrt(d));
    }
    if (f == kPhaseSchlick) {
        float d = 1.0 - k * c;
        return kInv4Pi * (1.0 - k * k) / (d * d);
    }
    if (f == kPhaseRayleigh) return 3.0 / (16.0 * kPi) * (1.0 + c * c);
    if (f == kPhaseMieHazy) return kInv4Pi * (0.5 + 4.5 * pow(0.5 * (1.0 + c), 8.0));
    if (f == kPhaseMieMurky) return kInv4Pi * (0.5 + 16.5 * pow(0.5 * (1.0 + c), 32.0));
    return kInv4Pi;
}
