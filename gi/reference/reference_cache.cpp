#include "gi/reference/reference_cache.h"
#include "gi/util/budget.h"

#include "gi/envmap/envmap_image.h"
#include "gi/preset/reflect.h"
#include "gi/util/error.h"
#include "gi/util/hash.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <map>
#include <mutex>
#include <sys/stat.h>
#include <unistd.h>

namespace gi {

namespace {

// What identifies an environment map's contents without reading it: nothing more than the name
// for a built-in (made by code), the device, inode, size and modification time of the file (or
// of each cube face); empty when a file cannot be found as named.
std::string environmentStamp(const std::string& file) {
    if (file.rfind("builtin:", 0) == 0) return file;
    std::vector<std::string> paths;
    if (size_t at = file.find("{face}"); at != std::string::npos) {
        for (const char* face : {"px", "nx", "py", "ny", "pz", "nz"}) paths.push_back(file.substr(0, at) + face + file.substr(at + 6));
    } else {
        paths.push_back(file);
    }
    std::string stamp;
    for (const std::string& path : paths) {
        struct stat st {};
        if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return {};
        // The inode too: a file replaced by rename (as writeEXR does) within one clock tick.
        for (long long v : {(long long)st.st_dev, (long long)st.st_ino, (long long)st.st_size, (long long)st.st_mtim.tv_sec,
                            (long long)st.st_mtim.tv_nsec})
            stamp += std::to_string(v) + ":";
        stamp += path + ";";
    }
    return stamp;
}

// The hash of an environment map's pixels, remembered per file while its stamp holds: the
// editor keys its reference every frame and must not decode the map each time. A map that
// cannot be loaded hashes to 0 here; rendering it then fails with the error naming the file.
uint64_t environmentHash(const std::string& file, size_t budgetBytes) {
    static std::mutex mutex;
    static std::map<std::string, std::pair<std::string, uint64_t>> memo;  // file -> (stamp, hash)
    std::string stamp = environmentStamp(file);
    if (stamp.empty()) return 0;
    {
        std::lock_guard<std::mutex> lock(mutex);
        if (auto it = memo.find(file); it != memo.end() && it->second.first == stamp) return it->second.second;
    }
    Hasher h;
    try {
        EnvironmentImage env = loadEnvironment(file, {}, budgetBytes);
        h.value(env.width);
        h.value(env.height);
        h.bytes(env.rgb.data(), env.rgb.size() * sizeof(float));
    } catch (const Error&) {
        return 0;
    }
    std::lock_guard<std::mutex> lock(mutex);
    memo[file] = {stamp, h.result()};
    return h.result();
}

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
        for (int slot = 0; slot < kSlotCount; ++slot) {
            h.value(m.texture(slot));
            h.value(m.uvTransform[slot]);
        }
        h.value(m.normalScale);
        h.value(m.occlusionStrength);
    }
    for (const Texture& t : scene.textures) {
        h.value(t.width);
        h.value(t.height);
        h.value(t.srgb);
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
    // The environment's settings and pixels, so a map edited under the same name renders again.
    if (fs.environment.enabled) {
        // Only what the path tracer reads: the GPU prefilter's settings do not change the reference.
        json env = toJson(fs.environment);
        for (const char* gpuOnly : {"cubeSize", "samples", "distribution", "mipRoughness"}) env.erase(gpuOnly);
        h.text(env.dump());
        h.value(environmentHash(fs.environment.file, fs.render.memoryBudgetBytes()));
    }
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

namespace {

std::filesystem::path cacheFile(const Scene& scene, const FrameSettings& fs, const ReferenceSettings& rs) {
    char name[64];
    std::snprintf(name, sizeof name, "%016llx.exr", static_cast<unsigned long long>(referenceKey(scene, fs, rs)));
    return referenceCacheDir() / name;
}

// The CPU path tracer (Embree + oneTBB) on this project's 2-core machines, from gi-render's
// stats.json (reference.rays and .seconds, BVH build included) with --reference --spp 8 to 16
// at 320x180, a compile running beside it: 1.5 (environment_spheres) to 3.6 (sponza, default)
// rays per pixel sample, 0.6 (sponza: textures and alpha tests) to 4.1 (basic) million rays per
// second. The guess takes the most rays per sample and a middling rate, so a Cornell box is
// overestimated about 2x and Sponza underestimated about 2x: the budget refuses the absurd
// (1920x1080 at 65536 spp), not the merely slow.
constexpr double kReferenceRaysPerSample = 4.0;
constexpr double kReferenceRaysPerSecond = 2e6;

}  // namespace

bool referenceCached(const Scene& scene, const FrameSettings& fs, const ReferenceSettings& rs) {
    std::error_code ec;
    return std::filesystem::exists(cacheFile(scene, fs, rs), ec);
}

double estimateReferenceSeconds(const FrameSettings& fs, const ReferenceSettings& rs) {
    double pixels = double(std::max(fs.width, 0)) * double(std::max(fs.height, 0));
    return pixels * double(rs.spp) * kReferenceRaysPerSample / kReferenceRaysPerSecond;
}

void checkReferenceTimeBudget(const FrameSettings& fs, const ReferenceSettings& rs, int references) {
    if (references <= 0) return;
    std::string what = references > 1 ? std::to_string(references) + " path-traced references" : "path-traced reference";
    checkTimeBudget(estimateReferenceSeconds(fs, rs) * references, fs.render.timeBudgetSeconds, what,
                    std::to_string(fs.width) + "x" + std::to_string(fs.height) + ", " + std::to_string(rs.spp) + " spp",
                    "lower reference.spp (--spp) or the image size");
}

CachedReference cachedReference(const Scene& scene, const FrameSettings& fs, const ReferenceSettings& rs,
                                const std::function<bool(int, int)>& progress) {
    CachedReference out;
    out.file = cacheFile(scene, fs, rs);
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
    checkReferenceTimeBudget(fs, rs);
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
