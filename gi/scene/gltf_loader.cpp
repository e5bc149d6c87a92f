// glTF 2.0 loading through tinygltf. tinygltf parses the JSON and decodes images; everything it
// does not check (accessor bounds, index ranges, non-finite data, node cycles) is validated here
// before use, so a malformed file fails with a message naming the element instead of crashing.
#include "gi/scene/scene.h"
#include "gi/util/error.h"

#include <tiny_gltf.h>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

namespace gi {
namespace {

constexpr int kMaxNodeDepth = 256;

class GLTFReader {
public:
    GLTFReader(const tinygltf::Model& model, const std::string& file, Scene& scene)
        : mModel(model), mFile(file), mScene(scene) {}

    [[noreturn]] void fail(const std::string& what) const { throw Error(mFile + ": " + what); }

    // Reads `count * components` floats from an accessor, converting normalized integers.
    std::vector<float> readFloats(int accessorIndex, int components, const char* what) const {
        const tinygltf::Accessor& a = accessor(accessorIndex, what);
        if (componentsOf(a.type) != components)
            fail(std::string(what) + ": accessor " + std::to_string(accessorIndex) + " has type " +
                 typeName(a.type) + ", expected " + std::to_string(components) + " components");
        std::vector<float> out(size_t(a.count) * components, 0.0f);
        forEachElement(a, accessorIndex, components, what, [&](size_t i, const uint8_t* p) {
            for (int c = 0; c < components; ++c) out[i * components + c] = component(a, p, c, what, accessorIndex);
        });
        for (float f : out)
            if (!std::isfinite(f))
                fail(std::string(what) + ": accessor " + std::to_string(accessorIndex) + " contains non-finite values");
        return out;
    }

    std::vector<uint32_t> readIndices(int accessorIndex) const {
        const char* what = "indices";
        const tinygltf::Accessor& a = accessor(accessorIndex, what);
        if (a.type != TINYGLTF_TYPE_SCALAR)
            fail("indices: accessor " + std::to_string(accessorIndex) + " is not SCALAR");
        if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            fail("indices: accessor " + std::to_string(accessorIndex) + " has a non-integer component type");
        std::vector<uint32_t> out(a.count);
        forEachElement(a, accessorIndex, 1, what, [&](size_t i, const uint8_t* p) {
            switch (a.componentType) {
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: out[i] = *p; break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t v; std::memcpy(&v, p, 2); out[i] = v; break; }
                default: { uint32_t v; std::memcpy(&v, p, 4); out[i] = v; break; }
            }
        });
        return out;
    }

    void load() {
        loadMaterials();
        std::vector<int> roots;
        if (!mModel.scenes.empty()) {
            int s = mModel.defaultScene >= 0 ? mModel.defaultScene : 0;
            if (s >= int(mModel.scenes.size())) fail("scene " + std::to_string(s) + " does not exist");
            roots = mModel.scenes[s].nodes;
        } else {
            // No scene: every node that is nobody's child is a root.
            std::vector<bool> isChild(mModel.nodes.size(), false);
            for (const auto& n : mModel.nodes)
                for (int c : n.children)
                    if (c >= 0 && c < int(isChild.size())) isChild[c] = true;
            for (size_t i = 0; i < mModel.nodes.size(); ++i)
                if (!isChild[i]) roots.push_back(int(i));
        }
        std::vector<bool> onStack(mModel.nodes.size(), false);
        for (int r : roots) visitNode(r, glm::mat4(1.0f), onStack, 0);
    }

private:
    const tinygltf::Model& mModel;
    std::string mFile;
    Scene& mScene;
    std::map<int, int> mImageToTexture;
    int mDefaultMaterial = -1;

