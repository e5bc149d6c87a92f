// Light propagation volumes: the SH maths, flux through unoccluded propagation, cascade placement,
// and a two-room scene where the geometry volume must cut the light leaking through a thin wall.
#include "common/sh.h"
#include "gi/lpv/lpv.h"
#include "gi/preset/preset.h"
#include "gi/render/renderer.h"
#include "gi/scene/mesh_builder.h"
#include "test_util.h"

#include <glm/gtc/constants.hpp>

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
    fs.camera.eye = {1.9f, 1.0f, 0.0f};
    fs.camera.target = {0.0f, 0.8f, 0.0f};
    fs.camera.fovY = 70.0f;
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
}

}  // namespace
}  // namespace gi
