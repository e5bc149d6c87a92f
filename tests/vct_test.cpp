// Voxel cone tracing: cone set geometry, SH hemisphere projection, mip consistency, the clipmap's
// toroidal update against a full voxelization, the nudge on a flat floor, the two-room leak, shift
// invariance, and the memory budget.
#include "common/sh.h"
#include "gi/preset/preset.h"
#include "gi/render/renderer.h"
#include "gi/scene/mesh_builder.h"
#include "gi/vct/cone_set.h"
#include "gi/vct/vct.h"
#include "gi/util/error.h"
#include "test_util.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/packing.hpp>

#include <cmath>
#include <map>

namespace gi {
namespace {

double angleDeg(glm::vec3 a, glm::vec3 b) { return glm::degrees(std::acos(std::clamp(double(glm::dot(a, b)), -1.0, 1.0))); }

void expectNormalised(const ConeSet& set) {
    double sum = 0;
    for (const Cone& c : set.cones) {
        EXPECT_NEAR(glm::length(c.direction), 1.0f, 1e-5f);
        EXPECT_GT(c.direction.z, 0.0f) << "every cone points into the hemisphere";
        EXPECT_GT(c.weight, 0.0f);
        sum += c.weight;
    }
    EXPECT_NEAR(sum, 1.0, 1e-5);
}

TEST(VCTConeSet, SixIsSeed003sSet) {
    ConeSet set = makeConeSet(ConeSetKind::Six, 0, 60.0f, ConeWeighting::Cosine);
    ASSERT_EQ(set.cones.size(), 6u);
    expectNormalised(set);
    EXPECT_NEAR(set.cones[0].direction.z, 1.0f, 1e-6f);
    for (int i = 1; i < 6; ++i) {
        EXPECT_NEAR(angleDeg(set.cones[size_t(i)].direction, {0, 0, 1}), 60.0, 1e-3);
        // Neighbours on the ring are 72 degrees apart in azimuth.
        glm::vec3 a = set.cones[size_t(i)].direction, b = set.cones[size_t(i % 5 + 1)].direction;
        double phi = glm::degrees(std::acos(glm::dot(glm::normalize(glm::vec2(a)), glm::normalize(glm::vec2(b)))));
        EXPECT_NEAR(phi, 72.0, 1e-2);
    }
    // Seed 003's weights are cos(theta): 1 and 0.5, so 1/3.5 and 0.5/3.5 once normalised.
    EXPECT_NEAR(set.cones[0].weight, 1.0 / 3.5, 1e-6);
    EXPECT_NEAR(set.cones[3].weight, 0.5 / 3.5, 1e-6);
}

TEST(VCTConeSet, NineIsSeed000sSet) {
    ConeSet set = makeConeSet(ConeSetKind::Nine, 0, 60.0f, ConeWeighting::Cosine);
    ASSERT_EQ(set.cones.size(), 9u);
    expectNormalised(set);
    int corners = 0, sides = 0;
    for (size_t i = 1; i < 9; ++i) {
        double a = angleDeg(set.cones[i].direction, {0, 0, 1});
        if (std::abs(a - 54.7356) < 1e-3) ++corners;
        if (std::abs(a - 45.0) < 1e-3) ++sides;
    }
    EXPECT_EQ(corners, 4) << "the box's top corners";
    EXPECT_EQ(sides, 4) << "the box's sides";
}

TEST(VCTConeSet, CustomCoversTheHemisphereEvenly) {
    for (int n : {1, 4, 16, 32}) {
        ConeSet set = makeConeSet(ConeSetKind::Custom, n, 30.0f, ConeWeighting::Equal);
        ASSERT_EQ(int(set.cones.size()), n);
        expectNormalised(set);
        // Spherical Fibonacci: the mean direction is close to the normal (no lopsided set).
        glm::vec3 mean(0.0f);
        for (const Cone& c : set.cones) mean += c.direction;
        mean /= float(n);
        if (n >= 16) {
            EXPECT_LT(std::hypot(mean.x, mean.y), 0.05f) << n;
        }
    }
}

// For radiance L(w) = 1 the sets return E / pi = 1 exactly (weights sum to one); for the linear
// L(w) = w.z, the exact E / pi is the integral of cos^2 over the hemisphere / pi = 2/3; and a
// radiance varying along the surface, L(w) = w.x, gives 0 by symmetry.
TEST(VCTConeSet, IrradianceOfSimpleRadianceFields) {
    struct Case { ConeSetKind kind; int count; double tolerance; };
    for (Case c : {Case{ConeSetKind::Six, 0, 0.04}, Case{ConeSetKind::Nine, 0, 0.06}, Case{ConeSetKind::Custom, 32, 0.03}}) {
        ConeSet set = makeConeSet(c.kind, c.count, 60.0f, ConeWeighting::Cosine);
        double one = coneSetIrradianceOverPi(set, [](glm::vec3) { return 1.0; });
        double linear = coneSetIrradianceOverPi(set, [](glm::vec3 w) { return double(w.z); });
        double side = coneSetIrradianceOverPi(set, [](glm::vec3 w) { return double(w.x); });
        std::printf("%s: E/pi for L=1 %.4f, L=cos %.4f (exact 0.6667), L=x %.4f\n", enumName(c.kind), one, linear, side);
        EXPECT_NEAR(one, 1.0, 1e-6);
        EXPECT_NEAR(linear / (2.0 / 3.0), 1.0, c.tolerance);
        EXPECT_NEAR(side, 0.0, c.kind == ConeSetKind::Custom ? 0.01 : 1e-5);
    }
}

TEST(VCTConeSet, HemisphereCoverage) {
    double six = coneSetCoverage(makeConeSet(ConeSetKind::Six, 0, 60.0f, ConeWeighting::Cosine));
    double nine = coneSetCoverage(makeConeSet(ConeSetKind::Nine, 0, 60.0f, ConeWeighting::Cosine));
    double narrow = coneSetCoverage(makeConeSet(ConeSetKind::Six, 0, 20.0f, ConeWeighting::Cosine));
    double one = coneSetCoverage(makeConeSet(ConeSetKind::Custom, 1, 60.0f, ConeWeighting::Cosine));
    std::printf("hemisphere covered: six %.3f, nine %.3f, six at 20 deg %.3f, one cone %.3f\n", six, nine, narrow, one);
    // One 60-degree cone covers 1 - cos(30 deg) of the hemisphere exactly.
    EXPECT_NEAR(one, 1.0 - std::cos(glm::radians(30.0)), 0.01);
    // The nine cones overlap more (four sit 45 degrees off the normal), so they cover no more
    // than the six; both leave the grazing band uncovered.
    EXPECT_GT(six, 0.75);
    EXPECT_GT(nine, 0.75);
    EXPECT_LT(narrow, 0.25);
}

TEST(VCTSH, HemisphereProjection) {
    glm::vec3 n = glm::normalize(glm::vec3(0.2f, 0.9f, -0.3f));
    glm::vec4 h = sh::shHemisphere(n);
    // Projection of the indicator of the hemisphere around n, by numerical integration.
    const int steps = 400;
    glm::dvec4 projected(0.0);
    for (int i = 0; i < steps; ++i)
        for (int j = 0; j < 2 * steps; ++j) {
            double z = -1.0 + 2.0 * (i + 0.5) / steps, phi = glm::pi<double>() * (j + 0.5) / steps;
            double r = std::sqrt(std::max(0.0, 1.0 - z * z));
            glm::vec3 w(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
            if (glm::dot(w, n) > 0.0f) projected += glm::dvec4(sh::shBasis(w));
        }
    projected *= 4.0 * glm::pi<double>() / (2.0 * steps * steps);
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(projected[k], h[k], 2e-3) << k;
    EXPECT_NEAR(sh::shEval(h, n), 1.25f, 1e-4f);
}

class VCTGL : public test::GLTest {};

FrameSettings cornellFrame(const Scene& scene, int res) {
    Preset p;
    p.header.technique.name = "vct";
    p.vct.gridResolution = res;
    return frameSettings(p, scene, 64, 48);
}

const VCT& vctOf(const Renderer& r) {
    const VCT* v = dynamic_cast<const VCT*>(r.technique());
    if (!v) throw Error("the renderer holds no VCT");
    return *v;
}

// The first float of texel (x, y, z) in readRGBA's copy of an n^3 level.
size_t idx(int n, int x, int y, int z) { return ((size_t(z) * n + y) * n + x) * 4; }

std::vector<float> readRGBA(const gl::Texture& t, int level) {
    size_t texels = size_t(std::max(t.width() >> level, 1)) * std::max(t.height() >> level, 1) * std::max(t.depth() >> level, 1);
    std::vector<float> v(texels * 4);
    glGetTextureImage(t.id(), level, GL_RGBA, GL_FLOAT, GLsizei(v.size() * 4), v.data());
    return v;
}

// Each mip of a res^3 RGBA volume above level 0 is the mean of its 8 children (fp16 storage).
void expectBoxFilteredMips(const gl::Texture& t, int res, const char* what) {
    std::vector<float> fine = readRGBA(t, 0);
    for (int level = 1; level < vctMipCount(res); ++level) {
        std::vector<float> coarse = readRGBA(t, level);
        int n = res >> level;
        double worst = 0;
        for (int z = 0; z < n; ++z)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x)
                    for (int c = 0; c < 4; ++c) {
                        double mean = 0;
                        for (int k = 0; k < 8; ++k) mean += fine[idx(2 * n, 2 * x + (k & 1), 2 * y + ((k >> 1) & 1), 2 * z + (k >> 2)) + c];
                        mean /= 8.0;
                        worst = std::max(worst, std::abs(coarse[idx(n, x, y, z) + c] - mean) / std::max(1.0, std::abs(mean)));
                    }
        EXPECT_LT(worst, 2e-3) << what << " mip " << level;
        fine = coarse;
    }
}

std::vector<uint32_t> readPacked(const gl::Texture& t) {
    std::vector<uint32_t> v(size_t(t.width()) * t.height() * t.depth());
    glGetTextureImage(t.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, GLsizei(v.size() * 4), v.data());
    return v;
}

// Every mip texel is the mean of its 8 children (isotropic), and every anisotropic texel is the
// mean over 4 child pairs of front + (1 - front.a) * back along its direction. Without face sides,
// so that the atlas's mip 0 is the base level copied (with them it holds the sides, whose mips
// the same composite builds; the centroid volume is checked below).
TEST_F(VCTGL, MipsAreConsistent) {
    Scene scene = makeBuiltinScene("cornell");
    FrameSettings fs = cornellFrame(scene, 32);
    fs.vct.faceSides = false;
    Renderer r;
    r.setScene(scene);
    r.render(fs);
    const VCT& v = vctOf(r);
    const auto& radiance = v.levels()[0].radiance;
    int res = v.resolution();
    std::vector<float> fine = readRGBA(radiance, 0);
    size_t occupied = 0;
    for (size_t i = 3; i < fine.size(); i += 4) occupied += fine[i] > 0.5f;
    EXPECT_GT(occupied, size_t(res * res * 4)) << "the cornell box's six walls are voxelized";
    expectBoxFilteredMips(radiance, res, "radiance");
    // Anisotropic: the six directions side by side along x in one atlas (slab d starts at x = d n).
    // Its mip 0 is the base level in every slab; each mip above from the one below, for every
    // direction: along the direction, front + (1 - front.a) * back over the 4 child pairs, averaged.
    const gl::Texture& atlas = v.anisotropicAtlas();
    ASSERT_EQ(atlas.width(), 6 * res);
    ASSERT_EQ(atlas.height(), res);
    auto atlasIdx = [](int n, int d, int x, int y, int z) { return ((size_t(z) * n + y) * 6 * n + size_t(d) * n + x) * 4; };
    std::vector<float> base = readRGBA(radiance, 0);
    std::vector<std::vector<float>> atlasMips = {readRGBA(atlas, 0), readRGBA(atlas, 1), readRGBA(atlas, 2)};
    for (int d = 0; d < 6; ++d) {
        double copied = 0;
        for (int z = 0; z < res; ++z)
            for (int y = 0; y < res; ++y)
                for (int x = 0; x < res; ++x)
                    for (int c = 0; c < 4; ++c)
                        copied = std::max(copied, double(std::abs(atlasMips[0][atlasIdx(res, d, x, y, z) + size_t(c)] -
                                                                  base[idx(res, x, y, z) + size_t(c)])));
        EXPECT_EQ(copied, 0.0) << "anisotropic direction " << d << ": mip 0 is the base level";
        for (int level : {1, 2}) {
            int n = res >> level, axis = d / 2;
            bool positive = d % 2 == 0;
            // The source texel of child c: the atlas slab one mip down.
            auto child = [&](glm::ivec3 c) {
                const float* t = &atlasMips[size_t(level - 1)][atlasIdx(2 * n, d, c.x, c.y, c.z)];
                return glm::dvec4(t[0], t[1], t[2], t[3]);
            };
            const std::vector<float>& dest = atlasMips[size_t(level)];
            double worst = 0, largest = 0;
            for (int z = 0; z < n; ++z)
                for (int y = 0; y < n; ++y)
                    for (int x = 0; x < n; ++x) {
                        glm::dvec4 sum(0.0);
                        for (int k = 0; k < 8; ++k) {
                            glm::ivec3 c(2 * x + (k & 1), 2 * y + ((k >> 1) & 1), 2 * z + (k >> 2));
                            if (c[axis] % 2 == 1) continue;  // visit each pair from its lower child
                            glm::ivec3 c2 = c;
                            c2[axis] += 1;
                            glm::dvec4 lo = child(c), hi = child(c2);
                            glm::dvec4 nearer = positive ? lo : hi, farther = positive ? hi : lo;
                            sum += nearer + (1.0 - nearer.w) * farther;
                        }
                        for (int c = 0; c < 4; ++c) {
                            worst = std::max(worst, std::abs(dest[atlasIdx(n, d, x, y, z) + size_t(c)] - 0.25 * sum[c]) /
                                                        std::max(1.0, std::abs(0.25 * sum[c])));
                            largest = std::max(largest, 0.25 * sum[c]);
                        }
                    }
            EXPECT_LT(worst, 2e-3) << "anisotropic direction " << d << " mip " << level;
            EXPECT_GT(largest, 0.01) << "anisotropic direction " << d << " mip " << level << " is empty";
        }
    }
}

// Face sides' centroid volume (resolve.comp): at mip 0 where each occupied voxel's surface lies,
// in voxels (the position volume), times its opacity (1) and the opacity, 0 elsewhere; each mip
// above the mean of its 8 children, so a texel's rgb / a is the mean position of the surfaces it
// holds.
TEST_F(VCTGL, CentroidsAreTheMeanPositionOfTheSurfaces) {
    Scene scene = makeBuiltinScene("cornell");
    FrameSettings fs = cornellFrame(scene, 32);
    fs.vct.faceSides = true;
    Renderer r;
    r.setScene(scene);
    r.render(fs);
    const VCT& v = vctOf(r);
    int res = v.resolution();
    const gl::Texture& centroid = v.centroidVolume();
    ASSERT_EQ(centroid.width(), res);
    std::vector<float> opacity = readRGBA(v.levels()[0].radiance, 0), fine = readRGBA(centroid, 0);
    // Where each voxel's surface lies in it (voxelize.frag's position volume: RGBA8, 0 to 1 per axis).
    std::vector<uint32_t> position = readPacked(v.levels()[0].surface.position);
    double worst = 0, offCentre = 0;
    size_t occupied = 0;
    for (int z = 0; z < res; ++z)
        for (int y = 0; y < res; ++y)
            for (int x = 0; x < res; ++x) {
                float a = opacity[idx(res, x, y, z) + 3];
                occupied += a > 0.5f;
                uint32_t packed = position[size_t(idx(res, x, y, z)) / 4];
                glm::vec3 inside(glm::unpackUnorm4x8(packed));
                if (a > 0.5f) offCentre = std::max(offCentre, double(glm::length(inside - 0.5f)));
                glm::vec4 expected(glm::vec3(x, y, z) + inside, 1.0f);
                expected *= a;
                for (int c = 0; c < 4; ++c) worst = std::max(worst, double(std::abs(fine[idx(res, x, y, z) + size_t(c)] - expected[c])));
            }
    EXPECT_GT(occupied, size_t(res * res * 4)) << "the cornell box's six walls are voxelized";
    EXPECT_GT(offCentre, 0.25) << "the box's walls do not all lie at their voxels' centres";
    EXPECT_LT(worst, 0.02) << "mip 0: where the voxel's surface lies, times the opacity (fp16 storage)";
    expectBoxFilteredMips(centroid, res, "centroid");
}

// The grid is static: a second frame with the same scene and grid does not voxelize again.
TEST_F(VCTGL, StaticGridIsVoxelizedOnce) {
    Scene scene = makeBuiltinScene("cornell");
    FrameSettings fs = cornellFrame(scene, 32);
    Renderer r;
    r.setScene(scene);
    r.render(fs);
    r.render(fs);
    EXPECT_EQ(vctOf(r).voxelizationCount(), 1);
    fs.vct.levelExtent = 3.0f;  // a new grid placement
    r.render(fs);
    EXPECT_EQ(vctOf(r).voxelizationCount(), 2);
}

// Issue 17 item 4: static geometry under static lights keeps the lit volumes (injection, mips,
// bounces). A camera move keeps them, with the pixels of a renderer that relights every frame; a
// moved light, a VCT setting, the shadow maps' size and keepStaticWork off each relight.
TEST_F(VCTGL, LitVolumesAreKeptUnderStaticLights) {
    Scene scene = makeBuiltinScene("cornell");
    FrameSettings fs = cornellFrame(scene, 32);
    fs.vct.bounceCount = 2;
    Renderer r;
    r.setScene(scene);
    r.render(fs);
    r.render(fs);
    EXPECT_EQ(vctOf(r).lightingCount(), 1) << "static lights light the volumes once";
    FrameSettings turned = fs;
    turned.camera.eye += glm::vec3(0.3f, -0.2f, 0.0f);
    r.render(turned);
    EXPECT_EQ(vctOf(r).lightingCount(), 1) << "a camera move keeps them";
    EXPECT_EQ(r.readIndirectRadiance(), test::renderedAfresh(scene, turned)->readIndirectRadiance())
        << "kept volumes give the pixels relit ones do";

    FrameSettings moved = turned;
    moved.lights[0].position += glm::vec3(0.2f, 0.0f, 0.0f);
    std::vector<float> before = r.readIndirectRadiance();
    r.render(moved);
    EXPECT_EQ(vctOf(r).lightingCount(), 2) << "a moved light relights them";
    EXPECT_NE(r.readIndirectRadiance(), before);
    FrameSettings brighter = moved;
    brighter.vct.nudge += 0.5f;
    r.render(brighter);
    EXPECT_EQ(vctOf(r).lightingCount(), 3) << "a VCT setting relights them";
    brighter.render.shadowMapSize /= 2;
    r.render(brighter);
    EXPECT_EQ(vctOf(r).lightingCount(), 4) << "shadow maps of another size relight them";
    brighter.render.keepStaticWork = false;
    r.render(brighter);
    r.render(brighter);
    EXPECT_EQ(vctOf(r).lightingCount(), 6) << "keepStaticWork off: every frame";
}

// Voxels of every level in logical order (toroidal addressing undone).
std::vector<std::vector<uint32_t>> logicalAlbedo(const VCT& v) {
    std::vector<std::vector<uint32_t>> out;
    int n = v.resolution();
    for (const auto& level : v.levels()) {
        std::vector<uint32_t> physical = readPacked(level.surface.albedo), logical(physical.size());
        glm::ivec3 wrap = ((level.box.origin % n) + n) % n;
        for (int z = 0; z < n; ++z)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    glm::ivec3 t = (glm::ivec3(x, y, z) + wrap) % n;
                    logical[(size_t(z) * n + y) * n + x] = physical[(size_t(t.z) * n + t.y) * n + t.x];
                }
        out.push_back(std::move(logical));
    }
    return out;
}

TEST_F(VCTGL, ToroidalUpdateEqualsFullVoxelization) {
    Scene scene = makeBuiltinScene("cornell");
    FrameSettings fs = cornellFrame(scene, 32);
    fs.vct.mode = VCTMode::Clipmap;
    fs.vct.levelCount = 2;
    fs.vct.levelExtent = 1.5f;
    fs.camera.eye = {0.1f, 1.0f, 0.3f};
    fs.camera.target = {0.1f, 1.0f, -1.0f};
    Renderer moved;
    moved.setScene(scene);
    moved.render(fs);
    // Move by a few voxels of the finest level along every axis (both signs).
    float cell = 1.5f / 32.0f;
    fs.camera.eye += glm::vec3(3.2f * cell, -2.1f * cell, 5.4f * cell);
    fs.camera.target += glm::vec3(3.2f * cell, -2.1f * cell, 5.4f * cell);
    moved.render(fs);
    const VCT& partial = vctOf(moved);
    size_t full = size_t(32) * 32 * 32;
    ASSERT_GT(partial.voxelizedVoxels()[0], 0u) << "the finest level moved";
    EXPECT_LT(partial.voxelizedVoxels()[0], full / 2) << "only the exposed slabs are voxelized";
    Renderer fresh;
    fresh.setScene(scene);
    fresh.render(fs);
    auto a = logicalAlbedo(partial), b = logicalAlbedo(vctOf(fresh));
    ASSERT_EQ(a.size(), b.size());
    for (size_t k = 0; k < a.size(); ++k) {
        EXPECT_EQ(partial.levels()[k].box.origin, vctOf(fresh).levels()[k].box.origin);
        size_t occupancyDiffers = 0, colourDiffers = 0, occupied = 0;
        for (size_t i = 0; i < a[k].size(); ++i) {
            bool oa = (a[k][i] >> 24) != 0, ob = (b[k][i] >> 24) != 0;
            occupied += ob;
            if (oa != ob) ++occupancyDiffers;
            else if (oa)
                for (int c = 0; c < 3; ++c)
                    if (std::abs(int((a[k][i] >> (8 * c)) & 255u) - int((b[k][i] >> (8 * c)) & 255u)) > 2) {
                        ++colourDiffers;
                        break;
                    }
        }
        std::printf("level %zu: %zu occupied voxels, %zu differ in occupancy, %zu in colour\n", k, occupied, occupancyDiffers,
                    colourDiffers);
        EXPECT_GT(occupied, 100u);
        EXPECT_EQ(occupancyDiffers, 0u) << "level " << k;
        EXPECT_EQ(colourDiffers, 0u) << "level " << k;
    }
}

// A floor lit only by a large white panel above it: without face sides and without a nudge the
// cones start inside the floor's own voxels and are blocked by them; with the nudge they reach
// the panel and the floor receives what the panel's underside sends it. With face sides a
// sample drops what lies in the receiver's own plane (trace.glsl), so the floor gathers the
// panel's light at any nudge. The underside is lit from below, as the
// reference would need it to be to light the floor: a spot 0.1 above the floor's centre (1.5
// voxels, so the floor's voxel centres lie behind it too) points straight up (outer cone 89
// degrees, so the floor stays unlit, and no shadow map, which a cone that wide could not have).
// An emissive panel would not do: emitters reach VCT as area lights, which light other voxels,
// not their own. (Before issue 13's leak work the panel
// was lit on top and the floor saw it only because isotropic voxels glow on both sides.)
TEST_F(VCTGL, NudgeRemovesSelfOcclusionOnAFlatFloor) {
    Scene scene;
    MeshBuilder b(scene);
    int floor = b.material("floor", glm::vec3(0.8f), 1.0f);
    int panel = b.material("panel", glm::vec3(1.0f), 1.0f);
    const double side = 4.0, height = 1.0, floorSide = 3.6, lamp = 0.1;
    b.quad(floor, {-floorSide / 2, 0, floorSide / 2}, {floorSide, 0, 0}, {0, 0, -floorSide});
    b.quad(panel, {-side / 2, height, -side / 2}, {side, 0, 0}, {0, 0, side});
    scene.finalize();
    Preset p;
    p.header.technique.name = "vct";
    p.vct.gridResolution = 64;
    p.vct.specularCone = false;
    p.vct.traceScale = 1.0f;
    p.vct.coneSet = ConeSetKind::Nine;
    FrameSettings fs = frameSettings(p, scene, 32, 32);
    LightSettings spot;
    spot.type = LightType::Spot;
    spot.position = {0.0f, float(lamp), 0.0f};
    spot.direction = {0.0f, 1.0f, 0.0f};
    spot.innerConeDeg = 88.0f;
    spot.outerConeDeg = 89.0f;
    spot.castShadows = false;
    const double h = height - lamp;                       // lamp to panel
    spot.intensity = float(glm::pi<double>() * h * h);  // the panel (albedo 1) leaves radiance 1 above the lamp
    fs.lights = {spot};
    fs.camera.eye = {0.0f, 0.6f, 0.0f};
    fs.camera.target = {0.0f, 0.0f, 0.0f};
    fs.camera.up = {0.0f, 0.0f, -1.0f};
    fs.camera.fovY = 20.0f;
    fs.vct.bounceCount = 1;  // one bounce, as the analytic value and the reference below count it
    fs.vct.faceSides = false;  // first without face sides (which are the defaults)
    Renderer r;
    r.setScene(scene);
    // The panel's radiance at (x, z): albedo / pi * I cos / r^2 = I h / (pi r^3), r from the lamp
    // (every point lies inside the inner cone: the corners are 70.9 degrees off the axis). The
    // floor's centre, `height` below, then receives E = integral of L cos^2 / d^2 dA = L height^2
    // / d^4 dA, d from the floor's centre, and leaves 0.8 E / pi: integrated over a fine grid.
    const int n = 800;
    double cell = side / n, integral = 0.0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            double x = -side / 2 + (i + 0.5) * cell, z = -side / 2 + (j + 0.5) * cell, q = x * x + z * z;
            double radiance = spot.intensity * h / (glm::pi<double>() * std::pow(q + h * h, 1.5));
            integral += radiance * height * height / std::pow(q + height * height, 2.0) * cell * cell;
        }
    double expected = 0.8 * integral / glm::pi<double>();
    // The path tracer agrees with the integral (one bounce of indirect light, as VCT gathers it).
    bool cached = false;
    double reference = test::referenceOneBounceIndirect(scene, fs, &cached);
    std::printf("floor indirect: analytic %.4f, reference %.4f (%s)\n", expected, reference, cached ? "cached" : "rendered");
    EXPECT_NEAR(reference / expected, 1.0, 0.05);
    std::vector<double> lit;
    for (float nudge : {0.0f, 1.0f, 2.0f, 3.0f, 4.0f}) {
        fs.vct.nudge = nudge;
        lit.push_back(test::meanIndirect(r, fs));
        std::printf("floor indirect at nudge %.0f: %.4f (%.0f %% of the analytic %.4f)\n", nudge, lit.back(),
                    100.0 * lit.back() / expected, expected);
    }
    EXPECT_LT(lit[0], 0.1 * expected) << "without a nudge the floor's own voxels block its cones";
    // Up to the default nudge (3) each step frees more of the cones; beyond it the floor no
    // longer blocks them (nudge 4 gathers within 5 % of nudge 3).
    const int defaultNudge = int(VCTSettings{}.nudge);
    ASSERT_EQ(defaultNudge, 3);
    for (int i = 1; i <= defaultNudge; ++i) EXPECT_GT(lit[i], lit[i - 1]) << "a larger nudge frees more of the cones";
    EXPECT_NEAR(lit[4] / lit[3], 1.0, 0.05) << "past the default nudge the floor should no longer self-occlude";
    // What is missing is the trace's: with the cones sampling kVCTFootprintLod finer than their
    // width it gathers 89 % at nudge 3 (43 % when the texel was as wide as the cone, as before
    // issue 13); one voxel thin and 16 voxels away, the panel still falls between the coarse
    // samples a little.
    EXPECT_GT(lit[3] / expected, 0.75);
    EXPECT_LT(lit[3] / expected, 1.25);
    fs.vct.faceSides = true;
    for (float nudge : {0.0f, 1.0f, 2.0f, 3.0f, 4.0f}) {
        fs.vct.nudge = nudge;
        double sides = test::meanIndirect(r, fs);
        std::printf("face sides: floor indirect at nudge %.0f: %.4f (%.0f %% of the analytic %.4f)\n", nudge, sides,
                    100.0 * sides / expected, expected);
        // Where the samples fall on the one-voxel panel 16 voxels away moved it from 74 to 109 %
        // before the screen trace staggered them by pixel (traceCone's phase, trace.glsl); 90 % at
        // each since.
        EXPECT_GT(sides / expected, 0.7) << "nudge " << nudge << ": the floor's own plane blocks nothing";
        EXPECT_LT(sides / expected, 1.25) << "nudge " << nudge;
    }
}

