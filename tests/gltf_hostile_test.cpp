// Hostile glTF files: the regression corpus (tests/fuzz/regressions.json, the five classes of
// issue 11 and every later finding), sparse accessors per the spec, files that are no files, a
// short in-process fuzz run, and a render of texture coordinates that stalled llvmpipe.
#include "fuzz/mutator.h"
#include "gi/gl/debug.h"
#include "gi/preset/preset.h"
#include "gi/scene/scene.h"
#include "gi/util/error.h"
#include "gi/util/paths.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <functional>
#include <sys/resource.h>

namespace gi {
namespace {

using fuzz::json;
namespace fs = std::filesystem;

const fs::path kCorpus = fs::path(GI_SOURCE_DIR) / "tests" / "fuzz" / "corpus";
constexpr double kBudgetMB = 256.0;

fuzz::GLTFSeed seed(const std::string& name) { return fuzz::readSeed(kCorpus / name); }

Scene load(const fuzz::FuzzInput& in, const std::string& name) {
    return loadGLTFFromMemory(in.bytes, in.binary, name + (in.binary ? ".glb" : ".gltf"), kCorpus, kBudgetMB);
}

double peakRSSMiB() {
    struct rusage ru {};
    getrusage(RUSAGE_SELF, &ru);
    return double(ru.ru_maxrss) / 1024.0;
}

TEST(HostileGLTF, EveryCorpusSeedLoads) {
    for (const auto& s : fuzz::readSeeds(kCorpus)) {
        Scene scene = load(fuzz::applyEdits(s, json::array()), s.name);
        EXPECT_GT(scene.triangleCount(), 0u) << s.name;
    }
    EXPECT_EQ(seed("avocado.glb").doc["images"].size(), 3u);
    Scene avocado = load(fuzz::applyEdits(seed("avocado.glb"), json::array()), "avocado");
    // Base colour (sRGB), metallic-roughness and normal (linear), decoded from their buffer views.
    ASSERT_EQ(avocado.textures.size(), 3u);
    EXPECT_EQ(avocado.textures[0].width, 32);
    EXPECT_TRUE(avocado.textures[0].srgb);
    EXPECT_FALSE(avocado.textures[1].srgb || avocado.textures[2].srgb);
}

TEST(HostileGLTF, RegressionCorpusGivesItsErrors) {
    json cases = json::parse(readTextFile(fs::path(GI_SOURCE_DIR) / "tests" / "fuzz" / "regressions.json"))["cases"];
    ASSERT_GE(cases.size(), 10u);
    double rssBefore = peakRSSMiB();
    for (const json& c : cases) {
        std::string name = c["name"];
        fuzz::FuzzInput in = fuzz::applyEdits(seed(c["seed"]), c["edits"]);
        std::string expect = c["expect"];
        try {
            Scene s = load(in, name);
            EXPECT_EQ(expect, "loads") << name << " loaded";
            if (c.contains("warning")) {
                bool warned = false;
                for (const auto& w : s.warnings) warned |= w.find(c["warning"].get<std::string>()) != std::string::npos;
                EXPECT_TRUE(warned) << name << ": no warning with '" << c["warning"].get<std::string>() << "'";
            }
        } catch (const Error& e) {
            std::string msg = e.what();
            EXPECT_NE(msg.find(expect), std::string::npos) << name << ": " << msg;
            EXPECT_EQ(msg.rfind(name, 0), 0u) << name << ": the message does not start with the file: " << msg;
            EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        }
    }
    // The huge counts were refused before their memory was taken (the process' high-water mark
    // stays far below what they ask for: 4294967297 vertices are over 100 GiB).
    EXPECT_LT(peakRSSMiB() - rssBefore, kBudgetMB) << "a hostile count allocated past the budget";
}

TEST(HostileGLTF, SparseAccessorsSubstituteTheirValues) {
    fuzz::GLTFSeed s = seed("cornell_original.glb");
    ASSERT_EQ(s.doc["accessors"][0]["count"], 4);
    size_t at = s.bin.size();
    // Sparse block: index 1 (uint16, padded to 4 bytes), then one VEC3 value.
    std::vector<uint8_t> extra(16, 0);
    uint16_t index = 1;
    float value[3] = {0.25f, 0.5f, 0.75f};
    std::memcpy(extra.data(), &index, 2);
    std::memcpy(extra.data() + 4, value, 12);
    s.bin.insert(s.bin.end(), extra.begin(), extra.end());
    s.doc["buffers"][0]["byteLength"] = s.bin.size();
    size_t views = s.doc["bufferViews"].size();
    s.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", 2}});
    s.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at + 4}, {"byteLength", 12}});
    s.doc["accessors"][0]["sparse"] = {{"count", 1},
                                       {"indices", {{"bufferView", views}, {"componentType", 5123}}},
                                       {"values", {{"bufferView", views + 1}}}};
    Scene withSparse = load(fuzz::applyEdits(s, json::array()), "sparse");
    Scene plain = load(fuzz::applyEdits(seed("cornell_original.glb"), json::array()), "plain");
    ASSERT_EQ(withSparse.vertices.size(), plain.vertices.size());
    size_t moved = 0;
    bool found = false;
    for (size_t i = 0; i < plain.vertices.size(); ++i) {
        moved += plain.vertices[i].position != withSparse.vertices[i].position;
        found |= glm::length(withSparse.vertices[i].position - glm::vec3(0.25f, 0.5f, 0.75f)) < 1e-6f;
    }
    EXPECT_EQ(moved, 1u);  // exactly the substituted vertex (the floor's node has no transform)
    EXPECT_TRUE(found);
    // Without a bufferView the base is zeros and only the substitutions are set.
    s.doc["accessors"][0].erase("bufferView");
    Scene zeros = load(fuzz::applyEdits(s, json::array()), "sparse_zeros");
    EXPECT_TRUE(std::any_of(zeros.vertices.begin(), zeros.vertices.end(),
                            [](const Vertex& v) { return glm::length(v.position - glm::vec3(0.25f, 0.5f, 0.75f)) < 1e-6f; }));
}

