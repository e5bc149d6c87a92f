// glTF metallic-roughness materials end to end: tiny glTF files written here (a textured plane)
// are loaded and drawn by the raster pipeline and the path tracer. Normal maps against geometry
// tilted alike, the metallic-roughness texture's channels, emissive textures in the raster and
// the reference, KHR_texture_transform and TEXCOORD_1, alpha Mask and Blend, and the loader's
// range checks on the new indices.
#include "fuzz/mutator.h"
#include "gi/preset/preset.h"
#include "gi/reference/path_tracer.h"
#include "gi/render/image_io.h"
#include "gi/render/renderer.h"
#include "gi/scene/camera.h"
#include "gi/scene/mesh_builder.h"
#include "gi/scene/scene.h"
#include "gi/util/error.h"
#include "test_util.h"

#include <nlohmann/json.hpp>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cstring>
#include <fstream>

namespace gi {
namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

constexpr int kSize = 128;
constexpr float kHalf = 5.0f;  // the plane spans [-kHalf, kHalf]^2 at y = 0
const glm::vec3 kEye(0.0f, 14.0f, 8.0f);  // sees the whole plane

// A square image of one colour on the left half (u < 0.5) and another on the right, as a PNG
// beside the glTF. Rows do not matter: every row is the same.
void writeHalves(const fs::path& file, glm::u8vec4 left, glm::u8vec4 right, int size = 8) {
    std::vector<uint8_t> rgba(size_t(size * size * 4));
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            glm::u8vec4 c = x < size / 2 ? left : right;
            std::memcpy(&rgba[size_t((y * size + x) * 4)], &c[0], 4);
        }
    writePNG(file, size, size, rgba);
}

// The plane y = 0 over [-kHalf, kHalf]^2, normals +y, TEXCOORD_0 u = (x + kHalf) / 2 kHalf along
// +x and v along +z, TEXCOORD_1 = TEXCOORD_0 + (0.5, 0); `images` are URIs of PNGs beside the
// file, one texture per image in order. `node` may hold a rotation.
fs::path writePlane(const fs::path& dir, const std::string& name, const json& material, const std::vector<std::string>& images,
                    const json& node = json::object()) {
    const float h = kHalf;
    const float p[6][3] = {{-h, 0, -h}, {-h, 0, h}, {h, 0, h}, {-h, 0, -h}, {h, 0, h}, {h, 0, -h}};
    std::vector<float> f;
    for (auto& q : p) f.insert(f.end(), {q[0], q[1], q[2]});
    for (int i = 0; i < 6; ++i) f.insert(f.end(), {0.0f, 1.0f, 0.0f});
    for (auto& q : p) f.insert(f.end(), {(q[0] + h) / (2 * h), (q[2] + h) / (2 * h)});
    for (auto& q : p) f.insert(f.end(), {(q[0] + h) / (2 * h) + 0.5f, (q[2] + h) / (2 * h)});
    std::vector<uint8_t> bytes(f.size() * 4);
    std::memcpy(bytes.data(), f.data(), bytes.size());
    json textures = json::array(), imgs = json::array();
    for (size_t i = 0; i < images.size(); ++i) {
        imgs.push_back({{"uri", images[i]}});
        textures.push_back({{"source", i}});
    }
    json n = node;
    n["mesh"] = 0;
    json j = {
        {"asset", {{"version", "2.0"}}},
        {"extensionsUsed", {"KHR_texture_transform", "KHR_materials_emissive_strength"}},
        {"buffers", {{{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + fuzz::base64(bytes)}}}},
        {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", bytes.size()}}}},
        {"accessors",
         {{{"bufferView", 0}, {"byteOffset", 0}, {"componentType", 5126}, {"count", 6}, {"type", "VEC3"},
           {"min", {-h, 0, -h}}, {"max", {h, 0, h}}},
          {{"bufferView", 0}, {"byteOffset", 72}, {"componentType", 5126}, {"count", 6}, {"type", "VEC3"}},
          {{"bufferView", 0}, {"byteOffset", 144}, {"componentType", 5126}, {"count", 6}, {"type", "VEC2"}},
          {{"bufferView", 0}, {"byteOffset", 192}, {"componentType", 5126}, {"count", 6}, {"type", "VEC2"}}}},
        {"materials", {material}},
        {"meshes",
         {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}, {"TEXCOORD_1", 3}}}, {"material", 0}}}}}}},
        {"nodes", {n}},
        {"scenes", {{{"nodes", {0}}}}},
        {"scene", 0}};
    if (!images.empty()) {
        j["images"] = imgs;
        j["textures"] = textures;
    }
    fs::path file = dir / (name + ".gltf");
    std::ofstream(file) << j.dump();
    return file;
}

