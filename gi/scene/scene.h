// The CPU scene: world-space triangles grouped by material, materials, textures, the file's
// cameras and lights. glTF node hierarchies and instancing are flattened into world space at load,
// so the raster pipeline and the path tracer see exactly the same triangles.
#pragma once

#include "gi/scene/scene_settings.h"
#include "gi/util/budget.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace gi {

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 uv;
};

enum class AlphaMode { Opaque, Mask, Blend };

struct Material {
    std::string name;
    glm::vec4 baseColor{1.0f};   // linear RGBA factor
    int baseColorTexture = -1;   // index into Scene::textures, -1 for none
    float metallic = 0.0f;
    float roughness = 1.0f;
    glm::vec3 emissive{0.0f};    // linear, already multiplied by KHR_materials_emissive_strength
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;
    bool doubleSided = false;
};

// 8-bit RGBA image, sRGB encoded (base colour textures).
struct Texture {
    std::string name;
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba;
};

// A contiguous run of indices drawn with one material.
struct Draw {
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    int material = 0;
};

struct Bounds {
    glm::vec3 min{std::numeric_limits<float>::max()};
    glm::vec3 max{-std::numeric_limits<float>::max()};
    void grow(const glm::vec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    bool valid() const { return min.x <= max.x; }
    glm::vec3 center() const { return (min + max) * 0.5f; }
    glm::vec3 extent() const { return max - min; }
};

// Emissive triangles grouped into area lights when the scene loads (buildEmitters): connected
// triangles of one material, split in space into parts of kMaxEmitterTriangles (larger parts
// when the scene has more emissive triangles than kMaxEmitters such parts hold; lights of more
// than kMaxEmitterTriangles shade as points with a cosine lobe). Each triangle is wound so that
// its front, (p1 - p0) x (p2 - p0), faces the side it emits from.
inline constexpr int kMaxEmitterTriangles = 16;
inline constexpr int kMaxEmitters = 32;
struct Emitter {
    std::string name;                 // the material's name, with #k when it makes several
    int material = -1;
    std::vector<uint32_t> triangles;  // triangle indices (into Scene::indices / 3)
    std::vector<glm::vec3> corners;   // 3 per triangle, world space, front-wound
    std::vector<glm::vec3> radiance;  // per triangle: the material's emission (factor x strength)
    glm::vec3 centroid{0.0f};         // area-weighted
    glm::vec3 normal{0.0f, -1.0f, 0.0f};  // unit, area-weighted mean of the fronts: the way light leaves
    float area = 0.0f;
    glm::vec3 power{0.0f};            // sum of radiance x area (the flux is pi times this, one side)
    bool doubleSided = false;
};

struct Scene {
    std::string name;
    std::vector<Vertex> vertices;   // world space
    std::vector<uint32_t> indices;  // triangles
    std::vector<Draw> draws;        // sorted by material
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<CameraSettings> cameras;  // the file's cameras (eye/target/fov), in file order
    std::vector<LightSettings> lights;    // the file's or the built-in scene's punctual lights
    std::vector<Emitter> emitters;        // emissive surfaces as area lights (finalize builds them)
    std::vector<int> triangleEmitter;     // per triangle: its emitter, -1 for none
    std::vector<std::string> warnings;    // content that was skipped, one line each
    Bounds bounds;

    size_t triangleCount() const { return indices.size() / 3; }
    // Sorts draws by material, merges neighbours, computes bounds and groups the emissive triangles
    // into emitters (a warning when more than kMaxEmitters: the faintest then emit nothing, in
    // the raster and the reference alike). Loaders call it last.
    void finalize();
};

// The scene's lights as a preset lists them: its punctual lights, then one area light (intensity
// 1, white) per emitter; the four most powerful emitters cast shadows.
std::vector<LightSettings> sceneLights(const Scene& scene);

// Built-in scenes that need no files.
std::vector<std::string> builtinSceneNames();
bool isBuiltinScene(const std::string& name);
Scene makeBuiltinScene(const std::string& name);

// glTF 2.0 (.gltf or .glb). Throws gi::Error naming the file and the broken element. The memory
// the file will take (its JSON tree, buffers, decoded images and triangles) is counted before it
// is allocated and refused past `memoryBudgetMB` (render.memoryBudgetMB).
Scene loadGLTF(const std::filesystem::path& path, double memoryBudgetMB = kDefaultMemoryBudgetMB);
// The same from bytes in memory (a .gltf's JSON, or a whole .glb when `binary`); `name` stands
// for the file in messages, and external URIs resolve against `baseDir`. Used by the fuzzers.
Scene loadGLTFFromMemory(const std::vector<uint8_t>& bytes, bool binary, const std::string& name,
                         const std::filesystem::path& baseDir, double memoryBudgetMB = kDefaultMemoryBudgetMB);

// A camera that frames the bounds, looking at their centre from the front right and above.
CameraSettings frameBounds(const Bounds& b);

// Resolves a preset's scene string (built-in name, or file through the asset search path).
// A file without cameras gets one framing its bounds.
Scene loadScene(const std::string& scene, const std::filesystem::path& presetFolder = {},
                double memoryBudgetMB = kDefaultMemoryBudgetMB);

}  // namespace gi
