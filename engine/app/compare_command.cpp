// vct compare: the error of an image against a reference (linear HDR EXRs), for benchmarks and scripts.
#include <cstdio>

#include "app/cli.h"
#include "app/commands.h"
#include "core/error.h"
#include "io/image_metrics.h"

namespace vct {

int runCompareCommand(int argc, char** argv, int first) {
    static const CommandSpec spec(
        "compare", "Prints MSE, relative MSE, PSNR and max error of --image against --reference (EXR files).",
        {{"reference", "FILE", "reference image (.exr)", ""},
         {"image", "FILE", "image to measure (.exr)", ""},
         {"peak", "X", "PSNR peak (default: the reference's largest value)", ""},
         {"tonemap", "", "also compare as displayed: exposure, ACES, sRGB, PSNR with peak 1 (for final.exr)",
          ""},
         {"exposure", "X", "exposure of --tonemap (as vct render's)", "1"},
         {"error-map", "FILE.png", "write |image - reference| as a heat map (white at --error-scale)", ""},
         {"error-scale", "X", "error shown as white in --error-map", "0.05"}});
    auto parsed = spec.parse(argc, argv, first);
    if (!parsed) return 0;
    if (!parsed->has("reference") || !parsed->has("image"))
        throw UsageError("compare needs --reference FILE and --image FILE");
    const ParsedArgs& args = *parsed;
    const ImageRgba32f reference = readExr(args.get("reference"));
    const ImageRgba32f image = readExr(args.get("image"));
    const ImageError error =
        compareImages(reference, image, args.has("peak") ? args.getFloat("peak", 1e-30f, 1e30f) : 0.0);
    std::printf("%s\n", formatImageError(error).c_str());
    if (args.has("tonemap")) {
        const ImageError display =
            compareToneMapped(reference, image, args.getFloat("exposure", 1e-6f, 1e6f));
        std::printf("tone-mapped sRGB (peak 1): %s\n", formatImageError(display).c_str());
    }
    if (args.has("error-map")) {
        const ImageRgba8 map = errorHeatMap(reference, image, args.getFloat("error-scale", 1e-30f, 1e30f));
        writePng(args.get("error-map"), map.width, map.height, map.pixels);
    }
    return error.nonFinite ? 1 : 0;
}

}  // namespace vct