FrameSettings view(glm::vec3 eye, glm::vec3 target = glm::vec3(0.0f)) {
    FrameSettings fs;
    fs.camera.eye = eye;
    fs.camera.target = target;
    fs.camera.near = 0.05f;
    fs.camera.far = 100.0f;
    fs.render.ambient = glm::vec3(0.0f);
    fs.render.specular = false;
    fs.toneMap.op = ToneMapper::Linear;
    fs.width = fs.height = kSize;
    return fs;
}

// The pixel (x right, y up from the bottom row) where the camera of `fs` sees world point p.
glm::ivec2 pixelOf(const FrameSettings& fs, glm::vec3 p) {
    glm::vec4 c = projectionMatrix(fs.camera, float(fs.width) / float(fs.height)) * viewMatrix(fs.camera) * glm::vec4(p, 1.0f);
    glm::vec2 ndc = glm::vec2(c) / c.w;
    return glm::ivec2((ndc * 0.5f + 0.5f) * glm::vec2(fs.width, fs.height));
}

// Mean HDR radiance of the 3x3 pixels around where the camera sees p.
glm::vec3 radianceAt(const Renderer& r, const FrameSettings& fs, glm::vec3 p) {
    std::vector<float> px = r.readHDR();
    glm::ivec2 c = pixelOf(fs, p);
    glm::vec3 sum(0.0f);
    for (int y = c.y - 1; y <= c.y + 1; ++y)
        for (int x = c.x - 1; x <= c.x + 1; ++x) sum += glm::make_vec3(&px[size_t((y * fs.width + x) * 4)]);
    return sum / 9.0f;
}

// The same from a path-traced image (top row first).
glm::vec3 radianceAt(const ImageRGB& img, const FrameSettings& fs, glm::vec3 p) {
    glm::ivec2 c = pixelOf(fs, p);
    glm::vec3 sum(0.0f);
    for (int y = c.y - 1; y <= c.y + 1; ++y)
        for (int x = c.x - 1; x <= c.x + 1; ++x) sum += glm::make_vec3(&img.rgb[size_t(((img.height - 1 - y) * img.width + x) * 3)]);
    return sum / 9.0f;
}

// A G-buffer target read back as RGBA floats, bottom row first.
std::vector<float> readView(const Renderer& r, const std::string& name) {
    for (const DebugView& v : r.debugViews())
        if (v.name == name) {
            std::vector<float> px(size_t(v.width * v.height * 4));
            glGetTextureImage(v.texture, 0, GL_RGBA, GL_FLOAT, GLsizei(px.size() * sizeof(float)), px.data());
            return px;
        }
    ADD_FAILURE() << "no view " << name;
    return {};
}

