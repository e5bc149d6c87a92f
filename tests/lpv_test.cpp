// Light propagation volumes: the SH maths, flux through unoccluded propagation, cascade placement,
// a two-room scene where the geometry volume must cut the light leaking through a thin wall, and
// point lights through their cube RSM (energy, agreement with a spot, the path-traced reference).
#include "common/light.h"
#include "common/sh.h"
#include "gi/gl/extensions.h"
#include "gi/lpv/lpv.h"
#include "gi/preset/preset.h"
#include "gi/render/renderer.h"
#include "gi/scene/mesh_builder.h"
#include "test_util.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace gi {
namespace {

// Integrates f over the sphere with a midpoint rule in (cos theta, phi).
template <class F>
double integrateSphere(F&& f, int n = 400) {
    double sum = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < 2 * n; ++j) {
            double z = -1.0 + 2.0 * (i + 0.5) / n, phi = 2.0 * glm::pi<double>() * (j + 0.5) / (2 * n);
            double r = std::sqrt(std::max(0.0, 1.0 - z * z));
            sum += f(glm::vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)));
        }
    return sum * 4.0 * glm::pi<double>() / (2.0 * n * n);
}

TEST(SH, BasisIsOrthonormal) {
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
            double v = integrateSphere([&](glm::vec3 w) { return double(sh::shBasis(w)[a]) * sh::shBasis(w)[b]; });
            EXPECT_NEAR(v, a == b ? 1.0 : 0.0, 1e-4) << a << "," << b;
        }
}

TEST(SH, CosineLobeIsTheProjectionOfTheClampedCosine) {
    glm::vec3 n = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
    glm::vec4 lobe = sh::shCosLobe(n);
    for (int k = 0; k < 4; ++k) {
        double projected = integrateSphere([&](glm::vec3 w) { return std::max(0.0, double(glm::dot(n, w))) * sh::shBasis(w)[k]; });
        EXPECT_NEAR(projected, lobe[k], 1e-3) << k;
    }
    // The 2-band lobe is 0.25 + 0.5 cos, and it integrates to pi like max(cos, 0).
    EXPECT_NEAR(sh::shEval(lobe, n), 0.75f, 1e-5f);
    EXPECT_NEAR(sh::shEval(lobe, -n), -0.25f, 1e-5f);
    EXPECT_NEAR(integrateSphere([&](glm::vec3 w) { return double(sh::shEval(lobe, w)); }), glm::pi<double>(), 1e-3);
    // Irradiance from a uniform radiance 1: dot(L, cosLobe) = pi.
    EXPECT_NEAR(glm::dot(glm::vec4(std::sqrt(4.0f * glm::pi<float>()), 0, 0, 0), sh::shCosLobe(n)), glm::pi<float>(), 1e-4f);
}

class LPVGL : public test::GLTest {};

