// `vct render --view voxels --voxel-mip M` (shaders/voxel_view.comp): the voxel grid ray-marched at one mip,
// written to final.png through the same tone map as the other views. On the cornell scene at N = 32 (6 mips):
// mips 0 and 2 render under validation, show something, and differ; the voxel view stays out of the frame's
// pass timings; bad combinations are usage errors (exit 2, one line).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/image_io.h"
#include "test_util.h"

namespace vct {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr uint32_t kWidth = 160, kHeight = 90;

test::RunResult renderVoxels(const fs::path& dir, const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"render",     "--scene", "cornell",  "--size", "160x90",
                                     "--frames",   "2",       "--voxels", "32",     "--out",
                                     dir.string(), "--view",  "voxels"};
    args.insert(args.end(), extra.begin(), extra.end());
    return test::runVct(args);
}

ImageRgba8 renderMip(uint32_t mip) {
    const fs::path dir = test::freshOutputDir("voxel_view/mip" + std::to_string(mip));
    const test::RunResult run = renderVoxels(dir, {"--voxel-mip", std::to_string(mip), "--validate"});
    EXPECT_TRUE(run.exited() && run.exitCode == 0) << run.describe();
    EXPECT_EQ(run.err.find("validation"), std::string::npos) << run.err;
    // On demand after the frame: no voxel-view pass among the frame's timings.
    std::ifstream timings(dir / "timings.json");
    EXPECT_TRUE(timings.good());
    if (timings.good()) {
        const json report = json::parse(timings);
        for (const json& pass : report["passes"]) EXPECT_NE(pass["name"].get<std::string>(), "voxel_view");
    }
    if (!fs::exists(dir / "final.png")) return {};
    return readPng(dir / "final.png");
}

TEST(VoxelView, MipsZeroAndTwoRenderAndDiffer) {
    const ImageRgba8 mip0 = renderMip(0), mip2 = renderMip(2);
    for (const ImageRgba8* png : {&mip0, &mip2}) {
        ASSERT_EQ(png->width, kWidth);
        ASSERT_EQ(png->height, kHeight);
        // Not black: lit voxels (the spot-lit back wall and floor) reach well into the bright range, and the
        // image is not one flat colour.
        uint8_t lo = 255, hi = 0;
        for (size_t i = 0; i < png->pixels.size(); i += 4)
            for (size_t c = 0; c < 3; ++c) {
                lo = std::min(lo, png->pixels[i + c]);
                hi = std::max(hi, png->pixels[i + c]);
            }
        EXPECT_GE(hi, 128);
        EXPECT_GE(hi - lo, 64);
    }
    // A coarser mip is a different (blurrier, semi-transparent) picture of the grid.
    double difference = 0.0;
    size_t differing = 0;
    for (size_t i = 0; i < mip0.pixels.size(); i += 4) {
        int pixel = 0;
        for (size_t c = 0; c < 3; ++c) pixel += std::abs(int(mip0.pixels[i + c]) - int(mip2.pixels[i + c]));
        difference += pixel;
        differing += pixel > 6;
    }
    const size_t pixels = size_t(kWidth) * kHeight;
    difference /= double(pixels * 3);
    std::printf("voxel view mip 0 vs 2: mean |difference| %.2f / 255, %.1f%% of pixels differ\n", difference,
                100.0 * double(differing) / double(pixels));
    EXPECT_GT(difference, 4.0);
    EXPECT_GT(differing, pixels / 4);
}

// Exit status 2 with one line on stderr that contains `expected`.
void expectUsageError(const std::vector<std::string>& extra, const std::string& name,
                      const std::string& expected) {
    const fs::path dir = test::freshOutputDir("voxel_view/" + name);
    const test::RunResult run = renderVoxels(dir, extra);
    ASSERT_TRUE(run.exited()) << run.describe();
    EXPECT_EQ(run.exitCode, 2) << run.describe();
    EXPECT_NE(run.err.find(expected), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
}

TEST(VoxelView, MipOutOfRangeIsAUsageError) {
    // N = 32: mips 0..5. Known from --voxels before anything is rendered.
    expectUsageError({"--voxel-mip", "6"}, "mip6", "expected an integer from 0 to 5");
    expectUsageError({"--voxel-mip", "two"}, "mip-two", "expected an integer from 0 to 5");
}

TEST(VoxelView, NeedsTheGridAndTheView) {
    expectUsageError({"--gi", "off"}, "gi-off", "--gi off");
    // --voxel-mip without --view voxels (a later --view overrides the helper's).
    expectUsageError({"--view", "final", "--voxel-mip", "1"}, "no-view", "only with --view voxels");
}

}  // namespace
}  // namespace vct
