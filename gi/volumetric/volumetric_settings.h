// Settings of volumetric lighting (seed 004 chapter 1): single scattering of the lights in a
// homogeneous medium that fills the scene's bounding box, ray marched per pixel.
#pragma once

#include "gi/preset/settings.h"

namespace gi {

// Phase functions of seed 004 (eqs. 2.2 to 2.6), plus isotropic. gi/volumetric/phase.h
// evaluates them; shaders/volumetric/phase.glsl mirrors it.
enum class PhaseFunction { Isotropic, HenyeyGreenstein, Schlick, Rayleigh, MieHazy, MieMurky };
template <>
struct EnumNames<PhaseFunction> {
    static constexpr std::array<std::pair<PhaseFunction, const char*>, 6> values{
        {{PhaseFunction::Isotropic, "isotropic"},
         {PhaseFunction::HenyeyGreenstein, "henyeyGreenstein"},
         {PhaseFunction::Schlick, "schlick"},
         {PhaseFunction::Rayleigh, "rayleigh"},
         {PhaseFunction::MieHazy, "mieHazy"},
         {PhaseFunction::MieMurky, "mieMurky"}}};
};

// How light fades through the medium: the seed's optical thickness l (eq. 3.1: e^{-x/l} along
// the light's and the viewer's legs, so l is a mean free path), or the extinction coefficient
// sigma_t = density + absorption.
enum class VolumeAttenuation { OpticalThickness, Coefficients };
template <>
struct EnumNames<VolumeAttenuation> {
    static constexpr std::array<std::pair<VolumeAttenuation, const char*>, 2> values{
        {{VolumeAttenuation::OpticalThickness, "opticalThickness"}, {VolumeAttenuation::Coefficients, "coefficients"}}};
};

// The blur of the marched buffer: none, the seed's 5x5 Gaussian (Alg. 3), or the same kernel
// weighted by depth similarity so it does not bleed across depth edges (the seed's future work).
enum class VolumeBlur { None, Gaussian, DepthAware };
template <>
struct EnumNames<VolumeBlur> {
    static constexpr std::array<std::pair<VolumeBlur, const char*>, 3> values{
        {{VolumeBlur::None, "none"}, {VolumeBlur::Gaussian, "gaussian"}, {VolumeBlur::DepthAware, "depthAware"}}};
};

struct VolumetricSettings {
    static constexpr std::string_view kSection = "volumetric";
    // The pass these settings drive, registered by the section list (gi/preset/settings.h).
    static constexpr PassRole kRole = PassRole::Effect;
    static std::unique_ptr<Pass> createPass();
    static size_t estimateBytes(const FrameSettings& fs);
    bool enabled = false;                  // add in-scattered light (and fade the scene by the medium)
    float density = 0.1f;                  // scattering coefficient sigma_s, 1/m; 0 adds nothing
    VolumeAttenuation attenuation = VolumeAttenuation::Coefficients;
    float absorption = 0.0f;               // sigma_a, 1/m (coefficients): extinction = density + absorption
    float opticalThickness = 18.76f;       // l, m (opticalThickness): transmittance e^{-x/l} (seed 004's preset value)
    PhaseFunction phase = PhaseFunction::HenyeyGreenstein;
    float g = 0.3f;                        // asymmetry of Henyey-Greenstein (> 0 scatters forward)
    bool schlickFromG = true;              // Schlick's k = 1.55 g - 0.55 g^3 (Blasi et al.), else schlickK
    float schlickK = 0.3f;                 // Schlick's k when schlickFromG is off (> 0 forward, as g)
    int samples = 64;                      // march samples per pixel along the lit part of the ray
    float resolutionScale = 0.5f;          // march buffer size relative to the image
    bool jitter = true;                    // offset each pixel's samples by a per-pixel hash (fixed, so renders repeat)
    bool pcf = true;                       // filter the shadow test (3x3 hardware-compared taps), else one tap
    VolumeBlur blur = VolumeBlur::DepthAware;
    bool attenuateScene = true;            // fade the lit scene by the viewer leg's transmittance
    float intensity = 1.0f;                // scale of the in-scattered light (1 = physically based)

    template <class V>
    void visit(V&& v) {
        v(enabled, {"enabled", "Add volumetric lighting: single scattering of the lights in a medium filling the scene's bounds", ""});
        v(density, {"density", "Scattering coefficient sigma_s of the medium (0 adds nothing)", "1/m", 0, 100, Cost::Uniform, 0.005});
        v(attenuation, forDevelopers({"attenuation", "Transmittance from the seed's optical thickness (e^-x/l) or from the extinction coefficient"}));
        v(absorption, {"absorption", "Absorption coefficient sigma_a; extinction = density + absorption (coefficients)", "1/m", 0, 100,
                       Cost::Uniform, 0.005});
        v(opticalThickness, forDevelopers({"opticalThickness", "Mean free path l of the seed's attenuation e^-x/l (opticalThickness)", "m", 0.01,
                             1e5, Cost::Uniform, 0.1}));
        v(phase, {"phase", "Phase function: isotropic, henyeyGreenstein, schlick, rayleigh, mieHazy or mieMurky"});
        v(g, {"g", "Henyey-Greenstein asymmetry (and Schlick's through k = 1.55g - 0.55g^3); > 0 forward", "", -0.99, 0.99,
              Cost::Uniform, 0.01});
        v(schlickFromG, forDevelopers({"schlickFromG", "Derive Schlick's k from g", ""}));
        v(schlickK, forDevelopers({"schlickK", "Schlick's k when not derived from g; > 0 forward", "", -0.99, 0.99, Cost::Uniform, 0.01}));
        v(samples, forDevelopers({"samples", "March samples per pixel along the lit part of the view ray", "", 1, 1000, Cost::Uniform}));
        v(resolutionScale, forDevelopers({"resolutionScale", "Size of the march buffer relative to the image", "", 0.125, 1, Cost::Reallocate, 0.005}));
        v(jitter, forDevelopers({"jitter", "Offset each pixel's samples by a fixed per-pixel hash (trades banding for noise)", ""}));
        v(pcf, forDevelopers({"pcf", "Filter the shadow test over 3x3 compared taps", ""}));
        v(blur, forDevelopers({"blur", "Blur of the march buffer: none, gaussian (5x5) or depthAware"}));
        v(attenuateScene, forDevelopers({"attenuateScene", "Fade the lit scene by the transmittance to the viewer", ""}));
        v(intensity, {"intensity", "Scale of the in-scattered light (1 = physically based)", "", 0, 100, Cost::Uniform, 0.01});
    }
};

}  // namespace gi
