// Image loading and conversion, RMSE/PSNR, the leak measure and the metric maps; SSIM is in
// ssim.cpp. Definitions and choices are in metrics.h.
#include "gi/metrics/metrics.h"

#include "gi/render/image_io.h"
#include "gi/util/error.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <string>

namespace gi {

namespace {

// OIIO messages can span lines; our errors are one line.
std::string oneLine(std::string s) {
    std::replace(s.begin(), s.end(), '\n', ' ');
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s;
}

// shaders/common/color.glsl linearToSRGB: clamp, then the sRGB curve (step() takes the power
// branch at c >= 0.0031308).
float encodeSRGB(float c) {
    c = c > 0.0f ? std::min(c, 1.0f) : 0.0f;  // NaN counts as 0
    return c < 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

uint8_t toByte(float v) { return uint8_t(std::clamp(int(std::lround(v * 255.0f)), 0, 255)); }

float luminance(const float* rgb) { return 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2]; }

size_t pixelCount(const ImageRGB& image) { return size_t(image.width) * image.height; }

void requireSameSize(const ImageRGB& image, const ImageRGB& reference) {
    if (image.width != reference.width || image.height != reference.height)
        throw Error("metrics: the image is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                    " but the reference is " + std::to_string(reference.width) + "x" +
                    std::to_string(reference.height));
    GI_ASSERT(image.rgb.size() == pixelCount(image) * 3 && reference.rgb.size() == pixelCount(reference) * 3,
              "ImageRGB holds 3 floats per pixel");
}

bool namesLinear(std::string colorSpace) {
    for (char& c : colorSpace) c = char(std::tolower(static_cast<unsigned char>(c)));
    return colorSpace == "linear" || colorSpace == "scene_linear" || colorSpace == "lin_srgb";
}

// RGB8 top row first -> RGBA8 bottom row first, which gi::writePNG takes.
std::vector<uint8_t> toGLOrder(const std::vector<uint8_t>& rgb, int width, int height) {
    std::vector<uint8_t> rgba(size_t(width) * height * 4);
    for (int y = 0; y < height; ++y) {
        const uint8_t* src = &rgb[size_t(y) * width * 3];
        uint8_t* dst = &rgba[size_t(height - 1 - y) * width * 4];
        for (int x = 0; x < width; ++x) {
            dst[x * 4 + 0] = src[x * 3 + 0];
            dst[x * 4 + 1] = src[x * 3 + 1];
            dst[x * 4 + 2] = src[x * 3 + 2];
            dst[x * 4 + 3] = 255;
        }
    }
    return rgba;
}

}  // namespace

double meanLuminance(const ImageRGB& image) {
    double sum = 0.0;
    for (size_t p = 0; p < pixelCount(image); ++p) sum += luminance(&image.rgb[p * 3]);
    return pixelCount(image) > 0 ? sum / double(pixelCount(image)) : 0.0;
}

ImageRGB loadImageLinear(const std::filesystem::path& path) {
    if (!std::filesystem::is_regular_file(path)) throw Error(path.string() + ": no such image file");
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw Error(path.string() + ": cannot read image: " + oneLine(OIIO::geterror()));
    const OIIO::ImageSpec& spec = in->spec();
    int channelCount = spec.nchannels;
    if (spec.width <= 0 || spec.height <= 0 || channelCount <= 0)
        throw Error(path.string() + ": image has no pixels");
    std::vector<float> raw(size_t(spec.width) * spec.height * channelCount);
    if (!in->read_image(0, 0, 0, channelCount, OIIO::TypeDesc::FLOAT, raw.data()))
        throw Error(path.string() + ": cannot decode image: " + oneLine(in->geterror()));
    bool linear = spec.format.is_floating_point() || namesLinear(spec.get_string_attribute("oiio:ColorSpace"));

    ImageRGB image;
    image.width = spec.width;
    image.height = spec.height;
    image.rgb.resize(pixelCount(image) * 3);
    // Grey (with or without alpha) is replicated; extra channels such as alpha are dropped.
    bool grey = channelCount < 3;
    for (size_t p = 0; p < pixelCount(image); ++p) {
        for (int c = 0; c < 3; ++c) {
            float v = raw[p * channelCount + (grey ? 0 : c)];
            image.rgb[p * 3 + c] = linear ? v : srgbToLinear(v);
        }
    }
    return image;
}

ImageRGB imageFromGL(int width, int height, const std::vector<float>& rgba) {
    GI_ASSERT(rgba.size() == size_t(width) * height * 4, "imageFromGL takes width * height RGBA pixels");
    ImageRGB image;
    image.width = width;
    image.height = height;
    image.rgb.resize(size_t(width) * height * 3);
    for (int y = 0; y < height; ++y) {
        const float* src = &rgba[size_t(height - 1 - y) * width * 4];
        float* dst = &image.rgb[size_t(y) * width * 3];
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) dst[x * 3 + c] = src[x * 4 + c];
    }
    return image;
}