TEST_F(LPVGL, UnoccludedPropagationConservesFlux) {
    const int res = 9;
    const size_t floats = size_t(res) * res * res * 12;
    auto cellOf = [&](int x, int y, int z) { return size_t((z * res + y) * res + x); };
    // An isotropic source in the centre (red channel: SH (1, 0, 0, 0)), flux = 2 sqrt(pi) * c0.
    std::vector<float> src(floats, 0.0f);
    src[cellOf(4, 4, 4) * 12] = 1.0f;
    gl::Buffer a = gl::createBuffer(floats * 4, src.data(), GL_DYNAMIC_STORAGE_BIT);
    gl::Buffer b = gl::createBuffer(floats * 4, nullptr, GL_DYNAMIC_STORAGE_BIT);
    gl::Buffer accum = gl::createBuffer(floats * 4, src.data(), GL_DYNAMIC_STORAGE_BIT);
    gl::Buffer transmit = gl::createBuffer(size_t(res) * res * res * 32, nullptr, GL_DYNAMIC_STORAGE_BIT);
    LPV lpv;
    lpv.propagateStep(a.id(), b.id(), accum.id(), transmit.id(), res, false);
    std::vector<float> out(floats), acc(floats);
    glGetNamedBufferSubData(b.id(), 0, GLsizeiptr(floats * 4), out.data());
    glGetNamedBufferSubData(accum.id(), 0, GLsizeiptr(floats * 4), acc.data());
    double total = 0;
    for (size_t c = 0; c < floats / 12; ++c) total += out[c * 12];
    // The 30 faces around the source cover 4 pi sr, each re-emitting its flux as a lobe of the
    // same flux: the red c0 summed over the 6 neighbours is the source's.
    EXPECT_NEAR(total, 1.0, 1e-4);
    EXPECT_NEAR(out[cellOf(5, 4, 4) * 12], out[cellOf(3, 4, 4) * 12], 1e-6f);
    EXPECT_EQ(out[cellOf(4, 4, 4) * 12], 0.0f) << "a cell does not receive from itself";
    EXPECT_NEAR(acc[cellOf(4, 4, 4) * 12], 1.0f, 1e-6f);
    EXPECT_NEAR(acc[cellOf(5, 4, 4) * 12], out[cellOf(5, 4, 4) * 12], 1e-6f);

    // A lobe pointing along +x moves its light towards +x, step after step. Its first step sends
    // 1.48 / (1.48 + 4 x 0.52) of the flux to the +x neighbour (the clamped faces' intensities
    // times their solid angles), so the centre of the light moves about 0.41 cells, then less
    // per step as the lobes turn sideways.
    std::vector<float> lobe(floats, 0.0f);
    glm::vec4 l = sh::shCosLobe({1, 0, 0});
    for (int k = 0; k < 4; ++k) lobe[cellOf(2, 4, 4) * 12 + k] = l[k];
    glNamedBufferSubData(a.id(), 0, GLsizeiptr(floats * 4), lobe.data());
    GLuint from = a.id(), to = b.id();
    double previous = 2.0;
    for (int step = 0; step < 3; ++step) {
        lpv.propagateStep(from, to, accum.id(), transmit.id(), res, false);
        std::swap(from, to);
        glGetNamedBufferSubData(from, 0, GLsizeiptr(floats * 4), out.data());
        double weighted = 0, sum = 0;
        for (int z = 0; z < res; ++z)
            for (int y = 0; y < res; ++y)
                for (int x = 0; x < res; ++x) {
                    double c0 = out[cellOf(x, y, z) * 12];
                    weighted += c0 * x;
                    sum += c0;
                }
        double centre = weighted / sum;
        if (step == 0) {
            EXPECT_NEAR(centre - previous, 1.48 / (1.48 + 4 * 0.523), 0.02);
        }
        EXPECT_GT(centre, previous + 0.02) << "step " << step;
        previous = centre;
    }
}

TEST(LPVCascades, FitSnapAndNest) {
    LPVSettings s;
    glm::vec3 lo(-3, 0, -1), hi(5, 2, 1);
    auto one = lpvCascades(s, lo, hi, {0, 0, 0});
    ASSERT_EQ(one.size(), 1u);
    EXPECT_LE(one[0].min.x, lo.x);
    EXPECT_GE(one[0].min.x + one[0].extent, hi.x);
    EXPECT_NEAR(one[0].cellSize * s.gridResolution, one[0].extent, 1e-5f);
    s.cascadeCount = 3;
    s.cascadeExtent = 4.0f;
    auto boxes = lpvCascades(s, lo, hi, {1.03f, 0.5f, 0.2f});
    ASSERT_EQ(boxes.size(), 3u);
    for (size_t k = 0; k < boxes.size(); ++k) {
        EXPECT_NEAR(boxes[k].extent, 4.0f * float(1 << k), 1e-5f);
        glm::vec3 cells = boxes[k].min / boxes[k].cellSize;
        EXPECT_NEAR(cells.x, std::round(cells.x), 1e-3f) << "cascade " << k << " is not snapped to its cells";
        glm::vec3 c = boxes[k].center();
        EXPECT_LT(glm::length(c - glm::vec3(1.03f, 0.5f, 0.2f)), boxes[k].cellSize * 1.8f) << "centred on the camera";
    }
    // Moving the camera by less than a cell keeps every box where it was.
    auto moved = lpvCascades(s, lo, hi, {1.03f + 0.2f * boxes[0].cellSize, 0.5f, 0.2f});
    for (size_t k = 0; k < boxes.size(); ++k) EXPECT_EQ(moved[k].min, boxes[k].min);
}