json lambert(float albedo) {
    return {{"pbrMetallicRoughness", {{"baseColorFactor", {albedo, albedo, albedo, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}};
}

uint8_t unorm(float x) { return uint8_t(std::lround((x * 0.5f + 0.5f) * 255.0f)); }

// A 64x64 frame of a plane scene from kEye under one light, with small LPV and VCT grids.
FrameSettings planeFrame(const Scene& scene, const char* technique, const LightSettings& light) {
    Preset p;
    p.header.technique.name = technique;
    p.vct.gridResolution = 32;
    p.lpv.gridResolution = 16;
    FrameSettings fs = frameSettings(p, scene, 64, 64);
    fs.camera.eye = kEye;
    fs.camera.target = glm::vec3(0.0f);
    fs.lights = {light};
    return fs;
}

class Materials : public test::GLTest {};

// (1) A flat plane whose normal map holds one tilted normal is lit like the plane tilted alike:
// the red channel tilts towards the tangent (+u, +x here) and the green one towards the
// bitangent, which glTF points up the image (-v, -z here).
TEST_F(Materials, NormalMapShadesLikeTiltedGeometry) {
    fs::path dir = test::tempDir();
    const float a = glm::radians(30.0f);
    LightSettings sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(-1.0f, -1.0f, 0.6f));
    sun.intensity = 3.0f;
    struct Case {
        const char* name;
        glm::vec3 tangentNormal;  // in the map
        glm::vec3 axis;           // the geometric tilt that matches it: a rotation by +-a about this axis
        float angle;
    };
    // Rotating +y by -a about +z gives (sin a, cos a, 0); by -a about +x gives (0, cos a, -sin a).
    for (const Case& c : {Case{"tangent", {std::sin(a), 0.0f, std::cos(a)}, {0, 0, 1}, -a},
                          Case{"bitangent", {0.0f, std::sin(a), std::cos(a)}, {1, 0, 0}, -a}}) {
        writeHalves(dir / "n.png", {unorm(c.tangentNormal.x), unorm(c.tangentNormal.y), unorm(c.tangentNormal.z), 255},
                    {unorm(c.tangentNormal.x), unorm(c.tangentNormal.y), unorm(c.tangentNormal.z), 255});
        json mapped = lambert(0.5f);
        mapped["normalTexture"] = {{"index", 0}};
        Scene flat = loadGLTF(writePlane(dir, std::string("mapped_") + c.name, mapped, {"n.png"}));
        glm::quat q = glm::angleAxis(c.angle, c.axis);
        Scene tilted = loadGLTF(writePlane(dir, std::string("tilted_") + c.name, lambert(0.5f), {},
                                           json{{"rotation", {q.x, q.y, q.z, q.w}}}));
        // Tangents derived from the UVs (the file has no TANGENT): +x, bitangent to -z.
        EXPECT_NEAR(flat.vertices[0].tangent.x, 1.0f, 1e-5f);
        EXPECT_EQ(flat.vertices[0].tangent.w, 1.0f);
        FrameSettings fs = view({0.5f, 6.0f, 4.0f});
        fs.lights = {sun};
        Renderer r;
        r.setScene(flat);
        r.render(fs);
        glm::vec3 mappedL = radianceAt(r, fs, glm::vec3(0.0f));
        r.setScene(tilted);
        r.render(fs);
        glm::vec3 tiltedL = radianceAt(r, fs, glm::vec3(0.0f));
        Renderer plain;
        plain.setScene(loadGLTF(writePlane(dir, "plain", lambert(0.5f), {})));
        plain.render(fs);
        glm::vec3 flatL = radianceAt(plain, fs, glm::vec3(0.0f));
        std::printf("%s: normal-mapped %.4f, tilted %.4f, flat %.4f\n", c.name, mappedL.x, tiltedL.x, flatL.x);
        EXPECT_NEAR(mappedL.x, tiltedL.x, 0.02f * tiltedL.x) << c.name;
        EXPECT_GT(std::abs(tiltedL.x - flatL.x), 0.1f * flatL.x) << c.name << ": the tilt must show";

        // The path tracer bends the normal the same way.
        ReferenceSettings rs;
        rs.spp = 4;
        rs.maxBounces = 1;
        FrameSettings small = fs;
        small.width = small.height = 48;
        ImageRGB ref = PathTracer(flat).render(small, rs);
        ImageRGB refTilted = PathTracer(tilted).render(small, rs);
        glm::vec3 refL = radianceAt(ref, small, glm::vec3(0.0f)), refTiltedL = radianceAt(refTilted, small, glm::vec3(0.0f));
        EXPECT_NEAR(refL.x, refTiltedL.x, 0.02f * refTiltedL.x) << c.name << " (reference)";
    }
}

// (2) Metallic-roughness texture: G is roughness and B metallic, times the factors; R is not read.
TEST_F(Materials, MetallicRoughnessTextureReadsGreenAndBlue) {
    fs::path dir = test::tempDir();
    writeHalves(dir / "mr.png", {230, 64, 191, 255}, {230, 64, 191, 255});
    json m = {{"pbrMetallicRoughness",
               {{"baseColorFactor", {0.8, 0.8, 0.8, 1.0}}, {"metallicFactor", 1.0}, {"roughnessFactor", 0.5},
                {"metallicRoughnessTexture", {{"index", 0}}}}}};
    Scene s = loadGLTF(writePlane(dir, "mr", m, {"mr.png"}));
    ASSERT_GE(s.materials[0].metallicRoughnessTexture, 0);
    EXPECT_FALSE(s.textures[size_t(s.materials[0].metallicRoughnessTexture)].srgb);
    FrameSettings fs = view(kEye);
    fs.render.ambient = glm::vec3(1.0f);
    Renderer r;
    r.setScene(s);
    r.render(fs);
    std::vector<float> material = readView(r, "roughnessMetallic");
    glm::ivec2 c = pixelOf(fs, glm::vec3(0.0f));
    const float* px = &material[size_t((c.y * kSize + c.x) * 4)];
    EXPECT_NEAR(px[0], 0.5f * 64.0f / 255.0f, 2.0f / 255.0f) << "roughness: roughnessFactor times G";
    EXPECT_NEAR(px[1], 191.0f / 255.0f, 2.0f / 255.0f) << "metallic: metallicFactor times B";
    // Metallic 0.75 leaves a quarter of the diffuse albedo under the ambient light.
    EXPECT_NEAR(radianceAt(r, fs, glm::vec3(0.0f)).x, 0.8f * (1.0f - 191.0f / 255.0f), 0.02f);
}

// (3) Emissive texture: emissiveFactor times the sRGB texture times KHR_materials_emissive_strength,
// in the raster and in the path tracer; the texture's black half does not glow.
TEST_F(Materials, EmissiveTextureGlowsInRasterAndReference) {
    fs::path dir = test::tempDir();
    writeHalves(dir / "e.png", {255, 188, 0, 255}, {0, 0, 0, 255});  // sRGB 188 is linear 0.5
    json m = lambert(0.5f);
    m["emissiveFactor"] = {1.0, 1.0, 1.0};
    m["emissiveTexture"] = {{"index", 0}};
    m["extensions"] = {{"KHR_materials_emissive_strength", {{"emissiveStrength", 2.0}}}};
    Scene s = loadGLTF(writePlane(dir, "glow", m, {"e.png"}));
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    // The CPU evaluation other code (emissive area lights) reads.
    glm::vec3 cpu = emission(s, s.materials[0], {0.25f, 0.5f});
    EXPECT_NEAR(cpu.x, 2.0f, 1e-3f);
    EXPECT_NEAR(cpu.y, 2.0f * srgbToLinear(188.0f / 255.0f), 1e-3f);
    EXPECT_EQ(emission(s, s.materials[0], {0.75f, 0.5f}), glm::vec3(0.0f));

    // The emission belongs to the plane's area light, as frameSettings lists the scene's lights.
    FrameSettings fs = view(kEye);
    fs.lights = sceneLights(s);
    const glm::vec3 left(-kHalf / 2, 0, 0), right(kHalf / 2, 0, 0);
    Renderer r;
    r.setScene(s);
    r.render(fs);
    glm::vec3 l = radianceAt(r, fs, left), rr = radianceAt(r, fs, right);
    EXPECT_NEAR(l.x, 2.0f, 0.02f);
    EXPECT_NEAR(l.y, 2.0f * srgbToLinear(188.0f / 255.0f), 0.02f);
    EXPECT_LT(rr.x, 0.01f);

    ReferenceSettings rs;
    rs.spp = 4;
    rs.maxBounces = 1;
    FrameSettings small = fs;
    small.width = small.height = 48;
    ImageRGB ref = PathTracer(s).render(small, rs);
    glm::vec3 refL = radianceAt(ref, small, left), refR = radianceAt(ref, small, right);
    EXPECT_NEAR(refL.x, 2.0f, 0.05f);
    EXPECT_NEAR(refL.y, 2.0f * srgbToLinear(188.0f / 255.0f), 0.05f);
    EXPECT_LT(refR.x, 0.01f);

    // Single-sided: seen from below, the plane's back face emits nothing, in both; a
    // double-sided one emits on both sides.
    FrameSettings below = view(kEye * glm::vec3(1, -1, 1));
    below.lights = sceneLights(s);
    FrameSettings belowSmall = below;
    belowSmall.width = belowSmall.height = 48;
    r.render(below);
    EXPECT_LT(radianceAt(r, below, left).x, 0.01f);
    EXPECT_LT(radianceAt(PathTracer(s).render(belowSmall, rs), belowSmall, left).x, 0.01f);
    m["doubleSided"] = true;
    Scene twoSided = loadGLTF(writePlane(dir, "glow2", m, {"e.png"}));
    below.lights = belowSmall.lights = sceneLights(twoSided);
    r.setScene(twoSided);
    r.render(below);
    EXPECT_NEAR(radianceAt(r, below, left).x, 2.0f, 0.02f);
    EXPECT_NEAR(radianceAt(PathTracer(twoSided).render(belowSmall, rs), belowSmall, left).x, 2.0f, 0.05f);
}

// Occlusion texture: R with occlusionStrength scales the indirect (here ambient) term and leaves
// direct light alone.
TEST_F(Materials, OcclusionScalesOnlyTheIndirectTerm) {
    fs::path dir = test::tempDir();
    writeHalves(dir / "o.png", {64, 0, 0, 255}, {64, 0, 0, 255});
    json occluded = lambert(0.5f);
    occluded["occlusionTexture"] = {{"index", 0}, {"strength", 0.5}};
    Scene withMap = loadGLTF(writePlane(dir, "occluded", occluded, {"o.png"}));
    Scene without = loadGLTF(writePlane(dir, "open", lambert(0.5f), {}));
    const float occlusion = 1.0f + 0.5f * (64.0f / 255.0f - 1.0f);
    LightSettings sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, 0.2f));
    auto radiance = [&](const Scene& s, glm::vec3 ambient, bool lit) {
        FrameSettings fs = view(kEye);
        fs.render.ambient = ambient;
        if (lit) fs.lights = {sun};
        Renderer r;
        r.setScene(s);
        r.render(fs);
        return radianceAt(r, fs, glm::vec3(0.0f)).x;
    };
    EXPECT_NEAR(radiance(without, glm::vec3(1.0f), false), 0.5f, 0.01f);
    EXPECT_NEAR(radiance(withMap, glm::vec3(1.0f), false), 0.5f * occlusion, 0.01f);
    float direct = radiance(without, glm::vec3(0.0f), true);
    EXPECT_GT(direct, 0.1f);
    EXPECT_NEAR(radiance(withMap, glm::vec3(0.0f), true), direct, 0.005f * direct);
}

