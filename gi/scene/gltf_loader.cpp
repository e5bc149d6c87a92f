// glTF 2.0 loading through tinygltf, hardened against hostile files.
//
// tinygltf parses the JSON and little else: it does not check that views lie inside their
// buffers, that accessors fit their views, that a GLB's chunks fit the file, or how much memory
// the counts in a file will take. So, in order:
//   1. the file is read here (a regular file, its size counted against render.memoryBudgetMB
//      together with the JSON tree it will become) and a GLB's chunk layout is checked;
//   2. tinygltf parses it with this loader's file callbacks (external buffers and images are
//      bounded the same way) and image callback (a view must lie inside its buffer, the decoded
//      size is read from the image header and counted before anything is decoded, decoding is
//      OpenImageIO's);
//   3. the node hierarchy is walked once (cycles, depth and the number of node instances are
//      bounded, so shared subtrees cannot expand exponentially) and the memory the triangles will
//      take is estimated and counted before any of it is allocated;
//   4. accessors are read with range checks written so that offset + length cannot wrap, and
//      with the spec's alignment rules; sparse accessors are applied per the spec.
// Every failure is a gi::Error of one line that names the file and the element at fault.
//
// Materials are read whole (README "Materials"): each texture reference is range-checked and
// decoded in its slot's colour space (base colour and emissive sRGB, the others linear; an image
// used both ways is decoded twice, each counted), with its texCoord (0 or 1; a larger set leaves
// the texture out with a warning) and KHR_texture_transform. Alpha mode BLEND is kept and drawn
// everywhere as a dithered mask. Primitives whose material has a normal map get tangents: the
// file's TANGENT, else per-vertex tangents derived from the normal map's texture coordinates.
#include "gi/scene/scene.h"
#include "gi/util/budget.h"
#include "gi/util/error.h"
#include "gi/util/paths.h"
#include "gi/util/png_layout.h"

#include <tiny_gltf.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>

namespace gi {
namespace {

namespace fs = std::filesystem;

constexpr int kMaxNodeDepth = 256;
// Node visits over the whole hierarchy: a node may be the child of many parents, so a small file
// can describe an exponential number of instances.
constexpr size_t kMaxNodeInstances = size_t(1) << 20;
// nlohmann's JSON tree takes up to this many bytes per byte of JSON text (a one-byte value is a
// 16-byte node; an object member costs a map node and its key).
constexpr double kJSONTreeBytesPerByte = 32.0;
// World coordinates past this are refused: squared distances in single precision (lighting,
// bounds, shadow projections) overflow near 1e19.
constexpr float kMaxWorldCoordinate = 1e15f;
// Texture coordinates past 2^23 have no fractional part left in single precision, so they no
// longer address a point of the texture: such a primitive's coordinates are dropped.
constexpr float kMaxTexCoord = 8388608.0f;

std::string str(size_t v) { return std::to_string(v); }

// a + b <= limit, without computing a + b.
bool fits(size_t offset, size_t length, size_t limit) { return offset <= limit && length <= limit - offset; }

// A file read whole, after checking it is a regular file and counting its size.
std::vector<uint8_t> readBounded(const fs::path& path, MemoryBudget& budget, double bytesPerByte, const std::string& what) {
    uintmax_t size = regularFileSize(path, what);
    budget.reserve(double(size) * bytesPerByte, path.string() + ": " + what + " of " + str(size_t(size)) + " bytes");
    std::vector<uint8_t> bytes(static_cast<size_t>(size));
    std::ifstream in(path, std::ios::binary);
    if (!in || !in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size())))
        throw Error(path.string() + ": cannot read " + what);
    return bytes;
}

// Everything tinygltf's callbacks need: the budget, and the first error they hit (tinygltf's
// own messages for a failed callback are generic).
struct LoadContext {
    MemoryBudget* budget = nullptr;
    tinygltf::Model* model = nullptr;
    std::string error;
};

// Anything that exists "exists", so that fsReadWholeFile names what is wrong with it.
bool fsFileExists(const std::string& path, void*) {
    std::error_code ec;
    return fs::exists(path, ec);
}

std::string fsExpandFilePath(const std::string& path, void*) { return path; }  // no ~ or $VAR expansion

bool fsReadWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    auto* ctx = static_cast<LoadContext*>(user);
    try {
        *out = readBounded(path, *ctx->budget, 1.0, "referenced file");
        return true;
    } catch (const Error& e) {
        if (ctx->error.empty()) ctx->error = e.what();
        if (err) *err += e.what();
        return false;
    }
}

bool fsWriteWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "the loader writes no files";
    return false;
}

// Decodes a PNG or JPEG held in memory to 8-bit RGBA with OpenImageIO, after checking a PNG's
// chunk layout and counting the size its header states. Returns false with `warning` set when
// the bytes are no image it can read.
bool decodeImage(const uint8_t* bytes, size_t size, int index, MemoryBudget& budget, Texture& image, std::string& warning) {
    const char* name = nullptr;
    if (isPNG(bytes, size)) name = "image.png";
    else if (size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) name = "image.jpg";
    if (!name) {
        warning = "image " + str(size_t(index)) + " is neither PNG nor JPEG";
        return false;
    }
    if (name == std::string("image.png"))
        if (std::string problem = pngLayoutProblem(bytes, size); !problem.empty()) {
            warning = "image " + str(size_t(index)) + ": " + problem;
            return false;
        }
    OIIO::Filesystem::IOMemReader reader(bytes, size);
    auto in = OIIO::ImageInput::open(name, nullptr, &reader);
    if (!in) {
        warning = "image " + str(size_t(index)) + " cannot be read: " + OIIO::geterror();
        for (auto& c : warning)
            if (c == '\n') c = ' ';
        return false;
    }
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth != 1) {
        warning = "image " + str(size_t(index)) + " has no pixels";
        return false;
    }
    // The decoded file, the RGBA copy, and a progressive JPEG's 16-bit coefficients.
    double pixels = double(spec.width) * double(spec.height);
    budget.reserve(pixels * (3.0 * double(spec.nchannels) + 4.0),
                   "image " + str(size_t(index)) + " (" + std::to_string(spec.width) + "x" + std::to_string(spec.height) + ")");
    int channels = spec.nchannels;
    std::vector<uint8_t> px(size_t(spec.width) * size_t(spec.height) * size_t(channels));
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, px.data())) {
        warning = "image " + str(size_t(index)) + " cannot be decoded: " + in->geterror();
        for (auto& c : warning)
            if (c == '\n') c = ' ';
        return false;
    }
    image.width = spec.width;
    image.height = spec.height;
    image.rgba.resize(size_t(spec.width) * size_t(spec.height) * 4);
    for (size_t i = 0; i < size_t(spec.width) * size_t(spec.height); ++i) {
        const uint8_t* s = &px[i * size_t(channels)];
        uint8_t* d = &image.rgba[i * 4];
        switch (channels) {
            case 1: d[0] = d[1] = d[2] = s[0]; d[3] = 255; break;
            case 2: d[0] = d[1] = d[2] = s[0]; d[3] = s[1]; break;
            case 3: d[0] = s[0]; d[1] = s[1]; d[2] = s[2]; d[3] = 255; break;
            default: std::memcpy(d, s, 4); break;
        }
    }
    return true;
}

