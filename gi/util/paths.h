// Where files are found: shaders, presets, and scene assets through the search path.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace gi {

// The GLSL root: $GI_SHADER_DIR if set, else the source tree's shaders/ folder.
std::filesystem::path shaderDir();
// The bundled presets folder (source tree's presets/).
std::filesystem::path presetDir();

// The asset search path, in order: the preset's own folder (when given), each entry of
// $GI_ASSET_PATH (colon-separated), then ../shared/scenes and ../shared/envmaps beside the checkout.
std::vector<std::filesystem::path> assetSearchPath(const std::filesystem::path& presetFolder = {});

// Resolves a relative asset name against the search path. Absolute paths and paths that exist
// as given are returned unchanged. Throws gi::Error listing the folders tried.
std::filesystem::path resolveAsset(const std::string& name,
                                   const std::filesystem::path& presetFolder = {});

// The size of `path`, after checking it names a regular file; throws gi::Error naming the file
// ("file not found", "is a folder, not a WHAT", "is not a regular file") otherwise.
uintmax_t regularFileSize(const std::filesystem::path& path, const std::string& what);

// Reads a whole file; throws gi::Error naming the file when it cannot, when it is a folder or
// no regular file, or when it is larger than `maxBytes`.
std::string readTextFile(const std::filesystem::path& path, size_t maxBytes = size_t(1) << 30);

// Writes a file atomically: a temporary file beside it, flushed, then renamed over the target,
// so a crash or a full disk never leaves a half-written file in its place.
void writeFileAtomic(const std::filesystem::path& path, const std::string& contents);

}  // namespace gi
