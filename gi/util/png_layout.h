// A PNG's chunk layout, checked before libpng sees the file. libpng 1.6 (as Debian builds it,
// with no chunk size limit) allocates the length a chunk states before reading it: a 30 KB
// texture whose ancillary chunk stated 2 GB took 2 GB in OpenImageIO's open() (found by gi-fuzz).
// A file whose every chunk fits in the bytes after it bounds those allocations by its own size.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

namespace gi {

bool isPNG(const uint8_t* bytes, size_t size);

// Reads `n` bytes at `offset` into `out`; false when it cannot.
using ByteReader = std::function<bool(size_t offset, uint8_t* out, size_t n)>;

// What is wrong with the chunk layout of a PNG of `size` bytes, or "" when every chunk fits.
std::string pngLayoutProblem(size_t size, const ByteReader& read);
std::string pngLayoutProblem(const uint8_t* bytes, size_t size);
// The same for a file: "" also for a file that is no PNG (other formats are not checked here).
std::string pngFileLayoutProblem(const std::filesystem::path& path);

}  // namespace gi