// (4) KHR_texture_transform moves the texture: an offset of half the width swaps the halves, a
// scale of 2 repeats them, and a texCoord override to 1 reads TEXCOORD_1 (shifted by half here).
TEST_F(Materials, TextureTransformMovesTheTexture) {
    fs::path dir = test::tempDir();
    writeHalves(dir / "c.png", {255, 0, 0, 255}, {0, 255, 0, 255});
    FrameSettings fs = view(kEye);
    fs.render.ambient = glm::vec3(1.0f);
    auto colours = [&](const json& info) {
        json m = {{"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"baseColorTexture", info}}}};
        Renderer r;
        r.setScene(loadGLTF(writePlane(dir, "t", m, {"c.png"})));
        r.render(fs);
        // Where u is 0.125, 0.375 (red, red untransformed) and 0.625 (green).
        return std::array<glm::vec3, 3>{radianceAt(r, fs, {-0.75f * kHalf, 0, 0}), radianceAt(r, fs, {-0.25f * kHalf, 0, 0}),
                                        radianceAt(r, fs, {0.25f * kHalf, 0, 0})};
    };
    auto red = [](glm::vec3 c) { return c.r > 0.9f && c.g < 0.05f; };
    auto green = [](glm::vec3 c) { return c.g > 0.9f && c.r < 0.05f; };
    auto plain = colours({{"index", 0}});
    EXPECT_TRUE(red(plain[0]) && red(plain[1]) && green(plain[2]));
    auto offset = colours({{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"offset", {0.5, 0.0}}}}}}});
    EXPECT_TRUE(green(offset[0]) && green(offset[1]) && red(offset[2])) << offset[0].r << " " << offset[1].r << " " << offset[2].r;
    auto scale = colours({{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"scale", {2.0, 1.0}}}}}}});
    EXPECT_TRUE(red(scale[0]) && green(scale[1]) && red(scale[2]));  // u' = 0.25, 0.75, 1.25
    auto set1 = colours({{"index", 0}, {"texCoord", 1}});
    EXPECT_TRUE(green(set1[0]) && green(set1[1]) && red(set1[2]));
    auto override1 = colours({{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"texCoord", 1}}}}}});
    EXPECT_TRUE(green(override1[0]) && green(override1[1]) && red(override1[2]));
    // Rotation by 90 degrees: the map is (u, v) -> (v, -u), so u no longer varies along x.
    TextureTransform t;
    t.rotation = glm::half_pi<float>();
    glm::vec2 uv = t.apply({0.25f, 0.5f}, {});
    EXPECT_NEAR(uv.x, 0.5f, 1e-6f);
    EXPECT_NEAR(uv.y, -0.25f, 1e-6f);
}

