// Settings of environment lighting (seed 004 chapter 2): a distant environment map, prefiltered
// into a roughness mip chain that materials sample by roughness, drawn as the sky.
#pragma once

#include "gi/preset/settings.h"

#include <vector>

namespace gi {

// How a mip's texels gather the environment: GGX importance sampling of the microfacet
// distribution (what engines use, and the path tracer's BRDF), or the seed's Beckmann cone
// sampling (uniform disk of radius tan(theta) around the texel direction, Alg. 6).
enum class PrefilterDistribution { GGX, BeckmannCone };
template <>
struct EnumNames<PrefilterDistribution> {
    static constexpr std::array<std::pair<PrefilterDistribution, const char*>, 2> values{
        {{PrefilterDistribution::GGX, "ggx"}, {PrefilterDistribution::BeckmannCone, "beckmannCone"}}};
};

struct EnvironmentSettings {
    static constexpr std::string_view kSection = "environment";
    // The pass these settings drive, registered by the section list (gi/preset/settings.h).
    static constexpr PassRole kRole = PassRole::Effect;
    static std::unique_ptr<Pass> createPass();
    static size_t estimateBytes(const FrameSettings& fs);
    static void checkTime(const FrameSettings& fs);
    static std::string notes(const FrameSettings& fs);
    bool enabled = false;          // light the scene from the environment map and draw it as the sky
    // An equirectangular (latlong) .hdr/.exr/.png, a six-face cube map as a pattern with "{face}"
    // (replaced by px nx py ny pz nz), or a built-in: "builtin:sky" (a gradient sky with a sun) or
    // "builtin:constant" (uniform radiance 1). Found through the asset search path.
    std::string file = "builtin:sky";
    float intensity = 1.0f;        // radiance scale
    float rotation = 0.0f;         // turns the map about +y, degrees
    int cubeSize = 256;            // texels per cube face at mip 0
    int samples = 64;              // prefilter samples per texel
    PrefilterDistribution distribution = PrefilterDistribution::GGX;
    // Perceptual roughness of each mip (mip 0 first); the chain has as many mips as entries (at
    // most log2(cubeSize) + 1). The default is the seed's 11 levels (Fig. 3.24).
    std::vector<float> mipRoughness{0.0f, 0.01f, 0.05f, 0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f, 1.0f};
    bool skybox = true;            // draw the environment where no surface is

    template <class V>
    void visit(V&& v) {
        v(enabled, {"enabled", "Light the scene from an environment map and draw it as the sky", "", 0, 0, Cost::Reallocate});
        v(file, {"file", "Equirectangular HDR/EXR, a cube map pattern with {face}, or builtin:sky / builtin:constant", "", 0, 0,
                 Cost::Reallocate});
        v(intensity, {"intensity", "Scale of the environment's radiance", "", 0, 1e4, Cost::Uniform, 0.01});
        v(rotation, {"rotation", "Rotation of the map about +y", "deg", -360, 360, Cost::Uniform, 1});
        v(cubeSize, forDevelopers({"cubeSize", "Texels per cube face at mip 0", "px", 16, 2048, Cost::Reallocate}));
        v(samples, forDevelopers({"samples", "Prefilter samples per texel", "", 1, 4096, Cost::Reallocate}));
        v(distribution, forDevelopers({"distribution", "Prefilter lobe: ggx (importance sampled) or beckmannCone (the seed's cone sampling)", "", 0,
                         0, Cost::Reallocate}));
        v(mipRoughness, forDevelopers({"mipRoughness", "Perceptual roughness of each mip, mip 0 first (one mip per entry)", "", 0, 1,
                         Cost::Reallocate, 0.005}));
        v(skybox, {"skybox", "Draw the environment where no surface is", ""});
    }
};

}  // namespace gi