// The sky through the cones (issue 13 item 2): an open floor under a constant environment of
// radiance 1 has E / pi = 1, which technique none's irradiance map gives exactly (times the
// floor's albedo 0.8); the same floor inside a closed box must gather no sky. The scene has no
// light, so everything the floor gathers is sky. Without face sides VCT gathers 55 % of the open
// sky (measured): its oblique cones (45 and 55 degrees from the normal) keep sampling the floor's
// own voxels, since a mip texel's trilinear sample reaches 1.5 of its texels from the sample (half
// a texel for where the floor sits in its texel, one of filter), more than their height above
// the floor at every step; the vertical cone keeps 76 % of its transparency. Capping the footprint
// by the height above the receiver removed that (100 % of the sky) but let 20 % through the closed
// box's one-voxel walls, which the self-occlusion had hidden, so it is not done. Face sides (the
// defaults) drop the receiver's own plane instead, and gather 100 % of the open sky; through
// the closed box's walls they let 7.9 % of it through (bound 10 %), as the mean of the four
// sample phases the screen trace staggers its pixels by (traceCone's phase, trace.glsl): each phase
// alone lets 11.3, 5.7, 4.5 and 9.9 % through, and the unstaggered one, which every pixel used
// before, 3.9 %. The vertical cone lets most through (12.7 % of its sky against 6.9 % for the
// others): its samples straddle the one-voxel ceiling 16 voxels up, each some way from it in
// texels two voxels or more wide.
TEST_F(VCTGL, ConesThatEndUnoccludedSeeTheSky) {
    auto frame = [](const Scene& scene, const std::string& technique, bool faceSides) {
        FrameSettings fs = test::skyFrame(scene, technique);
        fs.vct.gridResolution = 64;
        fs.vct.specularCone = false;
        fs.vct.faceSides = faceSides;
        return fs;
    };
    Scene open = test::openFloor(), closed = test::closedBox();
    Renderer r;
    r.setScene(open);
    double none = test::meanIndirect(r, frame(open, "none", true));
    EXPECT_NEAR(none, 0.8, 0.02) << "the irradiance map of a constant sky of radiance 1";
    ASSERT_TRUE(VCTSettings{}.faceSides) << "the defaults this test describes";
    for (bool sides : {true, false}) {
        r.setScene(open);
        double vct = test::meanIndirect(r, frame(open, "vct", sides));
        r.setScene(closed);
        double inside = test::meanIndirect(r, frame(closed, "vct", sides));
        std::printf("%s: open floor under a constant sky: none %.4f, vct %.4f (%.0f %%); inside a closed box: vct %.5f (%.1f %%)\n",
                    sides ? "face sides" : "without face sides", none, vct, 100.0 * vct / none, inside, 100.0 * inside / none);
        EXPECT_GT(vct / none, sides ? 0.9 : 0.45) << "the cones should see the open sky";
        EXPECT_LT(vct / none, 1.05) << "more than the sky's irradiance";
        EXPECT_LT(inside, (sides ? 0.10 : 0.05) * none) << "no sky inside a closed box";
    }
}

