// Settings of the frame pipeline (shadows, direct light, the constant indirect term) and of
// tone mapping.
#pragma once

#include "gi/lpv/lpv_settings.h"
#include "gi/preset/settings.h"
#include "gi/util/budget.h"
#include "gi/scene/scene_settings.h"
#include "gi/diffusion/diffusion_settings.h"
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
    bool keepStaticWork = true;               // keep shadow maps, RSMs and VCT's lit volumes while nothing they depend on changes
    bool cullClusters = true;                 // the G-buffer and shadow passes skip triangle clusters outside the view (same pixels)
    bool materialPrograms = true;             // one program per set of material textures (same pixels; material_programs.h)

    template <class V>
    void visit(V&& v) {
        v(shadowMapSize, {"shadowMapSize", "Shadow map resolution per side", "px", 64, 8192, Cost::Reallocate, 64});
        v(pcfRadius, {"pcfRadius", "Percentage-closer filter radius", "texels", 0, 8});
        v(shadowBias, forDevelopers({"shadowBias", "Slope-scaled depth bias", "texels", 0, 16}));
        v(specular, forDevelopers({"specular", "Add GGX specular to direct light", ""}));
        v(ambient, {"ambient", "Uniform incident radiance standing in for indirect light when technique is none", "", 0, 100});
        v(memoryBudgetMB, forDevelopers({"memoryBudgetMB", "GPU memory budget; larger settings are refused", "MiB", 16, 1 << 20}));
        v(timeBudgetSeconds, forDevelopers({"timeBudgetSeconds", "Refuse work estimated to take longer than this", "s", 1, 1e6}));
        v(keepStaticWork, forDevelopers({"keepStaticWork",
                                         "Keep shadow maps, LPV's RSMs and VCT's lit volumes between frames while the scene, the lights and the settings "
                                         "they depend on stay (off: redo them every frame, as for a dynamic scene; benchmarks compare both)",
                                         ""}));
        v(cullClusters, forDevelopers({"cullClusters",
                                       "The G-buffer and shadow passes leave out clusters of 256 triangles that lie wholly outside the camera's or the "
                                       "light's frustum (the pixels are the same; stats.json counts the triangles drawn)",
                                       ""}));
        v(materialPrograms, forDevelopers({"materialPrograms",
                                           "The G-buffer, LPV's RSMs and the voxelization of VCT and diffusion draw each material with a program built for the textures it has "
                                           "(off: one program that tests every texture slot at run time; the pixels are the same)",
                                           ""}));
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

// The settings sections of a frame, each once: the preset holds them, the frame copies them, the
// JSON, --set, --list-settings, the editor's panels and the generic settings test walk them. A
// section whose struct declares createPass() (gi/preset/settings.h) registers a pass: the
// renderer, the budget check and the previewers find the pass through this list
// (gi/render/pass.h, passRegistry()), in this order, which is also the order the passes run in
// each stage. Adding a technique is one line here (and its settings header above).
#define GI_FRAME_SECTIONS(X)        \
    X(RenderSettings, render)       \
    X(ToneMapSettings, toneMap)     \
    X(LPVSettings, lpv)             \
    X(VCTSettings, vct)             \
    X(DiffusionSettings, diffusion) \
    X(SSAOSettings, ssao)           \
    X(EnvironmentSettings, environment) \
    X(VolumetricSettings, volumetric)

struct FrameSections {
#define GI_SECTION_MEMBER(Type, name)                                                   \
    Type name;                                                                          \
    static_assert(Type::kSection == #name, "a section's member is named as its key");
    GI_FRAME_SECTIONS(GI_SECTION_MEMBER)
#undef GI_SECTION_MEMBER

    template <class F>
    void forEachSection(F&& f) {
#define GI_SECTION_CALL(Type, name) f(name);
        GI_FRAME_SECTIONS(GI_SECTION_CALL)
#undef GI_SECTION_CALL
    }
    template <class F>
    void forEachSection(F&& f) const {
        const_cast<FrameSections&>(*this).forEachSection([&](const auto& s) { f(s); });
    }
};

// The technique that fills the indirect term: "none" or the section name of a registered
// technique (a section whose kRole is PassRole::Technique). Choices come from the section list.
struct TechniqueChoice {
    static constexpr std::string_view kNone = "none";
    std::string name{kNone};
    static std::vector<std::string> choices();
    bool operator==(std::string_view n) const { return name == n; }
};

// Everything one frame needs besides the scene: the preset resolved against the scene.
struct FrameSettings : FrameSections {
    CameraSettings camera;
    std::vector<LightSettings> lights;
    std::string technique{TechniqueChoice::kNone};
    int width = 640;
    int height = 360;
};

}  // namespace gi
