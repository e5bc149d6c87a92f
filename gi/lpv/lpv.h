// Light propagation volumes (Kaplanyan and Dachsbacher 2009/2010, "KD09"), as seed 000 section 1
// implements them, with compute shaders throughout.
//
// Passes, per cascade (timer names in brackets):
//   1. RSMs [lpv.rsm]: per directional or spot light and cascade, a reflective shadow map storing
//      world position, normal and flux. Directional maps are fitted to the cascade box as the
//      seed does (the extent of the box's corners projected on the plane normal to the light); a
//      spot light uses its own frustum. A point light has a cube RSM: six 90-degree faces in GL's
//      cube order, each a map like the spot's, rendered once and injected into every cascade
//      (its faces depend on the light and the scene's bounds, not on the cascade box, so a cube
//      per cascade would draw the same texels again). lpvIgnoredLights() names any light kind
//      without an RSM, so gi-render and the editor say so (none today).
//   2. Injection [lpv.inject]: each RSM texel becomes a virtual point light, moved `nudge`
//      cells along its normal, added to its cell as intensity I(w) = flux / pi * max(n.w, 0)
//      projected on 2-band SH, one SH per colour channel.
//   3. Geometry volume [lpv.geometry]: blocking potential from RSM texels and (subsampled)
//      G-buffer pixels: each surfel adds (area / cell face area) * the SH of its clamped cosine
//      lobe, on a grid whose samples sit on the LPV cell corners (offset half a cell). Blocking is
//      one-sided (a surfel blocks light hitting its front) and the two sources often see opposite
//      sides of a thin wall, or the same surface: they stay in two volumes and each face takes
//      the larger of their blockings, so a thin wall blocks both ways and nothing counts twice.
//      Likewise the RSMs of several lights: each light's surfels are summed apart and merged
//      corner by corner, the larger coverage kept (geometry_merge.comp; summed, sixteen lights
//      over a room made it 2.9x too bright). Each surfel also adds its diffuse albedo (RSM: a fourth attachment; G-buffer: base colour
//      x (1 - metallic)) weighted by its coverage to an albedo volume on the same corners.
//   4. Propagation [lpv.propagate]: once per frame, the transmittance of every cell face from the
//      geometry volume; then, per bounce, the gather steps. Each cell takes from its 6 neighbours
//      the flux through its faces: the face it shares with the neighbour (solid angle
//      0.4006696846) and the 4 side faces (0.4234413544), each weighted by 1 - blocking on the
//      shared face (the 2-band lobe's constant term removed, so a wall does not block light
//      running along it). Each face's flux is re-emitted as a clamped cosine lobe along that
//      face's normal (KD09), so the kernel keeps the flux from step to step (its first step on a
//      cosine lobe excepted, see the calibration below). Light diffuses rather than travels: its
//      mean distance from a VPL grows as about sqrt(steps) (3 cells after 8 steps, 6 after 32).
//      Re-emitting a side face's flux along the direction it was evaluated in (neighbour centre
//      to face centre) moves light further per step but makes light, 1.6 times the VPL's flux
//      after 32 steps, and loses the point-light room test below (tests/lpv_propagation_test.cpp
//      checks the flux). No blocking in a bounce's first step (the injected light would block itself). The steps'
//      results are summed per bounce; then [lpv.bounce, timed in lpv.propagate] the bounce's
//      injection and propagated light P join the accumulator, and, for the next bounce, each
//      geometry-volume corner reflects P: albedo / pi * E * GV, with E the irradiance on the
//      corner's mean normal (the direction of GV's band 1), injected half a cell along that
//      normal (as VPLs are). `bounces` 1 is KD09's single bounce; closed rooms need more (the
//      Cornell box's ceiling sees only bounced light).
//   5. Shading [lpv.shade]: per pixel, the finest cascade containing the point, blended towards
//      the next over the outer tenth of the cascade (LH04), trilinear SH lookups half a cell in
//      front of the surface (its own blocking sits on the corners around it), irradiance
//      E = dot(L, cosLobe(-N)) with radiance L = kLPVRadianceScale * intensity / cell face area,
//      written as E / pi.
//   6. Sky [lpv.shade, sky.comp], when the environment lights the scene (FrameContext::sky): its
//      irradiance at the normal (the map's 9 SH coefficients) times the sky's visibility is added,
//      and the prefiltered map along the reflection times the visibility around it is the
//      indirect specular. Visibility: from the cell in front of the surface, the product of the
//      coarsest cascade's face transmittances (surfaces facing either way block) along the six
//      axes, cosine-weighted. Only what an RSM or the camera saw is in the geometry volume, so
//      only that blocks the sky; six directions are coarse (an overhang open to the side reads
//      as covered). Sky light does not bounce.
//
// Choices where the seed is silent (documented and tested):
//   - Flux per RSM texel is physical: albedo * light * projected texel area (directional) or
//     albedo * intensity * texel solid angle (spot, cube faces), so the result does not depend on
//     the RSM size. The intensity towards a texel is the light model's color * lightProfile(l,
//     dist, cosAxis) (common/light.h) for every kind, so a kind whose intensity varies with
//     direction needs no code here beyond joining cubeRSM(). A texel's solid angle is the
//     standard dA cos^3 / d^2 form: (2 tan(fov/2) / size)^2 * cos^3 of the angle between the
//     texel's direction and the map's axis (the spot's, or the cube face's). Over a whole cube it
//     sums to 4 pi within 1e-3 at 16^2 texels a face, 1.5e-5 at 128^2. The exact form (sums of
//     atan(xy / sqrt(1 + x^2 + y^2)) at the texel's corners) subtracts nearly equal angles, which
//     float does poorly for large maps. The seed's weight lpvRes^2 / (rsmW * rsmH) is not used; `intensity` scales the result.
//   - Float atomics are emulated with atomicCompSwap on a uint SSBO (exact under contention).
//   - Cascades: with cascadeExtent 0 and one cascade, the grid is the scene's bounding cube;
//     with several, the finest spans the scene's largest side / 2^(count-1), all centred on the
//     camera and snapped to whole cells of their own size so they do not flicker.
//   - Radiance calibration: propagation's first step returns 1.1382 times the flux of a cosine
//     lobe (the 2-band lobe's negative back is clamped away and the rest sampled at 30 face
//     directions); later steps keep the flux. Every propagated lobe starts as one (a VPL, a
//     bounce's re-injection), so kLPVRadianceScale = 1 / 1.1382 (lpv_shared.h) scales the
//     accumulator; shade and the bounces read radiance through it. It is measured, not fitted:
//     tests/lpv_propagation_test.cpp checks the flux and, with it, the inverse-square law within
//     15 % at 2 to 4 cells from a VPL after 32 steps.
//   - Self-illumination damping (KD09 section 5): where the irradiance towards the surface
//     grows behind it (P - N * half a cell) compared to in front (P + N * half a cell), the light
//     mostly comes from the surface's own VPLs; it is scaled by front/back, blended by `damping`.
// Known artefacts: light leaks through walls thinner than a cell (the geometry volume reduces
// them, by an amount that depends on where the wall falls in its cell: the two-room scene's
// closed room takes 3.5 % of the lit room's light at the scene's own alignment, up to 12.7 %
// with the scene moved by a fraction of a cell, because shade's trilinear stencil reaches the
// cell behind the wall's blocking layer; diffusion stayed under 2.5 % at every alignment tried,
// DiffusionGL.TheClosedRoomStaysDarkWhereverTheWallFalls), one-cell blur of the injected light,
// energy spreading with many steps, and
// self-illumination (a lit floor brightens itself through its own VPLs and, with bounces, its
// own reflection; damping reduces it). The accumulator counts light once for every step it
// spends in a cell and diffusing light lingers near its source, so with more steps than cells a
// closed room reads high (a point light in a 4 x 3 x 4 m room, one bounce against the path
// tracer's: 1.12 at 32^3 and 32 steps, 1.03 at 64^3 and 64 steps, 1.33 at 32^3 and 64 steps).
// A small closed box does better on a coarse grid: the Cornell presets use 16^3 and 32 steps
// (the built-in Cornell box at the default 32^3 and 32 steps: SSIM 0.672 / 0.682, below
// technique none's 0.694 / 0.724). Measured SSIM (128x96 / 256x192, technique none in
// brackets): built-in Cornell 0.792 / 0.797 (0.694 / 0.724), CornellBox-Original 0.786 / 0.793
// (0.749 / 0.773), basic 0.951 / 0.966 (0.948 / 0.966), Sponza 0.748 / 0.751 (0.471 / 0.500),
// Sponza cascades 0.650 / 0.664.
#pragma once