// A closed room of one-sided walls under the sun: the sun reaches only the back of the ceiling,
// outside, so the path tracer's room is dark. A voxel's back counts only as far as its fragments
// face back (inject.comp and bounce.comp, backWeight): a one-sided ceiling's voxels have none, so
// the sunlight on their backs stays out of the room, where their isotropic radiance used to carry
// it (a room lit through a window took 3x the reference's brightness from its sunlit roof). The
// scale: the same room lit from inside by a point light. Face sides weigh a voxel's back sides
// the same way (inject.comp, injectSides): the voxelizer gives every surface both faces, and the
// sunlit outer faces of the walls, read through coarse mips whose texels straddle the room's
// corners, lit its edges (5.2 % of the point light's indirect light without the weight, 0.04 %
// with it).
TEST_F(VCTGL, ASunOnTheRoofDoesNotLightTheRoomBelow) {
    Scene room = test::closedRoom();
    Preset p;
    p.header.technique.name = "vct";
    FrameSettings fs = frameSettings(p, room, 64, 48);
    fs.camera.eye = {1.5f, 1.5f, 1.5f};
    fs.camera.target = {-1.0f, 1.0f, -1.0f};
    fs.camera.fovY = 70.0f;
    LightSettings sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    sun.intensity = 5.0f;
    Renderer r;
    r.setScene(room);
    for (bool sides : {false, true}) {
        fs.vct.faceSides = sides;
        fs.lights = {sun};
        double outside = test::meanIndirect(r, fs);
        fs.lights = {test::pointLight({0.0f, 1.5f, 0.0f}, 20.0f)};
        double inside = test::meanIndirect(r, fs);
        std::printf("%s: indirect light in the room: the sun on the roof %.5f, a point light inside %.5f (%.2f %%)\n",
                    sides ? "face sides" : "without face sides", outside, inside, 100.0 * outside / inside);
        EXPECT_GT(inside, 0.0);
        EXPECT_LT(outside, 0.01 * inside) << (sides ? "face sides: the walls' sunlit outer faces light the room"
                                                    : "the sunlit backs of the ceiling's voxels light the room");
    }
}