// tinygltf's image callback. For an image in a buffer view, tinygltf hands over a pointer
// computed from the view's unchecked offset: the view is checked here before it is read. The
// encoded bytes are kept (counted against the budget) and decoded only when a material uses
// the image (GLTFReader::textureFor), so unused normal or roughness maps cost no decoding.
bool loadImageCallback(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                       const unsigned char* bytes, int size, void* user) {
    auto* ctx = static_cast<LoadContext*>(user);
    try {
        size_t length = size > 0 ? size_t(size) : 0;
        if (image->bufferView >= 0) {
            const auto& views = ctx->model->bufferViews;
            if (size_t(image->bufferView) >= views.size())
                throw Error("image " + str(size_t(index)) + ": bufferView " + str(size_t(image->bufferView)) + " does not exist");
            const tinygltf::BufferView& view = views[size_t(image->bufferView)];
            if (view.buffer < 0 || size_t(view.buffer) >= ctx->model->buffers.size())
                throw Error("image " + str(size_t(index)) + ": bufferView " + str(size_t(image->bufferView)) +
                            " references a missing buffer");
            const auto& data = ctx->model->buffers[size_t(view.buffer)].data;
            if (!fits(view.byteOffset, view.byteLength, data.size()))
                throw Error("image " + str(size_t(index)) + ": bufferView " + str(size_t(image->bufferView)) + " (offset " +
                            str(view.byteOffset) + ", length " + str(view.byteLength) + ") lies outside buffer " +
                            str(size_t(view.buffer)) + " (" + str(data.size()) + " bytes)");
            bytes = data.data() + view.byteOffset;
            length = view.byteLength;
        }
        ctx->budget->reserve(double(length), "image " + str(size_t(index)) + " (" + str(length) + " encoded bytes)");
        image->image.assign(bytes, bytes + (bytes ? length : 0));
        image->width = image->height = image->component = image->bits = -1;  // encoded, not decoded
        return true;
    } catch (const Error& e) {
        if (ctx->error.empty()) ctx->error = e.what();
        if (err) *err += std::string(e.what()) + "\n";
        return false;
    }
}

// A GLB's chunk layout, checked in full before tinygltf reads it (tinygltf 2.7 lets the BIN
// chunk's payload run 8 bytes past the stated length).
void checkGLBLayout(const std::vector<uint8_t>& b, const std::string& file) {
    auto u32 = [&](size_t at) {
        uint32_t v;
        std::memcpy(&v, b.data() + at, 4);
        return v;
    };
    if (b.size() < 20) throw Error(file + ": malformed glTF: GLB shorter than its 20-byte header");
    if (std::memcmp(b.data(), "glTF", 4) != 0) throw Error(file + ": malformed glTF: no GLB magic");
    if (u32(4) != 2) throw Error(file + ": malformed glTF: GLB version " + str(u32(4)) + " (2 expected)");
    size_t length = u32(8);
    if (length > b.size()) throw Error(file + ": malformed glTF: GLB header states " + str(length) + " bytes, the file has " + str(b.size()));
    size_t at = 12;
    int chunk = 0;
    while (at < length) {
        if (!fits(at, 8, length)) throw Error(file + ": malformed glTF: GLB chunk " + str(size_t(chunk)) + " header is cut off");
        size_t chunkLength = u32(at);
        if (!fits(at + 8, chunkLength, length))
            throw Error(file + ": malformed glTF: GLB chunk " + str(size_t(chunk)) + " of " + str(chunkLength) +
                        " bytes runs past the end of the file");
        if (chunk == 0 && u32(at + 4) != 0x4E4F534Au) throw Error(file + ": malformed glTF: the first GLB chunk is not JSON");
        at += 8 + chunkLength;
        ++chunk;
    }
    if (chunk == 0) throw Error(file + ": malformed glTF: GLB has no JSON chunk");
}

class GLTFReader {
public:
    GLTFReader(tinygltf::Model& model, const std::string& file, Scene& scene, MemoryBudget& budget)
        : mModel(model), mFile(file), mScene(scene), mBudget(budget) {}

    [[noreturn]] void fail(const std::string& what) const { throw Error(mFile + ": " + what); }

    void load() {
        loadMaterials();
        std::vector<int> roots;
        if (!mModel.scenes.empty()) {
            int s = mModel.defaultScene >= 0 ? mModel.defaultScene : 0;
            if (s >= int(mModel.scenes.size())) fail("scene " + std::to_string(s) + " does not exist");
            roots = mModel.scenes[size_t(s)].nodes;
        } else {
            // No scene: every node that is nobody's child is a root.
            std::vector<bool> isChild(mModel.nodes.size(), false);
            for (const auto& n : mModel.nodes)
                for (int c : n.children)
                    if (c >= 0 && c < int(isChild.size())) isChild[size_t(c)] = true;
            for (size_t i = 0; i < mModel.nodes.size(); ++i)
                if (!isChild[i]) roots.push_back(int(i));
        }
        std::vector<bool> onStack(mModel.nodes.size(), false);
        for (int r : roots) visitNode(r, glm::mat4(1.0f), onStack, 0);
        reserveGeometry();
        for (const Instance& inst : mInstances) {
            const auto& mesh = mModel.meshes[size_t(inst.mesh)];
            for (size_t p = 0; p < mesh.primitives.size(); ++p) addPrimitive(mesh.primitives[p], inst.mesh, int(p), inst.world);
        }
    }

private:
    struct Instance {
        int mesh;
        glm::mat4 world;
    };
    // Where an accessor's elements are: `base` null means all zeros (no bufferView).
    struct Elements {
        const uint8_t* base = nullptr;
        size_t stride = 0;
    };