TEST(HostileGLTF, FoldersEmptyNamesAndOversizedFilesAreRefused) {
    auto dir = test::tempDir();
    auto expectError = [](const std::function<void()>& f, const std::string& text) {
        try {
            f();
            ADD_FAILURE() << "no error; expected '" << text << "'";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
        }
    };
    expectError([&] { loadScene(""); }, "key 'scene': empty");
    expectError([&] { loadGLTF(dir); }, "is a folder");
    fs::create_directories(dir / "folder.gltf");
    expectError([&] { loadGLTF(dir / "folder.gltf"); }, "folder.gltf: is a folder");
    expectError([&] { loadPreset(dir); }, "is a folder");
    // A buffer whose URI names a folder, through tinygltf's file callbacks.
    fuzz::GLTFSeed s = seed("cornell_original.glb");
    s.doc["buffers"][0]["uri"] = "folder.gltf";
    fuzz::FuzzInput in = fuzz::applyEdits(s, json::array());
    expectError([&] { loadGLTFFromMemory(in.bytes, true, "uri.glb", dir, kBudgetMB); }, "folder.gltf: is a folder");
    // A file larger than the budget is refused before it is read.
    {
        std::ofstream big(dir / "big.glb", std::ios::binary);
        big.seekp((std::streamoff(20) << 20) - 1);
        big.put(0);
    }
    expectError([&] { loadGLTF(dir / "big.glb", 16.0); }, "past the budget of 16 MiB (key 'render.memoryBudgetMB')");
}