// The two-room scene (issue 13 item 6): the closed room's indirect light over the lit room's.
// Without face sides (isotropic content, the same in every direction; the defaults before face
// sides became them) it is 60 %: the shared wall lies on a voxel boundary and is voxelized into
// column 32, on the dark side, which then shows its lit face to the dark room (68 % of the leak
// when it was 35 %, measured by zeroing the radiance, not the opacity, of voxel columns; with
// columns 31-32 zeroed 6 % remained, sent through the coarse mips whose texels straddle the wall).
// The defaults (face sides, the tail, three bounces) leak 4.1 %, under issue 13's 5 %. They leaked
// 6.1 % while a cone's start was divided by n.w with face sides too, which started the grazing
// cones of the dark room's surfaces near the wall past it (vctConeStart, vct_shared.h); then 2.6 %
// with one bounce, 3.8 % with two and no tail, 5.2 % with two and the tail (4.9 % before the screen
// trace staggered its samples by traceCone's phase in trace.glsl, which also darkened the lit
// room 9 %: the phase every pixel had sampled at was a bright one there). In the dark room the leaked light
// lies along the shared wall's edges: floor, ceiling and side walls gather the lit room's floor,
// ceiling and walls through mip texels that straddle the wall, which an edge-on wall does not
// occlude. Not at every alignment of the wall either (the next test). SH voxels, which radiate
// each side as a hemisphere, put less than half as much light in the dark room as isotropic
// ones, but their lit room is darker still. GI_TEST_IMAGES (test_util.h) writes the pictures.
TEST_F(VCTGL, TwoRoomLeak) {
    Scene scene = test::twoRooms();
    Preset p;
    p.header.technique.name = "vct";
    p.vct.gridResolution = 64;
    p.vct.specularCone = false;
    FrameSettings fs = frameSettings(p, scene, 96, 64);
    ASSERT_TRUE(fs.vct.faceSides && fs.vct.bounceTail) << "the defaults this test describes";
    Renderer r;
    r.setScene(scene);
    double dark = 0.0;
    auto leak = [&](const char* label) {
        test::lookIntoClosedRoom(fs.camera);
        dark = test::meanIndirect(r, fs);
        // The lit room, looking away from the shared wall (its surfaces there are lit indirectly).
        fs.camera.eye = {-0.1f, 1.0f, 0.0f};
        fs.camera.target = {-2.0f, 0.8f, 0.0f};
        double lit = test::meanIndirect(r, fs);
        std::printf("%s: indirect in the dark room %.5f, in the lit room %.5f: leak %.1f %%\n", label, dark, lit, 100.0 * dark / lit);
        EXPECT_GT(lit, 0.0) << label;
        return dark / lit;
    };
    double defaults = leak("defaults (face sides, the tail, three bounces)");
    fs.vct.faceSides = false;
    fs.vct.bounceTail = false;
    double plain = leak("without face sides and the tail");
    double darkPlain = dark;
    EXPECT_LT(defaults, 0.05) << "issue 13 item 6: the defaults' closed room under 5 % of the lit room's indirect light";
    EXPECT_LT(defaults, 0.15 * plain) << "face sides should keep the shared wall's lit face out of the dark room";
    fs.vct.sh = true;
    leak("SH voxels");
    EXPECT_LT(dark, 0.5 * darkPlain) << "SH voxels should put less than half the light of isotropic content in the dark room";
}

