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
        {{"reference", "FILE", "reference image (.exr)", ""}, {"image", "FILE", "image to measure (.exr)", ""}});
    auto parsed = spec.parse(argc, argv, first);
    if (!parsed) return 0;
    if (!parsed->has("reference") || !parsed->has("image"))
        throw UsageError("compare needs --reference FILE and --image FILE");
    const ImageError error = compareImages(readExr(parsed->get("reference")), readExr(parsed->get("image")));
    std::printf("%s\n", formatImageError(error).c_str());
    return error.nonFinite ? 1 : 0;
}

}  // namespace vct