#include "gi/gl/handle.h"
#include "gi/gl/shader.h"
#include "gi/gl/uniform_block.h"
#include "gi/render/material_binding.h"
#include "gi/render/material_programs.h"
#include "gi/render/pass.h"
#include "gi/scene/free_path.h"
#include "lpv/lpv_shared.h"

#include <glm/glm.hpp>

#include <functional>

namespace gi {

struct CascadeBox {
    glm::vec3 min{0.0f};
    float cellSize = 1.0f;
    float extent = 1.0f;  // cellSize * resolution
    glm::vec3 center() const { return min + glm::vec3(0.5f * extent); }
};

// Lights the LPV does not inject (kinds it has no RSM for; none today), as a one-line note, or "".
std::string lpvIgnoredLights(const std::vector<LightSettings>& lights);

// Fitted grid (LPVSettings::fitGrid): LPV's propagation hands most of a beam's flux to the side
// faces at every step, so light crosses only ten to fifteen cells, however many steps run. On a
// 32^3 grid over a Cornell box the ceiling, 31 cells above the lit floor, stays black even after
// 96 steps; on 16^3 it is lit. Sponza needs the finer grid the other way: on 16^3 (3.3 m cells)
// its arcades fill with light through walls and pillars thinner than a cell. The fit keys on the
// mean distance between surfaces (GPUScene::freePath(), rays leaving the surfaces): the coarsest
// grid, from kLPVFitMinCells up to gridResolution in steps of kLPVFitStep, on which that distance
// spans kLPVFitCellsPerGap cells. A closed room's mean gap is a third to two thirds of its size,
// so small rooms get 16^3, the two-room scene and larger rooms 24^3; in Sponza and open scenes it
// is a tenth of their size, or few rays meet a surface again, and they keep 32^3. Why 6 cells
// and steps of 8: with 4 cells and no steps (any size from 16 up) the two-room scene took 16^3,
// where its closed room gets 5.1 % of the lit room's light, over issue 13's 5 % (3.5 % on 24^3,
// as on 32^3; 4.0 % on 20^3; LPVGL.GeometryVolumeCutsTheLeakThroughAThinWall), and sizes
// between the steps scored erratically, where a wall falls in the cells mattering more than the
// size (a 12 x 3 x 12 m hall 0.726 / 0.636 / 0.645 / 0.696 on 16 / 20 / 23 / 24^3, a furnished
// room 0.878 / 0.829 / 0.852 on 16 / 19 / 24^3). Tried against the leak and not kept: a shading
// stencil that weighs each neighbour cell by the face transmittance between (4.8 % on 16^3; rooms
// lost up to 0.015 SSIM), every Opaque triangle of the scene in the geometry volume (4.4 %; a
// corridor lost 0.12, a room with three lights 0.04), occlusionStrength 2 (1.7 %; the corridor
// lost 0.05). Scenes without a preset, 128x96 against the path tracer, SSIM at 32^3 / 24^3 / 16^3
// (32 propagation steps), the fit's in brackets: CornellBox-Empty-CO 0.748 / 0.803 / 0.838 (16),
// -Empty-RG 0.726 / 0.765 / 0.795 (16), -Squashed 0.733 / 0.747 / 0.772 (16), -Mirror 0.601 /
// 0.611 / 0.625 (16), -Water 0.695 / 0.703 / 0.717 (24), -Original 0.713 / 0.739 / 0.790 (16),
// -Sphere 0.663 / 0.675 / 0.693 (16), -Glossy 0.703 / 0.730 / 0.764 (16), -Empty-White 0.652 /
// 0.727 / 0.772 (16); hand-made rooms: 4 x 3 x 4 m lit by a point 0.747 / 0.775 / 0.822 (16), by
// an emissive panel 0.811 / 0.841 / 0.877 (16), a furnished 6 x 3 x 5 m room 0.817 / 0.852 /
// 0.878 (24), three lights 0.726 / 0.775 / 0.862 (24), the 12 m hall 0.646 / 0.696 / 0.726 (24).
// Kept at 32^3: Sponza (0.761; 0.722 on 24^3, 0.584 on 16^3), basic (0.951), an open street
// (0.872), a 20 m corridor (0.780; 0.690 on 24^3), a colonnade (0.799). The propagation's work
// falls with the cells: 24^3 is 0.42 and 16^3 0.125 of 32^3's cell-steps.
// Tried and not kept: more steps on a coarser fitted grid (propagationSteps x (gridResolution /
// fitted)^2: 128 on 16^3, 57 on 24^3, at most half the cell-steps of 32^3 x 32). Light then
// reached the far walls of a 5 x 3 x 5 m room lit through a window (SSIM 0.277 -> 0.394 at
// 128x96), and the Cornell files scored 0.004-0.032 higher, but the steps' sum keeps growing in a
// closed room: LPVGL.PointLightIndirectMatchesTheReference (one bounce against the path tracer's
// one bounce) read 1.53x the reference on 16^3 against its bound of 1.25x, so the gains were
// added brightness standing in for missing bounces, not transport.
// The fit's constants, kLPVFitMinCells, kLPVFitCellsPerGap and kLPVFitStep, are in
// lpv_settings.h beside fitGrid, whose description states them.

// Whether the settings let the grid be fitted: fitGrid, one cascade, no set extent.
bool lpvFitsGrid(const LPVSettings& s);
// The grid resolution a frame uses: gridResolution, or the fit above.
int lpvGridResolution(const LPVSettings& s, const FreePath& path);

// The cascade boxes for a frame (exposed for tests and the editor's overlay).
std::vector<CascadeBox> lpvCascades(const LPVSettings& s, const glm::vec3& sceneMin, const glm::vec3& sceneMax,
                                    const glm::vec3& camera);

class LPV : public Pass {
public:
    LPV();
    ~LPV() override;