// The same at every alignment of the shared wall in the grid: the scene moved by 0, 0.25, 0.5
// and 0.75 of a voxel along x under a grid that stays put (two tiny black quads two voxels
// outside the rooms fix the bounds), as DiffusionGL.TheClosedRoomStaysDarkWhereverTheWallFalls
// does. Face sides with the tail (the defaults) leak 4.9, 21.2, 20.3 and 19.5 % (7.4, 24.5, 23.8
// and 23.0 % while their cones' start was divided by n.w, vctConeStart in vct_shared.h; 7.6, 26.0,
// 24.2 and 21.4 % before the screen trace staggered their samples, traceCone's phase), isotropic
// content 68.1, 64.8, 61.2 and 57.4 % (issue 13's 5 % is not met at any of them; before injection
// moved to the surfaces and to three bounces: 6.3, 25.5, 24.2 and 21.3 %, and 38.8, 60.7, 57.3
// and 53.1 %).
// Away from a voxel boundary the wall shares its voxel column with pieces of the floor, ceiling
// and side walls from both rooms, whose mean light that column then shows to both, and a
// one-voxel wall lets part of a cone through between its
// samples. Thicker walls were tried: kVCTSideMargin 0.25 leaked 6.6, 14.7, 23.5 and 18.0 % but
// the flat floor of the nudge test then gathered 120-133 % of the analytic light; 0.5 (every
// surface in two voxels) 6.4, 6.2, 10.3 and 18.6 % but cost vct_sponza 0.033 SSIM. Neither the
// nudge (1, 2) nor a shorter step (0.5, 0.75) changed the leak by more than 4 points. Where the
// face sides' leak comes from, at the wall's 0 / 0.25 / 0.5 / 0.75 voxel: with the radiance of
// every sample centred beyond the wall zeroed for apexes in the closed room, 1.7 / 11.6 / 11.2 /
// 9.5 % remain, so about half passes the wall inside the cones and half comes from samples on the
// closed side whose footprint holds the wall's column. Also tried, each under 5 points of change
// at the misaligned walls: opacity taken additively until a cone is opaque (a thin sheet split
// across two trilinear samples sums to its opacity, where compositing lets 25 % through), with
// the step correction linear to match (3.5 / 21.3 / 20.1 / 17.1 %); samples snapped to texel
// centres along the cone's dominant axis (6.4 / 27.2 / 26.0 / 24.2 %); that and whole mips
// (6.5 / 16.1 / 14.3 / 12.8 %).
TEST_F(VCTGL, FaceSidesCutTheLeakWhereverTheWallFalls) {
    Preset p;
    p.header.technique.name = "vct";
    p.vct.specularCone = false;
    const glm::vec3 size = test::twoRooms().bounds.max - test::twoRooms().bounds.min;
    const test::AnchoredRooms rooms = test::anchoredTwoRooms(2.0f * std::max(size.x, std::max(size.y, size.z)) / float(p.vct.gridResolution));
    for (float shift : {0.0f, 0.25f, 0.5f, 0.75f}) {
        Renderer r;
        r.setScene(rooms.scene);
        r.render(frameSettings(p, rooms.scene, 96, 64));
        const VoxelBox box = vctOf(r).levels()[0].box;
        const glm::vec3 offset(shift * box.cellSize, 0.0f, 0.0f);
        Scene scene = rooms.moved(offset);
        r.setScene(scene);
        double leak[2];
        for (int sides = 0; sides < 2; ++sides) {
            FrameSettings fs = frameSettings(p, scene, 96, 64);
            fs.vct.faceSides = fs.vct.bounceTail = sides == 1;
            test::RoomsIndirect light = test::twoRoomsIndirect(r, fs, offset);
            ASSERT_NEAR(vctOf(r).levels()[0].box.cellSize, box.cellSize, 1e-6f) << "the anchors hold the grid";
            ASSERT_NEAR(vctOf(r).levels()[0].box.min.x, box.min.x, 1e-5f) << "the anchors hold the grid";
            ASSERT_GT(light.lit, 0.0);
            leak[sides] = light.closed / light.lit;
        }
        std::printf("wall at voxel x %.2f: leak %.1f %% without face sides, %.1f %% with face sides (the defaults)\n",
                    (offset.x - box.min.x) / box.cellSize, 100.0 * leak[0], 100.0 * leak[1]);
        EXPECT_LT(leak[1], 0.5 * leak[0]) << "wall moved " << shift << " voxel";
    }
}