    tinygltf::Model& mModel;
    std::string mFile;
    Scene& mScene;
    MemoryBudget& mBudget;
    std::map<std::pair<int, bool>, int> mImageToTexture;  // (image, sRGB) to scene texture
    std::vector<Instance> mInstances;
    size_t mNodeVisits = 0;
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
    static bool isIndexType(int ct) {
        return ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
               ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    }

    const tinygltf::Accessor& accessor(int index, const char* what) const {
        if (index < 0 || index >= int(mModel.accessors.size()))
            fail(std::string(what) + ": accessor " + std::to_string(index) + " does not exist");
        return mModel.accessors[size_t(index)];
    }

    // The first of `count` elements of `elementBytes` each, `stride` apart, starting `offset`
    // bytes into bufferView `viewIndex`. Every sum is checked before it is formed, so offsets
    // near 2^64 cannot wrap into range.
    const uint8_t* viewData(int viewIndex, size_t offset, size_t count, size_t elementBytes, size_t stride, int componentBytes,
                            const std::string& name) const {
        if (viewIndex < 0 || size_t(viewIndex) >= mModel.bufferViews.size())
            fail(name + " references missing bufferView " + std::to_string(viewIndex));
        const tinygltf::BufferView& view = mModel.bufferViews[size_t(viewIndex)];
        std::string viewName = "bufferView " + std::to_string(viewIndex);
        if (view.buffer < 0 || size_t(view.buffer) >= mModel.buffers.size()) fail(name + ": " + viewName + " references a missing buffer");
        const auto& data = mModel.buffers[size_t(view.buffer)].data;
        if (!fits(view.byteOffset, view.byteLength, data.size()))
            fail(name + ": " + viewName + " (offset " + str(view.byteOffset) + ", length " + str(view.byteLength) +
                 ") lies outside buffer " + std::to_string(view.buffer) + " (" + str(data.size()) + " bytes)");
        if (!fits(offset, elementBytes, view.byteLength))
            fail(name + " starts past the end of " + viewName + " (offset " + str(offset) + ", view length " + str(view.byteLength) + ")");
        if (offset % size_t(componentBytes) != 0 || (view.byteOffset + offset) % size_t(componentBytes) != 0)
            fail(name + " is misaligned: offset " + str(offset) + " into " + viewName + " at " + str(view.byteOffset) +
                 " is not a multiple of its " + std::to_string(componentBytes) + "-byte components");
        if (stride == 0 || stride % size_t(componentBytes) != 0)
            fail(name + ": " + viewName + " has byteStride " + str(stride) + ", not a multiple of its " +
                 std::to_string(componentBytes) + "-byte components");
        if (count > 0 && (count - 1) > (view.byteLength - offset - elementBytes) / stride)
            fail(name + " reads past the end of its buffer (" + str(count) + " elements of stride " + str(stride) + " from offset " +
                 str(offset) + " in " + viewName + " of " + str(view.byteLength) + " bytes)");
        return data.data() + view.byteOffset + offset;
    }

    template <class T>
    static T componentAs(int componentType, bool normalized, const uint8_t* p, int c) {
        auto load = [&](auto v) {
            std::memcpy(&v, p + sizeof(v) * size_t(c), sizeof(v));
            return v;
        };
        if constexpr (std::is_same_v<T, uint32_t>) {
            switch (componentType) {
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return load(uint8_t());
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return load(uint16_t());
                default: return load(uint32_t());
            }
        } else {
            switch (componentType) {
                case TINYGLTF_COMPONENT_TYPE_FLOAT: return load(float());
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: { float v = load(uint8_t()); return normalized ? v / 255.0f : v; }
                case TINYGLTF_COMPONENT_TYPE_BYTE: { float v = load(int8_t()); return normalized ? std::max(v / 127.0f, -1.0f) : v; }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { float v = load(uint16_t()); return normalized ? v / 65535.0f : v; }
                case TINYGLTF_COMPONENT_TYPE_SHORT: { float v = load(int16_t()); return normalized ? std::max(v / 32767.0f, -1.0f) : v; }
                default: return float(load(uint32_t()));
            }
        }
    }

    // Reads accessor `index` (`components` values per element) as T, with its sparse
    // substitutions applied. reserveGeometry() counted the memory of POSITION and index accessors;
    // the other attributes must hold `expectedCount` elements (POSITION's), checked before anything
    // is allocated, as is the range of the data.
    template <class T>
    std::vector<T> read(int index, int components, const char* what, size_t expectedCount = SIZE_MAX) const {
        const tinygltf::Accessor& a = accessor(index, what);
        std::string name = std::string(what) + ": accessor " + std::to_string(index);
        if (componentsOf(a.type) != components)
            fail(name + " has type " + typeName(a.type) + ", expected " + std::to_string(components) + " components");
        int cb = componentBytes(a.componentType);
        if (cb == 0) fail(name + " has an unknown component type " + std::to_string(a.componentType));
        if constexpr (std::is_same_v<T, uint32_t>)
            if (!isIndexType(a.componentType)) fail(name + " has a non-integer component type");
        if (expectedCount != SIZE_MAX && a.count != expectedCount)
            fail(name + " holds " + str(a.count) + " elements where POSITION holds " + str(expectedCount));
        size_t elementBytes = size_t(cb) * size_t(components);
        const uint8_t* base = nullptr;
        size_t stride = elementBytes;
        if (a.bufferView >= 0 && a.count > 0) {
            if (size_t(a.bufferView) < mModel.bufferViews.size() && mModel.bufferViews[size_t(a.bufferView)].byteStride != 0)
                stride = mModel.bufferViews[size_t(a.bufferView)].byteStride;
            base = viewData(a.bufferView, a.byteOffset, a.count, elementBytes, stride, cb, name);
        }
        std::vector<T> out(a.count * size_t(components), T(0));
        if (base) {
            for (size_t i = 0; i < a.count; ++i)
                for (int c = 0; c < components; ++c)
                    out[i * size_t(components) + size_t(c)] = componentAs<T>(a.componentType, a.normalized, base + i * stride, c);
        }
        if (a.sparse.isSparse) {
            const auto& sp = a.sparse;
            if (sp.count < 1 || size_t(sp.count) > a.count)
                fail(name + ": sparse count " + std::to_string(sp.count) + " is outside 1.." + str(a.count));
            if (!isIndexType(sp.indices.componentType))
                fail(name + ": sparse indices have component type " + std::to_string(sp.indices.componentType) + ", not an unsigned integer");
            if (sp.indices.byteOffset < 0 || sp.values.byteOffset < 0) fail(name + ": sparse byteOffset is negative");
            size_t n = size_t(sp.count);
            int icb = componentBytes(sp.indices.componentType);
            const uint8_t* idx = viewData(sp.indices.bufferView, size_t(sp.indices.byteOffset), n, size_t(icb), size_t(icb), icb,
                                          name + " sparse indices");
            const uint8_t* val = viewData(sp.values.bufferView, size_t(sp.values.byteOffset), n, elementBytes, elementBytes, cb,
                                          name + " sparse values");
            for (size_t i = 0; i < n; ++i) {
                uint32_t j = componentAs<uint32_t>(sp.indices.componentType, false, idx + i * size_t(icb), 0);
                if (j >= a.count) fail(name + ": sparse index " + str(j) + " is past its count " + str(a.count));
                for (int c = 0; c < components; ++c)
                    out[size_t(j) * size_t(components) + size_t(c)] =
                        componentAs<T>(a.componentType, a.normalized, val + i * elementBytes, c);
            }
        }
        if constexpr (std::is_same_v<T, float>)
            for (float f : out)
                if (!std::isfinite(f)) fail(name + " contains non-finite values");
        return out;
    }

