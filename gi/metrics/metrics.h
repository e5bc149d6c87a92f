// Image metrics: SSIM and the seed-000 score, RMSE and PSNR, the leak measure, and the maps that
// show where two images differ.
//
// Source: seed 000 (ten Brug 2017), section 4, which re-implements SSIM after Wang, Bovik,
// Sheikh and Simoncelli 2004 ("Image quality assessment: from error visibility to structural
// similarity"), and the leak complaint of anchors/mission.md.
//
// SSIM, as computed here
//   - On the 8-bit sRGB image (encodeSRGB8), per R, G, B channel separately, L = 255,
//     K1 = 0.01, K2 = 0.03, C1 = (K1 L)^2, C2 = (K2 L)^2. With C3 = C2 / 2 the three-term form
//     of the seed's eq 4.8 reduces to ((2 mx my + C1)(2 sxy + C2)) / ((mx^2 + my^2 + C1)(sx^2 +
//     sy^2 + C2)), which is what is evaluated.
//   - Local statistics under a circular Gaussian window, sigma 1.5 (the seed leaves sigma out;
//     1.5 is Wang et al.'s value), truncated at 3.5 sigma: radius int(3.5 * 1.5 + 0.5) = 5, an
//     11x11 window, weights normalised to sum 1. Filtering is separable and the border is
//     mirrored with the edge pixel repeated (d c b a | a b c d), as scipy.ndimage's 'reflect'.
//   - Population (weighted) variances and covariance, as Wang et al. and scikit-image with
//     use_sample_covariance=False. The seed says n-1; with Gaussian weights there is no sample
//     count to correct by, and matching the published implementation lets users check numbers.
//   - The per-pixel map is full size, but the mean skips a band of 5 pixels (the window radius)
//     on each side, exactly as scikit-image's structural_similarity does, so that the mirrored
//     border does not count. Images of 10 pixels or fewer along a side have no interior; then
//     the mean is over every pixel.
//   - The channel means are averaged into the final SSIM.
//   This equals scikit-image's structural_similarity(a, b, channel_axis=-1,
//   gaussian_weights=True, sigma=1.5, use_sample_covariance=False, data_range=255); the tests
//   check it against values printed by tests/tools/ssim_reference.py.
//
// Seed-000 variants
//   - skipBlackInBoth: pixels whose 8-bit RGB is (0, 0, 0) in both images are left out of the
//     mean (the seed's scenes have large black backgrounds that inflate the score). When no
//     pixel is left, SSIM is 1: the images agree everywhere (they are black).
//   - seedScore = 10 * SSIM^1000. The seed does not say whether the exponent is applied per pixel
//     or to the mean; we apply it to the mean SSIM, so score 7.0 means SSIM 0.999643 and a score
//     is a monotone function of the SSIM it reports. A negative mean scores 0.
//
// RMSE and PSNR work on linear values (all three channels, every pixel). PSNR = 20 log10(peak /
// RMSE) with peak = the largest channel value of the reference (1 when the reference is black),
// so HDR references are not clipped at 1. Equal images have infinite PSNR; JSON, which has no
// infinity, reports kPSNRCap instead.
//
// The leak measure
//   Leaks, light where the scene is occluded, are the top complaint against grid-based GI. Given
//   the technique's indirect image and the reference's indirect-only image (both linear), with
//   Rec. 709 luminance Y and the reference's mean luminance m:
//     dark    Yref < darkLimit = max(darkThreshold * m, absoluteFloor): the reference leaves the
//             pixel (nearly) unlit by indirect light.
//     lit     Ytech > litFactor * darkLimit: the technique puts clearly more light there than
//             the reference's own dark limit; the gap between the two thresholds keeps small
//             biases (an ambient floor, path-tracer noise) from counting as leaks.
//     leak pixel  dark and lit.
//     fraction    leak pixels / all pixels.
//     energy      sum over leak pixels of (Ytech - Yref) / sum over all pixels of Yref: the leaked
//                 light as a share of all the indirect light the reference has, scale free.
//                 When the reference is black, the denominator is the technique's total
//                 luminance instead (energy is then the leaked share of the technique's light).
//   Defaults: darkThreshold 0.02 and litFactor 5, i.e. the reference is below 2% of its mean and
//   the technique above 10% of it.
//
// Maps (RGB8, top row first)
//   - SSIM map: grey, white where SSIM = 1 and black at SSIM 0; negative SSIM (inverted
//     structure) in blue, full blue at -1.
//   - Heat map: d = scale * (Yimage - Yref), clamped to [-1, 1]; red where the image is brighter
//     (d > 0), blue where darker, black where equal. The channel holds the sRGB encoding of |d|
//     so that small differences stay visible. writeMetricMaps picks scale = 1 / (mean reference
//     luminance): a difference as large as the average brightness saturates.
//   - Leak map: the reference luminance as a dim grey for orientation; leak pixels in red to
//     yellow, yellow where the excess reaches the reference's mean luminance.
#pragma once

#include "gi/render/image.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <vector>

