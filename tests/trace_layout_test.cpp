// The two layouts of the cone-tracing passes, trace, re-trace and the voxel gathers (--trace-layout,
// lib/cone_trace.glsl, docs/design.md §5.5): a pixel's or voxel's cones one after the other in one invocation (the CPU
// default) and one invocation per cone, combined through shared memory (the GPU default), run the same arithmetic
// per cone and per pixel, so they give bit-identical images.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "io/image_io.h"
#include "test_util.h"

namespace {

namespace fs = std::filesystem;

fs::path render(const std::string& name, std::vector<std::string> extra) {
    const fs::path dir = vct::test::freshOutputDir("trace_layout/" + name);
    std::vector<std::string> args = {"render", "--size",     "96x54", "--voxels",  "32",
                                     "--aux",  "--validate", "--out", dir.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = vct::test::runVct(args);
    EXPECT_TRUE(r.exited() && r.exitCode == 0) << name << ": " << r.describe();
    return dir;
}

// Every cone set (turned, the default; fixed; jittered), trace scale 4, 2 (a size that is not a multiple of it) and
// 1 (the every-pixel trace, which keeps a history with the turned set), many pixels re-traced (τ high, and a camera
// cut: the resample pass's cones), every bounce (the default: the gathers of one layer a frame) and four (whole-grid
// gathers), other scenes: the two layouts give the same images, and the layout the run used is the one asked for
// (timings.json).
TEST(TraceGpu, PixelAndConeLayoutsGiveTheSameImages) {
    const std::vector<std::vector<std::string>> configurations = {
        {"--scene", "cornell", "--frames", "5"},
        {"--scene", "cornell", "--frames", "3", "--cone-rotation", "off"},
        {"--scene", "cornell", "--frames", "3", "--cone-jitter", "on"},
        {"--scene", "cornell", "--frames", "4", "--trace-scale", "1"},
        {"--scene", "cornell", "--frames", "3", "--trace-scale", "2", "--size", "97x55"},
        {"--scene", "cornell", "--frames", "4", "--tau", "4", "--camera-cut", "2"},
        {"--scene", "plane", "--frames", "3"},
        // The voxel gathers' cones (the bounce pass): whole-grid iterations, and a scene with thin walls, whose
        // voxels gather on both sides.
        {"--scene", "cornell", "--frames", "2", "--bounces", "4"},
        {"--scene", "hall", "--frames", "3", "--bounces", "4", "--voxels", "64"}};
    int index = 0;
    for (const auto& flags : configurations) {
        const std::string name = "layouts_" + std::to_string(index++);
        std::vector<std::string> pixel = flags, cone = flags;
        pixel.insert(pixel.end(), {"--trace-layout", "pixel"});
        cone.insert(cone.end(), {"--trace-layout", "cone"});
        const fs::path a = render(name + "_pixel", pixel), b = render(name + "_cone", cone);
        for (const auto& [dir, layout] : {std::pair{a, "pixel"}, std::pair{b, "cone"}}) {
            const nlohmann::json timings = nlohmann::json::parse(std::ifstream(dir / "timings.json"));
            EXPECT_EQ(timings["settings"].value("trace_layout", ""), layout) << name;
        }
        for (const char* file : {"final.exr", "diffuse_indirect.exr", "specular_indirect.exr"}) {
            const vct::ImageRgba32f x = vct::readExr(a / file), y = vct::readExr(b / file);
            ASSERT_EQ(x.pixels.size(), y.pixels.size()) << name << " " << file;
            const vct::test::ExactDifference d = vct::test::exactDifference(x.pixels, y.pixels);
            EXPECT_EQ(d.different, 0u)
                << name << " " << file << ": largest relative difference " << d.largestRelative;
            // Not two black images: most channels carry light.
            const auto lit =
                std::count_if(x.pixels.begin(), x.pixels.end(), [](float v) { return v > 0.0f; });
            EXPECT_GT(size_t(lit), x.pixels.size() / 2) << name << " " << file;
        }
    }
}

}  // namespace
