// gi-imagecheck FILE WIDTH HEIGHT: exits 0 when the image has that size and shows content: the
// centre region is not black and the image is not one flat colour.
// gi-imagecheck --halves FILE: prints "left L right R", the mean grey level (0..255) of the
// image's left and right halves, for tests that compare the two sides of a split.
#include "gi/render/image_io.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv) {
    if (argc == 3 && std::string(argv[1]) == "--halves") {
        try {
            gi::ImageRGBA8 img = gi::readImage8(argv[2]);
            double sums[2] = {0, 0};
            size_t counts[2] = {0, 0};
            for (int y = 0; y < img.height; ++y)
                for (int x = 0; x < img.width; ++x) {
                    const uint8_t* p = &img.rgba[(size_t(y) * img.width + x) * 4];
                    const int side = x < img.width / 2 ? 0 : 1;
                    sums[side] += (p[0] + p[1] + p[2]) / 3.0;
                    ++counts[side];
                }
            std::printf("left %.2f right %.2f\n", sums[0] / double(std::max<size_t>(counts[0], 1)),
                        sums[1] / double(std::max<size_t>(counts[1], 1)));
            return 0;
        } catch (const std::exception& e) {
            std::fprintf(stderr, "imagecheck: %s\n", e.what());
            return 1;
        }
    }
    if (argc != 4) {
        std::fprintf(stderr, "usage: gi-imagecheck FILE WIDTH HEIGHT\n");
        return 2;
    }
    try {
        gi::ImageRGBA8 img = gi::readImage8(argv[1]);
        int w = std::atoi(argv[2]), h = std::atoi(argv[3]);
        if (img.width != w || img.height != h) {
            std::fprintf(stderr, "imagecheck: %s is %dx%d, expected %dx%d\n", argv[1], img.width, img.height, w, h);
            return 1;
        }
        double sum = 0, sum2 = 0, centre = 0;
        size_t n = 0, nc = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const uint8_t* p = &img.rgba[(size_t(y) * w + x) * 4];
                double l = (p[0] + p[1] + p[2]) / 3.0;
                sum += l;
                sum2 += l * l;
                ++n;
                if (std::abs(x - w / 2) < w / 8 && std::abs(y - h / 2) < h / 8) {
                    centre += l;
                    ++nc;
                }
            }
        double mean = sum / n, sd = std::sqrt(std::max(0.0, sum2 / n - mean * mean));
        std::printf("imagecheck: %s %dx%d mean %.1f stddev %.1f centre mean %.1f\n", argv[1], w, h, mean, sd, centre / nc);
        if (centre / nc < 10.0 || sd < 5.0) {
            std::fprintf(stderr, "imagecheck: image looks black or flat\n");
            return 1;
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "imagecheck: %s\n", e.what());
        return 1;
    }
}
