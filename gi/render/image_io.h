// Image files through OpenImageIO: PNG (8-bit sRGB) and EXR (linear half/float).
#pragma once

#include <filesystem>
#include <vector>

namespace gi {

// Pixels are RGBA, bottom row first (GL order); files are written top row first.
void writePNG(const std::filesystem::path& path, int width, int height, const std::vector<uint8_t>& rgba);
void writeEXR(const std::filesystem::path& path, int width, int height, const std::vector<float>& rgba);
// RGB8, top row first (the metrics' and the reference's order).
void writePNGTopFirst(const std::filesystem::path& path, int width, int height, const std::vector<uint8_t>& rgb);

struct ImageRGBA8 {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;  // top row first
};
ImageRGBA8 readImage8(const std::filesystem::path& path);

}  // namespace gi