    static size_t estimateBytes(const FrameSettings& fs);

    void indirect(FrameContext& ctx) override;
    std::vector<DebugView> debugViews() const override;
    // lpv.cascades: each cascade's box over the image; lpv.rsmCube<light>: a point light's cube
    // RSM flux as a cross (its faces are also the debug views lpv.rsm*<light>f<face>).
    std::vector<Previewer> previewers(const FrameSettings& fs) const override;
    size_t passMemory(const std::string& pass) const override;
    size_t memoryBytes() const override;
    std::vector<std::string> passNames(const FrameSettings& fs) const override;
    // The grid the frame used (gridResolution, or the fit and the free path it came from).
    PassReport report(const FrameSettings& fs) const override;
    bool reloadShaders(std::string& log) override;

    const std::vector<CascadeBox>& cascades() const { return mBoxes; }
    // RSMs drawn since creation (tests: static lights keep them).
    int rsmDrawCount() const { return mRSMDraws; }
    // Injections run since creation (tests: unchanged RSMs and boxes restore the kept one).
    int injectCount() const { return mInjects; }

    // One propagation step on SSBOs of 12 floats per cell (RGB x 4 SH coefficients): gathers
    // `src` into `dst` and adds `dst` to `accum`; `transmit` (8 floats per cell, from the geometry
    // volume) is read when `blocking`. indirect() runs it; tests call it directly.
    void propagateStep(GLuint src, GLuint dst, GLuint accum, GLuint transmit, int resolution, bool blocking);

private:
    struct RSM {
        gl::Texture flux, normal, position, depth, albedo;
        gl::Framebuffer fbo;
        glm::mat4 viewProj{1.0f};
        float texelArea = 0.0f;  // directional: projected world area of a texel
        float texelSolidAngle = 0.0f;  // spot, cube face: solid angle of a centre texel
        int light = 0;
        int cascade = 0;  // the cascade it feeds; -1: every cascade (a cube's faces)
        int face = -1;    // a point light's cube face (+X, -X, +Y, -Y, +Z, -Z), or -1
        bool drawn = false;              // it holds the scene seen through drawnViewProj
        glm::mat4 drawnViewProj{1.0f};
        bool feeds(size_t k) const { return cascade < 0 || size_t(cascade) == k; }
    };
    struct Cascade {
        gl::Buffer inject, ping, pong, gather, accum, geometryRSM, geometryGBuffer, albedo, transmit;
        gl::Buffer injected;  // the last injection, kept (inject() restores it while nothing it depends on changed)
        gl::Buffer geometryRSMKept, albedoKept;  // the RSMs' surfels' sums alone, kept alike (buildGeometry)
        gl::Texture shR, shG, shB, geometryRSMVolume, geometryGBufferVolume;
    };

