// glTF loading: a hand-made file checks hierarchy, instancing, cameras, lights and materials;
// every glTF2 file of Debian's assimp-testmodels loads or fails with gi::Error, never crashes;
// the shared scenes load with the triangle counts their README gives.
#include "fuzz/mutator.h"
#include "gi/scene/scene.h"
#include "gi/util/error.h"
#include "test_util.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

namespace gi {
namespace {

using json = nlohmann::json;

using fuzz::base64;

// One triangle (0,0,0) (1,0,0) (0,1,0) with +z normals, instanced by two nodes under a parent.
json handMadeGLTF() {
    std::vector<float> floats = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    std::vector<uint8_t> bytes(floats.size() * 4);
    std::memcpy(bytes.data(), floats.data(), bytes.size());
    const double s = std::sqrt(0.5);
    return json{
        {"asset", {{"version", "2.0"}}},
        {"extensionsUsed", {"KHR_lights_punctual", "KHR_materials_emissive_strength"}},
        {"buffers", {{{"byteLength", 72}, {"uri", "data:application/octet-stream;base64," + base64(bytes)}}}},
        {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 72}}}},
        {"accessors",
         {{{"bufferView", 0}, {"byteOffset", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"},
           {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
          {{"bufferView", 0}, {"byteOffset", 36}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}}}},
        {"materials",
         {{{"name", "glow"},
           {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 1.0, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.3}}},
           {"emissiveFactor", {1.0, 0.5, 0.0}},
           {"alphaMode", "MASK"},
           {"alphaCutoff", 0.3},
           {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"material", 0}}}}}}},
        {"cameras", {{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}, {"zfar", 50.0}}}}}},
        {"extensions",
         {{"KHR_lights_punctual",
           {{"lights",
             {{{"type", "spot"}, {"color", {1.0, 0.0, 0.0}}, {"intensity", 7.0}, {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 0.4}}}},
              {{"type", "directional"}, {"intensity", 2.0}}}}}}}},
        {"nodes",
         {{{"translation", {10, 0, 0}}, {"children", {1, 2}}},
          {{"mesh", 0}, {"scale", {2, 2, 2}}},
          {{"mesh", 0}, {"rotation", {0, s, 0, s}}},  // 90 degrees about +y
          {{"camera", 0}, {"translation", {0, 1, 5}}},
          {{"translation", {0, 3, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
          {{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}}}},
        {"scenes", {{{"nodes", {0, 3, 4, 5}}}}},
        {"scene", 0}};
}

std::filesystem::path writeJSON(const std::filesystem::path& dir, const std::string& name, const json& j) {
    auto p = dir / name;
    std::ofstream(p) << j.dump();
    return p;
}

void expectNear(glm::vec3 a, glm::vec3 b) {
    EXPECT_NEAR(a.x, b.x, 1e-5f);
    EXPECT_NEAR(a.y, b.y, 1e-5f);
    EXPECT_NEAR(a.z, b.z, 1e-5f);
}

TEST(GLTF, HierarchyInstancingCamerasLightsMaterials) {
    auto dir = test::tempDir();
    Scene s = loadGLTF(writeJSON(dir, "hand.gltf", handMadeGLTF()));
    ASSERT_EQ(s.triangleCount(), 2u);  // one mesh, two instances
    ASSERT_EQ(s.vertices.size(), 6u);
    // Instance 1: parent translation (10,0,0) times scale 2.
    expectNear(s.vertices[1].position, {12, 0, 0});
    expectNear(s.vertices[2].position, {10, 2, 0});
    expectNear(s.vertices[0].normal, {0, 0, 1});
    // Instance 2: rotated 90 degrees about +y: x goes to -z, and the +z normal to +x.
    expectNear(s.vertices[4].position, {10, 0, -1});
    expectNear(s.vertices[3].normal, {1, 0, 0});
    ASSERT_EQ(s.materials.size(), 1u);
    const Material& m = s.materials[0];
    EXPECT_EQ(m.alphaMode, AlphaMode::Mask);
    EXPECT_FLOAT_EQ(m.alphaCutoff, 0.3f);
    expectNear(m.emissive, {4.0f, 2.0f, 0.0f});
    EXPECT_FLOAT_EQ(m.roughness, 0.3f);
    EXPECT_FLOAT_EQ(m.baseColor.g, 0.25f);
    ASSERT_EQ(s.cameras.size(), 1u);
    expectNear(s.cameras[0].eye, {0, 1, 5});
    expectNear(s.cameras[0].target, {0, 1, 4});
    EXPECT_NEAR(s.cameras[0].fovY, glm::degrees(0.5f), 1e-3f);
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[0].type, LightType::Spot);
    expectNear(s.lights[0].position, {0, 3, 0});
    expectNear(s.lights[0].direction, {0, 0, -1});
    EXPECT_NEAR(s.lights[0].outerConeDeg, glm::degrees(0.4f), 1e-3f);
    expectNear(s.lights[0].color, {1, 0, 0});
    EXPECT_EQ(s.lights[1].type, LightType::Directional);
    expectNear(s.bounds.max, {12, 2, 0});
}

