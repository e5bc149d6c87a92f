// Settings of light propagation volumes (gi/lpv/lpv.h describes the technique).
#pragma once

#include "gi/preset/settings.h"

namespace gi {

// The fitted grid's rule (LPVSettings::fitGrid; lpv.h, "Fitted grid"), stated in fitGrid's
// description below: change them together.
constexpr int kLPVFitMinCells = 16;
constexpr float kLPVFitCellsPerGap = 6.0f;
constexpr int kLPVFitStep = 8;

struct LPVSettings {
    static constexpr std::string_view kSection = "lpv";
    // The pass these settings drive, registered by the section list (gi/preset/settings.h).
    static constexpr PassRole kRole = PassRole::Technique;
    // The environment lights the scene through the sky's visibility in the geometry volume (shade.comp).
    static constexpr bool kGathersSky = true;
    static std::unique_ptr<Pass> createPass();
    static size_t estimateBytes(const FrameSettings& fs);
    static std::string notes(const FrameSettings& fs);
    int gridResolution = 32;      // cells per side of every cascade (with fitGrid, the finest the fit may choose)
    // One scene-fitted grid (one cascade, cascadeExtent 0) takes as few cells as keep the mean
    // distance between the scene's surfaces kLPVFitCellsPerGap cells long, from kLPVFitMinCells
    // up to gridResolution in steps of kLPVFitStep (lpv.h, "Fitted grid"): a small closed room gets
    // 16^3, the two-room scene 24^3, Sponza 32^3.
    bool fitGrid = true;
    int cascadeCount = 1;         // nested grids, each twice the size of the previous
    float cascadeExtent = 0.0f;   // world size of the finest cascade; 0 fits the scene (see lpv.h)
    int propagationSteps = 32;    // gather iterations; light travels one cell per step, so about gridResolution
    int rsmResolution = 256;      // reflective shadow map texels per side, per light and cascade
    float nudge = 0.5f;           // VPLs move this many cells along their normal before injection
    bool occlusion = true;        // block propagation with the geometry volume
    float occlusionStrength = 1.0f;  // scale of the blocking potential
    float intensity = 1.0f;       // scale of the indirect light
    float damping = 0.5f;         // self-illumination damping, 0 (off) to 1
    int bounces = 2;              // diffuse bounces: 1 is KD09's single bounce; each more re-injects the propagated light at the geometry volume times its albedo

    template <class V>
    void visit(V&& v) {
        v(gridResolution, {"gridResolution", "Cells per side of each cascade", "cells", 4, 256, Cost::Reallocate, 1});
        // A developer setting, so auto-tune spends its renders on the grid, cascades and steps.
        v(fitGrid, forDevelopers({"fitGrid", "One grid over the scene: as coarse as 16 cells, in steps of 8, while the mean distance between surfaces spans 6 cells",
                                  "", 0, 0, Cost::Reallocate}));
        v(cascadeCount, {"cascadeCount", "Number of nested cascades, each doubling the extent", "", 1, 4, Cost::Reallocate});
        v(cascadeExtent, forDevelopers({"cascadeExtent", "World size of the finest cascade (0: fit the scene)", "m", 0, 1e5}));
        v(propagationSteps, {"propagationSteps", "Propagation iterations (light moves one cell per step)", "", 0, 512});
        v(rsmResolution, forDevelopers({"rsmResolution", "Reflective shadow map resolution per light and cascade", "px", 16, 4096,
                          Cost::Reallocate, 16}));
        v(nudge, forDevelopers({"nudge", "Move VPLs along their normal before injection", "cells", 0, 4}));
        v(occlusion, {"occlusion", "Block propagation with the geometry volume", ""});
        v(occlusionStrength, {"occlusionStrength", "Scale of the geometry volume's blocking", "", 0, 8});
        v(intensity, {"intensity", "Scale of the indirect light", "", 0, 100});
        v(damping, forDevelopers({"damping", "Self-illumination damping (0 off, 1 full)", "", 0, 1}));
        v(bounces, {"bounces", "Diffuse bounces (1: KD09; more re-inject the propagated light at the geometry volume)", "", 1, 4});
    }
};

}  // namespace gi