// Shift invariance (issue 13 item 5): the cornell box, its light and the camera moved together
// by 0.25, 0.5 and 0.75 of a voxel along the diagonal, under a grid that stays put (two tiny black
// triangles well outside the box fix the scene's bounds, so the dense grid does not follow), keep
// the mean indirect light of the view within 5 %: injection and the cones must not depend on
// where a wall falls inside its voxels.
TEST_F(VCTGL, IndirectLightDoesNotDependOnWhereTheSceneFallsInTheGrid) {
    Preset p;
    p.header.technique.name = "vct";
    double base = 0.0;
    glm::vec3 gridMin(0.0f);
    for (float shift : {0.0f, 0.25f, 0.5f, 0.75f}) {
        Scene scene = makeBuiltinScene("cornell");
        MeshBuilder b(scene);
        int anchor = b.material("anchor", glm::vec3(0.0f), 1.0f);
        b.quad(anchor, {-1.6f, -0.6f, -1.6f}, {1e-3f, 0, 0}, {0, 1e-3f, 0});
        b.quad(anchor, {1.6f, 2.6f, 1.6f}, {-1e-3f, 0, 0}, {0, -1e-3f, 0});
        FrameSettings fs = frameSettings(p, scene, 128, 96);
        float cell = 3.2f * 1.02f / float(fs.vct.gridResolution);  // vctLevels: the bounds' cube, 2 % larger
        glm::vec3 offset(shift * cell);
        size_t anchorVertices = 8;  // the two anchor quads, added last
        for (size_t i = 0; i + anchorVertices < scene.vertices.size(); ++i) scene.vertices[i].position += offset;
        for (LightSettings& l : scene.lights) l.position += offset;
        scene.finalize();
        fs = frameSettings(p, scene, 128, 96);
        fs.camera.eye += offset;
        fs.camera.target += offset;
        Renderer r;
        r.setScene(scene);
        double mean = test::meanIndirect(r, fs);
        const VoxelBox& box = vctOf(r).levels()[0].box;
        ASSERT_NEAR(box.cellSize, cell, 1e-5f) << "the anchors set the grid";
        if (shift == 0.0f) {
            base = mean;
            gridMin = box.min;
        }
        EXPECT_LT(glm::length(box.min - gridMin), 1e-5f) << "the grid stays put while the scene moves";
        std::printf("shift %.2f voxel: mean indirect %.5f (%+.2f %%)\n", shift, mean, 100.0 * (mean / base - 1.0));
        EXPECT_GT(mean, 0.0);
        EXPECT_NEAR(mean / base, 1.0, 0.05) << "shift of " << shift << " voxel";
    }
}