// (5) Mask cuts below alphaCutoff in the raster and the path tracer; Blend is a dithered mask
// whose coverage follows alpha.
TEST_F(Materials, AlphaMaskCutoffAndDitheredBlend) {
    fs::path dir = test::tempDir();
    writeHalves(dir / "a.png", {255, 255, 255, 51}, {255, 255, 255, 204});  // alpha 0.2 | 0.8
    FrameSettings fs = view(kEye);
    const glm::vec3 left(-kHalf / 2, 0, 0), right(kHalf / 2, 0, 0);
    auto scene = [&](const char* mode, double cutoff) {
        json m = {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
                  {"emissiveFactor", {1.0, 1.0, 1.0}},
                  {"alphaMode", mode},
                  {"alphaCutoff", cutoff}};
        return loadGLTF(writePlane(dir, "a", m, {"a.png"}));
    };
    ReferenceSettings rs;
    rs.spp = 2;
    rs.maxBounces = 1;
    FrameSettings small = fs;
    small.width = small.height = 48;
    for (double cutoff : {0.5, 0.1}) {
        Scene s = scene("MASK", cutoff);
        fs.lights = small.lights = sceneLights(s);  // the plane's emission is its area light's
        Renderer r;
        r.setScene(s);
        r.render(fs);
        ImageRGB ref = PathTracer(s).render(small, rs);
        bool leftCut = cutoff > 0.2;
        EXPECT_NEAR(radianceAt(r, fs, left).x, leftCut ? 0.0f : 1.0f, 0.01f) << "cutoff " << cutoff;
        EXPECT_NEAR(radianceAt(r, fs, right).x, 1.0f, 0.01f) << "cutoff " << cutoff;
        EXPECT_NEAR(radianceAt(ref, small, left).x, leftCut ? 0.0f : 1.0f, 0.01f) << "cutoff " << cutoff << " (reference)";
        EXPECT_NEAR(radianceAt(ref, small, right).x, 1.0f, 0.01f) << "cutoff " << cutoff << " (reference)";
    }
    // Blend: the fraction of covered pixels over each half is about its alpha.
    Scene s = scene("BLEND", 0.5);
    fs.lights = small.lights = sceneLights(s);
    Renderer r;
    r.setScene(s);
    r.render(fs);
    std::vector<float> px = r.readHDR();
    auto coverage = [&](glm::vec3 centre) {
        glm::ivec2 c = pixelOf(fs, centre);
        int covered = 0, n = 0;
        for (int y = c.y - 6; y <= c.y + 6; ++y)
            for (int x = c.x - 6; x <= c.x + 6; ++x, ++n) covered += px[size_t((y * kSize + x) * 4)] > 0.5f;
        return double(covered) / n;
    };
    EXPECT_NEAR(coverage(left), 0.2, 0.08);
    EXPECT_NEAR(coverage(right), 0.8, 0.08);
    ReferenceSettings many;
    many.spp = 64;
    many.maxBounces = 1;
    ImageRGB ref = PathTracer(s).render(small, many);
    EXPECT_NEAR(radianceAt(ref, small, left).x, 0.2f, 0.08f);
    EXPECT_NEAR(radianceAt(ref, small, right).x, 0.8f, 0.08f);
}