namespace gi {

using json = nlohmann::json;

// Reported in JSON for the PSNR of equal images, whose true value is infinite.
inline constexpr double kPSNRCap = 999.0;


// Reads PNG, JPEG, EXR, HDR or anything else OpenImageIO reads. Float files are taken as linear;
// integer files as sRGB (unless the file says it is linear) and decoded. Grey is replicated to
// RGB, alpha dropped. Throws gi::Error naming the file.
ImageRGB loadImageLinear(const std::filesystem::path& path);

// From the renderer's readback: RGBA, bottom row first.
ImageRGB imageFromGL(int width, int height, const std::vector<float>& rgba);

// Mean Rec. 709 luminance of a linear image (0 for an empty one).
double meanLuminance(const ImageRGB& image);

// RGB8, top row first: clamp to [0, 1], sRGB encode as shaders/common/color.glsl linearToSRGB
// does, round to nearest.
std::vector<uint8_t> encodeSRGB8(const ImageRGB& image);

struct SSIMOptions {
    bool skipBlackInBoth = false;  // seed 000: leave pixels black in both images out of the mean
};

struct SSIMResult {
    double ssim = 0;                  // mean of the three channel means
    double channel[3] = {0, 0, 0};    // mean SSIM of R, G, B
    int width = 0, height = 0;
    std::vector<float> map;           // per-pixel SSIM, mean of the channels, top row first
};

// SSIM of two RGB8 images (top row first, 3 bytes per pixel) of the same size; see above.
SSIMResult computeSSIM(const std::vector<uint8_t>& image, const std::vector<uint8_t>& reference, int width,
                       int height, const SSIMOptions& options = {});

// Seed 000's score, 10 * ssim^1000, applied to the mean SSIM (negative SSIM scores 0).
double seedScore(double ssim);

// On linear values; the images must have the same size (gi::Error otherwise).
double rmse(const ImageRGB& a, const ImageRGB& b);
// 20 log10(max reference value / rmse); infinite for equal images.
double psnr(const ImageRGB& image, const ImageRGB& reference);

// Visualisations, RGB8 top row first; see above for the colours.
std::vector<uint8_t> ssimMapImage(const SSIMResult& result);
std::vector<uint8_t> differenceHeatMap(const ImageRGB& image, const ImageRGB& reference, float scale);

struct LeakOptions {
    float darkThreshold = 0.02f;   // reference dark below this fraction of its mean luminance
    float absoluteFloor = 1e-4f;   // ... or below this linear luminance, whichever is larger
    float litFactor = 5.0f;        // technique lit above this multiple of the dark limit
};

struct LeakResult {
    double fraction = 0;           // leak pixels / all pixels
    double energy = 0;             // leaked luminance / total reference luminance
    std::vector<uint8_t> map;      // RGB8, top row first
};

// Both images are indirect-only, linear, same size (gi::Error otherwise).
LeakResult computeLeak(const ImageRGB& techniqueIndirect, const ImageRGB& referenceIndirect,
                       const LeakOptions& options = {});

struct Metrics {
    double ssim = 0;
    double score = 0;
    double rmse = 0;
    double psnr = 0;          // may be infinite; metricsToJson caps it at kPSNRCap
    double leakFraction = 0;
    double leakEnergy = 0;
    double brightness = 0;    // mean linear luminance of the image over the reference's (1: as bright)
};

// Mean luminance of `image` over that of `reference` (0 when the reference is black).
double brightnessRatio(const ImageRGB& image, const ImageRGB& reference);

// The noise left in a Monte Carlo image, estimated from two independent halves of its samples:
// `halfA` the mean of nA samples per pixel, `halfB` of nB. Per pixel, the luminance difference d
// of the halves has variance s^2 (1/nA + 1/nB), which gives the per-sample variance s^2; the mean
// of all nA + nB samples has variance s^2 / (nA + nB). Returns the RMS over pixels of that
// standard error over the image's mean luminance (0.02: pixels stand about 2 % of the average
// brightness off their converged values), 0 for a black image. Sizes must match; nA, nB >= 1.
double relativeNoise(const ImageRGB& halfA, int nA, const ImageRGB& halfB, int nB);

// Every metric; the leak measure treats the two images as indirect images. Sizes must match.
Metrics compareImages(const ImageRGB& image, const ImageRGB& reference, const SSIMOptions& options = {});

// Keys ssim, score, rmse, psnr, leakFraction, leakEnergy, brightness.
json metricsToJson(const Metrics& metrics);

// Writes DIR/ssim_map.png, DIR/heat_map.png and DIR/leak_map.png (DIR is created). heatScale 0
// picks 1 / mean reference luminance.
void writeMetricMaps(const std::filesystem::path& dir, const ImageRGB& image, const ImageRGB& reference,
                     const SSIMOptions& ssimOptions = {}, const LeakOptions& leakOptions = {},
                     float heatScale = 0.0f);

// Scoring a render against its path-traced reference, as gi-render --score and the editor do:
// SSIM and score on the tone-mapped 8-bit images (what a viewer compares), RMSE and PSNR on the
// linear HDR images, the leak measure on the indirect terms alone.
struct RenderScoreInputs {
    const ImageRGB* image = nullptr;              // the render, linear HDR
    const ImageRGB* reference = nullptr;          // the full reference, linear HDR
    const ImageRGB* indirect = nullptr;           // the render's indirect term; null: no leak measure
    const ImageRGB* referenceIndirect = nullptr;  // the indirect-only reference
    ToneMapSettings toneMap;
};
Metrics scoreRender(const RenderScoreInputs& in, const SSIMOptions& options = {});
// DIR/ssim_map.png and DIR/heat_map.png for the image, DIR/leak_map.png for the indirect terms.
void writeRenderScoreMaps(const std::filesystem::path& dir, const RenderScoreInputs& in,
                          const SSIMOptions& options = {});

}  // namespace gi