TEST(VCTBudget, HugeGridsAreRefusedBeforeAllocation) {
    Scene scene = makeBuiltinScene("cornell");
    Preset p;
    p.header.technique.name = "vct";
    p.vct.gridResolution = 256;
    p.vct.mode = VCTMode::Clipmap;
    p.vct.levelCount = 6;
    FrameSettings fs = frameSettings(p, scene, 64, 48);
    try {
        Renderer::checkBudget(fs, scene);
        FAIL() << "expected the budget to refuse " << VCT::estimateBytes(fs) / (1 << 20) << " MiB";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("vct"), std::string::npos) << e.what();
    }
    p.vct.levelCount = 1;
    EXPECT_NO_THROW(Renderer::checkBudget(frameSettings(p, scene, 64, 48), scene));
    // Out-of-range settings name the key.
    try {
        applySetting(p, "vct.gridResolution=4096");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("gridResolution"), std::string::npos) << e.what();
    }
}

// VAO: at strength 0 it changes nothing; at strength 1 it darkens the indirect light (the
// cornell box's corners and the blocks' feet occlude the cones), and a shorter occlusion range
// darkens less.
TEST_F(VCTGL, VAOScalesTheIndirectLightByTheConesVisibility) {
    Scene scene = makeBuiltinScene("cornell");
    FrameSettings fs = cornellFrame(scene, 32);
    Renderer r;
    r.setScene(scene);
    double off = test::meanIndirect(r, fs);
    fs.vct.vao = true;
    fs.vct.vaoStrength = 0.0f;
    double zero = test::meanIndirect(r, fs);
    fs.vct.vaoStrength = 1.0f;
    double full = test::meanIndirect(r, fs);
    fs.vct.vaoDistance = 0.6f;  // the cones start 0.33 m out (nudge 3 voxel diagonals of 0.11 m)
    double near = test::meanIndirect(r, fs);
    std::printf("mean indirect: VAO off %.5f, strength 0 %.5f, strength 1 %.5f, strength 1 within 0.6 m %.5f\n", off, zero, full,
                near);
    EXPECT_NEAR(zero, off, 1e-6 + 1e-4 * off);
    EXPECT_LT(full, 0.9 * off);
    EXPECT_GT(near, full);
    EXPECT_LT(near, off);
}

