#include "gi/render/image_io.h"

#include "gi/util/error.h"

#include <OpenImageIO/imageio.h>

#include <cstring>

namespace gi {

namespace {

template <class T>
void writeImage(const std::filesystem::path& path, int width, int height, const std::vector<T>& rgba,
                OIIO::TypeDesc type, OIIO::TypeDesc fileType) {
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) throw Error(path.string() + ": cannot write image: " + OIIO::geterror());
    OIIO::ImageSpec spec(width, height, 4, fileType);
    if (!out->open(path.string(), spec)) throw Error(path.string() + ": cannot write image: " + out->geterror());
    // GL rows are bottom first: write with a negative y stride starting at the last row.
    const T* last = rgba.data() + size_t(height - 1) * width * 4;
    OIIO::stride_t ystride = -OIIO::stride_t(width) * 4 * OIIO::stride_t(sizeof(T));
    bool ok = out->write_image(type, last, OIIO::AutoStride, ystride);
    ok = out->close() && ok;
    if (!ok) throw Error(path.string() + ": write failed: " + out->geterror());
}

}  // namespace

void writePNG(const std::filesystem::path& path, int width, int height, const std::vector<uint8_t>& rgba) {
    writeImage(path, width, height, rgba, OIIO::TypeDesc::UINT8, OIIO::TypeDesc::UINT8);
}

void writePNGTopFirst(const std::filesystem::path& path, int width, int height, const std::vector<uint8_t>& rgb) {
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) throw Error(path.string() + ": cannot write image: " + OIIO::geterror());
    OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
    bool ok = out->open(path.string(), spec) && out->write_image(OIIO::TypeDesc::UINT8, rgb.data());
    ok = out->close() && ok;
    if (!ok) throw Error(path.string() + ": write failed: " + out->geterror());
}

void writeEXR(const std::filesystem::path& path, int width, int height, const std::vector<float>& rgba) {
    writeImage(path, width, height, rgba, OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::HALF);
}

ImageRGBA8 readImage8(const std::filesystem::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw Error(path.string() + ": cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    ImageRGBA8 img;
    img.width = spec.width;
    img.height = spec.height;
    std::vector<uint8_t> raw(size_t(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, raw.data()))
        throw Error(path.string() + ": cannot decode image: " + in->geterror());
    img.rgba.resize(size_t(spec.width) * spec.height * 4);
    for (size_t i = 0; i < size_t(spec.width) * spec.height; ++i) {
        for (int c = 0; c < 4; ++c) {
            int src = c < spec.nchannels ? c : (c == 3 ? -1 : 0);
            img.rgba[i * 4 + c] = src < 0 ? 255 : raw[i * spec.nchannels + src];
        }
    }
    return img;
}

}  // namespace gi
