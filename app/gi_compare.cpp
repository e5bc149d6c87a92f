// gi-compare: scores any image against a reference (PNG, EXR, or whatever OpenImageIO reads) with
// the workbench's metrics (gi/metrics/metrics.h), so renders from other tools can be scored too.
#include "gi/metrics/metrics.h"
#include "gi/util/error.h"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

namespace {

std::string sizeText(const gi::ImageRGB& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height);
}

int run(int argc, char** argv) {
    CLI::App app{"gi-compare: score an image against a reference (SSIM, seed-000 score, RMSE, PSNR, leaks)"};
    std::string imagePath, referencePath, mapDir;
    bool asJson = false, skipBlack = false;
    app.add_option("image", imagePath, "The image to score (PNG, EXR, ...)")->required();
    app.add_option("reference", referencePath, "The reference image, same size")->required();
    app.add_flag("--json", asJson, "Print one JSON object: ssim, score, rmse, psnr, leakFraction, leakEnergy");
    app.add_option("--maps", mapDir, "Write ssim_map.png, heat_map.png and leak_map.png into this folder");
    app.add_flag("--skip-black", skipBlack, "Leave pixels black in both images out of the SSIM mean (seed 000)");
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "gi-compare: %s (see --help)\n", e.what());
        return 2;
    }

    gi::ImageRGB image = gi::loadImageLinear(imagePath);
    gi::ImageRGB reference = gi::loadImageLinear(referencePath);
    if (image.width != reference.width || image.height != reference.height)
        throw gi::Error(imagePath + " is " + sizeText(image) + " but " + referencePath + " is " + sizeText(reference));

    gi::SSIMOptions options;
    options.skipBlackInBoth = skipBlack;
    gi::Metrics m = gi::compareImages(image, reference, options);
    if (!mapDir.empty()) gi::writeMetricMaps(mapDir, image, reference, options);

    if (asJson) {
        std::cout << gi::metricsToJson(m).dump() << "\n";
        return 0;
    }
    std::printf("ssim          %.6f\n", m.ssim);
    std::printf("score         %.5f   (10 * ssim^1000)\n", m.score);
    std::printf("rmse          %.6g   (linear)\n", m.rmse);
    if (std::isfinite(m.psnr))
        std::printf("psnr          %.2f dB (peak = reference maximum)\n", m.psnr);
    else
        std::printf("psnr          inf (identical)\n");
    std::printf("leakFraction  %.6f\n", m.leakFraction);
    std::printf("leakEnergy    %.6f\n", m.leakEnergy);
    if (!mapDir.empty()) std::printf("maps in %s\n", mapDir.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) { return gi::reportErrors("gi-compare", [&] { return run(argc, argv); }); }
