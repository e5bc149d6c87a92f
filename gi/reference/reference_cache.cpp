#include "gi/reference/reference_cache.h"

#include "gi/preset/reflect.h"
#include "gi/util/error.h"

#include <OpenImageIO/imageio.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <unistd.h>

namespace gi {

namespace {

// FNV-1a, 64 bit: simple, stable across runs and machines, fast enough for Sponza's 100 MB.
class Hasher {
public:
    void bytes(const void* data, size_t n) {
        const auto* p = static_cast<const uint8_t*>(data);
        for (size_t i = 0; i < n; ++i) {
            mHash ^= p[i];
            mHash *= 0x100000001b3ULL;
        }
    }
    template <class T>
    void value(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        bytes(&v, sizeof(T));
    }
    void text(const std::string& s) {
        value(s.size());
        bytes(s.data(), s.size());
    }
    uint64_t result() const { return mHash; }

private:
    uint64_t mHash = 0xcbf29ce484222325ULL;
};

}  // namespace

uint64_t referenceKey(const Scene& scene, const FrameSettings& fs, const ReferenceSettings& rs) {
    Hasher h;
    h.value(kReferenceVersion);
    h.value(scene.vertices.size());
    h.bytes(scene.vertices.data(), scene.vertices.size() * sizeof(Vertex));
    h.value(scene.indices.size());
    h.bytes(scene.indices.data(), scene.indices.size() * sizeof(uint32_t));
    for (const Draw& d : scene.draws) h.value(d);
    for (const Material& m : scene.materials) {
        h.value(m.baseColor);
        h.value(m.baseColorTexture);
        h.value(m.metallic);
        h.value(m.roughness);
        h.value(m.emissive);
        h.value(m.alphaMode);
        h.value(m.alphaCutoff);
        h.value(m.doubleSided);
    }
    for (const Texture& t : scene.textures) {
        h.value(t.width);
        h.value(t.height);
        h.bytes(t.rgba.data(), t.rgba.size());
    }
    // Settings go in through the settings table, so a field added there is never missed here.
    h.text(toJson(fs.camera).dump());
    h.value(fs.lights.size());
    for (const LightSettings& l : fs.lights) h.text(toJson(l).dump());
    h.text(toJson(rs).dump());
    h.value(fs.width);
    h.value(fs.height);
    h.value(fs.render.specular);
    // Only when on, so the references cached before volumetric lighting existed keep their keys.
    if (fs.volumetric.enabled) h.text(toJson(fs.volumetric).dump());
    return h.result();
}

std::filesystem::path referenceCacheDir() {
    if (const char* dir = std::getenv("GI_CACHE_DIR"); dir && *dir) return dir;
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
        return std::filesystem::path(xdg) / "gi-workbench" / "references";
    if (const char* home = std::getenv("HOME"); home && *home)
        return std::filesystem::path(home) / ".cache" / "gi-workbench" / "references";
    return std::filesystem::temp_directory_path() / "gi-workbench" / "references";
}

void writeEXR(const std::filesystem::path& path, const ImageRGB& image) {
    // OIIO picks the format from the extension, so the temporary file keeps ".exr".
    std::filesystem::path tmp = path;
    tmp.replace_filename("." + path.stem().string() + ".tmp" + std::to_string(::getpid()) + ".exr");
    auto out = OIIO::ImageOutput::create(tmp.string());
    if (!out) throw Error(path.string() + ": cannot write image: " + OIIO::geterror());
    OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT);
    bool ok = out->open(tmp.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, image.rgb.data());
    ok = out->close() && ok;
    std::error_code ec;
    if (ok) std::filesystem::rename(tmp, path, ec);
    if (!ok || ec) {
        std::filesystem::remove(tmp, ec);
        throw Error(path.string() + ": cannot write image");
    }
}

ImageRGB readEXR(const std::filesystem::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw Error(path.string() + ": cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.nchannels < 3) throw Error(path.string() + ": expected an RGB image");
    ImageRGB img;
    img.width = spec.width;
    img.height = spec.height;
    img.rgb.resize(size_t(spec.width) * spec.height * 3);
    if (!in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, img.rgb.data()))
        throw Error(path.string() + ": cannot decode image: " + in->geterror());
    return img;
}

CachedReference cachedReference(const Scene& scene, const FrameSettings& fs, const ReferenceSettings& rs,
                                const std::function<bool(int, int)>& progress) {
    CachedReference out;
    char name[64];
    std::snprintf(name, sizeof name, "%016llx.exr", static_cast<unsigned long long>(referenceKey(scene, fs, rs)));
    out.file = referenceCacheDir() / name;
    if (std::filesystem::exists(out.file)) {
        try {
            out.image = readEXR(out.file);
            if (out.image.width == fs.width && out.image.height == fs.height) {
                out.fromCache = true;
                return out;
            }
        } catch (const Error&) {
            // A damaged cache file is rendered again and replaced.
        }
    }
    auto start = std::chrono::steady_clock::now();
    PathTracer tracer(scene);
    bool complete = true;
    out.image = tracer.render(fs, rs, [&](int done, int total) {
        bool go = !progress || progress(done, total);
        complete = go || done == total;
        return go;
    });
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out.rays = tracer.raysTraced();
    if (complete) {
        std::error_code ec;
        std::filesystem::create_directories(out.file.parent_path(), ec);
        try {
            writeEXR(out.file, out.image);
        } catch (const Error& e) {
            std::fprintf(stderr, "warning: reference cache not written: %s\n", e.what());
        }
    }
    return out;
}

}  // namespace gi
