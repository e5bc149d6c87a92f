// A linear RGB image on the CPU: path-traced references, renders read back for scoring, files.
#pragma once

#include "gi/render/render_settings.h"

#include <vector>

namespace gi {

struct ImageRGB {
    int width = 0, height = 0;
    std::vector<float> rgb;  // linear RGB, 3 floats per pixel, top row first
};

// The sRGB transfer curve, decoding an encoded value in [0, 1] to linear light.
float srgbToLinear(float encoded);

// Exposure (2^EV) and the tone curve of ToneMapSettings, as the tone-map pass applies them on the
// GPU (the curves are shared with GLSL through shaders/common/shared.h). The result is
// display-referred linear light in [0, 1]; encodeSRGB8 (gi/metrics) turns it into the 8-bit image.
ImageRGB toneMapped(const ImageRGB& hdr, const ToneMapSettings& toneMap);

}  // namespace gi