TEST(HostileGLTF, ShortFuzzRunOnlyLoadsOrRefusesWithOneLine) {
    // The same mutations as gi-fuzz, in-process; gi-fuzz runs longer in the sanitizer build.
    std::vector<fuzz::GLTFSeed> seeds = fuzz::readSeeds(kCorpus);
    int loaded = 0, refused = 0;
    for (uint64_t i = 0; i < 400; ++i) {
        std::mt19937_64 rng = fuzz::iterationRng(11, i);
        const fuzz::GLTFSeed& s = seeds[rng() % seeds.size()];
        json edits = fuzz::randomEdits(s, rng);
        try {
            load(fuzz::applyEdits(s, edits), "fuzz");
            ++loaded;
        } catch (const Error& e) {
            std::string msg = e.what();
            ASSERT_EQ(msg.find('\n'), std::string::npos) << msg;
            ASSERT_EQ(msg.rfind("fuzz.gl", 0), 0u) << msg << "\nedits: " << edits.dump();
            ++refused;
        }
    }
    std::printf("  400 mutations: %d loaded, %d refused\n", loaded, refused);
    EXPECT_GT(loaded, 20);   // the mutations leave many files valid,
    EXPECT_GT(refused, 100); // and break many
}

TEST(HostilePreset, RegressionCasesGiveTheirErrors) {
    json cases = json::parse(readTextFile(fs::path(GI_SOURCE_DIR) / "tests" / "fuzz" / "preset_regressions.json"))["cases"];
    ASSERT_GE(cases.size(), 1u);
    for (const json& c : cases) {
        std::string name = c["name"];
        try {
            presetFromText(c["text"].get<std::string>(), "fuzz.json");
            ADD_FAILURE() << name << " parsed";
        } catch (const Error& e) {
            std::string msg = e.what();
            EXPECT_NE(msg.find(c["expect"].get<std::string>()), std::string::npos) << name << ": " << msg;
            EXPECT_EQ(msg.rfind("fuzz.json", 0), 0u) << name << ": " << msg;
            EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        }
    }
    // --set takes its value as JSON: a number past a double's range is no number, and says so.
    Preset p;
    try {
        applySetting(p, "camera.fovY=1e999");
        ADD_FAILURE() << "1e999 was taken as a field of view";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("key 'camera.fovY': expected a number"), std::string::npos) << e.what();
    }
}

class HostileGLTFRender : public test::GLTest {};

TEST_F(HostileGLTFRender, TextureCoordinatesFarFromTheOriginRenderPromptly) {
    // Avocado with its texture coordinates scaled by 1e5: before sampleMaterial() wrapped them,
    // llvmpipe's anisotropic filter stalled the shadow pass for minutes on such a file.
    fuzz::GLTFSeed s = seed("avocado.glb");
    const json& view = s.doc["bufferViews"][s.doc["accessors"][0]["bufferView"].get<size_t>()];
    size_t begin = view.value("byteOffset", size_t(0)), floats = view["byteLength"].get<size_t>() / 4;
    for (size_t i = 0; i < floats; ++i) {
        float f;
        std::memcpy(&f, s.bin.data() + begin + 4 * i, 4);
        f *= 1e5f;
        std::memcpy(s.bin.data() + begin + 4 * i, &f, 4);
    }
    Scene scene = load(fuzz::applyEdits(s, json::array()), "far_uv");
    for (const auto& w : scene.warnings) EXPECT_EQ(w.find("texture coordinates"), std::string::npos) << w;
    scene.cameras.push_back(frameBounds(scene.bounds));
    Preset p;
    p.camera.sceneCamera = 0;
    p.lightsFromScene = true;
    FrameSettings fs = frameSettings(p, scene, 64, 64);
    Renderer r;
    r.setScene(scene);
    r.render(fs);
    std::vector<uint8_t> img = r.readLDR();
    size_t lit = 0;
    for (size_t i = 0; i < img.size(); i += 4) lit += img[i] + img[i + 1] + img[i + 2] > 30;
    EXPECT_GT(lit, 50u) << "the avocado is not drawn";
}

}  // namespace
}  // namespace gi
