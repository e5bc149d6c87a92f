// Settings of the frame pipeline (shadows, direct light, the constant indirect term) and of
// tone mapping.
#pragma once

#include "gi/lpv/lpv_settings.h"
#include "gi/preset/settings.h"
#include "gi/util/budget.h"
#include "gi/scene/scene_settings.h"
#include "gi/ssao/ssao_settings.h"
#include "gi/vct/vct_settings.h"
#include "gi/volumetric/volumetric_settings.h"
#include "gi/envmap/envmap_settings.h"

#include <vector>

#include <glm/vec3.hpp>

namespace gi {

struct RenderSettings {
    static constexpr std::string_view kSection = "render";
    int shadowMapSize = 1024;                 // texels per side of each shadow map (cube face for point lights)
    float pcfRadius = 1.5f;                   // PCF filter radius in shadow-map texels; 0 = one hard tap
    float shadowBias = 1.5f;                  // depth bias in shadow-map texels, scaled by the slope
    bool specular = true;                     // add the GGX specular lobe to direct light
    glm::vec3 ambient{0.03f, 0.03f, 0.03f};   // uniform incident radiance used as the indirect term when technique is none
    float memoryBudgetMB = float(kDefaultMemoryBudgetMB);  // refuse settings whose GPU allocations would exceed this
    float timeBudgetSeconds = 600.0f;         // refuse work (environment prefilter, reference) estimated to take longer, s

    template <class V>
    void visit(V&& v) {
        v(shadowMapSize, {"shadowMapSize", "Shadow map resolution per side", "px", 64, 8192, Cost::Reallocate, 64});
        v(pcfRadius, {"pcfRadius", "Percentage-closer filter radius", "texels", 0, 8});
        v(shadowBias, {"shadowBias", "Slope-scaled depth bias", "texels", 0, 16});
        v(specular, {"specular", "Add GGX specular to direct light", ""});
        v(ambient, {"ambient", "Uniform incident radiance standing in for indirect light when technique is none", "", 0, 100});
        v(memoryBudgetMB, {"memoryBudgetMB", "GPU memory budget; larger settings are refused", "MiB", 16, 1 << 20});
        v(timeBudgetSeconds, {"timeBudgetSeconds", "Refuse work estimated to take longer than this", "s", 1, 1e6});
    }

    size_t memoryBudgetBytes() const { return size_t(double(memoryBudgetMB) * 1024.0 * 1024.0); }
};

enum class ToneMapper { Linear, Reinhard, ACES };
template <>
struct EnumNames<ToneMapper> {
    static constexpr std::array<std::pair<ToneMapper, const char*>, 3> values{
        {{ToneMapper::Linear, "linear"}, {ToneMapper::Reinhard, "reinhard"}, {ToneMapper::ACES, "aces"}}};
};

struct ToneMapSettings {
    static constexpr std::string_view kSection = "toneMap";
    float exposure = 0.0f;                 // exposure compensation in stops (EV), scale = 2^exposure
    ToneMapper op = ToneMapper::ACES;      // tone curve applied before sRGB encoding

    template <class V>
    void visit(V&& v) {
        v(exposure, {"exposure", "Exposure compensation", "EV", -20, 20, Cost::Uniform, 0.05});
        v(op, {"op", "Tone curve: linear (clamp), reinhard or aces (Narkowicz fit)"});
    }
};

}  // namespace gi

namespace gi {

// The technique that fills the indirect term. Each names its settings section in the preset.
enum class TechniqueKind { None, LPV, VCT };
template <>
struct EnumNames<TechniqueKind> {
    static constexpr std::array<std::pair<TechniqueKind, const char*>, 3> values{
        {{TechniqueKind::None, "none"}, {TechniqueKind::LPV, "lpv"}, {TechniqueKind::VCT, "vct"}}};
};

// Everything one frame needs besides the scene: the preset resolved against the scene.
struct FrameSettings {
    CameraSettings camera;
    std::vector<LightSettings> lights;
    RenderSettings render;
    ToneMapSettings toneMap;
    TechniqueKind technique = TechniqueKind::None;
    LPVSettings lpv;
    VCTSettings vct;
    SSAOSettings ssao;
    VolumetricSettings volumetric;
    EnvironmentSettings environment;
    int width = 640;
    int height = 360;
};

}  // namespace gi