    // The elements an accessor holds, for estimates: 0 when it does not exist (the read fails later).
    double countOf(int index) const {
        return index >= 0 && size_t(index) < mModel.accessors.size() ? double(mModel.accessors[size_t(index)].count) : 0.0;
    }

    // Counts the memory the triangles of every instance will take, before any is allocated:
    // the world-space vertices and indices (and finalize()'s sorted copy), plus the largest
    // primitive's decoded attributes while it is read.
    void reserveGeometry() {
        std::vector<double> meshBytes(mModel.meshes.size(), 0.0), meshTemp(mModel.meshes.size(), 0.0),
            meshVerts(mModel.meshes.size(), 0.0), meshTris(mModel.meshes.size(), 0.0);
        for (size_t m = 0; m < mModel.meshes.size(); ++m)
            for (const auto& prim : mModel.meshes[m].primitives) {
                if (prim.mode >= 0 && prim.mode <= 3) continue;
                auto pos = prim.attributes.find("POSITION");
                if (pos == prim.attributes.end()) continue;
                double verts = countOf(pos->second);
                double idx = prim.indices >= 0 ? countOf(prim.indices) : verts;
                double tris = prim.mode == 5 || prim.mode == 6 ? std::max(idx - 2.0, 0.0) : std::floor(idx / 3.0);
                double out = prim.attributes.count("NORMAL") ? verts : 3.0 * tris;
                meshVerts[m] += out;
                meshTris[m] += tris;
                meshBytes[m] += out * double(sizeof(Vertex)) + tris * 3.0 * 4.0 * 2.0;
                // POSITION, NORMAL, two TEXCOORDs and TANGENT (read or derived, with its sums).
                meshTemp[m] = std::max(meshTemp[m], verts * (3.0 + 3.0 + 2.0 + 2.0 + 4.0 + 4.0) * 4.0 + idx * 4.0 + tris * 12.0);
            }
        double bytes = 0.0, temp = 0.0, verts = 0.0, tris = 0.0, primitives = 0.0;
        for (const Instance& inst : mInstances) {
            size_t m = size_t(inst.mesh);
            bytes += meshBytes[m];
            temp = std::max(temp, meshTemp[m]);
            verts += meshVerts[m];
            tris += meshTris[m];
            primitives += double(mModel.meshes[m].primitives.size());
        }
        if (primitives > double(kMaxNodeInstances) * 16.0)
            fail("the node hierarchy instances " + str(size_t(primitives)) + " primitives (at most " + str(kMaxNodeInstances * 16) + ")");
        char what[160];
        std::snprintf(what, sizeof what, "the scene's %.0f triangles and %.0f vertices over %zu mesh instances", tris, verts,
                      mInstances.size());
        mBudget.reserve(bytes + temp, mFile + ": " + what);
        if (verts >= 4294967296.0) fail("the scene would hold " + str(size_t(verts)) + " vertices (at most 2^32 - 1)");
    }

    // The scene texture of glTF texture `textureIndex` decoded as sRGB or linear data (an image
    // used both ways becomes two textures). `where` names the material's slot in messages.
    int textureFor(int textureIndex, bool srgb, const std::string& where) {
        if (textureIndex < 0) return -1;
        if (textureIndex >= int(mModel.textures.size()))
            fail(where + ": texture " + std::to_string(textureIndex) + " does not exist");
        int source = mModel.textures[size_t(textureIndex)].source;
        if (source < 0 || source >= int(mModel.images.size())) {
            mScene.warnings.push_back("texture " + std::to_string(textureIndex) + " has no usable image; ignored");
            return -1;
        }
        auto key = std::make_pair(source, srgb);
        auto it = mImageToTexture.find(key);
        if (it != mImageToTexture.end()) return it->second;
        tinygltf::Image& img = mModel.images[size_t(source)];
        // The image callback kept the encoded bytes (none when an external file was missing).
        Texture t;
        std::string warning;
        if (img.image.empty() || !decodeImage(img.image.data(), img.image.size(), source, mBudget, t, warning)) {
            mScene.warnings.push_back((warning.empty() ? "image " + std::to_string(source) + " has no data" : warning) +
                                      (img.uri.empty() ? "" : " ('" + img.uri + "')") + "; its texture is left out");
            mImageToTexture[key] = -1;
            return -1;
        }
        t.name = img.name.empty() ? img.uri : img.name;
        t.srgb = srgb;
        // Keep the encoded bytes while the other colour space may still ask for them.
        if (mImageToTexture.count(std::make_pair(source, !srgb))) img.image = {};
        mScene.textures.push_back(std::move(t));
        return mImageToTexture[key] = int(mScene.textures.size()) - 1;
    }