TEST(GLTF, MalformedHandMadeFilesFailWithNamedElements) {
    auto dir = test::tempDir();
    struct Case {
        const char* name;
        std::function<void(json&)> breakIt;
        const char* expect;
    };
    std::vector<Case> cases = {
        {"cycle", [](json& j) { j["nodes"][1]["children"] = {0}; }, "its own ancestor"},
        {"index", [](json& j) { j["meshes"][0]["primitives"][0]["indices"] = 9; }, "accessor"},
        {"overrun", [](json& j) { j["accessors"][0]["count"] = 1000; }, "reads past the end"},
        {"mesh", [](json& j) { j["nodes"][1]["mesh"] = 5; }, "mesh 5 does not exist"},
        {"material", [](json& j) { j["meshes"][0]["primitives"][0]["material"] = 3; }, "material 3 does not exist"},
        {"type", [](json& j) { j["accessors"][1]["type"] = "VEC2"; }, "expected 3 components"},
        {"nopos", [](json& j) { j["meshes"][0]["primitives"][0]["attributes"].erase("POSITION"); }, "no POSITION"},
        {"required", [](json& j) { j["extensionsRequired"] = {"KHR_draco_mesh_compression"}; }, "draco"},
    };
    for (const auto& c : cases) {
        json j = handMadeGLTF();
        c.breakIt(j);
        auto path = writeJSON(dir, std::string(c.name) + ".gltf", j);
        try {
            loadGLTF(path);
            ADD_FAILURE() << c.name << " loaded";
        } catch (const Error& e) {
            std::string msg = e.what();
            EXPECT_NE(msg.find(c.expect), std::string::npos) << c.name << ": " << msg;
            EXPECT_NE(msg.find(path.filename().string()), std::string::npos) << msg;
            EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        }
    }
}

TEST(GLTF, EveryAssimpTestModelLoadsOrFailsCleanly) {
    // Debian's assimp-testmodels (installed by scripts/install-deps.sh) holds broken and odd files.
    std::filesystem::path root = "/usr/share/assimp/models/glTF2";
    ASSERT_TRUE(std::filesystem::exists(root)) << "install assimp-testmodels (scripts/install-deps.sh)";
    int loaded = 0, failed = 0;
    std::map<std::string, std::string> outcome;
    for (const auto& e : std::filesystem::recursive_directory_iterator(root)) {
        std::string ext = e.path().extension().string();
        if (ext != ".gltf" && ext != ".glb") continue;
        try {
            Scene s = loadGLTF(e.path());
            EXPECT_GT(s.triangleCount(), 0u) << e.path();
            for (const auto& v : s.vertices) ASSERT_TRUE(std::isfinite(v.position.x + v.position.y + v.position.z)) << e.path();
            outcome[e.path().string()] = "loaded";
            ++loaded;
        } catch (const Error& err) {
            std::string msg = err.what();
            EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
            EXPECT_NE(msg.find(e.path().filename().string()), std::string::npos) << msg;
            outcome[e.path().string()] = msg;
            ++failed;
        }
    }
    for (auto& [path, what] : outcome) std::printf("  %s: %s\n", path.c_str(), what.c_str());
    EXPECT_GT(loaded, 20);
    EXPECT_GT(failed, 5);
    auto failedWith = [&](const std::string& rel, const std::string& text) {
        auto it = outcome.find((root / rel).string());
        ASSERT_NE(it, outcome.end()) << rel;
        EXPECT_NE(it->second.find(text), std::string::npos) << rel << ": " << it->second;
    };
    failedWith("IndexOutOfRange/IndexOutOfRange.gltf", "out of range");
    failedWith("IndexOutOfRange/AllIndicesOutOfRange.gltf", "out of range");
    failedWith("RecursiveNodes/RecursiveNodes.gltf", "ancestor");
    failedWith("BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "non-finite");
    failedWith("MissingBin/BoxTextured.gltf", "malformed glTF");
    failedWith("SchemaFailures/sceneWrongType.gltf", "malformed glTF");
    failedWith("BoxTextured-glTF-techniqueWebGL/BoxTextured.gltf", "unsupported extension");
}

TEST(BuiltinScenes, CornellAndBasic) {
    Scene c = makeBuiltinScene("cornell");
    EXPECT_EQ(c.triangleCount(), 5u * 2 + 2 * 12);
    expectNear(c.bounds.min, {-1, 0, -1});
    expectNear(c.bounds.max, {1, 2, 1});
    ASSERT_EQ(c.lights.size(), 1u);
    EXPECT_LT(c.lights[0].position.y, 2.0f);  // just below the ceiling
    Scene b = makeBuiltinScene("basic");
    EXPECT_GT(b.triangleCount(), 1000u);  // the sphere
    ASSERT_EQ(b.textures.size(), 1u);     // the crate's planks
    EXPECT_THROW(makeBuiltinScene("nope"), Error);
    for (const Scene* s : {&c, &b})
        for (const auto& v : s->vertices) EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-4f);
}