std::vector<uint8_t> encodeSRGB8(const ImageRGB& image) {
    std::vector<uint8_t> out(image.rgb.size());
    for (size_t i = 0; i < image.rgb.size(); ++i) out[i] = toByte(encodeSRGB(image.rgb[i]));
    return out;
}

double rmse(const ImageRGB& a, const ImageRGB& b) {
    requireSameSize(a, b);
    if (a.rgb.empty()) return 0.0;
    double sum = 0.0;
    for (size_t i = 0; i < a.rgb.size(); ++i) {
        double d = double(a.rgb[i]) - double(b.rgb[i]);
        sum += d * d;
    }
    return std::sqrt(sum / double(a.rgb.size()));
}

double psnr(const ImageRGB& image, const ImageRGB& reference) {
    double error = rmse(image, reference);
    double peak = 0.0;
    for (float v : reference.rgb) peak = std::max(peak, double(v));
    if (peak <= 0.0) peak = 1.0;
    if (error == 0.0) return std::numeric_limits<double>::infinity();
    return 20.0 * std::log10(peak / error);
}

std::vector<uint8_t> ssimMapImage(const SSIMResult& result) {
    std::vector<uint8_t> out(result.map.size() * 3, 0);
    for (size_t p = 0; p < result.map.size(); ++p) {
        float s = result.map[p];
        if (s >= 0.0f) {
            uint8_t g = toByte(std::min(s, 1.0f));
            out[p * 3 + 0] = out[p * 3 + 1] = out[p * 3 + 2] = g;
        } else {
            out[p * 3 + 2] = toByte(std::min(-s, 1.0f));
        }
    }
    return out;
}

std::vector<uint8_t> differenceHeatMap(const ImageRGB& image, const ImageRGB& reference, float scale) {
    requireSameSize(image, reference);
    std::vector<uint8_t> out(pixelCount(image) * 3, 0);
    for (size_t p = 0; p < pixelCount(image); ++p) {
        float d = scale * (luminance(&image.rgb[p * 3]) - luminance(&reference.rgb[p * 3]));
        uint8_t v = toByte(encodeSRGB(std::min(std::abs(d), 1.0f)));
        if (d > 0.0f) out[p * 3 + 0] = v;
        if (d < 0.0f) out[p * 3 + 2] = v;
    }
    return out;
}

LeakResult computeLeak(const ImageRGB& techniqueIndirect, const ImageRGB& referenceIndirect,
                       const LeakOptions& options) {
    requireSameSize(techniqueIndirect, referenceIndirect);
    size_t count = pixelCount(referenceIndirect);
    double refMean = meanLuminance(referenceIndirect);
    double darkLimit = std::max(double(options.darkThreshold) * refMean, double(options.absoluteFloor));
    double litLimit = double(options.litFactor) * darkLimit;
    // The leak map's yellow point and the grey ramp of the reference both follow its brightness.
    double excessFull = std::max(refMean, double(options.absoluteFloor));

    LeakResult result;
    result.map.assign(count * 3, 0);
    size_t leakCount = 0;
    double excess = 0.0, refTotal = 0.0, techTotal = 0.0;
    for (size_t p = 0; p < count; ++p) {
        double yRef = luminance(&referenceIndirect.rgb[p * 3]);
        double yTech = luminance(&techniqueIndirect.rgb[p * 3]);
        refTotal += yRef;
        techTotal += yTech;
        uint8_t* m = &result.map[p * 3];
        if (yRef < darkLimit && yTech > litLimit) {
            ++leakCount;
            excess += yTech - yRef;
            m[0] = 255;
            m[1] = toByte(float(std::min((yTech - yRef) / excessFull, 1.0)));
        } else {
            uint8_t g = toByte(0.35f * encodeSRGB(float(yRef / (2.0 * excessFull))));
            m[0] = m[1] = m[2] = g;
        }
    }
    result.fraction = count > 0 ? double(leakCount) / double(count) : 0.0;
    double denominator = refTotal > 0.0 ? refTotal : techTotal;
    result.energy = denominator > 0.0 ? excess / denominator : 0.0;
    return result;
}

double brightnessRatio(const ImageRGB& image, const ImageRGB& reference) {
    double ref = meanLuminance(reference);
    return ref > 0.0 ? meanLuminance(image) / ref : 0.0;
}

