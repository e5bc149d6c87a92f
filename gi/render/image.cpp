#include "gi/render/image.h"

#include "common/shared.h"

#include <cmath>

namespace gi {

ImageRGB toneMapped(const ImageRGB& hdr, const ToneMapSettings& toneMap) {
    ImageRGB out = hdr;
    const float scale = std::exp2(toneMap.exposure);
    for (float& v : out.rgb) v = shared::giToneChannel(v * scale, int(toneMap.op));
    return out;
}

}  // namespace gi