    gl::Program mInjectProg, mGeometryProg, mGeometryResolveProg, mGeometryMergeProg, mTransmitProg, mPropagateProg, mBounceProg,
        mResolveProg, mShadeProg, mSkyProg;
    gl::UniformBlock<shared::LPVParams> mBlock;  // every pass reads it
    // propagate's views of its grids (propagateStep), which bounce and resolve re-point too
    gl::TextureHandle mSourceView = gl::createBufferTexture(), mTransmitView = gl::createBufferTexture(),
                      mDestinationView = gl::createBufferTexture(), mAccumView = gl::createBufferTexture(),
                      mGeometryRSMView = gl::createBufferTexture(), mGeometryGBufferView = gl::createBufferTexture(),
                      mAlbedoView = gl::createBufferTexture();
    MaterialBinding mMaterialBinding;  // the RSM pass reads it
    // The RSM pass's programs, one per set of material textures (gi/render/material_programs.h),
    // for Opaque materials (no discard) and for the rest.
    MaterialPrograms mRSMProgs, mRSMOpaqueProgs;
    std::vector<Cascade> mCascadeData;
    std::vector<CascadeBox> mBoxes;
    std::vector<RSM> mRSMs;
    int mResolution = 0, mRSMResolution = 0;
    FreePath mFreePath;  // the scene's, which the fitted grid follows (report())
    size_t mRSMBytes = 0, mVolumeBytes = 0, mGeometryBytes = 0;
    uint64_t mRSMSceneId = 0;  // the scene the RSMs show
    int mRSMDraws = 0;
    bool mRSMsChanged = true;                // this frame's renderRSMs drew a map (or redraws every one)
    std::vector<CascadeBox> mInjectedBoxes;  // the boxes `injected` was made for; empty: none kept
    std::vector<CascadeBox> mGeometryBoxes;  // and those geometryRSMKept and albedoKept were
    int mInjects = 0;
    gl::Sampler mLinear;

    void allocate(const FrameSettings& fs, uint8_t changes, int resolution);
    void renderRSMs(const FrameContext& ctx);
    // Whether this frame may restore RSM-derived work kept for the boxes `keptFor`: static work is
    // kept, no RSM was drawn (nor every one redrawn), and the cascades have not moved.
    bool keepsRSMWork(const FrameContext& ctx, const std::vector<CascadeBox>& keptFor) const;
    // One dispatch, a thread per texel of RSM m, for each cascade m feeds: p with the grid's
    // resolution, the map's size and the cascade's box in the block, and bindTargets(cascade) for
    // the buffers it adds to (inject, buildGeometry).
    void dispatchPerTexel(const RSM& m, shared::LPVParams p, const std::function<void(const Cascade&)>& bindTargets);
    void inject(const FrameContext& ctx);
    void buildGeometry(const FrameContext& ctx);
    void propagate(const FrameContext& ctx);
    void shade(const FrameContext& ctx);
};

}  // namespace gi
