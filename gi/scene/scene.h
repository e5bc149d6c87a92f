// The CPU scene: world-space triangles grouped by material, materials, textures, the file's
// cameras and lights. glTF node hierarchies and instancing are flattened into world space at load,
// so the raster pipeline and the path tracer see exactly the same triangles.
#pragma once

#include "common/light.h"
#include "gi/scene/scene_settings.h"
#include "gi/util/budget.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace gi {

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 uv;                 // TEXCOORD_0
    glm::vec4 tangent{0.0f};      // xyz: world tangent, w: bitangent sign (+-1); all 0 where no material needs one
    glm::vec2 uv1{0.0f};          // TEXCOORD_1, read where a material's texture asks for it
};

// Blend is drawn as a dithered mask everywhere (raster G-buffer, shadow maps, RSMs,
// voxelization: a per-pixel threshold; the path tracer: a per-ray one): a fragment whose alpha
// is below the threshold is cut out, so coverage averages to alpha without sorting.
enum class AlphaMode { Opaque, Mask, Blend };

// The textures of a glTF metallic-roughness material, in the order of the texture units
// (kUnitBaseColor + slot) and of MaterialParams::uvTransform (common/material_shared.h).
enum TextureSlot { kSlotBaseColor = 0, kSlotMetallicRoughness, kSlotNormal, kSlotOcclusion, kSlotEmissive, kSlotCount };

// Which texture coordinates a texture reads and KHR_texture_transform's affine map of them:
// uv' = offset + rotate(rotation) * (scale * uv), as the extension defines it.
struct TextureTransform {
    glm::vec2 offset{0.0f};
    float rotation = 0.0f;  // radians, counter-clockwise in UV space
    glm::vec2 scale{1.0f};
    int texCoord = 0;       // 0: Vertex::uv, 1: Vertex::uv1
    // Rows of the 2x3 matrix (the third column is the offset).
    glm::vec3 row(int r) const;
    glm::vec2 apply(glm::vec2 uv0, glm::vec2 uv1) const;
};

struct Material {
    std::string name;
    glm::vec4 baseColor{1.0f};   // linear RGBA factor
    int baseColorTexture = -1;   // index into Scene::textures, -1 for none
    float metallic = 0.0f;
    float roughness = 1.0f;
    glm::vec3 emissive{0.0f};    // linear, already multiplied by KHR_materials_emissive_strength
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;
    bool doubleSided = false;    // false: back faces emit nothing
    int metallicRoughnessTexture = -1;  // linear; G roughness, B metallic, times the factors
    int normalTexture = -1;             // linear tangent-space normal map
    float normalScale = 1.0f;           // scales the map's x and y
    int occlusionTexture = -1;          // linear; R, scales the indirect term only
    float occlusionStrength = 1.0f;     // occlusion = 1 + strength * (R - 1)
    int emissiveTexture = -1;           // sRGB; emission = emissive * texture
    TextureTransform uvTransform[kSlotCount];
    int texture(int slot) const;        // the index of a slot's texture, -1 for none
};

// 8-bit RGBA image: sRGB encoded (base colour, emissive) or linear (metallic-roughness,
// occlusion, normal), uploaded with the matching internal format.
struct Texture {
    std::string name;
    int width = 0;
    int height = 0;
    bool srgb = true;
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
    // Half the diagonal, at least 1 mm: the scale framing, light placement and grids fit to.
    float radius() const { return std::max(0.5f * glm::length(extent()), 1e-3f); }
    // The cube a grid over the whole scene spans (LPV's single grid, VCT's dense grid, the free
    // path's occupancy): the largest extent, at least 1 mm, 2 % larger so that surfaces on the
    // bounds fall inside, centred on the bounds.
    float gridCubeSize() const {
        glm::vec3 e = extent();
        return std::max(std::max(e.x, e.y), std::max(e.z, 1e-3f)) * 1.02f;
    }
    glm::vec3 gridCubeMin() const { return center() - glm::vec3(0.5f * gridCubeSize()); }
};

// Emissive triangles grouped into area lights when the scene loads (buildEmitters): connected
// triangles of one material, split in space into parts of kMaxEmitterTriangles (larger parts
// when the scene has more emissive triangles than kMaxEmitters such parts hold; lights of more
// than kMaxEmitterTriangles shade as points with a cosine lobe). Each triangle is wound so that
// its front, (p1 - p0) x (p2 - p0), faces the side it emits from.
inline constexpr int kMaxEmitterTriangles = light::kAreaMaxExactTriangles;  // so each part shades exactly
inline constexpr int kMaxEmitters = 32;
struct Emitter {
    std::string name;                 // the material's name, with #k when it makes several
    int material = -1;
    std::vector<uint32_t> triangles;  // triangle indices (into Scene::indices / 3)
    std::vector<glm::vec3> corners;   // 3 per triangle, world space, front-wound
    std::vector<glm::vec3> radiance;  // per triangle: the material's emission (factor x strength x the texture's mean)
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
    std::vector<std::string> cameraNames; // their names (the camera's, else its node's); may be shorter
    bool framedCamera = false;            // cameras[0] was made by loadScene: the file has none
    // The camera's name as the editor lists it: its own, else "camera N".
    std::string cameraName(size_t i) const {
        return i < cameraNames.size() && !cameraNames[i].empty() ? cameraNames[i] : "camera " + std::to_string(i);
    }
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

// Bilinear, repeating lookup of a texture at uv on the CPU, as the GPU's sampler reads mip 0:
// rgb decoded to linear when the texture is sRGB, alpha linear.
glm::vec4 sampleTexture(const Texture& texture, glm::vec2 uv);
// A material's emitted radiance at a point with texture coordinates uv0 (TEXCOORD_0) and uv1
// (TEXCOORD_1): emissive factor (times emissive strength) times the emissive texture.
glm::vec3 emission(const Scene& scene, const Material& material, glm::vec2 uv0, glm::vec2 uv1 = glm::vec2(0.0f));

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