// Mask and Blend cut holes in the shadow maps too: a plate whose alpha is below the cutoff
// casts no shadow; above it, it does; a Blend plate of alpha 0.5 lets about half the light through.
TEST_F(Materials, CutOutsCutTheShadowMaps) {
    auto shadowed = [](AlphaMode mode, float cutoff, uint8_t alpha) {
        Scene s;
        MeshBuilder b(s);
        int floor = b.material("floor", glm::vec3(0.5f), 1.0f);
        b.quad(floor, {-20, 0, 20}, {40, 0, 0}, {0, 0, -40});
        Texture t;
        t.width = t.height = 4;
        t.rgba.assign(4 * 4 * 4, 255);
        for (size_t i = 3; i < t.rgba.size(); i += 4) t.rgba[i] = alpha;
        s.textures.push_back(t);
        int plate = b.material("plate", glm::vec3(0.5f), 1.0f, 0);
        s.materials[size_t(plate)].alphaMode = mode;
        s.materials[size_t(plate)].alphaCutoff = cutoff;
        b.quad(plate, {-2.0f, 1.0f, 2.0f}, {4, 0, 0}, {0, 0, -4});
        s.finalize();
        LightSettings sun;
        sun.type = LightType::Directional;
        sun.direction = {0.0f, -1.0f, 0.0f};
        sun.intensity = 1.0f;
        // The camera looks from the side, under the plate, at the floor below its centre.
        FrameSettings fs = view({6.0f, 0.5f, 0.3f});
        fs.lights = {sun};
        Renderer r;
        r.setScene(s);
        r.render(fs);
        return radianceAt(r, fs, glm::vec3(0.0f)).x;
    };
    float lit = 0.5f / glm::pi<float>();
    EXPECT_NEAR(shadowed(AlphaMode::Mask, 0.5f, 51), lit, 0.02f * lit) << "alpha 0.2 under cutoff 0.5 casts no shadow";
    EXPECT_LT(shadowed(AlphaMode::Mask, 0.1f, 51), 0.01f * lit) << "alpha 0.2 over cutoff 0.1 casts a shadow";
    EXPECT_NEAR(shadowed(AlphaMode::Blend, 0.5f, 128), 0.5f * lit, 0.15f * lit) << "Blend alpha 0.5: a dithered half shadow";
}