// The sky (issue 13 item 2): an open floor under a constant environment of radiance 1 has
// E / pi = 1, which technique none's irradiance map gives exactly (times the floor's albedo 0.8);
// LPV adds the same map times the sky's visibility through the geometry volume, so the open floor
// gets it all and the same floor inside a closed box gets almost none. The open floor has no light,
// so all it gathers is sky. The box has a point light inside, whose cube RSM puts the walls in the
// geometry volume (with no light and a camera looking down, nothing would know the ceiling is
// there); its sky is what the environment adds to the same frame without it.
TEST_F(LPVGL, TheSkyLightsWhatTheGeometryVolumeLeavesOpen) {
    auto frame = test::skyFrame;
    Scene open = test::openFloor(), closed = test::closedBox();
    Renderer r;
    r.setScene(open);
    double lpv = test::meanIndirect(r, frame(open, "lpv"));
    double none = test::meanIndirect(r, frame(open, "none"));
    r.setScene(closed);
    FrameSettings box = frame(closed, "lpv");
    LightSettings bulb;
    bulb.type = LightType::Point;
    bulb.position = {0.0f, 0.7f, 0.0f};
    bulb.intensity = 2.0f;
    box.lights = {bulb};
    double withSky = test::meanIndirect(r, box);
    box.environment.enabled = false;
    double withoutSky = test::meanIndirect(r, box);
    double inside = withSky - withoutSky;
    std::printf("closed box lit by a bulb: %.5f with the sky, %.5f without\n", withSky, withoutSky);
    EXPECT_GT(withoutSky, 0.0) << "the bulb's light propagates";
    std::printf("open floor under a constant sky: none %.4f, lpv %.4f (%.1f %%); inside a closed box: lpv %.5f (%.1f %%)\n", none,
                lpv, 100.0 * lpv / none, inside, 100.0 * inside / none);
    EXPECT_NEAR(none, 0.8, 0.02) << "the irradiance map of a constant sky of radiance 1";
    EXPECT_NEAR(lpv / none, 1.0, 0.05) << "nothing stands between the open floor and the sky";
    EXPECT_LT(inside, 0.05 * none) << "no sky inside a closed box";
}

TEST_F(LPVGL, GeometryVolumeCutsTheLeakThroughAThinWall) {
    Scene scene = test::twoRooms();
    Preset p;
    p.header.technique.name = "lpv";
    p.lpv.gridResolution = 16;
    p.lpv.propagationSteps = 16;
    FrameSettings fs = frameSettings(p, scene, 96, 64);
    Renderer r;
    r.setScene(scene);
    // Looking into room B from its outer wall.
    test::lookIntoClosedRoom(fs.camera);
    fs.lpv.occlusion = false;
    double leakOpen = test::meanIndirect(r, fs);
    fs.lpv.occlusion = true;
    double leakBlocked = test::meanIndirect(r, fs);
    // The lit room, for scale.
    fs.camera.eye = {-1.9f, 1.0f, 0.0f};
    fs.camera.target = {0.0f, 0.8f, 0.0f};
    double litRoom = test::meanIndirect(r, fs);
    std::printf("indirect in the dark room: %.5f without, %.5f with the geometry volume; lit room %.5f\n", leakOpen,
                leakBlocked, litRoom);
    EXPECT_GT(litRoom, 5.0 * leakBlocked);
    EXPECT_LT(leakBlocked, 0.5 * leakOpen) << "the geometry volume should cut the leak at least in half";
    // With the default settings (issue 13 item 6: the closed room below 5 % of the lit room). This
    // holds where this scene's wall falls in the default grid; moved by a fraction of a cell the
    // leak reached 12.7 % (gi/lpv/lpv.h, Known artefacts).
    FrameSettings d = frameSettings(Preset{}, scene, 96, 64);
    d.technique = "lpv";
    d.camera = fs.camera;
    double litDefault = test::meanIndirect(r, d);
    d.camera.eye = {1.9f, 1.0f, 0.0f};
    double leakDefault = test::meanIndirect(r, d);
    std::printf("with the defaults (%d^3 fitted, %d steps, %d bounces): dark room %.5f, lit room %.5f (%.1f %%)\n",
                lpvGridResolution(d.lpv, meanFreePath(scene)), d.lpv.propagationSteps, d.lpv.bounces, leakDefault, litDefault,
                100.0 * leakDefault / litDefault);
    EXPECT_LT(leakDefault, 0.05 * litDefault) << "the closed room takes more than 5 % of the lit room's indirect light";
}


