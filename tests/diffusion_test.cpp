// The diffusion technique's propagation (gi/diffusion/diffusion.h) on hand-made grids: the flux
// it carries through free space, a one-voxel wall that stops it, and the bounces in a closed box.
#include "common/sh.h"
#include "diffusion/diffusion_shared.h"
#include "gi/diffusion/diffusion.h"
#include "gi/metrics/metrics.h"
#include "gi/reference/reference_cache.h"
#include "gi/scene/mesh_builder.h"
#include "gi/preset/preset.h"
#include "gi/render/render_settings.h"
#include "gi/render/renderer.h"
#include "gi/scene/scene.h"
#include "gi/util/error.h"
#include "test_util.h"

#include <algorithm>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/packing.hpp>

#include <cmath>
#include <functional>
#include <queue>

namespace gi {
namespace {

class DiffusionGL : public test::GLTest {};

// A res^3 grid: occupancy, albedo and mean normal per cell (packed as the voxelizer writes
// them), and the light in flight (12 floats per cell: R, G, B SH).
struct Grid {
    int res;
    std::vector<uint32_t> albedo, normal;
    std::vector<float> light;
    explicit Grid(int r) : res(r), albedo(cells(), 0u), normal(cells(), 0u), light(cells() * 12, 0.0f) {}
    size_t cells() const { return size_t(res) * res * res; }
    size_t cell(int x, int y, int z) const { return size_t((z * res + y) * res + x); }
    void solid(int x, int y, int z, glm::vec3 rgb, glm::vec3 n) {
        albedo[cell(x, y, z)] = glm::packUnorm4x8(glm::vec4(rgb, 1.0f / 255.0f));
        normal[cell(x, y, z)] = glm::packUnorm4x8(glm::vec4(n * 0.5f + 0.5f, 1.0f / 255.0f));
    }
    bool occupied(size_t i) const { return (albedo[i] >> 24) != 0u; }
    // A clamped cosine lobe of flux 1 (per colour) along n in cell (x, y, z), as init.comp makes them.
    void source(int x, int y, int z, glm::vec3 n) {
        glm::vec4 lobe = sh::shCosLobe(n) / glm::pi<float>();
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 4; ++k) light[cell(x, y, z) * 12 + size_t(c) * 4 + size_t(k)] = lobe[k];
    }
};

// The red flux of 12-float SH cells for which `keep` is true: band 0 times 2 sqrt(pi).
double flux(const std::vector<float>& sh, const std::function<bool(size_t)>& keep = nullptr) {
    double sum = 0.0;
    for (size_t i = 0; i * 12 < sh.size(); ++i)
        if (!keep || keep(i)) sum += sh[i * 12];
    return sum * 2.0 * std::sqrt(glm::pi<double>());
}

struct Result {
    std::vector<float> light, accum;  // the last step's light in flight, and the accumulation
    std::vector<float> order;         // the accumulated bounce order times flux, per cell
};

// `afterStep`, when given, sees the light in flight after every step.
Result propagate(Diffusion& d, const Grid& g, int steps, DiffusionAlbedo mode = DiffusionAlbedo::Voxel,
                 const std::function<void(const std::vector<float>&)>& afterStep = nullptr) {
    auto volume = [&](const std::vector<uint32_t>& data) {
        gl::Texture t = gl::Texture::create3D(GL_R32UI, g.res, g.res, g.res);
        glTextureSubImage3D(t.id(), 0, 0, 0, 0, g.res, g.res, g.res, GL_RED_INTEGER, GL_UNSIGNED_INT, data.data());
        return t;
    };
    gl::Texture albedo = volume(g.albedo), normal = volume(g.normal);
    const size_t floats = g.light.size();
    gl::Buffer a = gl::createBuffer(floats * 4, g.light.data(), GL_DYNAMIC_STORAGE_BIT);
    gl::Buffer b = gl::createBuffer(floats * 4, nullptr, GL_DYNAMIC_STORAGE_BIT);
    std::vector<float> zeros(floats, 0.0f);
    gl::Buffer accum = gl::createBuffer(floats * 4, zeros.data(), GL_DYNAMIC_STORAGE_BIT);
    gl::Buffer outgoing = gl::createBuffer(g.cells() * 6 * 16, nullptr, GL_DYNAMIC_STORAGE_BIT);
    GLuint from = a.id(), to = b.id();
    d.resetBounceOrders(g.res);
    for (int s = 0; s < steps; ++s) {
        d.propagateStep(albedo.id(), normal.id(), from, to, outgoing.id(), accum.id(), g.res, mode);
        std::swap(from, to);
        if (afterStep) {
            std::vector<float> light(floats);
            glGetNamedBufferSubData(from, 0, GLsizeiptr(floats * 4), light.data());
            afterStep(light);
        }
    }
    Result r{std::vector<float>(floats), std::vector<float>(floats), std::vector<float>(g.cells())};
    glGetNamedBufferSubData(from, 0, GLsizeiptr(floats * 4), r.light.data());
    glGetNamedBufferSubData(accum.id(), 0, GLsizeiptr(floats * 4), r.accum.data());
    glGetNamedBufferSubData(d.accumulatedOrder().id(), 0, GLsizeiptr(g.cells() * 4), r.order.data());
    return r;
}

// Seed 001's transfer as printed multiplies the flux by the face's solid angle (2.09) at each
// step, and clamping a 2-band lobe's negative faces alone adds 11 % at the first; the kernel
// keeps the flux in free space to float precision, for a cosine VPL and for the beams it
// becomes.
TEST_F(DiffusionGL, PropagationThroughEmptyCellsKeepsTheFlux) {
    Grid g(33);  // no light reaches the border in 14 steps
    g.source(16, 16, 16, {1, 0, 0});
    EXPECT_NEAR(flux(g.light), 1.0, 1e-6);
    Diffusion d;
    for (int steps : {1, 2, 5, 14}) {
        Result r = propagate(d, g, steps);
        std::printf("flux after %d steps %.6f\n", steps, flux(r.light));
        EXPECT_NEAR(flux(r.light), 1.0, 1e-4) << steps << " steps";
        EXPECT_NEAR(flux(r.accum), 0.0, 1e-12) << "nothing is absorbed in empty space";
        for (float v : r.light) ASSERT_TRUE(std::isfinite(v));
    }
    // The light moves away from the source, forwards more than back.
    Result r = propagate(d, g, 6);
    double ahead = flux(r.light, [&](size_t i) { return int(i % 33) > 16; });
    double behind = flux(r.light, [&](size_t i) { return int(i % 33) < 16; });
    EXPECT_GT(ahead, 2.0 * behind);
}

// A one-voxel wall across the grid, lit from one side: no light reaches the other side, in
// flight or accumulated, whichever way its normal points; the wall takes the light that
// reaches it.
TEST_F(DiffusionGL, AOneVoxelWallStopsTheLight) {
    for (float side : {-1.0f, 1.0f}) {
        Grid g(24);
        for (int z = 0; z < 24; ++z)
            for (int y = 0; y < 24; ++y) g.solid(12, y, z, glm::vec3(0.8f), {side, 0, 0});
        g.source(6, 12, 12, {1, 0, 0});
        Diffusion d;
        Result r = propagate(d, g, 40);
        auto beyond = [&](size_t i) { return int(i % 24) > 12; };
        auto wall = [&](size_t i) { return int(i % 24) == 12; };
        EXPECT_EQ(flux(r.light, beyond), 0.0) << "normal " << side;
        EXPECT_EQ(flux(r.accum, beyond), 0.0) << "normal " << side;
        double absorbed = flux(r.accum, wall);
        std::printf("normal %+.0f: the wall took %.4f of the flux\n", side, absorbed);
        EXPECT_GT(absorbed, 0.3) << "the VPL faces the wall, 6 cells away";
        EXPECT_LE(absorbed, 1.0 + 1e-4);
    }
}

// A lit wall facing an occluder (issue 16): a VPL in front of a black wall sends its light to a
// plate of albedo 0.5 six cells away. The light stops at the plate's cells and is re-emitted
// from them: the flux the plate sends back out (the light in flight in its cells, summed over the
// steps, each reflection in flight there for one step) is half the flux that reached it, and
// part of it reaches the wall as a second bounce (the wall's light is of order 1, what the VPL
// sends it sideways, and 2: its mean order lies above 1).
TEST_F(DiffusionGL, AnOccluderReEmitsHalfTheFirstBounceWithAlbedoHalf) {
    const int res = 16;
    Grid g(res);
    for (int z = 2; z < 14; ++z)
        for (int y = 2; y < 14; ++y) {
            g.solid(3, y, z, glm::vec3(0.0f), {1, 0, 0});    // the wall, black: it reflects nothing
            g.solid(10, y, z, glm::vec3(0.5f), {-1, 0, 0});  // the occluder, facing the wall
        }
    g.source(4, 8, 8, {1, 0, 0});
    auto plate = [&](size_t i) { return int(i % res) == 10 && g.occupied(i); };
    auto wall = [&](size_t i) { return int(i % res) == 3 && g.occupied(i); };
    double reemitted = 0.0;
    Diffusion d;
    Result r = propagate(d, g, 60, DiffusionAlbedo::Voxel, [&](const std::vector<float>& light) { reemitted += flux(light, plate); });
    const double reached = flux(r.accum, plate), second = flux(r.accum, wall);
    double order = 0.0;
    for (size_t i = 0; i < g.cells(); ++i)
        if (wall(i)) order += r.order[i];
    order /= 3.0 * second;
    const double albedo = 128.0 / 255.0;  // 0.5 as RGBA8 stores it
    std::printf("the occluder: reached by %.5f, re-emitted %.5f (%.4f of it); the wall received %.5f, mean bounce order %.3f\n",
                reached, reemitted, reemitted / reached, second, order);
    EXPECT_GT(reached, 0.2) << "the VPL faces the plate";
    EXPECT_NEAR(reemitted / reached, albedo, 0.05 * albedo) << "the second bounce carries half the first";
    EXPECT_GT(second, 0.0);
    EXPECT_GT(order, 1.0) << "the wall sees light that bounced off the plate";
    EXPECT_LT(order, 2.0);
}

// A closed box: with black walls every bit of the flux is absorbed once (nothing leaves, nothing
// is made); with seed 001's constant albedo 0.5 each bounce carries half the one before, so the
// light arriving sums to 1 / (1 - 0.5) = 2 times the source's.
TEST_F(DiffusionGL, InAClosedBoxEachBounceCarriesTheAlbedoTimesTheOneBefore) {
    const int res = 10;
    auto box = [&](glm::vec3 rgb) {
        Grid g(res);
        for (int z = 0; z < res; ++z)
            for (int y = 0; y < res; ++y)
                for (int x = 0; x < res; ++x) {
                    glm::ivec3 c(x, y, z);
                    glm::vec3 n(0.0f);
                    for (int a = 0; a < 3; ++a) {
                        if (c[a] == 0) n[a] += 1.0f;
                        if (c[a] == res - 1) n[a] -= 1.0f;
                    }
                    if (n != glm::vec3(0.0f)) g.solid(x, y, z, rgb, glm::normalize(n));
                }
        g.source(3, 4, 5, glm::normalize(glm::vec3(1, 0.5f, 0.2f)));
        return g;
    };
    Diffusion d;
    Grid black = box(glm::vec3(0.0f));
    Result once = propagate(d, black, 300);
    double inFlight = flux(once.light);
    std::printf("black walls: absorbed %.5f, in flight %.2e\n", flux(once.accum), inFlight);
    EXPECT_LT(inFlight, 1e-3) << "converged";
    EXPECT_NEAR(flux(once.accum), 1.0, 2e-3) << "all of it, once";
    // The bounce orders (the diffusion.bounces view): the flux-weighted mean order of the light
    // arrived. Black walls: first-bounce light only, order 1 exactly.
    auto meanOrder = [](const Result& r) {
        double weighted = 0.0;
        for (float o : r.order) weighted += o;
        return weighted / (3.0 * flux(r.accum));  // the order sums flux over the three colours
    };
    EXPECT_NEAR(meanOrder(once), 1.0, 1e-4);

    Grid grey = box(glm::vec3(0.6f));  // the albedo volume is not read with `half`
    Result half = propagate(d, grey, 600, DiffusionAlbedo::Half);
    double arrived = flux(half.accum);
    std::printf("albedo 0.5: arrived %.5f (1 / (1 - 0.5) = 2), in flight %.2e\n", arrived, flux(half.light));
    EXPECT_NEAR(arrived, 2.0, 0.05 * 1.0) << "the bounces after the first sum to the first times 0.5 / (1 - 0.5), within 5 %";
    // Bounce k carries 0.5^(k - 1) of the first, so the mean order is sum k 0.5^(k-1) / sum
    // 0.5^(k-1) = 1 / (1 - 0.5) = 2: with the total above, each bounce is half the one before.
    std::printf("albedo 0.5: mean bounce order of the light arrived %.5f (2)\n", meanOrder(half));
    EXPECT_NEAR(meanOrder(half), 2.0, 0.05 * 1.0);
    Result voxel = propagate(d, grey, 600, DiffusionAlbedo::Voxel);
    std::printf("albedo 0.6 (voxel): arrived %.5f (1 / (1 - 0.6) = 2.5)\n", flux(voxel.accum));
    EXPECT_NEAR(flux(voxel.accum), 2.5, 0.05 * 1.5);
}

// The two-room scene (test_util.h): a spot lights room A; room B shares a one-quad wall with it.
// Light moves through empty cells only and the wall's cells reflect it back where it came from,
// so the closed room's indirect light stays below 5 % of the lit room's (issue 16; VCT leaks
// 22 % here, tests/vct_test.cpp).
TEST_F(DiffusionGL, TheClosedRoomStaysDark) {
    Scene scene = test::twoRooms();
    Preset p;
    p.header.technique.name = "diffusion";
    FrameSettings fs = frameSettings(p, scene, 96, 64);
    Renderer r;
    r.setScene(scene);
    test::lookIntoClosedRoom(fs.camera);
    double dark = test::meanIndirect(r, fs);
    fs.camera.eye = {-0.1f, 1.0f, 0.0f};
    fs.camera.target = {-2.0f, 0.8f, 0.0f};
    double lit = test::meanIndirect(r, fs);
    std::printf("indirect: lit room %.5f, closed room %.6f (%.2f %%)\n", lit, dark, 100.0 * dark / lit);
    EXPECT_GT(lit, 0.0);
    EXPECT_LT(dark, 0.05 * lit);
}

// The same at every alignment of the shared wall in the grid: the scene moved by 0, 0.25, 0.5
// and 0.75 of a cell along x under a grid that stays put (two tiny black quads two cells outside
// the rooms fix the bounds). A leak test at one alignment can pass by luck: LPV's default leaks
// 3.5 % where this scene's wall falls and up to 12.7 % at other shifts (closing note of stop 37).
const Diffusion& diffusionOf(const Renderer& r);

TEST_F(DiffusionGL, TheClosedRoomStaysDarkWhereverTheWallFalls) {
    Preset p;
    p.header.technique.name = "diffusion";
    const glm::vec3 size = test::twoRooms().bounds.max - test::twoRooms().bounds.min;
    const test::AnchoredRooms rooms = test::anchoredTwoRooms(2.0f * std::max(size.x, std::max(size.y, size.z)) / float(p.diffusion.gridResolution));
    for (float shift : {0.0f, 0.25f, 0.5f, 0.75f}) {
        FrameSettings fs = frameSettings(p, rooms.scene, 96, 64);
        Renderer r;
        r.setScene(rooms.scene);
        r.render(fs);
        const float cell = diffusionOf(r).box().cellSize;
        const glm::vec3 offset(shift * cell, 0.0f, 0.0f);
        Scene scene = rooms.moved(offset);
        r.setScene(scene);
        test::RoomsIndirect light = test::twoRoomsIndirect(r, frameSettings(p, scene, 96, 64), offset);
        ASSERT_NEAR(diffusionOf(r).box().cellSize, cell, 1e-6f) << "the anchors hold the grid";
        std::printf("wall moved %.2f cell: lit room %.5f, closed room %.6f (%.2f %%)\n", shift, light.lit, light.closed,
                    100.0 * light.closed / light.lit);
        EXPECT_GT(light.lit, 0.0);
        EXPECT_LT(light.closed, 0.05 * light.lit) << "wall moved " << shift << " cell";
    }
}

// iterationsPerFrame spreads the solve over frames: the light arrives step by step, the frame
// after the last step equals the whole solve in one frame, later frames hold it (the same
// picture, without propagating), a camera move keeps it, and a light change or shadow maps of
// another size start it again.
TEST_F(DiffusionGL, ASolveSpreadOverFramesMatchesTheWholeSolveAndRestartsOnChange) {
    Scene scene = makeBuiltinScene("cornell");
    Preset p;
    p.header.technique.name = "diffusion";
    p.diffusion.iterations = 24;
    FrameSettings fs = frameSettings(p, scene, 64, 48);
    ASSERT_FALSE(fs.lights.empty());
    Renderer whole;
    whole.setScene(scene);
    const double full = test::meanIndirect(whole, fs);

    fs.diffusion.iterationsPerFrame = 8;
    Renderer spread;
    spread.setScene(scene);
    double frames[4];
    for (double& f : frames) f = test::meanIndirect(spread, fs);
    std::printf("mean indirect over frames: %.5f %.5f %.5f, held %.5f; whole solve %.5f\n", frames[0], frames[1], frames[2], frames[3], full);
    EXPECT_LT(frames[0], frames[1]);
    EXPECT_LT(frames[1], frames[2]);
    EXPECT_NEAR(frames[2], full, 1e-4 * full) << "24 steps in three frames of 8";
    EXPECT_NEAR(frames[3], frames[2], 1e-6 * full) << "held";
    fs.camera.eye += glm::vec3(0.1f, 0.0f, 0.0f);
    double moved = test::meanIndirect(spread, fs);
    EXPECT_GT(moved, 0.9 * frames[2]) << "a camera move keeps the solve";
    fs.lights[0].intensity *= 0.5f;
    double restarted = test::meanIndirect(spread, fs);
    EXPECT_LT(restarted, 0.75 * moved) << "a light change starts again from injection (8 steps, half the light)";
    test::meanIndirect(spread, fs);
    double completed = test::meanIndirect(spread, fs);
    fs.render.shadowMapSize /= 2;  // the injection reads the shadow maps
    double resized = test::meanIndirect(spread, fs);
    std::printf("after the light change: first frame %.5f, completed %.5f; shadow maps resized: %.5f\n", restarted, completed, resized);
    EXPECT_LT(resized, 0.9 * completed) << "shadow maps of another size start the solve again";
    EXPECT_NEAR(resized, restarted, 0.05 * restarted);
}

const Diffusion& diffusionOf(const Renderer& r) {
    const Diffusion* d = dynamic_cast<const Diffusion*>(r.technique());
    if (!d) throw Error("the renderer holds no diffusion pass");
    return *d;
}

// Issue 17 item 4: the whole solve in one frame (iterationsPerFrame 0, the default) is held like
// a spread one under static lights: later frames start no solve and show the pixels a fresh
// renderer does, a camera move keeps it, a light change solves again, and keepStaticWork off
// solves every frame.
TEST_F(DiffusionGL, AWholeSolveIsHeldUnderStaticLights) {
    Scene scene = makeBuiltinScene("cornell");
    Preset p;
    p.header.technique.name = "diffusion";
    FrameSettings fs = frameSettings(p, scene, 64, 48);
    ASSERT_EQ(fs.diffusion.iterationsPerFrame, 0);
    ASSERT_FALSE(fs.lights.empty());
    Renderer r;
    r.setScene(scene);
    r.render(fs);
    EXPECT_EQ(diffusionOf(r).solveCount(), 1);
    r.render(fs);
    EXPECT_EQ(diffusionOf(r).solveCount(), 1) << "static lights: the solve is held";
    FrameSettings moved = fs;
    moved.camera.eye += glm::vec3(0.1f, 0.05f, 0.0f);
    r.render(moved);
    EXPECT_EQ(diffusionOf(r).solveCount(), 1) << "a camera move keeps it";
    EXPECT_EQ(r.readHDR(), test::renderedAfresh(scene, moved)->readHDR()) << "the held solve gives a fresh one's pixels";
    moved.lights[0].intensity *= 0.5f;
    r.render(moved);
    EXPECT_EQ(diffusionOf(r).solveCount(), 2) << "a light change solves again";
    EXPECT_EQ(r.readHDR(), test::renderedAfresh(scene, moved)->readHDR());
    moved.render.keepStaticWork = false;
    r.render(moved);
    r.render(moved);
    EXPECT_EQ(diffusionOf(r).solveCount(), 4) << "keepStaticWork off: every frame";
}

// The occupancy of the renderer's diffusion grid, one bool per cell (x fastest).
std::vector<bool> occupancy(const Renderer& r) {
    const Diffusion& d = diffusionOf(r);
    int res = d.resolution();
    std::vector<uint32_t> packed(size_t(res) * res * res);
    glGetTextureImage(d.albedoVolume().id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, GLsizei(packed.size() * 4), packed.data());
    std::vector<bool> solid(packed.size());
    for (size_t i = 0; i < packed.size(); ++i) solid[i] = (packed[i] >> 24) != 0u;
    return solid;
}

// Seed 001's slicing (voxelization = slicing): three draws, one along each axis, merged. On a
// panel tilted against every axis it must leave no face-connected gap, since light moves
// between empty cells through faces: empty cells flood-filled from above the panel never reach
// the cell below it. Every cell it marks is one the conservative voxelizer marks too (that one
// grows triangles by half a pixel), and it marks most of them.
TEST_F(DiffusionGL, SlicingAlongThreeAxesLeavesNoGapInATiltedPanel) {
    Scene scene;
    MeshBuilder b(scene);
    int white = b.material("white", glm::vec3(0.8f), 1.0f);
    // y = 0.5 x + 0.3 z over x, z in [-1, 1]: tilted about two axes.
    b.quad(white, {-1.0f, -0.8f, -1.0f}, {2.0f, 1.0f, 0.0f}, {0.0f, 0.6f, 2.0f});
    scene.finalize();
    Preset p;
    p.header.technique.name = "diffusion";
    p.diffusion.iterations = 1;
    p.diffusion.voxelization = DiffusionVoxelization::Conservative;
    FrameSettings fs = frameSettings(p, scene, 32, 32);
    Renderer r;
    r.setScene(scene);
    r.render(fs);
    const std::vector<bool> conservative = occupancy(r);
    fs.diffusion.voxelization = DiffusionVoxelization::Slicing;
    r.render(fs);
    const std::vector<bool> sliced = occupancy(r);
    const int res = diffusionOf(r).resolution();
    size_t both = 0, slicedCount = 0, conservativeCount = 0;
    for (size_t i = 0; i < sliced.size(); ++i) {
        slicedCount += sliced[i];
        conservativeCount += conservative[i];
        both += sliced[i] && conservative[i];
    }
    std::printf("tilted panel at %d^3: conservative %zu cells, slicing %zu, both %zu\n", res, conservativeCount, slicedCount, both);
    EXPECT_EQ(both, slicedCount) << "slicing marks a cell the conservative voxelizer does not";
    EXPECT_GT(double(slicedCount), 0.5 * double(conservativeCount));
    EXPECT_LT(slicedCount, conservativeCount) << "the conservative voxelizer grows triangles; slicing does not";
    // Flood fill the empty cells from above the panel's centre, inside the panel's span (two
    // cells in from the grid's sides, where light could go round it).
    const glm::vec3 lo = diffusionOf(r).box().min;
    const float cell = diffusionOf(r).box().cellSize;
    auto cellOf = [&](glm::vec3 w) { return glm::ivec3(glm::floor((w - lo) / cell)); };
    auto index = [&](glm::ivec3 c) { return size_t((c.z * res + c.y) * res + c.x); };
    auto inside = [&](glm::ivec3 c) { return c.x >= 2 && c.z >= 2 && c.x < res - 2 && c.z < res - 2 && c.y >= 0 && c.y < res; };
    for (const std::vector<bool>* solid : {&conservative, &sliced}) {
        std::vector<bool> seen(solid->size(), false);
        std::queue<glm::ivec3> todo;
        glm::ivec3 start = cellOf({0.0f, 0.5f, 0.0f}), goal = cellOf({0.0f, -0.5f, 0.0f});
        ASSERT_FALSE((*solid)[index(start)]);
        todo.push(start);
        seen[index(start)] = true;
        while (!todo.empty()) {
            glm::ivec3 c = todo.front();
            todo.pop();
            for (int a = 0; a < 3; ++a)
                for (int s : {-1, 1}) {
                    glm::ivec3 n = c;
                    n[a] += s;
                    if (!inside(n) || seen[index(n)] || (*solid)[index(n)]) continue;
                    seen[index(n)] = true;
                    todo.push(n);
                }
        }
        EXPECT_FALSE(seen[index(goal)]) << (solid == &sliced ? "slicing" : "conservative") << ": empty cells go through the panel";
    }
}

// Multiple bounces on a closed Cornell box (the classic room with a front wall, the camera
// inside): each doubling of the iterations carries more light, and the indirect light and the
// picture come closer to the path tracer's as the bounces add up. Prints SSIM against iterations.
TEST_F(DiffusionGL, MoreIterationsCarryMoreBouncesTowardsTheReference) {
    Scene scene = makeBuiltinScene("cornell");
    MeshBuilder b(scene);
    int white = 0;
    while (scene.materials[size_t(white)].name != "white") ++white;
    b.quad(white, {1, 0, 1}, {-2, 0, 0}, {0, 2, 0});  // front wall, facing -z
    scene.finalize();
    Preset p;
    p.header.technique.name = "diffusion";
    FrameSettings fs = frameSettings(p, scene, 64, 64);
    fs.camera.eye = {0.0f, 1.0f, 0.97f};
    fs.camera.target = {0.0f, 0.9f, 0.0f};
    fs.camera.fovY = 75.0f;
    ReferenceSettings rs;
    rs.spp = 128;
    CachedReference full = cachedReference(scene, fs, rs);
    rs.mode = ReferenceMode::Indirect;
    CachedReference indirectRef = cachedReference(scene, fs, rs);
    const double refIndirect = meanLuminance(indirectRef.image);
    Renderer r;
    r.setScene(scene);
    std::vector<double> mean, ssim;
    const std::vector<int> counts = {8, 16, 32, 64, 128, 256};
    for (int n : counts) {
        fs.diffusion.iterations = n;
        r.render(fs);
        ImageRGB image = imageFromGL(fs.width, fs.height, r.readHDR());
        ImageRGB indirect = imageFromGL(fs.width, fs.height, r.readIndirectRadiance());
        Metrics m = scoreRender({&image, &full.image, &indirect, &indirectRef.image, fs.toneMap});
        mean.push_back(meanLuminance(indirect));
        ssim.push_back(m.ssim);
        std::printf("iterations %3d: mean indirect %.5f (%.2f of the reference's %.5f), ssim %.4f\n", n, mean.back(),
                    mean.back() / refIndirect, refIndirect, m.ssim);
    }
    for (size_t i = 1; i < counts.size(); ++i) EXPECT_GT(mean[i], mean[i - 1]) << counts[i] << " against " << counts[i - 1] << " iterations";
    EXPECT_LT(std::abs(mean.back() / refIndirect - 1.0), std::abs(mean.front() / refIndirect - 1.0));
    EXPECT_GT(ssim.back(), ssim.front());
}

// A face tilted in the grid (a panel turned 20 degrees about y in the closed Cornell box, seen
// head on from inside) is voxelized as a staircase: cells open on one face beside cells open on
// two, which take light through both. Shaded from the raw accumulation it shows stripes a cell
// or two wide (as every Cornell box's rotated boxes did); smoothing (smooth.comp) averages each
// cell with its neighbours on the same surface. Measured over the panel: the mean difference of
// horizontally adjacent pixels' indirect light, over its mean. The light the panel receives in
// all stays within 5 %.
TEST_F(DiffusionGL, ATiltedFaceShadesWithoutVoxelStripes) {
    Scene scene = makeBuiltinScene("cornell");
    MeshBuilder b(scene);
    int white = 0;
    while (scene.materials[size_t(white)].name != "white") ++white;
    b.quad(white, {1, 0, 1}, {-2, 0, 0}, {0, 2, 0});  // front wall, facing -z: a closed room
    const float yaw = glm::radians(20.0f);
    const glm::vec3 across(std::cos(yaw), 0.0f, -std::sin(yaw)), normal(std::sin(yaw), 0.0f, std::cos(yaw));
    const glm::vec3 centre(0.0f, 1.0f, -0.1f);
    b.quad(white, centre - 0.6f * across - glm::vec3(0, 0.6f, 0), 1.2f * across, {0, 1.2f, 0});  // faces +normal
    scene.finalize();
    Preset p;
    p.header.technique.name = "diffusion";
    FrameSettings fs = frameSettings(p, scene, 64, 64);
    fs.camera.eye = centre + 0.9f * normal;
    fs.camera.target = centre;
    fs.camera.fovY = 50.0f;
    Renderer r;
    r.setScene(scene);
    // Over the middle of the view (all panel): the mean |difference| of horizontal neighbours
    // over the mean, and the mean.
    auto measure = [&](bool smoothing, double& mean) {
        fs.diffusion.smoothing = smoothing;
        test::meanIndirect(r, fs);  // renders (GI_TEST_IMAGES writes the pictures)
        std::vector<float> rgba = r.readIndirectRadiance();
        auto lum = [&](int x, int y) {
            const float* q = &rgba[size_t(y * fs.width + x) * 4];
            return 0.2126 * q[0] + 0.7152 * q[1] + 0.0722 * q[2];
        };
        double sum = 0.0, steps = 0.0;
        int n = 0;
        for (int y = 16; y < 48; ++y)
            for (int x = 8; x < 56; ++x) {
                sum += lum(x, y);
                steps += std::abs(lum(x + 1, y) - lum(x, y));
                ++n;
            }
        mean = sum / n;
        return steps / n / mean;
    };
    double meanRaw = 0.0, meanSmoothed = 0.0;
    const double raw = measure(false, meanRaw), smoothed = measure(true, meanSmoothed);
    std::printf("tilted panel: adjacent-pixel difference over the mean %.4f raw, %.4f smoothed; mean %.5f raw, %.5f smoothed\n", raw,
                smoothed, meanRaw, meanSmoothed);
    ASSERT_GT(meanRaw, 0.0);
    EXPECT_LT(smoothed, 0.5 * raw) << "the panel's stripes should at least halve";
    EXPECT_NEAR(meanSmoothed / meanRaw, 1.0, 0.05);
}

// A closed room whose walls lie at the grid's edge, lit by a point light: looking down at the
// back wall's foot, the indirect light down the middle column of the view has no dark line where
// the floor meets the wall. The cell there is open only below the floor, to the outside, so it
// holds almost no light; shading read it beside the floor's cells and drew a line at 0.10 of the
// column's median (shade.comp now reads only cells open on the pixel's side: 0.91).
TEST_F(DiffusionGL, NoDarkLineWhereAFloorMeetsAWall) {
    Scene scene = test::closedRoom();
    Preset p;
    p.header.technique.name = "diffusion";
    FrameSettings fs = frameSettings(p, scene, 64, 64);
    fs.lights = {test::pointLight({0.0f, 2.5f, 0.0f}, 8.0f)};
    fs.camera.eye = {0.0f, 1.2f, 1.0f};
    fs.camera.target = {0.0f, 0.2f, -2.0f};
    fs.camera.fovY = 60.0f;
    Renderer r;
    r.setScene(scene);
    test::meanIndirect(r, fs);  // renders (GI_TEST_IMAGES writes the picture)
    std::vector<float> rgba = r.readIndirectRadiance();
    std::vector<double> column;
    for (int y = 0; y < fs.height; ++y) {
        const float* q = &rgba[size_t(y * fs.width + fs.width / 2) * 4];
        column.push_back(0.2126 * q[0] + 0.7152 * q[1] + 0.0722 * q[2]);
    }
    std::vector<double> sorted = column;
    std::sort(sorted.begin(), sorted.end());
    const double median = sorted[sorted.size() / 2], darkest = sorted.front();
    std::printf("floor and back wall, middle column: darkest %.5f, median %.5f (%.2f)\n", darkest, median, darkest / median);
    ASSERT_GT(median, 0.0);
    EXPECT_GT(darkest, 0.5 * median);
}

// Settings that would stall the frame are refused before anything is allocated, naming the key.
TEST(Diffusion, APropagationPastTheTimeBudgetIsRefused) {
    FrameSettings fs;
    fs.technique = "diffusion";
    fs.render.timeBudgetSeconds = 10.0f;
    fs.diffusion.gridResolution = 64;
    fs.diffusion.iterations = 64;  // 1.7e7 cell-steps: about 4 s
    EXPECT_NO_THROW(DiffusionSettings::checkTime(fs));
    fs.diffusion.iterations = 1024;
    try {
        DiffusionSettings::checkTime(fs);
        FAIL() << "not refused";
    } catch (const Error& e) {
        std::string m = e.what();
        EXPECT_NE(m.find("render.timeBudgetSeconds"), std::string::npos) << m;
        EXPECT_NE(m.find("iterations 1024"), std::string::npos) << m;
    }
    EXPECT_GT(DiffusionSettings::estimateBytes(fs), size_t(64 * 64 * 64) * 200);
}

}  // namespace
}  // namespace gi
