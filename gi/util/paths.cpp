#include "gi/util/paths.h"

#include "gi/util/error.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;

namespace gi {

fs::path shaderDir() {
    if (const char* env = std::getenv("GI_SHADER_DIR"); env && *env) return env;
    return GI_SHADER_DIR;
}

fs::path presetDir() { return GI_PRESET_DIR; }

std::vector<fs::path> assetSearchPath(const fs::path& presetFolder) {
    std::vector<fs::path> dirs;
    if (!presetFolder.empty()) dirs.push_back(presetFolder);
    if (const char* env = std::getenv("GI_ASSET_PATH"); env && *env) {
        std::stringstream ss(env);
        std::string item;
        while (std::getline(ss, item, ':'))
            if (!item.empty()) dirs.emplace_back(item);
    }
    dirs.push_back(fs::path(GI_SHARED_DIR) / "scenes");
    dirs.push_back(fs::path(GI_SHARED_DIR) / "envmaps");
    return dirs;
}

fs::path resolveAsset(const std::string& name, const fs::path& presetFolder) {
    if (name.empty()) throw Error("empty file name");
    fs::path p(name);
    if (p.is_absolute()) {
        if (fs::exists(p)) return p;
        throw Error("file not found: " + name);
    }
    std::string tried;
    for (const fs::path& dir : assetSearchPath(presetFolder)) {
        fs::path candidate = dir / p;
        if (fs::exists(candidate)) return candidate;
        tried += (tried.empty() ? "" : ", ") + dir.string();
    }
    if (fs::exists(p)) return p;
    throw Error("asset '" + name + "' not found in the search path (" + tried +
                "; set GI_ASSET_PATH to add folders)");
}

uintmax_t regularFileSize(const fs::path& path, const std::string& what) {
    std::error_code ec;
    fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st)) throw Error(path.string() + ": file not found");
    if (fs::is_directory(st)) throw Error(path.string() + ": is a folder, not a " + what);
    if (!fs::is_regular_file(st)) throw Error(path.string() + ": is not a regular file");
    uintmax_t size = fs::file_size(path, ec);
    if (ec) throw Error(path.string() + ": cannot read its size: " + ec.message());
    return size;
}

std::string readTextFile(const fs::path& path, size_t maxBytes) {
    uintmax_t size = regularFileSize(path, "file");
    if (size > maxBytes)
        throw Error(path.string() + ": " + std::to_string(size) + " bytes, larger than the " + std::to_string(maxBytes) +
                    " bytes such a file may have");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path.string() + ": cannot open file");
    std::stringstream ss;
    ss << in.rdbuf();
    if (in.bad()) throw Error(path.string() + ": read error");
    return ss.str();
}

void writeFileAtomic(const fs::path& path, const std::string& contents) {
    fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    fs::path tmp = dir / ("." + path.filename().string() + ".tmp" + std::to_string(::getpid()));
    {
        FILE* f = std::fopen(tmp.c_str(), "wb");
        if (!f) throw Error(path.string() + ": cannot write (folder missing or not writable)");
        bool ok = std::fwrite(contents.data(), 1, contents.size(), f) == contents.size();
        ok = std::fflush(f) == 0 && ok;
        ok = ::fsync(fileno(f)) == 0 && ok;
        ok = std::fclose(f) == 0 && ok;
        if (!ok) {
            std::error_code ec;
            fs::remove(tmp, ec);
            throw Error(path.string() + ": write failed; the previous file is untouched");
        }
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw Error(path.string() + ": cannot replace file: " + ec.message());
    }
}

}  // namespace gi