// A closed room, 4 x 3 x 4 m, red wall at -x, green at +x, the rest white, lit by `light`.
Scene closedRoom(const LightSettings& light) {
    Scene s = test::closedRoom(0.75f, glm::vec3(0.7f, 0.15f, 0.1f), glm::vec3(0.15f, 0.6f, 0.1f));
    s.lights.push_back(light);
    s.finalize();
    return s;
}

// Off centre, so the faces see the walls at different distances.
LightSettings pointLight() { return test::pointLight({0.4f, 2.2f, -0.3f}, 10.0f); }

FrameSettings roomSettings(const Scene& scene, int rsmResolution) {
    Preset p;
    p.header.technique.name = "lpv";
    p.lpv.rsmResolution = rsmResolution;
    FrameSettings fs = frameSettings(p, scene, 128, 96);
    fs.lights = scene.lights;
    fs.camera.eye = {0.0f, 1.5f, 1.9f};
    fs.camera.target = {0.0f, 1.2f, -2.0f};
    fs.camera.fovY = 70.0f;
    return fs;
}

// One RSM texel as read back: the flux it carries (RGB: the exitance the RSM holds times its
// surfel's world area, as injection takes it) and the world position of its surfel.
struct RSMTexel {
    glm::vec3 flux, position;
    bool covered;
};

// The texels of the RSM debug view `name` (lpv.rsmFlux..., with its lpv.rsmPosition... twin).
std::vector<RSMTexel> readRSM(const Renderer& r, const std::string& flux, const std::string& position) {
    std::vector<RSMTexel> texels;
    const DebugView *f = nullptr, *p = nullptr;
    std::vector<DebugView> views = r.debugViews();
    for (const DebugView& v : views) {
        if (v.name == flux) f = &v;
        if (v.name == position) p = &v;
    }
    if (!f || !p) {
        ADD_FAILURE() << "no debug views " << flux << ", " << position;
        return texels;
    }
    size_t n = size_t(f->width) * f->height * 4;
    std::vector<float> fv(n), pv(n);
    glGetTextureImage(f->texture, 0, GL_RGBA, GL_FLOAT, GLsizei(n * 4), fv.data());
    glGetTextureImage(p->texture, 0, GL_RGBA, GL_FLOAT, GLsizei(n * 4), pv.data());
    for (size_t i = 0; i < n; i += 4)
        texels.push_back({glm::vec3(fv[i], fv[i + 1], fv[i + 2]) * pv[i + 3], {pv[i], pv[i + 1], pv[i + 2]}, pv[i + 3] > 0.0f});
    return texels;
}

// The cube RSM of light 0, all six faces.
std::vector<RSMTexel> readCube(const Renderer& r) {
    std::vector<RSMTexel> all;
    for (int face = 0; face < 6; ++face) {
        auto t = readRSM(r, "lpv.rsmFlux0f" + std::to_string(face), "lpv.rsmPosition0f" + std::to_string(face));
        all.insert(all.end(), t.begin(), t.end());
    }
    return all;
}

