// Settings of voxel cone tracing (gi/vct/vct.h describes the technique).
#pragma once

#include "gi/preset/settings.h"

namespace gi {

// How the voxel grid covers the scene.
enum class VCTMode { Dense, Cascaded, Clipmap };
template <>
struct EnumNames<VCTMode> {
    static constexpr std::array<std::pair<VCTMode, const char*>, 3> values{
        {{VCTMode::Dense, "dense"}, {VCTMode::Cascaded, "cascaded"}, {VCTMode::Clipmap, "clipmap"}}};
};

// Which diffuse cones are traced (gi/vct/cone_set.h gives their directions and weights).
enum class ConeSetKind { Six, Nine, Custom };
template <>
struct EnumNames<ConeSetKind> {
    static constexpr std::array<std::pair<ConeSetKind, const char*>, 3> values{
        {{ConeSetKind::Six, "six"}, {ConeSetKind::Nine, "nine"}, {ConeSetKind::Custom, "custom"}}};
};

// How the diffuse cones' results are weighted before they are normalised to sum to one.
enum class ConeWeighting { Cosine, Equal };
template <>
struct EnumNames<ConeWeighting> {
    static constexpr std::array<std::pair<ConeWeighting, const char*>, 2> values{
        {{ConeWeighting::Cosine, "cosine"}, {ConeWeighting::Equal, "equal"}}};
};

struct VCTSettings {
    static constexpr std::string_view kSection = "vct";
    // The pass these settings drive, registered by the section list (gi/preset/settings.h).
    static constexpr PassRole kRole = PassRole::Technique;
    // Cones that leave the grid, or end unoccluded, read the environment (FrameContext::sky).
    static constexpr bool kGathersSky = true;
    static std::unique_ptr<Pass> createPass();
    static size_t estimateBytes(const FrameSettings& fs);
    int gridResolution = 64;          // voxels per side of the grid (of every level in cascaded and clipmap modes)
    VCTMode mode = VCTMode::Dense;    // dense: one grid over the scene; cascaded and clipmap: nested levels around the camera
    int levelCount = 3;               // cascaded and clipmap: nested levels, each twice the extent of the previous
    float levelExtent = 0.0f;         // cascaded and clipmap: world size of the finest level; 0 fits the scene
    ConeSetKind coneSet = ConeSetKind::Nine;        // six (seed 003), nine (seed 000) or custom
    int coneCount = 16;               // custom set: number of diffuse cones
    float coneAperture = 60.0f;       // full aperture of every diffuse cone, degrees
    ConeWeighting coneWeighting = ConeWeighting::Cosine;  // cone weights before normalisation
    float nudge = 3.0f;               // start offset in voxel diagonals over n.w (seed 000 eq. 3.4)
    float stepMultiplier = 1.0f;      // step = multiplier * cone diameter; below 1 oversamples
    float maxDistance = 0.0f;         // cone length in world units; 0 = the grid's diagonal
    // 1: direct light in the voxels; 2 or 3 re-inject traced indirect light. Against the reference
    // (8 bounces) one bounce left the light of a closed room far short (the nine Cornell box files'
    // SSIM 0.52-0.81 at 1, 0.55-0.85 at 2; the default preset 0.749 -> 0.812, Sponza 0.793 ->
    // 0.808). 3 by default since voxels stopped showing their back's light to their front
    // (inject.comp, backWeight): 2 had been the default because 3 over-brightened Sponza and the
    // lamp-lit box, but part of that light came from backs no cone could see (the lamp's own voxels
    // lit from behind by the lamp; a sunlit roof's underside in a room below it). At 128x96 against
    // the reference, two bounces before that change -> three after it: default 0.868 -> 0.877,
    // vct_cornell_lamp 0.872 -> 0.913, CornellBox-Empty-White 0.763 -> 0.798, vct_sponza 0.820 ->
    // 0.824, a room lit by the sun through a window 0.646 -> 0.662 (thick walls 0.361 -> 0.460),
    // a corridor 0.459 -> 0.478, two rooms joined by a doorway 0.626 -> 0.608. A bounce costs one
    // cone trace per lit voxel when the light changes, on the voxel's back only where it has one,
    // and nothing in the editor's steady state.
    int bounceCount = 3;
    // The last bounce also stands for the bounces after it (bounce.comp): its gathered light is
    // divided by 1 - albedo x the cones' opacity, the sum of the bounces a surface enclosed by
    // surfaces like itself would still receive. No effect with one bounce. Off by default: it
    // breaks issue 13's shift invariance (VCTGL.IndirectLightDoesNotDependOnWhereTheSceneFallsInTheGrid:
    // +6.4 / +3.9 / +5.7 %, bound 5 %; +4.6 / +2.8 / +4.8 % without it, and a floor of 0.4
    // instead of kVCTTailMinRemainder 0.2 still gives +6.2 %), since it multiplies the second
    // bounce, whose light varies most with the alignment; and it multiplies the two-room leak
    // (35 -> 44 %). On scenes it was not tuned on it is better (128x96, no preset, SSIM): a
    // corridor lit from its far end 0.517 -> 0.632, a room lit by an emissive panel 0.825 ->
    // 0.879, a room lit by a point light 0.874 -> 0.889, CornellBox-Empty-White 0.752 -> 0.845,
    // Sphere 0.778 -> 0.797, Original 0.878 -> 0.882, an open street 0.926 -> 0.923; presets:
    // vct_cornell 0.868 -> 0.883, cascaded and clipmap 0.819 -> 0.854 and 0.820 -> 0.856, vct_basic
    // within 0.001, vct_sponza 0.809 -> 0.800 (Sponza is open and already 1.10x too bright), and
    // vct_cornell_original with two bounces and the tail 0.874 (0.876 with its three bounces).
    // With face sides it brings their bounces to the reference's brightness (vct_cornell 0.829 -> 0.855).
    // Measured again once voxels stopped showing their back's light (two bounces and the tail
    // against the three bounces of the defaults, 128x96): default 0.890 / 0.877,
    // CornellBox-Empty-White 0.857 / 0.798, the corridor 0.501 / 0.478, but a room lit by the sun
    // through a window 0.602 / 0.662 (1.54x the reference's brightness), vct_cornell_lamp 0.868 /
    // 0.913, and the shift test +6.7 % / +4.2 %, so it stays off.
    bool bounceTail = false;
    bool anisotropic = true;          // six directional mip volumes instead of one (isotropic voxels only)
    bool sh = false;                  // store voxel radiance as 2-band SH per colour (direction-dependent)
    // Anisotropic voxels keep each face of a surface on its own side (gi/vct/vct.h, "Face
    // sides"): a thin wall no longer shows its lit face to the room behind it. Off by default:
    // with bounceTail (and two bounces) the two-room leak falls from 60 % to 4.8 % where the test
    // scene's wall falls, and to 8-26 % at the alignments VCTGL.FaceSidesCutTheLeakWhereverTheWallFalls
    // tries (57-68 % without), but the Cornell presets and boxes lose 0.003-0.018 SSIM and Sponza
    // 0.008, and a cone sample makes 7 texture calls instead of 3 (the trace 1.75x the time).
    // Where it matters most: a room lit by the sun through a window, whose sunlit roof and outer
    // walls the anisotropic mips show to the cones inside. A slab averages the layers that a cone
    // marching along its axis passes edge-on, so a roof's sunlit top reaches a cone rising at 45
    // degrees through the ceiling at any resolution: the one-bounce indirect light of such a room
    // with 0.6 m walls is 9.5x the reference's at 64^3 and 10x at 128^3, 1.2x with face sides.
    // With face sides and the tail it scores 0.821 against the defaults' 0.662 (0.796 against 0.460
    // with the thick walls), but the two-room doorway scene 0.515 against 0.608 and the Cornell
    // presets about 0.03 less.
    // Face sides, the tail and three bounces against the defaults (128x96, no preset, SSIM /
    // brightness against the reference, after face sides stopped showing back sides' light,
    // inject.comp): the sunlit room 0.795 / 1.14 against 0.644 / 1.47, with thick walls 0.751 /
    // 1.45 against 0.418 / 2.66, the corridor 0.549 against 0.485, the doorway scene 0.603 against
    // 0.584, an open courtyard in the sun 0.915 against 0.872; CornellBox-Original 0.889 against
    // 0.894, Empty-White 0.789 / 0.88 against 0.798 / 0.62, Empty-CO 0.868 against 0.893, Empty-RG
    // 0.887 against 0.900, Squashed, Glossy, Sphere, Mirror and Water within 0.006, vct_cornell
    // 0.857 against 0.877, vct_basic 0.960 against 0.964, vct_sponza 0.822 against 0.824 (mean of
    // these 17: 0.815 against 0.783; technique none 0.707; the corridor, Cornell files, basic and
    // Sponza measured before that change, which moved the others by at most 0.005). It stays off: issue
    // 13's shift invariance (VCTGL.IndirectLightDoesNotDependOnWhereTheSceneFallsInTheGrid, bound
    // 5 %) gives +3.5 / +6.2 / +5.3 % since the centroids lie at the surfaces (resolve.comp;
    // +2.9 / +8.2 / +5.6 % before), +1.4 / +4.4 / +3.8 % at one bounce; the defaults give
    // -0.0 / +4.7 / +3.9 % at one bounce and +1.8 / +4.2 / +2.6 % at three. The bounced energy
    // in the voxels varies less with the shift than the defaults' (+3.6 against +4.4 %), so the
    // excess is the screen trace's sampling of it. Passing it cost quality each time (the 17
    // scenes' mean against 1024-spp references, where the defaults score 0.756 and face sides
    // with the tail 0.781): nudge 4 (+3.1 %; 0.741), a footprint lod of 1.0 for face sides
    // (+3.7 %; 0.758, two-room leak 5.3 %), stepMultiplier 0.75 (+4.7 %, a third more samples);
    // kVCTSideMargin 0 or 0.15 did not bring it under 5 %),
    // and the trace's 7 texture calls per sample against 3 (vct_cornell at 1280x720, trace 430 ->
    // 790 ms, steady frame 540 -> 900 ms on llvmpipe). The two-room leak with them: 5.7 %.
    bool faceSides = false;
    bool specularCone = true;         // trace one cone along the reflection, aperture from roughness
    float specularApertureMin = 1.0f;   // specular cone aperture at roughness 0, degrees
    float specularApertureMax = 80.0f;  // specular cone aperture at roughness 1, degrees
    bool vao = false;                 // voxel ambient occlusion from the diffuse cones' alpha
    float vaoStrength = 1.0f;         // 0: no effect, 1: indirect light times the cones' visibility
    float vaoDistance = 0.0f;         // occluders farther than this do not occlude; 0 = maxDistance
    float intensity = 1.0f;           // scale of the indirect light
    bool revoxelizeEveryFrame = false;  // voxelize every frame (dynamic geometry) instead of when the grid moves
    float traceScale = 0.5f;          // cones are traced per pixel of an image this much smaller per side, then upsampled