    static int componentsOf(int type) {
        switch (type) {
            case TINYGLTF_TYPE_SCALAR: return 1;
            case TINYGLTF_TYPE_VEC2: return 2;
            case TINYGLTF_TYPE_VEC3: return 3;
            case TINYGLTF_TYPE_VEC4: return 4;
            case TINYGLTF_TYPE_MAT2: return 4;
            case TINYGLTF_TYPE_MAT3: return 9;
            case TINYGLTF_TYPE_MAT4: return 16;
        }
        return 0;
    }
    static std::string typeName(int type) {
        switch (type) {
            case TINYGLTF_TYPE_SCALAR: return "SCALAR";
            case TINYGLTF_TYPE_VEC2: return "VEC2";
            case TINYGLTF_TYPE_VEC3: return "VEC3";
            case TINYGLTF_TYPE_VEC4: return "VEC4";
        }
        return "type " + std::to_string(type);
    }
    static int componentBytes(int ct) {
        switch (ct) {
            case TINYGLTF_COMPONENT_TYPE_BYTE:
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
            case TINYGLTF_COMPONENT_TYPE_SHORT:
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        }
        return 0;
    }

    const tinygltf::Accessor& accessor(int index, const char* what) const {
        if (index < 0 || index >= int(mModel.accessors.size()))
            fail(std::string(what) + ": accessor " + std::to_string(index) + " does not exist");
        return mModel.accessors[index];
    }

    template <class F>
    void forEachElement(const tinygltf::Accessor& a, int index, int components, const char* what, F&& f) const {
        std::string name = std::string(what) + ": accessor " + std::to_string(index);
        int cb = componentBytes(a.componentType);
        if (cb == 0) fail(name + " has an unknown component type " + std::to_string(a.componentType));
        if (a.sparse.isSparse) fail(name + " is sparse, which is not supported");
        if (a.count == 0) return;
        if (a.count > (size_t(1) << 28)) fail(name + " has an absurd count " + std::to_string(a.count));
        if (a.bufferView < 0) return;  // no data: all zeros, as the spec says
        if (a.bufferView >= int(mModel.bufferViews.size()))
            fail(name + " references missing bufferView " + std::to_string(a.bufferView));
        const tinygltf::BufferView& view = mModel.bufferViews[a.bufferView];
        if (view.buffer < 0 || view.buffer >= int(mModel.buffers.size()))
            fail(name + ": bufferView " + std::to_string(a.bufferView) + " references a missing buffer");
        const tinygltf::Buffer& buffer = mModel.buffers[view.buffer];
        size_t elementBytes = size_t(cb) * components;
        size_t stride = view.byteStride ? view.byteStride : elementBytes;
        size_t begin = view.byteOffset + a.byteOffset;
        size_t last = begin + stride * (a.count - 1) + elementBytes;
        if (a.byteOffset + stride * (a.count - 1) + elementBytes > view.byteLength || last > buffer.data.size())
            fail(name + " reads past the end of its buffer (needs " + std::to_string(last) + " bytes, buffer has " +
                 std::to_string(buffer.data.size()) + ")");
        const uint8_t* base = buffer.data.data() + begin;
        for (size_t i = 0; i < a.count; ++i) f(i, base + i * stride);
    }

