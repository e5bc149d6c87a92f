// Settings of screen-space ambient occlusion (seed 000, Sec 3.5.1, after Chapman 2011). Every
// field is a uniform: SSAO::execute() regenerates the kernel when sampleCount changes and
// allocates its targets on first use, so no change needs a rebuild.
//
// Lengths are in units of the scene's size: radius and bias are fractions of the diagonal of the
// scene's bounds, so one preset gives the same AO whether a glTF is in metres or centimetres
// (and a glTF rendered without a preset gets an AO fitted to its size). The defaults are the
// former 0.5 m and 0.025 m in the built-in Cornell box, whose diagonal is sqrt(12) = 3.46 m.
// Presets before schemaVersion 2 gave both in metres (gi/preset/preset.cpp refuses them there).
#pragma once

#include "gi/preset/settings.h"

namespace gi {

struct SSAOSettings {
    static constexpr std::string_view kSection = "ssao";
    // The pass these settings drive, registered by the section list (gi/preset/settings.h).
    static constexpr PassRole kRole = PassRole::Effect;
    static std::unique_ptr<Pass> createPass();
    static size_t estimateBytes(const FrameSettings& fs);
    bool enabled = false;    // multiply the indirect term by ambient occlusion
    float radius = 0.1443f;  // hemisphere radius, fraction of the scene bounds' diagonal (0.001..1)
    int sampleCount = 16;    // kernel samples per pixel (4..64)
    float bias = 0.00722f;   // depth a sample must lie behind the stored surface to count, fraction of the diagonal (0..0.1)
    float strength = 1.0f;   // AO = pow(visibility, strength); 0 turns AO off (0..4)
    int blurRadius = 2;      // box blur half-width in pixels; 2 covers the 4x4 noise tile exactly (0..4)

    template <class V>
    void visit(V&& v) {
        v(enabled, {"enabled", "Multiply the indirect term by screen-space ambient occlusion", ""});
        v(radius, {"radius", "Radius of the sampling hemisphere (0.144 is 0.5 m in the built-in Cornell box)",
                   "fraction of the scene bounds' diagonal", 0.001, 1, Cost::Uniform, 0.001});
        v(sampleCount, forDevelopers({"sampleCount", "Kernel samples per pixel", "", 4, 64}));
        v(bias, forDevelopers({"bias", "Depth a sample must lie behind the stored surface to count as occluded",
                 "fraction of the scene bounds' diagonal", 0, 0.1, Cost::Uniform, 0.0001}));
        v(strength, {"strength", "Exponent applied to the visibility (0 turns AO off)", "", 0, 4, Cost::Uniform, 0.01});
        v(blurRadius, forDevelopers({"blurRadius", "Box blur half-width; the window is 2*blurRadius pixels wide (0 = no blur)", "px", 0, 4}));
    }
};

}  // namespace gi
