// Environment maps on the CPU: loading (OpenImageIO), the latlong convention every part shares
// (the GPU cube conversion, the skybox, the prefilter and the path tracer), and lookups.
//
// Convention: an equirectangular image, row 0 at the top (+y, the zenith); for a direction d
// (after turning it by -rotation about +y) u = 0.5 + atan2(d.x, -d.z) / (2 pi), v = acos(d.y) / pi,
// so the image's centre column looks along -z (the default camera's view direction) and u grows
// towards +x. shaders/envmap/envmap.glsl mirrors latLongUV.
//
// Inputs: an equirectangular .hdr/.exr (or any format OpenImageIO reads; 8-bit images are
// decoded from sRGB), six cube faces given as a pattern with "{face}" (px nx py ny pz nz, GL's
// face orientations) which are resampled to a latlong of 4n x 2n, or a built-in:
//   builtin:constant  uniform radiance 1 (tests: prefiltering it must return 1 at every mip)
//   builtin:sky       a clear-sky gradient (zenith blue, bright horizon, dark ground) with a
//                     soft sun 30 degrees above the horizon, for scenes that ship no map.
// Errors name the file (or the key when the name is malformed); nothing is loaded by halves.
// Bad files are refused from their header, before any pixel buffer exists: a folder, an empty
// file, not an image, no pixels, a 3D or deep image, more than kMaxEnvironmentSide per side, or
// decoding that would take more memory than the budget (render.memoryBudgetMB); cube faces that
// are not square or not of one size. Channels past the third (alpha, AOVs) are ignored.
#pragma once

#include "gi/util/budget.h"

#include <glm/glm.hpp>

#include <array>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace gi {

struct EnvironmentImage {
    int width = 0, height = 0;
    std::vector<float> rgb;  // linear radiance, row 0 at the top
    std::string source;      // the file (or built-in name) it came from

    glm::vec3 texel(int x, int y) const {
        const float* p = &rgb[(size_t(y) * size_t(width) + size_t(x)) * 3];
        return {p[0], p[1], p[2]};
    }
};

// EnvironmentSettings::file made independent of the working folder: a file (or a cube pattern's
// first face) found through the asset search path becomes its absolute path; built-ins stay.
// Throws gi::Error naming the file when it cannot be found.
std::string resolveEnvironmentFile(const std::string& file, const std::filesystem::path& presetFolder);

// The largest latlong side (a cube face's latlong is 4 faces wide): GL 4.5's least
// GL_MAX_TEXTURE_SIZE, since the map is uploaded as one 2D texture.
inline constexpr int kMaxEnvironmentSide = 16384;
// render.memoryBudgetMB's default (gi/util/budget.h), for callers without settings (tests, built-ins).
inline constexpr size_t kDefaultEnvironmentBudgetBytes = size_t(kDefaultMemoryBudgetMB) << 20;

// Loads `file` as EnvironmentSettings::file describes; relative names go through the asset
// search path (gi/util/paths.h). Refuses, from the header, a map whose decoding needs more host
// memory than `budgetBytes` (RenderSettings::memoryBudgetBytes()). Throws gi::Error naming the file.
EnvironmentImage loadEnvironment(const std::string& file, const std::filesystem::path& presetFolder = {},
                                 size_t budgetBytes = kDefaultEnvironmentBudgetBytes);

// The latlong coordinates (u, v in [0, 1]) of a unit direction, and back.
glm::vec2 latLongUV(const glm::vec3& dir, float rotationDeg);
glm::vec3 latLongDirection(const glm::vec2& uv, float rotationDeg);

// Irradiance as 9 spherical-harmonic coefficients (bands 0 to 2, Ramamoorthi and Hanrahan 2001),
// projected from every texel by its solid angle and already convolved with the clamped cosine
// and divided by pi: sum_i c[i] Y_i(n) is E(n) / pi for the unrotated map. Y order: Y00, Y1-1
// (y), Y10 (z), Y11 (x), Y2-2 (xy), Y2-1 (yz), Y20 (3z^2 - 1), Y21 (xz), Y22 (x^2 - y^2).
std::array<glm::vec3, 9> irradianceSH(const EnvironmentImage& env);
// The basis at a unit direction, in that order.
std::array<float, 9> shBasis9(const glm::vec3& n);

// Bilinear lookup (u wraps, v clamps) of the radiance arriving from direction `dir`.
glm::vec3 sampleEnvironment(const EnvironmentImage& env, const glm::vec3& dir, float rotationDeg);

}  // namespace gi