    float component(const tinygltf::Accessor& a, const uint8_t* p, int c, const char* what, int index) const {
        switch (a.componentType) {
            case TINYGLTF_COMPONENT_TYPE_FLOAT: { float v; std::memcpy(&v, p + 4 * c, 4); return v; }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: { float v = p[c]; return a.normalized ? v / 255.0f : v; }
            case TINYGLTF_COMPONENT_TYPE_BYTE: { float v = float(int8_t(p[c])); return a.normalized ? std::max(v / 127.0f, -1.0f) : v; }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t v; std::memcpy(&v, p + 2 * c, 2); return a.normalized ? v / 65535.0f : float(v); }
            case TINYGLTF_COMPONENT_TYPE_SHORT: { int16_t v; std::memcpy(&v, p + 2 * c, 2); return a.normalized ? std::max(v / 32767.0f, -1.0f) : float(v); }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t v; std::memcpy(&v, p + 4 * c, 4); return float(v); }
        }
        fail(std::string(what) + ": accessor " + std::to_string(index) + " has an unsupported component type");
    }

    int textureFor(int textureIndex) {
        if (textureIndex < 0) return -1;
        if (textureIndex >= int(mModel.textures.size()))
            fail("texture " + std::to_string(textureIndex) + " does not exist");
        int source = mModel.textures[textureIndex].source;
        if (source < 0 || source >= int(mModel.images.size())) {
            mScene.warnings.push_back("texture " + std::to_string(textureIndex) + " has no usable image; ignored");
            return -1;
        }
        auto it = mImageToTexture.find(source);
        if (it != mImageToTexture.end()) return it->second;
        const tinygltf::Image& img = mModel.images[source];
        if (img.width <= 0 || img.height <= 0 || img.image.empty() || img.bits != 8 || img.component < 1 ||
            img.component > 4 || img.image.size() < size_t(img.width) * img.height * img.component) {
            mScene.warnings.push_back("image " + std::to_string(source) + " ('" + img.uri +
                                      "') could not be decoded as 8-bit; ignored");
            mImageToTexture[source] = -1;
            return -1;
        }
        Texture t;
        t.name = img.name.empty() ? img.uri : img.name;
        t.width = img.width;
        t.height = img.height;
        t.rgba.resize(size_t(img.width) * img.height * 4);
        for (size_t i = 0; i < size_t(img.width) * img.height; ++i) {
            const uint8_t* s = &img.image[i * img.component];
            uint8_t* d = &t.rgba[i * 4];
            switch (img.component) {
                case 1: d[0] = d[1] = d[2] = s[0]; d[3] = 255; break;
                case 2: d[0] = d[1] = d[2] = s[0]; d[3] = s[1]; break;
                case 3: d[0] = s[0]; d[1] = s[1]; d[2] = s[2]; d[3] = 255; break;
                default: std::memcpy(d, s, 4); break;
            }
        }
        mScene.textures.push_back(std::move(t));
        return mImageToTexture[source] = int(mScene.textures.size()) - 1;
    }

    void loadMaterials() {
        for (size_t i = 0; i < mModel.materials.size(); ++i) {
            const tinygltf::Material& m = mModel.materials[i];
            Material out;
            out.name = m.name.empty() ? "material" + std::to_string(i) : m.name;
            const auto& pbr = m.pbrMetallicRoughness;
            for (int c = 0; c < 4 && c < int(pbr.baseColorFactor.size()); ++c) out.baseColor[c] = float(pbr.baseColorFactor[c]);
            out.baseColorTexture = textureFor(pbr.baseColorTexture.index);
            out.metallic = std::clamp(float(pbr.metallicFactor), 0.0f, 1.0f);
            out.roughness = std::clamp(float(pbr.roughnessFactor), 0.0f, 1.0f);
            for (int c = 0; c < 3 && c < int(m.emissiveFactor.size()); ++c) out.emissive[c] = float(m.emissiveFactor[c]);
            auto ext = m.extensions.find("KHR_materials_emissive_strength");
            if (ext != m.extensions.end() && ext->second.IsObject() && ext->second.Has("emissiveStrength")) {
                const auto& s = ext->second.Get("emissiveStrength");
                if (s.IsNumber()) out.emissive *= float(s.GetNumberAsDouble());
            }
            if (m.emissiveTexture.index >= 0 && glm::length(out.emissive) > 0.0f) {
                // The factor only scales the texture, which holds the pattern: emitting the bare
                // factor would light the whole surface. Emissive textures are not loaded yet.
                out.emissive = glm::vec3(0.0f);
                mScene.warnings.push_back("material '" + out.name +
                                          "': emissive textures are not supported; its emission is left out");
            }
            if (m.alphaMode == "MASK") out.alphaMode = AlphaMode::Mask;
            else if (m.alphaMode == "BLEND") out.alphaMode = AlphaMode::Blend;
            out.alphaCutoff = float(m.alphaCutoff);
            out.doubleSided = m.doubleSided;
            for (int c = 0; c < 4; ++c)
                if (!std::isfinite(out.baseColor[c])) fail("material " + std::to_string(i) + ": non-finite baseColorFactor");
            if (!std::isfinite(out.emissive.x + out.emissive.y + out.emissive.z))
                fail("material " + std::to_string(i) + ": non-finite emissive");
            mScene.materials.push_back(out);
        }
    }

    int defaultMaterial() {
        if (mDefaultMaterial < 0) {
            Material m;
            m.name = "default";
            m.baseColor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
            mScene.materials.push_back(m);
            mDefaultMaterial = int(mScene.materials.size()) - 1;
        }
        return mDefaultMaterial;
    }

    static glm::mat4 localMatrix(const tinygltf::Node& n) {
        if (n.matrix.size() == 16) {
            glm::mat4 m;
            for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = float(n.matrix[i]);
            return m;
        }
        glm::mat4 t(1.0f), r(1.0f), s(1.0f);
        if (n.translation.size() == 3) t = glm::translate(glm::mat4(1.0f), glm::vec3(n.translation[0], n.translation[1], n.translation[2]));
        if (n.rotation.size() == 4)
            r = glm::mat4_cast(glm::normalize(glm::quat(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]), float(n.rotation[2]))));
        if (n.scale.size() == 3) s = glm::scale(glm::mat4(1.0f), glm::vec3(n.scale[0], n.scale[1], n.scale[2]));
        return t * r * s;
    }

    void visitNode(int index, const glm::mat4& parent, std::vector<bool>& onStack, int depth) {
        if (index < 0 || index >= int(mModel.nodes.size())) fail("node " + std::to_string(index) + " does not exist");
        if (onStack[index]) fail("node " + std::to_string(index) + " is its own ancestor (cyclic node hierarchy)");
        if (depth > kMaxNodeDepth) fail("node hierarchy deeper than " + std::to_string(kMaxNodeDepth));
        const tinygltf::Node& node = mModel.nodes[index];
        glm::mat4 world = parent * localMatrix(node);
        for (int i = 0; i < 16; ++i)
            if (!std::isfinite(glm::value_ptr(world)[i])) fail("node " + std::to_string(index) + ": non-finite transform");
        onStack[index] = true;
        if (node.mesh >= 0) {
            if (node.mesh >= int(mModel.meshes.size())) fail("node " + std::to_string(index) + ": mesh " + std::to_string(node.mesh) + " does not exist");
            const auto& mesh = mModel.meshes[node.mesh];
            for (size_t p = 0; p < mesh.primitives.size(); ++p) addPrimitive(mesh.primitives[p], node.mesh, int(p), world);
        }
        if (node.camera >= 0) addCamera(node.camera, world);
        auto ext = node.extensions.find("KHR_lights_punctual");
        if (ext != node.extensions.end() && ext->second.IsObject() && ext->second.Has("light")) {
            const auto& l = ext->second.Get("light");
            if (l.IsInt()) addLight(l.GetNumberAsInt(), world);
        }
        for (int c : node.children) visitNode(c, world, onStack, depth + 1);
        onStack[index] = false;
    }

    void addCamera(int index, const glm::mat4& world) {
        if (index >= int(mModel.cameras.size())) fail("camera " + std::to_string(index) + " does not exist");
        const auto& c = mModel.cameras[index];
        CameraSettings cam;
        cam.eye = glm::vec3(world[3]);
        glm::vec3 forward = -glm::normalize(glm::vec3(world[2]));
        cam.target = cam.eye + forward;
        cam.up = glm::normalize(glm::vec3(world[1]));
        if (c.type == "perspective") {
            cam.fovY = std::clamp(float(glm::degrees(c.perspective.yfov)), 1.0f, 170.0f);
            if (c.perspective.znear > 0) cam.near = float(c.perspective.znear);
            if (c.perspective.zfar > c.perspective.znear) cam.far = float(c.perspective.zfar);
        } else {
            mScene.warnings.push_back("camera " + std::to_string(index) + " is orthographic; shown as perspective");
        }
        mScene.cameras.push_back(cam);
    }

    void addLight(int index, const glm::mat4& world) {
        if (index < 0 || index >= int(mModel.lights.size())) fail("light " + std::to_string(index) + " does not exist");
        const auto& l = mModel.lights[index];
        LightSettings out;
        if (l.type == "directional") out.type = LightType::Directional;
        else if (l.type == "point") out.type = LightType::Point;
        else if (l.type == "spot") out.type = LightType::Spot;
        else fail("light " + std::to_string(index) + ": unknown type '" + l.type + "'");
        if (l.color.size() == 3) out.color = glm::vec3(l.color[0], l.color[1], l.color[2]);
        out.intensity = float(l.intensity);
        out.range = float(l.range);
        out.position = glm::vec3(world[3]);
        out.direction = -glm::normalize(glm::vec3(world[2]));
        out.innerConeDeg = float(glm::degrees(l.spot.innerConeAngle));
        out.outerConeDeg = std::max(float(glm::degrees(l.spot.outerConeAngle)), out.innerConeDeg + 0.1f);
        mScene.lights.push_back(out);
    }

    void addPrimitive(const tinygltf::Primitive& prim, int meshIndex, int primIndex, const glm::mat4& world) {
        std::string where = "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(primIndex);
        if (prim.mode >= 0 && prim.mode <= 3) {
            mScene.warnings.push_back(where + ": points and lines are not surfaces; skipped");
            return;
        }
        if (prim.mode > 6) fail(where + ": unknown primitive mode " + std::to_string(prim.mode));
        auto posIt = prim.attributes.find("POSITION");
        if (posIt == prim.attributes.end()) fail(where + " has no POSITION attribute");
        std::vector<float> pos = readFloats(posIt->second, 3, "POSITION");
        size_t vertexCount = pos.size() / 3;
        std::vector<float> nrm, uv;
        if (auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end()) {
            nrm = readFloats(it->second, 3, "NORMAL");
            if (nrm.size() / 3 != vertexCount) fail(where + ": NORMAL count differs from POSITION count");
        }
        int material = prim.material;
        if (material >= int(mModel.materials.size()))
            fail(where + ": material " + std::to_string(material) + " does not exist");
        if (material < 0) material = defaultMaterial();
        int texCoord = 0;
        if (material < int(mModel.materials.size()))
            texCoord = mModel.materials[material].pbrMetallicRoughness.baseColorTexture.texCoord;
        if (auto it = prim.attributes.find("TEXCOORD_" + std::to_string(texCoord)); it != prim.attributes.end()) {
            uv = readFloats(it->second, 2, "TEXCOORD");
            if (uv.size() / 2 != vertexCount) fail(where + ": TEXCOORD count differs from POSITION count");
        }

        std::vector<uint32_t> idx;
        if (prim.indices >= 0) {
            idx = readIndices(prim.indices);
            for (uint32_t i : idx)
                if (i >= vertexCount)
                    fail(where + ": index " + std::to_string(i) + " out of range (" + std::to_string(vertexCount) + " vertices)");
        } else {
            idx.resize(vertexCount);
            for (size_t i = 0; i < vertexCount; ++i) idx[i] = uint32_t(i);
        }
        std::vector<uint32_t> tris;
        if (prim.mode == 5) {  // strip
            for (size_t i = 2; i < idx.size(); ++i) {
                if (i % 2 == 0) tris.insert(tris.end(), {idx[i - 2], idx[i - 1], idx[i]});
                else tris.insert(tris.end(), {idx[i - 1], idx[i - 2], idx[i]});
            }
        } else if (prim.mode == 6) {  // fan
            for (size_t i = 2; i < idx.size(); ++i) tris.insert(tris.end(), {idx[0], idx[i - 1], idx[i]});
        } else {
            if (idx.size() % 3 != 0)
                mScene.warnings.push_back(where + ": index count is not a multiple of 3; the tail is ignored");
            tris.assign(idx.begin(), idx.begin() + (idx.size() / 3) * 3);
        }
        if (tris.empty()) return;

        glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(world));
        bool flip = glm::determinant(glm::mat3(world)) < 0.0f;
        auto transformPos = [&](uint32_t i) { return glm::vec3(world * glm::vec4(pos[i * 3], pos[i * 3 + 1], pos[i * 3 + 2], 1.0f)); };

        uint32_t firstIndex = uint32_t(mScene.indices.size());
        if (nrm.empty()) {
            // No normals: flat shading, one vertex per triangle corner (as the spec asks).
            for (size_t t = 0; t + 2 < tris.size(); t += 3) {
                glm::vec3 p[3] = {transformPos(tris[t]), transformPos(tris[t + 1]), transformPos(tris[t + 2])};
                glm::vec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
                float len = glm::length(n);
                n = len > 0.0f ? n / len : glm::vec3(0, 1, 0);
                if (flip) n = -n;
                uint32_t base = uint32_t(mScene.vertices.size());
                for (int k = 0; k < 3; ++k) {
                    uint32_t i = tris[t + k];
                    glm::vec2 tc = uv.empty() ? glm::vec2(0.0f) : glm::vec2(uv[i * 2], uv[i * 2 + 1]);
                    mScene.vertices.push_back({p[k], n, tc});
                }
                if (flip) mScene.indices.insert(mScene.indices.end(), {base, base + 2, base + 1});
                else mScene.indices.insert(mScene.indices.end(), {base, base + 1, base + 2});
            }
        } else {
            uint32_t base = uint32_t(mScene.vertices.size());
            for (size_t i = 0; i < vertexCount; ++i) {
                glm::vec3 n = normalMatrix * glm::vec3(nrm[i * 3], nrm[i * 3 + 1], nrm[i * 3 + 2]);
                float len = glm::length(n);
                n = len > 1e-20f ? n / len : glm::vec3(0, 1, 0);
                glm::vec2 tc = uv.empty() ? glm::vec2(0.0f) : glm::vec2(uv[i * 2], uv[i * 2 + 1]);
                mScene.vertices.push_back({transformPos(uint32_t(i)), n, tc});
            }
            for (size_t t = 0; t + 2 < tris.size(); t += 3) {
                if (flip) mScene.indices.insert(mScene.indices.end(), {base + tris[t], base + tris[t + 2], base + tris[t + 1]});
                else mScene.indices.insert(mScene.indices.end(), {base + tris[t], base + tris[t + 1], base + tris[t + 2]});
            }
        }
        if (mScene.vertices.size() > (size_t(1) << 31)) fail("scene has more than 2^31 vertices");
        mScene.draws.push_back({firstIndex, uint32_t(mScene.indices.size()) - firstIndex, material});
    }
};

}  // namespace