// Light adds up: two point lights at one place, each of half the intensity, light a closed
// room as one. Each light's RSMs add their surfels to the geometry volume, and summed, a surface
// both lights see blocked and reflected twice: the mean indirect light came out 1.3x that of the
// single light (geometry_merge.comp now keeps one light's surfels per corner, the larger coverage).
TEST_F(LPVGL, TwoLightsAtOnePlaceLightTheRoomAsOne) {
    Scene scene = test::closedRoom();
    MeshBuilder b(scene);
    b.box(0, {0.5f, 0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}, 20.0f);  // material 0: the room's white
    scene.finalize();
    Preset p;
    p.header.technique.name = "lpv";
    FrameSettings fs = frameSettings(p, scene, 64, 48);
    fs.camera.eye = {0.0f, 1.5f, 1.8f};
    fs.camera.target = {0.0f, 0.8f, -2.0f};
    LightSettings point = test::pointLight({-0.8f, 2.5f, 0.3f}, 16.0f);
    Renderer r;
    r.setScene(scene);
    fs.lights = {point};
    const double one = test::meanIndirect(r, fs);
    point.intensity = 8.0f;
    fs.lights = {point, point};
    const double two = test::meanIndirect(r, fs);
    std::printf("indirect light: one light %.5f, two at its place with half its intensity %.5f (%.3f)\n", one, two, two / one);
    ASSERT_GT(one, 0.0);
    EXPECT_NEAR(two / one, 1.0, 0.01);
}

// Energy: a closed room catches everything a point light emits, 4 pi I, so the flux its cube RSM
// hands to injection is albedo * 4 pi I (each wall's share weighted by its albedo).
TEST_F(LPVGL, PointLightCubeRSMCarriesTheEmittedFlux) {
    LightSettings light = pointLight();
    // One albedo everywhere, so the expected total needs no per-wall solid angles.
    Scene scene;
    {
        MeshBuilder b(scene);
        int grey = b.material("grey", glm::vec3(0.5f), 1.0f);
        b.quad(grey, {-2, 0, 2}, {4, 0, 0}, {0, 0, -4});
        b.quad(grey, {-2, 3, -2}, {4, 0, 0}, {0, 0, 4});
        b.quad(grey, {-2, 0, -2}, {4, 0, 0}, {0, 3, 0});
        b.quad(grey, {2, 0, 2}, {-4, 0, 0}, {0, 3, 0});
        b.quad(grey, {-2, 0, 2}, {0, 0, -4}, {0, 3, 0});
        b.quad(grey, {2, 0, -2}, {0, 0, 4}, {0, 3, 0});
        scene.lights.push_back(light);
        scene.finalize();
    }
    FrameSettings fs = roomSettings(scene, 128);
    Renderer r;
    r.setScene(scene);
    r.render(fs);
    std::vector<RSMTexel> texels = readCube(r);
    ASSERT_EQ(texels.size(), size_t(6 * 128 * 128));
    double flux = 0.0;
    size_t covered = 0;
    for (const RSMTexel& t : texels) {
        flux += t.flux.r;
        covered += t.covered;
    }
    double emitted = 4.0 * glm::pi<double>() * light.intensity * 0.5;
    std::printf("cube RSM flux %.4f, albedo x emitted %.4f (ratio %.4f), %zu of %zu texels covered\n", flux, emitted,
                flux / emitted, covered, texels.size());
    EXPECT_EQ(covered, texels.size()) << "a closed room covers every texel of the cube";
    EXPECT_NEAR(flux / emitted, 1.0, 0.02);
    // The estimate the budget check uses counts the six faces, once for every cascade, as allocated.
    size_t rsmBytes = 0;
    r.render(fs);  // timers report the newest finished frame
    for (const PassStats& p : r.passStats())
        if (p.name == "lpv.rsm") rsmBytes = p.memoryBytes;
    FrameSettings unlit = fs;
    unlit.lights.clear();
    EXPECT_EQ(LPV::estimateBytes(fs) - LPV::estimateBytes(unlit), rsmBytes);
    EXPECT_EQ(rsmBytes, size_t(6) * 128 * 128 * (8 + 8 + 16 + 4 + 4));  // flux, normal, position, depth, albedo
    fs.lpv.cascadeCount = unlit.lpv.cascadeCount = 3;
    EXPECT_EQ(LPV::estimateBytes(fs) - LPV::estimateBytes(unlit), rsmBytes) << "one cube serves every cascade";
}

