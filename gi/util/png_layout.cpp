#include "gi/util/png_layout.h"

#include <cstring>
#include <fstream>

namespace gi {

namespace {
const uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
}

bool isPNG(const uint8_t* bytes, size_t size) { return size >= 8 && std::memcmp(bytes, kSignature, 8) == 0; }

std::string pngLayoutProblem(size_t size, const ByteReader& read) {
    size_t at = 8;
    while (at < size) {
        uint8_t head[8];
        if (size - at < 12 || !read(at, head, 8)) return "PNG chunk header at byte " + std::to_string(at) + " is cut off";
        uint32_t length = uint32_t(head[0]) << 24 | uint32_t(head[1]) << 16 | uint32_t(head[2]) << 8 | head[3];
        std::string type(reinterpret_cast<const char*>(head + 4), 4);
        for (char& c : type)
            if (!std::isalpha(static_cast<unsigned char>(c))) c = '?';
        if (length > size - at - 12)
            return "PNG chunk '" + type + "' at byte " + std::to_string(at) + " states " + std::to_string(length) +
                   " bytes, past the end of the image (" + std::to_string(size) + " bytes)";
        at += 12 + size_t(length);
        if (type == "IEND") break;
    }
    return "";
}

std::string pngLayoutProblem(const uint8_t* bytes, size_t size) {
    return pngLayoutProblem(size, [&](size_t offset, uint8_t* out, size_t n) {
        std::memcpy(out, bytes + offset, n);
        return true;
    });
}

std::string pngFileLayoutProblem(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::error_code ec;
    size_t size = size_t(std::filesystem::file_size(path, ec));
    uint8_t sig[8];
    if (!in || ec || !in.read(reinterpret_cast<char*>(sig), 8) || !isPNG(sig, 8)) return "";
    return pngLayoutProblem(size, [&](size_t offset, uint8_t* out, size_t n) {
        in.seekg(std::streamoff(offset));
        return bool(in.read(reinterpret_cast<char*>(out), std::streamsize(n)));
    });
}

}  // namespace gi
