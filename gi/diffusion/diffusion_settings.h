// Settings of volume-based diffuse GI by occupancy-aware SH diffusion (gi/diffusion/diffusion.h
// describes the technique).
#pragma once

#include "gi/preset/settings.h"

namespace gi {

// The albedo a cell reflects the light that reaches it with.
enum class DiffusionAlbedo { Voxel, Half };
template <>
struct EnumNames<DiffusionAlbedo> {
    static constexpr std::array<std::pair<DiffusionAlbedo, const char*>, 2> values{
        {{DiffusionAlbedo::Voxel, "voxel"}, {DiffusionAlbedo::Half, "half"}}};
};

// How the scene becomes cells: VCT's one-draw voxelizer (each triangle along its dominant axis,
// grown for conservative rasterization), or seed 001's slicing along the three axes, merged.
enum class DiffusionVoxelization { Conservative, Slicing };
template <>
struct EnumNames<DiffusionVoxelization> {
    static constexpr std::array<std::pair<DiffusionVoxelization, const char*>, 2> values{
        {{DiffusionVoxelization::Conservative, "conservative"}, {DiffusionVoxelization::Slicing, "slicing"}}};
};

struct DiffusionSettings {
    static constexpr std::string_view kSection = "diffusion";
    static constexpr PassRole kRole = PassRole::Technique;
    static std::unique_ptr<Pass> createPass();
    static size_t estimateBytes(const FrameSettings& fs);
    // Refuses a frame whose propagation is estimated past render.timeBudgetSeconds.
    static void checkTime(const FrameSettings& fs);
    int gridResolution = 32;       // cells per side of the grid, which holds the scene's bounding cube
    // Propagation steps; light moves at most one cell per step and bounces where it meets a
    // surface. Seed 001 gives 64 for rooms at 32^3, but the light here diffuses rather than
    // travels straight, so 64 steps leave a closed room short of light: the closed Cornell box of
    // DiffusionGL.MoreIterationsCarryMoreBouncesTowardsTheReference holds 0.71 of the path
    // tracer's mean indirect light at 64, 0.96 at 128 and 1.09 at 256 (closing note of stop 37).
    int iterations = 128;
    int iterationsPerFrame = 0;    // steps a frame, the solve spread over frames and then held until a change; 0: all every frame
    DiffusionAlbedo bounceAlbedo = DiffusionAlbedo::Voxel;  // the voxel's own albedo, or seed 001's constant 0.5
    float intensity = 1.0f;        // scale of the indirect light
    float nudge = 0.0f;            // shading reads the grid this many cells along the pixel's normal (seed 001: none)
    DiffusionVoxelization voxelization = DiffusionVoxelization::Slicing;  // seed 001's; scores higher on unseen scenes (closing note)
    bool smoothing = true;         // shading reads each surface cell's light averaged over the surface's neighbouring cells (smooth.comp)

    template <class V>
    void visit(V&& v) {
        v(gridResolution, {"gridResolution", "Cells per side of the grid (the scene's bounding cube)", "cells", 8, 128, Cost::Reallocate, 1});
        v(iterations, {"iterations", "Propagation steps (light moves one cell per step; bounces happen on the way)", "", 0, 1024});
        v(iterationsPerFrame, {"iterationsPerFrame", "Steps a frame: the solve spreads over frames, then holds until a light, setting or the scene changes (0: all every frame)", "", 0, 1024});
        v(bounceAlbedo, {"bounceAlbedo", "Albedo of the light a surface reflects: the voxel's own (voxel) or seed 001's 0.5 (half)"});
        v(intensity, {"intensity", "Scale of the indirect light", "", 0, 100});
        v(nudge, {"nudge", "Shading reads the grid this far along the pixel's normal (seed 001 has none)", "cells", 0, 2});
        v(smoothing, forDevelopers({"smoothing", "Shading reads each surface cell's light averaged with its neighbours on the same surface, so tilted faces show no voxel stripes", ""}));
        v(voxelization, {"voxelization", "conservative: one draw, each triangle along its dominant axis, grown; slicing: seed 001's three axes, merged", "", 0, 0, Cost::Reallocate});
    }
};

}  // namespace gi