// A spot with a 90-degree outer cone at the point light's place, pointing down, emits the same
// intensity into the lower hemisphere: both RSMs must carry the same flux from the directions
// both cover (within 80 degrees of straight down: the -Y face and the lower parts of the four
// side faces; the spot's 170-degree map stops at 85).
TEST_F(LPVGL, PointLightAgreesWithASpotOverTheFacesItCovers) {
    LightSettings point = pointLight();
    LightSettings spot = point;
    spot.type = LightType::Spot;
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.innerConeDeg = 90.0f;
    spot.outerConeDeg = 90.0f;
    const float cosLimit = std::cos(glm::radians(80.0f));
    auto lowerFlux = [&](const std::vector<RSMTexel>& texels, glm::dvec3& sides) {
        glm::dvec3 sum(0.0);
        sides = glm::dvec3(0.0);
        for (const RSMTexel& t : texels) {
            if (!t.covered) continue;
            glm::vec3 d = glm::normalize(t.position - point.position);
            if (-d.y < cosLimit) continue;
            sum += glm::dvec3(t.flux);
            // Directions outside the -Y face's frustum: the side faces' share.
            if (std::abs(d.x) > -d.y || std::abs(d.z) > -d.y) sides += glm::dvec3(t.flux);
        }
        return sum;
    };
    Scene pointScene = closedRoom(point), spotScene = closedRoom(spot);
    Renderer r;
    r.setScene(pointScene);
    r.render(roomSettings(pointScene, 256));
    glm::dvec3 pointSides, spotSides;
    glm::dvec3 fromPoint = lowerFlux(readCube(r), pointSides);
    Renderer rs;
    rs.setScene(spotScene);
    rs.render(roomSettings(spotScene, 512));
    glm::dvec3 fromSpot = lowerFlux(readRSM(rs, "lpv.rsmFlux0c0", "lpv.rsmPosition0c0"), spotSides);
    for (int c = 0; c < 3; ++c) {
        std::printf("channel %d: point %.4f (side faces %.4f), spot %.4f (%.4f)\n", c, fromPoint[c], pointSides[c], fromSpot[c],
                    spotSides[c]);
        EXPECT_NEAR(fromPoint[c] / fromSpot[c], 1.0, 0.03) << c;
        EXPECT_NEAR(pointSides[c] / spotSides[c], 1.0, 0.05) << c;
    }
    EXPECT_GT(pointSides.r, 0.3 * fromPoint.r) << "the side faces should carry a good part of the flux";
}

// A point light in a closed room: the LPV's one bounce (lpv.bounces 1) against the path tracer's
// one bounce (maxBounces 2, paths of exactly two surface bounces), diffuse only on both sides, at
// the defaults (the fitted grid: 16^3 in this room, 1.21), at 32^3 and at 64^3 with as many steps
// (the settings' rule). Without
// kLPVRadianceScale (the kernel's first-step flux gain, tests/lpv_propagation_test.cpp) the LPV
// read 1.27 and 1.17; with it, 1.12 and 1.03. It reads high where light lingers near the walls
// that emit it (a spot in the same place: 1.60 unscaled at 32^3), and rises with more steps than
// cells (32^3 at 64 steps: 1.33) and with kernels that make light (re-emitting a side face's
// flux along its evaluation direction, with the scale that fits it to free space: 0.56 and 0.50).
TEST_F(LPVGL, PointLightIndirectMatchesTheReference) {
    Scene scene = closedRoom(pointLight());
    FrameSettings fs = roomSettings(scene, 256);
    fs.render.specular = false;
    fs.lpv.bounces = 1;
    bool cached = false;
    double reference = test::referenceOneBounceIndirect(scene, fs, &cached);
    Renderer r;
    r.setScene(scene);
    double defaults = test::meanIndirect(r, fs);
    const int fitted = lpvGridResolution(fs.lpv, meanFreePath(scene));
    fs.lpv.fitGrid = false;
    double coarse = test::meanIndirect(r, fs);
    fs.lpv.gridResolution = 64;
    fs.lpv.propagationSteps = 64;
    double fine = test::meanIndirect(r, fs);
    std::printf("mean indirect luminance: reference %.5f (%s); LPV defaults (fitted %d^3) %.5f, ratio %.3f; 32^3 %.5f, "
                "ratio %.3f; 64^3 %.5f, ratio %.3f\n",
                reference, cached ? "cached" : "rendered", fitted, defaults, defaults / reference, coarse, coarse / reference,
                fine, fine / reference);
    EXPECT_NEAR(defaults / reference, 1.0, 0.25);
    EXPECT_NEAR(coarse / reference, 1.0, 0.25);
    EXPECT_NEAR(fine / reference, 1.0, 0.25);
}

