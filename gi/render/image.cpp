#include "gi/render/image.h"

#include "common/shared.h"

#include <cmath>

namespace gi {

float srgbToLinear(float encoded) {
    double v = encoded;
    return float(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
}

ImageRGB toneMapped(const ImageRGB& hdr, const ToneMapSettings& toneMap) {
    ImageRGB out = hdr;
    const float scale = std::exp2(toneMap.exposure);
    for (float& v : out.rgb) v = shared::giToneChannel(v * scale, int(toneMap.op));
    return out;
}

}  // namespace gi