// Every technique's scene passes (shadow maps, RSMs, voxelization) draw a material with every
// map, a texture transform, TEXCOORD_1 and Blend without a GL error (GLTest fails on one), and
// light the plane.
TEST_F(Materials, EveryTechniqueDrawsEveryMap) {
    fs::path dir = test::tempDir();
    writeHalves(dir / "c.png", {255, 128, 64, 200}, {64, 255, 128, 255});
    writeHalves(dir / "n.png", {150, 128, 240, 255}, {110, 140, 240, 255});
    json m = {{"pbrMetallicRoughness",
               {{"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"offset", {0.25, 0.0}}, {"rotation", 0.3}}}}}}},
                {"metallicRoughnessTexture", {{"index", 0}, {"texCoord", 1}}}}},
              {"normalTexture", {{"index", 1}, {"scale", 0.8}}},
              {"occlusionTexture", {{"index", 0}}},
              {"emissiveTexture", {{"index", 0}, {"texCoord", 1}}},
              {"emissiveFactor", {0.5, 0.5, 0.5}},
              {"alphaMode", "BLEND"}};
    Scene scene = loadGLTF(writePlane(dir, "all", m, {"c.png", "n.png"}));
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
    for (const char* technique : {"none", "lpv", "vct"}) {
        LightSettings sun;
        sun.type = LightType::Directional;
        sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, 0.2f));
        FrameSettings fs = planeFrame(scene, technique, sun);
        Renderer r;
        r.setScene(scene);
        r.render(fs);
        std::vector<float> px = r.readHDR();
        double sum = 0.0;
        for (float v : px) {
            ASSERT_TRUE(std::isfinite(v)) << technique;
            sum += v;
        }
        EXPECT_GT(sum, 0.0) << technique;
    }
}

// render.materialPrograms: the G-buffer, LPV's RSMs and VCT's voxelization draw each material with
// a program built for its texture slots (gi/render/material_programs.h), which must draw the pixels of the
// general program that tests the slots at run time, for materials with a few maps and with all.
TEST_F(Materials, ProgramsBuiltPerTextureSetDrawTheSamePixels) {
    fs::path dir = test::tempDir();
    writeHalves(dir / "c.png", {255, 128, 64, 150}, {64, 255, 128, 255});
    writeHalves(dir / "n.png", {150, 128, 240, 255}, {110, 140, 240, 255});
    const json base = {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.0}};
    const std::vector<std::pair<const char*, json>> materials = {
        {"base colour", {{"pbrMetallicRoughness", base}}},
        {"normal and metallic-roughness",
         {{"pbrMetallicRoughness", {{"metallicRoughnessTexture", {{"index", 0}, {"texCoord", 1}}}}}, {"normalTexture", {{"index", 1}}}}},
        {"occlusion and emissive",
         {{"pbrMetallicRoughness", base},
          {"occlusionTexture", {{"index", 0}}},
          {"emissiveTexture", {{"index", 0}}},
          {"emissiveFactor", {0.3, 0.3, 0.3}}}},
        {"every map, masked",
         {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicRoughnessTexture", {{"index", 0}}}}},
          {"normalTexture", {{"index", 1}}},
          {"occlusionTexture", {{"index", 0}}},
          {"emissiveTexture", {{"index", 0}}},
          {"emissiveFactor", {0.2, 0.2, 0.2}},
          {"alphaMode", "MASK"},
          {"alphaCutoff", 0.7}}}};
    int index = 0;
    for (const auto& [label, material] : materials) {
        Scene scene = loadGLTF(writePlane(dir, "m" + std::to_string(index++), material, {"c.png", "n.png"}));
        for (const char* technique : {"none", "lpv", "vct"}) {
            LightSettings spot;
            spot.type = LightType::Spot;
            spot.position = {1.0f, 4.0f, 1.0f};
            spot.direction = glm::vec3(0.0f, -1.0f, 0.0f);
            spot.outerConeDeg = 60.0f;
            spot.intensity = 20.0f;
            FrameSettings fs = planeFrame(scene, technique, spot);
            auto frame = [&](bool specialise) {
                FrameSettings f = fs;
                f.render.materialPrograms = specialise;
                Renderer r;
                r.setScene(scene);
                r.render(f);
                return r.readHDR();
            };
            std::vector<float> general = frame(false), specialised = frame(true);
            ASSERT_EQ(specialised.size(), general.size());
            double worst = 0.0, sum = 0.0;
            for (size_t i = 0; i < general.size(); ++i) {
                sum += general[i];
                worst = std::max(worst, std::abs(double(specialised[i]) - general[i]) / std::max(std::abs(double(general[i])), 1e-3));
            }
            EXPECT_GT(sum, 0.0) << label << ", " << technique;
            std::printf("%s, %s: largest relative difference %.2e\n", label, technique, worst);
            // Exact without GI; LPV's injection sums floats with atomics in thread order, so
            // its frame may differ by one step of fp16 (gl_test.cpp, cluster culling), and VCT's
            // voxelization keeps RGBA8 running averages in thread order, a step of 8 bits in
            // the voxels (each pair of frames here was identical in two runs).
            const std::string t = technique;
            if (t == "none")
                EXPECT_EQ(specialised, general) << label;
            else
                EXPECT_LE(worst, t == "lpv" ? 1.0 / 1024.0 : 1.0 / 100.0) << label << ", " << technique;
        }
    }
}