double relativeNoise(const ImageRGB& halfA, int nA, const ImageRGB& halfB, int nB) {
    requireSameSize(halfA, halfB);
    GI_ASSERT(nA >= 1 && nB >= 1, "each half holds at least one sample");
    const size_t pixels = pixelCount(halfA);
    if (pixels == 0) return 0.0;
    const double pair = 1.0 / nA + 1.0 / nB, n = double(nA) + double(nB);
    double variance = 0.0, mean = 0.0;
    for (size_t p = 0; p < pixels; ++p) {
        const double a = luminance(&halfA.rgb[p * 3]), b = luminance(&halfB.rgb[p * 3]);
        const double d = a - b;
        variance += d * d / pair / n;  // the per-sample variance over n: the variance of the full mean
        mean += (a * nA + b * nB) / n;
    }
    variance /= double(pixels);
    mean /= double(pixels);
    return mean > 0.0 ? std::sqrt(variance) / mean : 0.0;
}

Metrics compareImages(const ImageRGB& image, const ImageRGB& reference, const SSIMOptions& options) {
    requireSameSize(image, reference);
    Metrics m;
    SSIMResult s = computeSSIM(encodeSRGB8(image), encodeSRGB8(reference), image.width, image.height, options);
    m.ssim = s.ssim;
    m.score = seedScore(s.ssim);
    m.brightness = brightnessRatio(image, reference);
    m.rmse = rmse(image, reference);
    m.psnr = psnr(image, reference);
    LeakResult leak = computeLeak(image, reference);
    m.leakFraction = leak.fraction;
    m.leakEnergy = leak.energy;
    return m;
}

json metricsToJson(const Metrics& m) {
    double psnrValue = std::isfinite(m.psnr) ? std::min(m.psnr, kPSNRCap) : kPSNRCap;
    return json{{"ssim", m.ssim},       {"score", m.score},
                {"rmse", m.rmse},       {"psnr", psnrValue},
                {"leakFraction", m.leakFraction}, {"leakEnergy", m.leakEnergy},
                {"brightness", m.brightness}};
}

void writeMetricMaps(const std::filesystem::path& dir, const ImageRGB& image, const ImageRGB& reference,
                     const SSIMOptions& ssimOptions, const LeakOptions& leakOptions, float heatScale) {
    requireSameSize(image, reference);
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw Error(dir.string() + ": cannot create folder: " + ec.message());
    int w = image.width, h = image.height;
    SSIMResult s = computeSSIM(encodeSRGB8(image), encodeSRGB8(reference), w, h, ssimOptions);
    writePNG(dir / "ssim_map.png", w, h, toGLOrder(ssimMapImage(s), w, h));
    if (heatScale <= 0.0f) heatScale = float(1.0 / std::max(meanLuminance(reference), 1e-6));
    writePNG(dir / "heat_map.png", w, h, toGLOrder(differenceHeatMap(image, reference, heatScale), w, h));
    writePNG(dir / "leak_map.png", w, h, toGLOrder(computeLeak(image, reference, leakOptions).map, w, h));
}

Metrics scoreRender(const RenderScoreInputs& in, const SSIMOptions& options) {
    requireSameSize(*in.image, *in.reference);
    Metrics m;
    std::vector<uint8_t> a = encodeSRGB8(toneMapped(*in.image, in.toneMap));
    std::vector<uint8_t> b = encodeSRGB8(toneMapped(*in.reference, in.toneMap));
    m.ssim = computeSSIM(a, b, in.image->width, in.image->height, options).ssim;
    m.score = seedScore(m.ssim);
    m.brightness = brightnessRatio(*in.image, *in.reference);
    m.rmse = rmse(*in.image, *in.reference);
    m.psnr = psnr(*in.image, *in.reference);
    if (in.indirect && in.referenceIndirect) {
        LeakResult leak = computeLeak(*in.indirect, *in.referenceIndirect);
        m.leakFraction = leak.fraction;
        m.leakEnergy = leak.energy;
    }
    return m;
}

void writeRenderScoreMaps(const std::filesystem::path& dir, const RenderScoreInputs& in, const SSIMOptions& options) {
    requireSameSize(*in.image, *in.reference);
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw Error(dir.string() + ": cannot create folder: " + ec.message());
    int w = in.image->width, h = in.image->height;
    SSIMResult s = computeSSIM(encodeSRGB8(toneMapped(*in.image, in.toneMap)),
                               encodeSRGB8(toneMapped(*in.reference, in.toneMap)), w, h, options);
    writePNG(dir / "ssim_map.png", w, h, toGLOrder(ssimMapImage(s), w, h));
    float heatScale = float(1.0 / std::max(meanLuminance(*in.reference), 1e-6));
    writePNG(dir / "heat_map.png", w, h, toGLOrder(differenceHeatMap(*in.image, *in.reference, heatScale), w, h));
    if (in.indirect && in.referenceIndirect)
        writePNG(dir / "leak_map.png", w, h, toGLOrder(computeLeak(*in.indirect, *in.referenceIndirect).map, w, h));
}

}  // namespace gi