// Light transport does not depend on the units: the lamp-lit Cornell box (its quad the only
// light) and its camera scaled to 1/100 (a 2 cm box) and to 100x gather the original's indirect
// light. The RSMs and volumes once held flux, which scales with the square of the units: at 1/100
// the half floats underflowed and the LPV added nothing (the mean 0.45x the reference's).
TEST_F(LPVGL, TheIndirectLightIsTheSameAtAnyScale) {
    auto mean = [](float scale) {
        Scene scene = test::scaledBuiltinScene("cornell_lamp", scale);
        Preset p;
        p.header.technique.name = "lpv";
        FrameSettings fs = frameSettings(p, scene, 64, 64);
        test::scaleCamera(fs.camera, scale);
        Renderer r;
        r.setScene(scene);
        return test::meanIndirect(r, fs);
    };
    const double original = mean(1.0f);
    EXPECT_GT(original, 0.005);
    for (float scale : {0.01f, 100.0f}) EXPECT_NEAR(mean(scale) / original, 1.0, 0.02) << "scale " << scale;
}

// Issue 17 item 4: RSMs are kept under static lights, and so is their injection. A camera move
// inside the cascades' snap keeps them, with the pixels of a renderer that redraws them; a moving
// camera carries a directional light's cascade maps along with their boxes; a moved light redraws
// its maps and injects again.
TEST_F(LPVGL, StaticRSMsAreKeptAndRedrawnWhenALightMoves) {
    Scene scene = makeBuiltinScene("cornell");
    Preset p;
    p.header.technique.name = "lpv";
    FrameSettings fs = frameSettings(p, scene, 64, 48);
    ASSERT_FALSE(fs.lights.empty());
    Renderer r;
    r.setScene(scene);
    r.render(fs);
    auto lpvOf = [](const Renderer& x) { return dynamic_cast<const LPV*>(x.technique()); };
    ASSERT_NE(lpvOf(r), nullptr);
    int maps = lpvOf(r)->rsmDrawCount();
    ASSERT_GT(maps, 0);
    EXPECT_EQ(lpvOf(r)->injectCount(), 1);
    r.render(fs);
    EXPECT_EQ(lpvOf(r)->rsmDrawCount(), maps) << "static lights: no map drawn again";
    EXPECT_EQ(lpvOf(r)->injectCount(), 1) << "static lights: the injection is kept";
    FrameSettings turned = fs;
    turned.camera.target += glm::vec3(0.2f, -0.1f, 0.0f);
    r.render(turned);
    EXPECT_EQ(lpvOf(r)->rsmDrawCount(), maps) << "a camera turn keeps the cascades and the maps";
    EXPECT_EQ(lpvOf(r)->injectCount(), 1);
    EXPECT_EQ(r.readHDR(), test::renderedAfresh(scene, turned)->readHDR()) << "kept maps give the pixels redrawn ones do";

    FrameSettings moved = turned;
    moved.lights[0].position += glm::vec3(0.2f, 0.0f, 0.0f);
    moved.lights[0].direction += glm::vec3(0.05f, 0.0f, 0.0f);
    r.render(moved);
    EXPECT_EQ(lpvOf(r)->rsmDrawCount(), 2 * maps) << "a moved light redraws them";
    EXPECT_EQ(lpvOf(r)->injectCount(), 2) << "and injects them again";
    EXPECT_EQ(r.readHDR(), test::renderedAfresh(scene, moved)->readHDR());
    moved.render.keepStaticWork = false;
    r.render(moved);
    EXPECT_EQ(lpvOf(r)->rsmDrawCount(), 3 * maps) << "keepStaticWork off: every frame";
    EXPECT_EQ(lpvOf(r)->injectCount(), 3);
}