// The new texture references are range-checked; errors name the material and the slot.
TEST(MaterialLoader, BadTextureReferencesNameTheElement) {
    fs::path dir = test::tempDir();
    writeHalves(dir / "c.png", {255, 0, 0, 255}, {0, 255, 0, 255});
    auto error = [&](const json& m) {
        try {
            loadGLTF(writePlane(dir, "bad", m, {"c.png"}));
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("loads");
    };
    json m = lambert(0.5f);
    m["normalTexture"] = {{"index", 7}};
    EXPECT_NE(error(m).find("material 0 normalTexture: texture 7 does not exist"), std::string::npos) << error(m);
    m = lambert(0.5f);
    m["occlusionTexture"] = {{"index", 0}, {"texCoord", -2}};
    EXPECT_NE(error(m).find("material 0 occlusionTexture: texCoord -2 is negative"), std::string::npos) << error(m);
    m = lambert(0.5f);
    m["emissiveTexture"] = {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"offset", {0.5}}}}}}};
    EXPECT_NE(error(m).find("material 0 emissiveTexture: KHR_texture_transform offset is not an array of 2 numbers"), std::string::npos)
        << error(m);
    m = lambert(0.5f);
    m["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"rotation", "x"}}}}}};
    EXPECT_NE(error(m).find("metallicRoughnessTexture: KHR_texture_transform rotation is not a number"), std::string::npos) << error(m);
    // TEXCOORD_2 and up are not read: the texture is left out with a warning naming it.
    m = lambert(0.5f);
    m["normalTexture"] = {{"index", 0}, {"texCoord", 2}};
    Scene s = loadGLTF(writePlane(dir, "set2", m, {"c.png"}));
    EXPECT_EQ(s.materials[0].normalTexture, -1);
    ASSERT_FALSE(s.warnings.empty());
    EXPECT_NE(s.warnings[0].find("material 0 normalTexture: texCoord 2"), std::string::npos) << s.warnings[0];
    // One image used as colour and as data becomes an sRGB and a linear texture.
    m = lambert(0.5f);
    m["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
    m["normalTexture"] = {{"index", 0}};
    s = loadGLTF(writePlane(dir, "both", m, {"c.png"}));
    ASSERT_EQ(s.textures.size(), 2u);
    EXPECT_NE(s.textures[0].srgb, s.textures[1].srgb);
}

// Tangents derived from the UVs agree with the ones WaterBottle ships (MikkTSpace), sign included:
// the derived frame is the one glTF normal maps are authored for.
TEST(MaterialLoader, DerivedTangentsMatchTheFilesTangents) {
    fs::path src = fs::path(GI_SHARED_DIR) / "scenes/water_bottle";
    if (!fs::exists(src / "WaterBottle.gltf")) GTEST_SKIP() << "no ../shared/scenes";
    fs::path dir = test::tempDir();
    for (const auto& e : fs::directory_iterator(src)) fs::copy_file(e.path(), dir / e.path().filename());
    json j = json::parse(std::ifstream(dir / "WaterBottle.gltf"));
    j["meshes"][0]["primitives"][0]["attributes"].erase("TANGENT");
    std::ofstream(dir / "derived.gltf") << j.dump();
    Scene file = loadGLTF(dir / "WaterBottle.gltf"), derived = loadGLTF(dir / "derived.gltf");
    ASSERT_EQ(file.vertices.size(), derived.vertices.size());
    size_t agree = 0, sameSign = 0;
    for (size_t i = 0; i < file.vertices.size(); ++i) {
        agree += glm::dot(glm::vec3(file.vertices[i].tangent), glm::vec3(derived.vertices[i].tangent)) > 0.9f;
        sameSign += file.vertices[i].tangent.w == derived.vertices[i].tangent.w;
    }
    std::printf("derived tangents: %zu of %zu within 25 degrees, %zu with the same sign\n", agree, file.vertices.size(), sameSign);
    EXPECT_GT(agree, file.vertices.size() * 9 / 10);
    EXPECT_GT(sameSign, file.vertices.size() * 95 / 100);
}

}  // namespace
}  // namespace gi