    // A material's texture reference: its texture (decoded in the slot's colour space), its
    // texCoord and KHR_texture_transform. Returns the scene texture, -1 for none.
    int textureInfo(size_t material, const char* slotName, int slot, int index, int texCoord, const tinygltf::ExtensionMap& extensions,
                    Material& out) {
        if (index < 0) return -1;
        std::string where = "material " + std::to_string(material) + " " + slotName;
        TextureTransform& tt = out.uvTransform[slot];
        auto ext = extensions.find("KHR_texture_transform");
        if (ext != extensions.end() && ext->second.IsObject()) {
            const tinygltf::Value& v = ext->second;
            auto number = [&](const tinygltf::Value& x, const char* key) {
                if (!x.IsNumber()) fail(where + ": KHR_texture_transform " + key + " is not a number");
                double d = x.GetNumberAsDouble();
                if (!std::isfinite(d) || std::abs(d) > 1e30) fail(where + ": KHR_texture_transform " + key + " is not finite");
                return float(d);
            };
            auto pair = [&](const char* key, glm::vec2& dst) {
                if (!v.Has(key)) return;
                const tinygltf::Value& a = v.Get(key);
                if (!a.IsArray() || a.ArrayLen() != 2) fail(where + ": KHR_texture_transform " + key + " is not an array of 2 numbers");
                dst = glm::vec2(number(a.Get(0), key), number(a.Get(1), key));
            };
            pair("offset", tt.offset);
            pair("scale", tt.scale);
            if (v.Has("rotation")) tt.rotation = number(v.Get("rotation"), "rotation");
            if (v.Has("texCoord")) {
                const tinygltf::Value& c = v.Get("texCoord");
                if (!c.IsInt()) fail(where + ": KHR_texture_transform texCoord is not an integer");
                texCoord = c.GetNumberAsInt();
            }
        }
        if (texCoord < 0) fail(where + ": texCoord " + std::to_string(texCoord) + " is negative");
        if (texCoord > 1) {
            mScene.warnings.push_back(where + ": texCoord " + std::to_string(texCoord) +
                                      " (TEXCOORD_0 and TEXCOORD_1 are supported); the texture is left out");
            return -1;
        }
        tt.texCoord = texCoord;
        bool srgb = slot == kSlotBaseColor || slot == kSlotEmissive;
        return textureFor(index, srgb, where);
    }