// Injection and the geometry volume add floats from many RSM texels into one cell: with
// GL_NV_shader_atomic_float (llvmpipe has it) by atomicAdd, else by an atomicCompSwap loop.
// Both give the same picture; GI_DISABLE_GL_EXTENSIONS forces the loop on a driver with the
// extension.
TEST_F(LPVGL, FloatAtomicsAddAsTheCompareAndSwapLoopDoes) {
    Scene scene = makeBuiltinScene("cornell_lamp");  // an area light: a cube RSM crowding a 32^3 grid
    Preset p;
    p.header.technique.name = "lpv";
    FrameSettings fs = frameSettings(p, scene, 64, 48);
    const std::string withExtension = gl::floatAtomicsDefine();
    std::printf("driver: %s\n", withExtension.c_str());
    std::vector<float> fast = test::renderedAfresh(scene, fs)->readIndirectRadiance();
    ::setenv("GI_DISABLE_GL_EXTENSIONS", "GL_EXT_unrelated,GL_NV_shader_atomic_float", 1);
    const std::string without = gl::floatAtomicsDefine();
    std::vector<float> loop = test::renderedAfresh(scene, fs)->readIndirectRadiance();
    ::unsetenv("GI_DISABLE_GL_EXTENSIONS");
    EXPECT_EQ(without, "FLOAT_ATOMICS=0");
    ASSERT_EQ(fast.size(), loop.size());
    float peak = 0.0f, worst = 0.0f;
    for (size_t i = 0; i < fast.size(); ++i) {
        if (i % 4 == 3) continue;  // RGBA: alpha is 1
        peak = std::max(peak, std::abs(loop[i]));
        worst = std::max(worst, std::abs(fast[i] - loop[i]));
    }
    std::printf("indirect peak %.5f, largest difference %.3g\n", peak, worst);
    EXPECT_GT(peak, 0.01f) << "the view holds indirect light";
    EXPECT_LE(worst, 1e-5f * peak) << "the sums differ by more than the order of the adds can";
}

// A point light's cube RSM feeds every cascade and stays while the camera moves, but the boxes
// it was injected into follow the camera: a move past a cell injects again, into the new boxes.
TEST_F(LPVGL, KeptInjectionFollowsTheCascades) {
    Scene scene = makeBuiltinScene("cornell_lamp");
    Preset p;
    p.header.technique.name = "lpv";
    FrameSettings fs = frameSettings(p, scene, 64, 48);
    // Inside the box, so both cascades hold lit walls.
    fs.camera.eye = glm::vec3(0.0f, 1.0f, 0.6f);
    fs.camera.target = glm::vec3(0.0f, 1.0f, -1.0f);
    fs.lpv.cascadeCount = 2;
    fs.lpv.cascadeExtent = 1.5f;
    Renderer r;
    r.setScene(scene);
    r.render(fs);
    const LPV* lpv = dynamic_cast<const LPV*>(r.technique());
    ASSERT_NE(lpv, nullptr);
    const int maps = lpv->rsmDrawCount();
    ASSERT_EQ(lpv->injectCount(), 1);
    FrameSettings moved = fs;
    const glm::vec3 step(4.0f * lpv->cascades()[1].cellSize, 0.0f, 0.0f);
    moved.camera.eye += step;
    moved.camera.target += step;
    r.render(moved);
    EXPECT_EQ(lpv->rsmDrawCount(), maps) << "the cube RSM does not depend on the camera";
    EXPECT_EQ(lpv->injectCount(), 2) << "the boxes moved";
    EXPECT_EQ(r.readHDR(), test::renderedAfresh(scene, moved)->readHDR());
    std::vector<float> indirect = r.readIndirectRadiance();
    double mean = 0.0;
    for (float v : indirect) mean += v;
    EXPECT_GT(mean / double(indirect.size()), 0.01) << "the view holds indirect light the injection decides";
    r.render(moved);
    EXPECT_EQ(lpv->injectCount(), 2);
    EXPECT_EQ(r.readHDR(), test::renderedAfresh(scene, moved)->readHDR());
}

}  // namespace
}  // namespace gi
