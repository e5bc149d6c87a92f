#include "gi/volumetric/phase.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gi {

namespace {
constexpr double kInv4Pi = 1.0 / (4.0 * std::numbers::pi);
}

// 1.55 g - 0.55 g^3 peaks at 1.0017 (g = 0.969): past |k| = 1 the lobe has a pole, so k is
// held within 0.99.
float schlickKFromG(float g) { return std::clamp(1.55f * g - 0.55f * g * g * g, -0.99f, 0.99f); }

PhaseParams phaseParams(const VolumetricSettings& s) {
    PhaseParams p;
    p.function = s.phase;
    p.g = s.g;
    p.k = s.schlickFromG ? schlickKFromG(s.g) : s.schlickK;
    return p;
}

double phase(const PhaseParams& p, double c) {
    switch (p.function) {
        case PhaseFunction::Isotropic: return kInv4Pi;
        case PhaseFunction::HenyeyGreenstein: {
            double g = p.g, d = 1.0 + g * g - 2.0 * g * c;
            return kInv4Pi * (1.0 - g * g) / (d * std::sqrt(d));
        }
        case PhaseFunction::Schlick: {
            double k = p.k, d = 1.0 - k * c;
            return kInv4Pi * (1.0 - k * k) / (d * d);
        }
        case PhaseFunction::Rayleigh: return 3.0 / (16.0 * std::numbers::pi) * (1.0 + c * c);
        case PhaseFunction::MieHazy: return kInv4Pi * (0.5 + 4.5 * std::pow(0.5 * (1.0 + c), 8.0));
        case PhaseFunction::MieMurky: return kInv4Pi * (0.5 + 16.5 * std::pow(0.5 * (1.0 + c), 32.0));
    }
    return kInv4Pi;
}

}  // namespace gi