    void loadMaterials() {
        for (size_t i = 0; i < mModel.materials.size(); ++i) {
            const tinygltf::Material& m = mModel.materials[i];
            Material out;
            out.name = m.name.empty() ? "material" + std::to_string(i) : m.name;
            const auto& pbr = m.pbrMetallicRoughness;
            for (int c = 0; c < 4 && c < int(pbr.baseColorFactor.size()); ++c) out.baseColor[c] = float(pbr.baseColorFactor[c]);
            out.baseColorTexture = textureInfo(i, "baseColorTexture", kSlotBaseColor, pbr.baseColorTexture.index,
                                               pbr.baseColorTexture.texCoord, pbr.baseColorTexture.extensions, out);
            out.metallicRoughnessTexture =
                textureInfo(i, "metallicRoughnessTexture", kSlotMetallicRoughness, pbr.metallicRoughnessTexture.index,
                            pbr.metallicRoughnessTexture.texCoord, pbr.metallicRoughnessTexture.extensions, out);
            out.normalTexture = textureInfo(i, "normalTexture", kSlotNormal, m.normalTexture.index, m.normalTexture.texCoord,
                                            m.normalTexture.extensions, out);
            out.occlusionTexture = textureInfo(i, "occlusionTexture", kSlotOcclusion, m.occlusionTexture.index,
                                               m.occlusionTexture.texCoord, m.occlusionTexture.extensions, out);
            out.emissiveTexture = textureInfo(i, "emissiveTexture", kSlotEmissive, m.emissiveTexture.index, m.emissiveTexture.texCoord,
                                              m.emissiveTexture.extensions, out);
            out.normalScale = float(m.normalTexture.scale);
            out.occlusionStrength = float(m.occlusionTexture.strength);
            if (!std::isfinite(out.normalScale) || std::abs(out.normalScale) > 1e6f)
                fail("material " + std::to_string(i) + ": normalTexture scale is not finite");
            if (!std::isfinite(out.occlusionStrength)) fail("material " + std::to_string(i) + ": occlusionTexture strength is not finite");
            out.occlusionStrength = std::clamp(out.occlusionStrength, 0.0f, 1.0f);
            out.metallic = std::clamp(float(pbr.metallicFactor), 0.0f, 1.0f);
            out.roughness = std::clamp(float(pbr.roughnessFactor), 0.0f, 1.0f);
            for (int c = 0; c < 3 && c < int(m.emissiveFactor.size()); ++c) out.emissive[c] = float(m.emissiveFactor[c]);
            auto ext = m.extensions.find("KHR_materials_emissive_strength");
            if (ext != m.extensions.end() && ext->second.IsObject() && ext->second.Has("emissiveStrength")) {
                const auto& s = ext->second.Get("emissiveStrength");
                if (s.IsNumber()) out.emissive *= float(s.GetNumberAsDouble());
            }
            if (m.alphaMode == "MASK") out.alphaMode = AlphaMode::Mask;
            else if (m.alphaMode == "BLEND") out.alphaMode = AlphaMode::Blend;  // drawn as a dithered mask (AlphaMode)
            out.alphaCutoff = float(m.alphaCutoff);
            if (!std::isfinite(out.alphaCutoff)) fail("material " + std::to_string(i) + ": non-finite alphaCutoff");
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

    // Collects mesh instances, cameras and lights. Depth, cycles and the total number of node
    // visits are bounded: a small file can share subtrees into an exponential hierarchy.
    void visitNode(int index, const glm::mat4& parent, std::vector<bool>& onStack, int depth) {
        if (index < 0 || index >= int(mModel.nodes.size())) fail("node " + std::to_string(index) + " does not exist");
        if (onStack[size_t(index)]) fail("node " + std::to_string(index) + " is its own ancestor (cyclic node hierarchy)");
        if (depth > kMaxNodeDepth) fail("node hierarchy deeper than " + std::to_string(kMaxNodeDepth));
        if (++mNodeVisits > kMaxNodeInstances)
            fail("the node hierarchy expands to more than " + str(kMaxNodeInstances) + " node instances");
        const tinygltf::Node& node = mModel.nodes[size_t(index)];
        glm::mat4 world = parent * localMatrix(node);
        for (int i = 0; i < 16; ++i)
            if (!std::isfinite(glm::value_ptr(world)[i])) fail("node " + std::to_string(index) + ": non-finite transform");
        onStack[size_t(index)] = true;
        if (node.mesh >= 0) {
            if (node.mesh >= int(mModel.meshes.size())) fail("node " + std::to_string(index) + ": mesh " + std::to_string(node.mesh) + " does not exist");
            mInstances.push_back({node.mesh, world});
        }
        if (node.camera >= 0) addCamera(index, node.camera, world);
        auto ext = node.extensions.find("KHR_lights_punctual");
        if (ext != node.extensions.end() && ext->second.IsObject() && ext->second.Has("light")) {
            const auto& l = ext->second.Get("light");
            if (l.IsInt()) addLight(index, l.GetNumberAsInt(), world);
        }
        for (int c : node.children) visitNode(c, world, onStack, depth + 1);
        onStack[size_t(index)] = false;
    }

    // A unit axis of a node's frame; a node scaled to nothing has none.
    glm::vec3 axis(int node, const glm::vec4& column, const char* what) const {
        glm::vec3 v(column);
        float len = glm::length(v);
        if (!(len > 1e-20f) || !std::isfinite(len)) fail("node " + std::to_string(node) + ": " + what + " under a degenerate transform");
        return v / len;
    }

    void addCamera(int node, int index, const glm::mat4& world) {
        if (index >= int(mModel.cameras.size())) fail("camera " + std::to_string(index) + " does not exist");
        const auto& c = mModel.cameras[size_t(index)];
        CameraSettings cam;
        cam.eye = glm::vec3(world[3]);
        glm::vec3 forward = -axis(node, world[2], "camera");
        cam.target = cam.eye + forward;
        cam.up = axis(node, world[1], "camera");
        if (c.type == "perspective") {
            double fov = glm::degrees(c.perspective.yfov);
            cam.fovY = std::isfinite(fov) ? float(std::clamp(fov, 1.0, 170.0)) : 40.0f;
            if (c.perspective.znear > 0 && c.perspective.znear < 1e30) cam.near = float(c.perspective.znear);
            if (c.perspective.zfar > c.perspective.znear && c.perspective.zfar < 1e30) cam.far = float(c.perspective.zfar);
        } else {
            mScene.warnings.push_back("camera " + std::to_string(index) + " is orthographic; shown as perspective");
        }
        mScene.cameras.push_back(cam);
        mScene.cameraNames.resize(mScene.cameras.size() - 1);
        mScene.cameraNames.push_back(!c.name.empty() ? c.name : mModel.nodes[size_t(node)].name);
    }

    void addLight(int node, int index, const glm::mat4& world) {
        if (index < 0 || index >= int(mModel.lights.size())) fail("light " + std::to_string(index) + " does not exist");
        const auto& l = mModel.lights[size_t(index)];
        LightSettings out;
        if (l.type == "directional") out.type = LightType::Directional;
        else if (l.type == "point") out.type = LightType::Point;
        else if (l.type == "spot") out.type = LightType::Spot;
        else fail("light " + std::to_string(index) + ": unknown type '" + l.type + "'");
        if (l.color.size() == 3) out.color = glm::vec3(l.color[0], l.color[1], l.color[2]);
        out.intensity = float(l.intensity);
        out.range = float(l.range);
        if (!std::isfinite(out.color.x + out.color.y + out.color.z + out.intensity + out.range) || out.intensity < 0.0f ||
            out.range < 0.0f || glm::any(glm::lessThan(out.color, glm::vec3(0.0f))))
            fail("light " + std::to_string(index) + ": colour, intensity and range must be finite and not negative");
        out.position = glm::vec3(world[3]);
        out.direction = -axis(node, world[2], "light");
        double inner = glm::degrees(l.spot.innerConeAngle), outer = glm::degrees(l.spot.outerConeAngle);
        if (!std::isfinite(inner) || !std::isfinite(outer)) fail("light " + std::to_string(index) + ": non-finite cone angles");
        out.innerConeDeg = float(std::clamp(inner, 0.0, 90.0));
        out.outerConeDeg = std::max(float(std::clamp(outer, 0.0, 90.0)), out.innerConeDeg + 0.1f);
        mScene.lights.push_back(out);
    }

    // TEXCOORD_<set> of a primitive, empty when absent or past the range where coordinates
    // still address texels.
    std::vector<float> readTexCoords(const tinygltf::Primitive& prim, int set, const std::string& where, size_t vertexCount) {
        std::string name = "TEXCOORD_" + std::to_string(set);
        auto it = prim.attributes.find(name);
        if (it == prim.attributes.end()) return {};
        std::vector<float> uv = read<float>(it->second, 2, name.c_str(), vertexCount);
        float largest = 0.0f;
        for (float f : uv) largest = std::max(largest, std::abs(f));
        if (largest > kMaxTexCoord) {
            char buf[200];
            std::snprintf(buf, sizeof buf, ": %s texture coordinates reach %g, past +-2^23 where they address no texel; ignored", name.c_str(),
                          double(largest));
            warnOnce(where + buf);
            uv.clear();
        }
        return uv;
    }

    // The tangent (xyz: the direction of increasing u) and bitangent sign (w) of a triangle in
    // its own space, from the change of its texture coordinates along its edges (Lengyel 2001);
    // zero where the mapping is degenerate.
    static glm::vec4 triangleTangent(const glm::vec3 p[3], const glm::vec2 tc[3]) {
        glm::vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
        glm::vec2 d1 = tc[1] - tc[0], d2 = tc[2] - tc[0];
        float det = d1.x * d2.y - d2.x * d1.y;
        if (!(std::abs(det) > 1e-20f)) return glm::vec4(0.0f);
        float r = 1.0f / det;
        glm::vec3 t = (e1 * d2.y - e2 * d1.y) * r;
        glm::vec3 b = (e2 * d1.x - e1 * d2.x) * r;
        glm::vec3 n = glm::cross(e1, e2);
        if (!std::isfinite(t.x + t.y + t.z + b.x + b.y + b.z)) return glm::vec4(0.0f);
        // glTF's bitangent, cross(normal, tangent) * w, points up the image: towards decreasing v.
        return glm::vec4(t, glm::dot(glm::cross(n, t), b) > 0.0f ? -1.0f : 1.0f);
    }

    // Per-vertex tangents for a primitive without TANGENT: each triangle's unit tangent, weighted
    // by its area, summed at its corners; the area-weighted sum of the triangles' bitangent signs
    // decides each vertex's handedness. Orthogonalised against the normal later.
    static std::vector<float> deriveTangents(const std::vector<float>& pos, const std::vector<float>& nrm, const std::vector<float>& uv,
                                             const std::vector<uint32_t>& tris) {
        size_t n = pos.size() / 3;
        std::vector<glm::vec3> t(n, glm::vec3(0.0f));
        std::vector<float> sign(n, 0.0f);
        if (uv.empty()) return std::vector<float>(n * 4, 0.0f);
        for (size_t k = 0; k + 2 < tris.size(); k += 3) {
            glm::vec3 p[3];
            glm::vec2 tc[3];
            for (int c = 0; c < 3; ++c) {
                uint32_t i = tris[k + size_t(c)];
                p[c] = glm::vec3(pos[i * 3], pos[i * 3 + 1], pos[i * 3 + 2]);
                tc[c] = glm::vec2(uv[i * 2], uv[i * 2 + 1]);
            }
            glm::vec4 tb = triangleTangent(p, tc);
            float area = 0.5f * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
            glm::vec3 dir = glm::length(glm::vec3(tb)) > 0.0f ? glm::normalize(glm::vec3(tb)) : glm::vec3(0.0f);
            for (int c = 0; c < 3; ++c) {
                uint32_t i = tris[k + size_t(c)];
                t[i] += dir * area;
                sign[i] += tb.w * area;
            }
        }
        std::vector<float> out(n * 4);
        for (size_t i = 0; i < n; ++i) {
            glm::vec3 nn(nrm[i * 3], nrm[i * 3 + 1], nrm[i * 3 + 2]);
            glm::vec3 ti = t[i];
            if (!(glm::length(ti) > 0.0f) || !std::isfinite(ti.x + ti.y + ti.z)) {
                // No usable mapping here: any tangent perpendicular to the normal.
                glm::vec3 a = std::abs(nn.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
                ti = glm::cross(a, nn);
            }
            out[i * 4] = ti.x;
            out[i * 4 + 1] = ti.y;
            out[i * 4 + 2] = ti.z;
            out[i * 4 + 3] = sign[i] < 0.0f ? -1.0f : 1.0f;
        }
        return out;
    }

    void addPrimitive(const tinygltf::Primitive& prim, int meshIndex, int primIndex, const glm::mat4& world) {
        std::string where = "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(primIndex);
        if (prim.mode >= 0 && prim.mode <= 3) {
            warnOnce(where + ": points and lines are not surfaces; skipped");
            return;
        }
        if (prim.mode > 6) fail(where + ": unknown primitive mode " + std::to_string(prim.mode));
        auto posIt = prim.attributes.find("POSITION");
        if (posIt == prim.attributes.end()) fail(where + " has no POSITION attribute");
        std::vector<float> pos = read<float>(posIt->second, 3, "POSITION");
        size_t vertexCount = pos.size() / 3;
        std::vector<float> nrm;
        if (auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end()) {
            nrm = read<float>(it->second, 3, "NORMAL", vertexCount);
        }
        int material = prim.material;
        if (material >= int(mModel.materials.size()))
            fail(where + ": material " + std::to_string(material) + " does not exist");
        if (material < 0) material = defaultMaterial();
        const Material& mat = mScene.materials[size_t(material)];
        bool needsUV1 = false;
        for (int slot = 0; slot < kSlotCount; ++slot) needsUV1 |= mat.texture(slot) >= 0 && mat.uvTransform[slot].texCoord == 1;
        std::vector<float> uv = readTexCoords(prim, 0, where, vertexCount);
        std::vector<float> uv1 = needsUV1 ? readTexCoords(prim, 1, where, vertexCount) : std::vector<float>();
        if (needsUV1 && uv1.empty()) warnOnce(where + ": a texture of its material reads TEXCOORD_1, which it lacks; it reads (0, 0)");
        // Normal maps need tangents: the file's TANGENT (w the handedness), else derived from
        // the coordinates the normal map reads.
        std::vector<float> tan;
        bool needsTangents = mat.normalTexture >= 0;
        if (needsTangents && !nrm.empty())
            if (auto it = prim.attributes.find("TANGENT"); it != prim.attributes.end()) tan = read<float>(it->second, 4, "TANGENT", vertexCount);
        const std::vector<float>& tangentUV = mat.uvTransform[kSlotNormal].texCoord == 1 ? uv1 : uv;

        std::vector<uint32_t> idx;
        if (prim.indices >= 0) {
            idx = read<uint32_t>(prim.indices, 1, "indices");
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
            if (idx.size() % 3 != 0) warnOnce(where + ": index count is not a multiple of 3; the tail is ignored");
            tris.assign(idx.begin(), idx.begin() + std::ptrdiff_t((idx.size() / 3) * 3));
        }
        if (tris.empty()) return;

        glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(world));
        bool flip = glm::determinant(glm::mat3(world)) < 0.0f;
        auto transformPos = [&](uint32_t i) {
            glm::vec3 p = glm::vec3(world * glm::vec4(pos[i * 3], pos[i * 3 + 1], pos[i * 3 + 2], 1.0f));
            float m = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
            if (!(m <= kMaxWorldCoordinate)) {
                char buf[160];
                std::snprintf(buf, sizeof buf, ": a vertex lies %g from the origin (at most 1e15: single precision overflows past it)", double(m));
                fail(where + buf);
            }
            return p;
        };

        auto texCoord = [](const std::vector<float>& t, uint32_t i) { return t.empty() ? glm::vec2(0.0f) : glm::vec2(t[i * 2], t[i * 2 + 1]); };
        glm::mat3 tangentMatrix(world);
        float handedness = flip ? -1.0f : 1.0f;  // a mirroring transform swaps the bitangent's side
        auto worldTangent = [&](glm::vec3 t, float w, const glm::vec3& n) {
            t = tangentMatrix * t;
            t -= n * glm::dot(n, t);
            float len = glm::length(t);
            if (!(len > 1e-20f) || !std::isfinite(len)) return glm::vec4(0.0f);
            return glm::vec4(t / len, (w < 0.0f ? -1.0f : 1.0f) * handedness);
        };

        uint32_t firstIndex = uint32_t(mScene.indices.size());
        if (nrm.empty()) {
            // No normals: flat shading, one vertex per triangle corner (as the spec asks).
            for (size_t t = 0; t + 2 < tris.size(); t += 3) {
                glm::vec3 p[3] = {transformPos(tris[t]), transformPos(tris[t + 1]), transformPos(tris[t + 2])};
                glm::vec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
                float len = glm::length(n);
                n = len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(0, 1, 0);
                if (flip) n = -n;
                glm::vec4 tangent(0.0f);
                if (needsTangents) {
                    glm::vec3 local[3];
                    glm::vec2 tc[3];
                    for (int k = 0; k < 3; ++k) {
                        uint32_t i = tris[t + size_t(k)];
                        local[k] = glm::vec3(pos[i * 3], pos[i * 3 + 1], pos[i * 3 + 2]);
                        tc[k] = texCoord(tangentUV, i);
                    }
                    glm::vec4 tb = triangleTangent(local, tc);
                    tangent = worldTangent(glm::vec3(tb), tb.w, n);
                }
                uint32_t base = uint32_t(mScene.vertices.size());
                for (int k = 0; k < 3; ++k) {
                    uint32_t i = tris[t + size_t(k)];
                    mScene.vertices.push_back({p[k], n, texCoord(uv, i), tangent, texCoord(uv1, i)});
                }
                if (flip) mScene.indices.insert(mScene.indices.end(), {base, base + 2, base + 1});
                else mScene.indices.insert(mScene.indices.end(), {base, base + 1, base + 2});
            }
        } else {
            if (needsTangents && tan.empty()) tan = deriveTangents(pos, nrm, tangentUV, tris);
            uint32_t base = uint32_t(mScene.vertices.size());
            for (size_t i = 0; i < vertexCount; ++i) {
                glm::vec3 n = normalMatrix * glm::vec3(nrm[i * 3], nrm[i * 3 + 1], nrm[i * 3 + 2]);
                float len = glm::length(n);
                n = len > 1e-20f && std::isfinite(len) ? n / len : glm::vec3(0, 1, 0);
                glm::vec4 tangent(0.0f);
                if (!tan.empty()) tangent = worldTangent(glm::vec3(tan[i * 4], tan[i * 4 + 1], tan[i * 4 + 2]), tan[i * 4 + 3], n);
                mScene.vertices.push_back({transformPos(uint32_t(i)), n, texCoord(uv, uint32_t(i)), tangent, texCoord(uv1, uint32_t(i))});
            }
            for (size_t t = 0; t + 2 < tris.size(); t += 3) {
                if (flip) mScene.indices.insert(mScene.indices.end(), {base + tris[t], base + tris[t + 2], base + tris[t + 1]});
                else mScene.indices.insert(mScene.indices.end(), {base + tris[t], base + tris[t + 1], base + tris[t + 2]});
            }
        }
        mScene.draws.push_back({firstIndex, uint32_t(mScene.indices.size()) - firstIndex, material});
    }

    // A warning about a mesh's primitive, once however many nodes instance it.
    void warnOnce(const std::string& text) {
        if (std::find(mScene.warnings.begin(), mScene.warnings.end(), text) == mScene.warnings.end()) mScene.warnings.push_back(text);
    }
};

// Parses `bytes` (a .gltf's JSON or a whole .glb) with tinygltf through the bounded callbacks.
Scene parse(const std::vector<uint8_t>& bytes, bool binary, const std::string& file, const fs::path& baseDir, MemoryBudget& budget,
            const std::string& sceneName) {
    if (binary) {
        checkGLBLayout(bytes, file);
        uint32_t jsonLength;
        std::memcpy(&jsonLength, bytes.data() + 12, 4);
        budget.reserve(double(jsonLength) * kJSONTreeBytesPerByte + double(bytes.size()), file + ": its JSON tree and binary chunk");
    } else {
        budget.reserve(double(bytes.size()) * kJSONTreeBytesPerByte, file + ": its JSON tree");
    }
    if (bytes.size() > size_t(UINT32_MAX)) throw Error(file + ": malformed glTF: larger than 4 GiB");
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    LoadContext ctx{&budget, &model, {}};
    loader.SetFsCallbacks({&fsFileExists, &fsExpandFilePath, &fsReadWholeFile, &fsWriteWholeFile, &ctx});
    loader.SetImageLoader(&loadImageCallback, &ctx);
    std::string err, warn;
    bool ok = false;
    try {
        if (binary)
            ok = loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), baseDir.string());
        else
            ok = loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()), unsigned(bytes.size()),
                                            baseDir.string());
    } catch (const Error& e) {
        throw Error(file + ": " + e.what());
    } catch (const std::exception& e) {
        throw Error(file + ": malformed glTF: " + e.what());
    }
    if (!ctx.error.empty()) throw Error(file + ": " + ctx.error);
    if (!ok) {
        std::string msg = err.empty() ? warn : err;
        while (!msg.empty() && (msg.back() == '\n' || msg.back() == '\r')) msg.pop_back();
        for (auto& c : msg)
            if (c == '\n' || c == '\r') c = ';';
        throw Error(file + ": malformed glTF: " + (msg.empty() ? "unknown error" : msg));
    }
    for (const auto& e : model.extensionsRequired)
        if (e != "KHR_lights_punctual" && e != "KHR_materials_emissive_strength" && e != "KHR_texture_transform")
            throw Error(file + ": requires unsupported extension " + e);

    Scene scene;
    scene.name = sceneName;
    GLTFReader(model, file, scene, budget).load();
    if (scene.indices.empty()) throw Error(file + ": contains no triangles");
    scene.finalize();
    return scene;
}

bool isBinaryName(const fs::path& path) {
    std::string ext = path.extension().string();
    for (auto& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".glb";
}

}  // namespace

Scene loadGLTF(const fs::path& path, double memoryBudgetMB) {
    MemoryBudget budget(memoryBudgetMB);
    std::vector<uint8_t> bytes = readBounded(path, budget, 1.0, "glTF file");
    return parse(bytes, isBinaryName(path), path.string(), path.parent_path(), budget, path.stem().string());
}

Scene loadGLTFFromMemory(const std::vector<uint8_t>& bytes, bool binary, const std::string& name, const fs::path& baseDir,
                         double memoryBudgetMB) {
    MemoryBudget budget(memoryBudgetMB);
    budget.reserve(double(bytes.size()), name + ": glTF data");
    return parse(bytes, binary, name, baseDir, budget, fs::path(name).stem().string());
}

}  // namespace gi
