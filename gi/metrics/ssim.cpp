// SSIM after Wang et al. 2004 with scikit-image's conventions; the definition is in metrics.h.
#include "gi/metrics/metrics.h"

#include "gi/util/error.h"

#ifdef GI_METRICS_HAVE_TBB
#include <tbb/parallel_for.h>
#endif

#include <algorithm>
#include <array>
#include <cmath>

namespace gi {

namespace {

constexpr double kSigma = 1.5;
constexpr double kTruncate = 3.5;
constexpr int kRadius = int(kTruncate * kSigma + 0.5);  // 5, as scipy.ndimage computes it
constexpr int kWindow = 2 * kRadius + 1;                // 11
constexpr double kK1 = 0.01, kK2 = 0.03, kL = 255.0;
constexpr double kC1 = (kK1 * kL) * (kK1 * kL);
constexpr double kC2 = (kK2 * kL) * (kK2 * kL);
// The five filtered quantities: means of x and y, and of x^2, y^2, xy.
constexpr int kMomentCount = 5;

// scipy.ndimage's _gaussian_kernel1d, term for term, so the weights agree to the last bit.
std::array<double, kWindow> gaussianWeights() {
    std::array<double, kWindow> w{};
    double sum = 0.0;
    for (int i = 0; i < kWindow; ++i) {
        double x = double(i - kRadius);
        w[i] = std::exp(-0.5 / (kSigma * kSigma) * x * x);
        sum += w[i];
    }
    for (double& v : w) v /= sum;
    return w;
}

// scipy.ndimage mode 'reflect' (d c b a | a b c d), for any offset and any size.
int reflectIndex(int i, int n) {
    if (n == 1) return 0;
    int period = 2 * n;
    i %= period;
    if (i < 0) i += period;
    return i < n ? i : period - 1 - i;
}

// The per-pixel SSIM of one channel into `s` (width * height). Rows stream through: the vertical
// pass accumulates the five moments of one output row, the horizontal pass filters that row
// from a mirrored copy. Both inner loops run along x, so they vectorise.
void ssimChannel(const std::vector<uint8_t>& image, const std::vector<uint8_t>& reference, int channel, int width,
                 int height, double* s) {
    static const std::array<double, kWindow> kWeights = gaussianWeights();
    size_t pixelCount = size_t(width) * height;
    std::vector<double> x(pixelCount), y(pixelCount);
    for (size_t p = 0; p < pixelCount; ++p) {
        x[p] = image[p * 3 + channel];
        y[p] = reference[p * 3 + channel];
    }
    int paddedWidth = width + 2 * kRadius;
    std::vector<double> column(size_t(kMomentCount) * width), padded(size_t(kMomentCount) * paddedWidth),
        moment(size_t(kMomentCount) * width);
    std::array<int, kWindow> rows{};
    for (int row = 0; row < height; ++row) {
        for (int k = 0; k < kWindow; ++k) rows[k] = reflectIndex(row + k - kRadius, height);
        double* c0 = column.data();
        double* c1 = c0 + width;
        double* c2 = c1 + width;
        double* c3 = c2 + width;
        double* c4 = c3 + width;
        std::fill(column.begin(), column.end(), 0.0);
        for (int k = 0; k < kWindow; ++k) {
            const double w = kWeights[k];
            const double* xr = x.data() + size_t(rows[k]) * width;
            const double* yr = y.data() + size_t(rows[k]) * width;
            for (int i = 0; i < width; ++i) {
                double xv = xr[i], yv = yr[i];
                c0[i] += w * xv;
                c1[i] += w * yv;
                c2[i] += w * (xv * xv);
                c3[i] += w * (yv * yv);
                c4[i] += w * (xv * yv);
            }
        }
        for (int q = 0; q < kMomentCount; ++q) {
            const double* src = column.data() + size_t(q) * width;
            double* dst = padded.data() + size_t(q) * paddedWidth;
            for (int i = 0; i < paddedWidth; ++i) dst[i] = src[reflectIndex(i - kRadius, width)];
        }
        std::fill(moment.begin(), moment.end(), 0.0);
        for (int q = 0; q < kMomentCount; ++q) {
            const double* src = padded.data() + size_t(q) * paddedWidth;
            double* dst = moment.data() + size_t(q) * width;
            for (int k = 0; k < kWindow; ++k) {
                const double w = kWeights[k];
                const double* srck = src + k;
                for (int i = 0; i < width; ++i) dst[i] += w * srck[i];
            }
        }
        const double* ux = moment.data();
        const double* uy = ux + width;
        const double* uxx = uy + width;
        const double* uyy = uxx + width;
        const double* uxy = uyy + width;
        double* out = s + size_t(row) * width;
        for (int i = 0; i < width; ++i) {
            double vx = uxx[i] - ux[i] * ux[i];
            double vy = uyy[i] - uy[i] * uy[i];
            double vxy = uxy[i] - ux[i] * uy[i];
            double a1 = 2.0 * ux[i] * uy[i] + kC1, a2 = 2.0 * vxy + kC2;
            double b1 = ux[i] * ux[i] + uy[i] * uy[i] + kC1, b2 = vx + vy + kC2;
            out[i] = (a1 * a2) / (b1 * b2);
        }
    }
}

}  // namespace

SSIMResult computeSSIM(const std::vector<uint8_t>& image, const std::vector<uint8_t>& reference, int width,
                       int height, const SSIMOptions& options) {
    GI_ASSERT(width > 0 && height > 0, "computeSSIM needs a non-empty image");
    size_t pixelCount = size_t(width) * height;
    GI_ASSERT(image.size() == pixelCount * 3 && reference.size() == pixelCount * 3,
              "computeSSIM takes two RGB8 images of width * height pixels");

    std::vector<double> s(pixelCount * 3);
    auto channel = [&](int c) { ssimChannel(image, reference, c, width, height, s.data() + pixelCount * c); };
#ifdef GI_METRICS_HAVE_TBB
    tbb::parallel_for(0, 3, channel);
#else
    for (int c = 0; c < 3; ++c) channel(c);
#endif

    SSIMResult result;
    result.width = width;
    result.height = height;
    result.map.resize(pixelCount);
    for (size_t p = 0; p < pixelCount; ++p)
        result.map[p] = float((s[p] + s[pixelCount + p] + s[2 * pixelCount + p]) / 3.0);

    // The mean skips the window radius at each border, as scikit-image does; a side too small to
    // have an interior keeps all its pixels.
    int x0 = kRadius, x1 = width - kRadius, y0 = kRadius, y1 = height - kRadius;
    if (x1 <= x0) x0 = 0, x1 = width;
    if (y1 <= y0) y0 = 0, y1 = height;
    double sum[3] = {0, 0, 0};
    size_t counted = 0;
    for (int yy = y0; yy < y1; ++yy) {
        for (int xx = x0; xx < x1; ++xx) {
            size_t p = size_t(yy) * width + xx;
            if (options.skipBlackInBoth) {
                const uint8_t* a = &image[p * 3];
                const uint8_t* b = &reference[p * 3];
                if ((a[0] | a[1] | a[2] | b[0] | b[1] | b[2]) == 0) continue;
            }
            for (int c = 0; c < 3; ++c) sum[c] += s[pixelCount * c + p];
            ++counted;
        }
    }
    for (int c = 0; c < 3; ++c) result.channel[c] = counted > 0 ? sum[c] / double(counted) : 1.0;
    result.ssim = (result.channel[0] + result.channel[1] + result.channel[2]) / 3.0;
    return result;
}

// Negative SSIM clamps to 0: an even power would otherwise turn inverted images into good scores.
double seedScore(double ssim) { return 10.0 * std::pow(std::max(ssim, 0.0), 1000.0); }

}  // namespace gi