class SharedScenes : public ::testing::Test {
protected:
    void SetUp() override {
        if (!std::filesystem::exists(std::filesystem::path(GI_SHARED_DIR) / "scenes"))
            GTEST_SKIP() << "../shared/scenes is not beside this checkout";
    }
};

TEST_F(SharedScenes, TriangleCountsMatchTheReadme) {
    struct Expect {
        const char* file;
        size_t triangles;
    };
    for (auto [file, tris] : {Expect{"cornell_box/CornellBox-Original.gltf", 36}, Expect{"cornell_box/CornellBox-Water.gltf", 7088},
                              Expect{"avocado/Avocado.gltf", 682}, Expect{"water_bottle/WaterBottle.gltf", 4510}}) {
        Scene s = loadScene(file);
        EXPECT_EQ(s.triangleCount(), tris) << file;
    }
    // WaterBottle's emission lives in a texture: the factor (1, 1, 1) times the sRGB texture,
    // with every map of the material read (the maps' colour spaces as the spec gives them).
    Scene bottle = loadScene("water_bottle/WaterBottle.gltf");
    ASSERT_EQ(bottle.materials.size(), 1u);
    const Material& m = bottle.materials[0];
    EXPECT_EQ(m.emissive, glm::vec3(1.0f));
    ASSERT_GE(m.emissiveTexture, 0);
    ASSERT_GE(m.normalTexture, 0);
    ASSERT_GE(m.metallicRoughnessTexture, 0);
    ASSERT_GE(m.occlusionTexture, 0);
    EXPECT_TRUE(bottle.textures[size_t(m.emissiveTexture)].srgb);
    EXPECT_TRUE(bottle.textures[size_t(m.baseColorTexture)].srgb);
    EXPECT_FALSE(bottle.textures[size_t(m.normalTexture)].srgb);
    EXPECT_FALSE(bottle.textures[size_t(m.metallicRoughnessTexture)].srgb);
    EXPECT_TRUE(bottle.warnings.empty()) << bottle.warnings.front();
    // The bottle has TANGENTs: every vertex carries a unit tangent with a sign.
    for (const Vertex& v : bottle.vertices) {
        ASSERT_NEAR(glm::length(glm::vec3(v.tangent)), 1.0f, 1e-3f);
        ASSERT_EQ(std::abs(v.tangent.w), 1.0f);
    }
    Scene cornell = loadScene("cornell_box/CornellBox-Original.gltf");
    bool emissive = false;
    for (auto& m : cornell.materials) emissive |= m.emissive.x > 1.0f;  // Ke 17 via emissive strength
    EXPECT_TRUE(emissive);
}

TEST_F(SharedScenes, SponzaFlattensInstancesAndKeepsAlphaMasks) {
    Scene s = loadScene("sponza_crytek/Sponza.gltf");
    EXPECT_EQ(s.triangleCount(), 262087u);
    EXPECT_NEAR(s.bounds.min.y, 2.28f, 0.01f);
    EXPECT_NEAR(s.bounds.max.x, 24.18f, 0.01f);
    int masked = 0;
    for (auto& m : s.materials) masked += m.alphaMode == AlphaMode::Mask;
    EXPECT_GE(masked, 3);
    EXPECT_GE(s.textures.size(), 20u);
}

}  // namespace
}  // namespace gi