// Face sides take the bounced light too: bounce.comp adds each side's gathered light to the
// atlas's mip 0 (sidesBounced), so a second bounce brightens a closed box with face sides about
// as much as with isotropic voxels. Before, the sides held direct light only and the second
// bounce changed nothing that the cones read.
TEST_F(VCTGL, FaceSidesTakeTheBouncedLight) {
    Scene scene = makeBuiltinScene("cornell");
    FrameSettings fs = cornellFrame(scene, 32);
    Renderer r;
    r.setScene(scene);
    double gain[2];
    for (int sides = 0; sides < 2; ++sides) {
        fs.vct.faceSides = sides == 1;
        fs.vct.bounceCount = 1;
        double one = test::meanIndirect(r, fs);
        fs.vct.bounceCount = 2;
        double two = test::meanIndirect(r, fs);
        gain[sides] = two / one;
        std::printf("%s: mean indirect %.5f at one bounce, %.5f at two (x%.3f)\n", sides ? "face sides" : "isotropic", one, two,
                    gain[sides]);
    }
    EXPECT_GT(gain[1], 1.1) << "the second bounce should reach the face sides";
    EXPECT_GT(gain[1], 0.5 * gain[0]);
}

// Issue 17 item 3: the screen trace counts its work (VCT::report). In a view that surfaces fill,
// every pixel is traced with the diffuse set and the specular cone; the isotropic volume takes one
// texture call a sample, the anisotropic atlas three (its mip 0 is level 0, so no sample reads
// beside it), the SH volumes four; half the step takes more samples (not twice: most cones here end
// opaque on a wall within three steps), and a cone that ends sooner fewer.
TEST_F(VCTGL, TraceCountsItsWork) {
    Scene scene = test::twoRooms();
    Preset p;
    p.header.technique.name = "vct";
    p.vct.gridResolution = 32;
    FrameSettings fs = frameSettings(p, scene, 64, 48);
    fs.vct.traceScale = 1.0f;
    fs.vct.specularCone = true;
    fs.vct.faceSides = false;  // the plain atlas first; face sides below
    test::lookIntoClosedRoom(fs.camera);
    Renderer r;
    r.setScene(scene);
    auto work = [&](const char* label) {
        r.render(fs);
        std::map<std::string, double> n;
        for (const auto& [name, report] : r.passReports(fs))
            if (name == "vct")
                for (const auto& [key, value] : report.numbers) n[key] = value;
        std::printf("%s: %.0f pixels, %.0f cones, %.2f samples per cone, %.3f texture calls per sample\n", label, n["tracedPixels"],
                    n["cones"], n["samplesPerCone"], n["textureCallsPerSample"]);
        return n;
    };
    auto base = work("anisotropic");
    EXPECT_EQ(base["tracedPixels"], double(fs.width * fs.height));
    EXPECT_EQ(base["cones"], base["tracedPixels"] * double(makeConeSet(fs.vct).cones.size() + 1));
    // Up to three directions from the atlas, one per axis the cone has a component along: the
    // rooms' walls lie along the axes, and so do some cones of the pixels that face them.
    EXPECT_GT(base["textureCallsPerSample"], 1.0);
    EXPECT_LT(base["textureCallsPerSample"], 3.0) << "a cone reads the slab of an axis it has no component along";
    EXPECT_GE(base["samplesPerCone"], 1.0);
    EXPECT_NEAR(base["samplesPerPixel"], base["samples"] / base["tracedPixels"], 1e-9 * base["samplesPerPixel"]);
    fs.vct.stepMultiplier = 0.5f;
    auto halfStep = work("half the step");
    EXPECT_GT(halfStep["samplesPerCone"], 1.3 * base["samplesPerCone"]);
    fs.vct.stepMultiplier = 1.0f;
    fs.vct.maxDistance = 1.0f;  // the cones start 0.66 m out (nudge 3 voxel diagonals of 0.22 m)
    auto shortCones = work("cones 1 m long");
    EXPECT_GT(shortCones["samplesPerCone"], 0.0);
    EXPECT_LT(shortCones["samplesPerCone"], 0.8 * base["samplesPerCone"]);
    fs.vct.maxDistance = 0.0f;
    fs.vct.faceSides = true;
    // The centroid, the atlas for each direction read, and their coverage in one call (the octant
    // atlas, octants.comp; it was one call per direction, 6.7 calls a sample on vct_cornell).
    double sides = work("face sides")["textureCallsPerSample"];
    EXPECT_GT(sides, 3.0);
    EXPECT_LE(sides, 5.0) << "one coverage call a sample, not one per direction";
    fs.vct.faceSides = false;
    fs.vct.anisotropic = false;
    EXPECT_EQ(work("isotropic")["textureCallsPerSample"], 1.0);
    fs.vct.sh = true;
    EXPECT_EQ(work("SH")["textureCallsPerSample"], 4.0);
}

}  // namespace
}  // namespace gi