Scene loadGLTF(const std::filesystem::path& path) {
    if (!std::filesystem::exists(path)) throw Error(path.string() + ": file not found");
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string err, warn;
    bool ok = false;
    try {
        std::string ext = path.extension().string();
        for (auto& c : ext) c = char(std::tolower(c));
        if (ext == ".glb") ok = loader.LoadBinaryFromFile(&model, &err, &warn, path.string());
        else ok = loader.LoadASCIIFromFile(&model, &err, &warn, path.string());
    } catch (const std::exception& e) {
        throw Error(path.string() + ": malformed glTF: " + e.what());
    }
    if (!ok) {
        std::string msg = err.empty() ? warn : err;
        while (!msg.empty() && (msg.back() == '\n' || msg.back() == '\r')) msg.pop_back();
        for (auto& c : msg)
            if (c == '\n') c = ';';
        throw Error(path.string() + ": malformed glTF: " + (msg.empty() ? "unknown error" : msg));
    }
    for (const auto& e : model.extensionsRequired)
        if (e != "KHR_lights_punctual" && e != "KHR_materials_emissive_strength")
            throw Error(path.string() + ": requires unsupported extension " + e);

    Scene scene;
    scene.name = path.stem().string();
    GLTFReader(model, path.string(), scene).load();
    if (scene.indices.empty()) throw Error(path.string() + ": contains no triangles");
    scene.finalize();
    return scene;
}

}  // namespace gi
