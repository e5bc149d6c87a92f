// A cache of path-traced references, so tests and the editor pay for each one once. The key is
// a hash of everything that determines the image: the scene's contents (vertices, indices,
// materials, texture pixels, whatever file they came from), the resolved camera and lights,
// the image size, the specular switch, every reference setting, the volumetric settings when
// volumetric lighting is enabled, and kReferenceVersion (bumped whenever the path tracer's
// output changes). Files are float EXRs written atomically.
// With environment lighting enabled the key also has the environment settings and a hash of the
// map's pixels, remembered per file while its size and modification time hold (so keying every
// frame does not decode the map); a map that cannot be loaded adds nothing, and rendering it
// then fails with the error naming the file.
#pragma once

#include "gi/reference/path_tracer.h"

#include <filesystem>
#include <functional>

namespace gi {

inline constexpr int kReferenceVersion = 5;  // 3: the full glTF material (normal, metallic-roughness, emissive maps, texture transforms, Blend); 4: the surface offset scales with the scene, not a floor of 1e-4 units; 5: 2^-19 of each coordinate, not 1e-4 of the largest, and camera rays from a camera at the origin

uint64_t referenceKey(const Scene& scene, const FrameSettings& fs, const ReferenceSettings& rs);

// $GI_CACHE_DIR, else $XDG_CACHE_HOME/gi-workbench/references, else ~/.cache/gi-workbench/references.
std::filesystem::path referenceCacheDir();

struct CachedReference {
    ImageRGB image;
    bool fromCache = false;
    double seconds = 0.0;        // time to render (0 when read from the cache)
    uint64_t rays = 0;           // rays traced (0 when read from the cache)
    std::filesystem::path file;  // the cache file
};

// Whether the reference for these settings is in the cache (then it costs nothing).
bool referenceCached(const Scene& scene, const FrameSettings& fs, const ReferenceSettings& rs);

// The time a fresh reference takes on this machine's CPU tracer: pixels x spp x
// kReferenceRaysPerSample / kReferenceRaysPerSecond (reference_cache.cpp says where they were
// measured). Throws gi::Error naming render.timeBudgetSeconds when `references` fresh ones
// (e.g. 2 for --score: full and indirect) are estimated past it; 0 references never throw.
double estimateReferenceSeconds(const FrameSettings& fs, const ReferenceSettings& rs);
void checkReferenceTimeBudget(const FrameSettings& fs, const ReferenceSettings& rs, int references = 1);

// The cached reference, or a fresh render that is then stored. `progress` as PathTracer::render;
// a render stopped early is returned but not stored. A fresh one past render.timeBudgetSeconds
// is refused before it starts (checkReferenceTimeBudget); a cached one never is.
CachedReference cachedReference(const Scene& scene, const FrameSettings& fs, const ReferenceSettings& rs,
                                const std::function<bool(int, int)>& progress = {});

void writeEXR(const std::filesystem::path& path, const ImageRGB& image);  // float RGB, atomic
ImageRGB readEXR(const std::filesystem::path& path);

}  // namespace gi