    template <class V>
    void visit(V&& v) {
        v(gridResolution, {"gridResolution", "Voxels per side of the grid (of each level)", "voxels", 32, 256, Cost::Reallocate, 1});
        v(mode, {"mode", "dense: one grid over the scene; cascaded: nested grids snapped to res/8 cells; clipmap: nested grids with toroidal updates", "", 0, 0, Cost::Reallocate | Cost::Recompile});
        v(levelCount, forDevelopers({"levelCount", "Nested levels in cascaded and clipmap modes", "", 1, 6, Cost::Reallocate | Cost::Recompile}));
        v(levelExtent, forDevelopers({"levelExtent", "World size of the finest level (0: fit the scene)", "m", 0, 1e5}));
        v(coneSet, {"coneSet", "Diffuse cones: six (seed 003), nine (seed 000) or custom (coneCount on the hemisphere)"});
        v(coneCount, forDevelopers({"coneCount", "Diffuse cones of the custom set", "", 1, 32}));
        v(coneAperture, forDevelopers({"coneAperture", "Full aperture of each diffuse cone", "deg", 5, 120}));
        v(coneWeighting, forDevelopers({"coneWeighting", "Diffuse cone weights: cosine of the angle to the normal, or equal"}));
        v(nudge, forDevelopers({"nudge", "Cone start offset in voxel diagonals, divided by n.w (seed 000 eq. 3.4)", "voxels", 0, 8}));
        v(stepMultiplier, forDevelopers({"stepMultiplier", "Step length in cone diameters", "", 0.1, 4}));
        v(maxDistance, {"maxDistance", "Cone length (0: the grid's diagonal)", "m", 0, 1e5});
        v(bounceCount, {"bounceCount", "Light bounces stored in the voxels (2 or 3 re-inject traced light)", "", 1, 3});
        v(bounceTail, {"bounceTail", "The last bounce also adds the bounces after it (1 / (1 - albedo x enclosure))", ""});
        v(anisotropic, forDevelopers({"anisotropic", "Six directional mip volumes (seed 003); isotropic voxels only", "", 0, 0, Cost::Reallocate | Cost::Recompile}));
        v(faceSides, forDevelopers({"faceSides", "Anisotropic voxels keep each face's light on its own side (no leaks through thin walls)", "", 0, 0, Cost::Reallocate | Cost::Recompile}));
        v(sh, forDevelopers({"sh", "Voxel radiance as 2-band SH per colour (seed 000's VCT SH)", "", 0, 0, Cost::Reallocate | Cost::Recompile}));
        v(specularCone, {"specularCone", "Trace a specular cone along the reflection", ""});
        v(specularApertureMin, forDevelopers({"specularApertureMin", "Specular cone aperture at roughness 0", "deg", 0.5, 120}));
        v(specularApertureMax, forDevelopers({"specularApertureMax", "Specular cone aperture at roughness 1", "deg", 0.5, 120}));
        v(vao, {"vao", "Voxel ambient occlusion from the diffuse cones", ""});
        v(vaoStrength, {"vaoStrength", "Strength of the voxel ambient occlusion", "", 0, 1});
        v(vaoDistance, forDevelopers({"vaoDistance", "Occlusion range of the VAO (0: maxDistance)", "m", 0, 1e5}));
        v(intensity, {"intensity", "Scale of the indirect light", "", 0, 100});
        v(revoxelizeEveryFrame, forDevelopers({"revoxelizeEveryFrame", "Voxelize every frame (dynamic geometry, benchmarks) instead of only when the grid moves", ""}));
        // Uniform: the trace targets follow the image size, which the pass checks every frame.
        v(traceScale, forDevelopers({"traceScale", "Resolution scale of the cone trace (depth- and normal-aware upsampling below 1)", "", 0.125, 1,
                       Cost::Uniform, 0.125}));
    }
};

}  // namespace gi
