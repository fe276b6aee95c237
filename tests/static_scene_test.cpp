// Model only what the scene needs: when nothing moved and no light changed, frames after the first skip the
// voxel grid's passes (voxelize, inject, mips) and the image stays the one that rebuilding the grid every
// frame gives; a camera cut and a moving object still rebuild it. And with GI off the frame allocates none
// of the indirect-light targets: the views and --aux files that need them say so or are left out.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/image_io.h"
#include "test_util.h"

namespace vct {
namespace {

namespace fs = std::filesystem;

constexpr uint32_t kFrames = 6, kWarmup = 1;  // 5 timed frames, all after the first

struct Render {
    fs::path dir;
    std::map<std::string, nlohmann::json> passes;  // timings.json's passes by name
};

// `vct render` of `scene` at 160x90 with a 32³ grid under validation, frames 1..5 timed.
Render render(const std::string& name, const std::string& scene, const std::vector<std::string>& extra = {}) {
    Render r;
    r.dir = test::freshOutputDir("static_scene/" + name);
    std::vector<std::string> args = {"render",
                                     "--scene",
                                     scene,
                                     "--size",
                                     "160x90",
                                     "--frames",
                                     std::to_string(kFrames),
                                     "--warmup",
                                     std::to_string(kWarmup),
                                     "--voxels",
                                     "32",
                                     "--validate",
                                     "--out",
                                     r.dir.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const test::RunResult run = test::runVct(args);
    EXPECT_TRUE(run.exited() && run.exitCode == 0) << run.describe();
    EXPECT_EQ(run.err.find("validation"), std::string::npos) << run.err;
    std::ifstream file(r.dir / "timings.json");
    EXPECT_TRUE(file) << "no timings.json in " << r.dir;
    if (!file) return r;
    const nlohmann::json timings = nlohmann::json::parse(file);  // kept: the loop below refers into it
    for (const nlohmann::json& pass : timings.at("passes"))
        r.passes[pass.at("name").get<std::string>()] = pass;
    return r;
}

// In how many of the timed frames the pass ran (timings.json "runs"); -1 when it is not listed.
int runs(const Render& r, const std::string& pass) {
    auto it = r.passes.find(pass);
    return it == r.passes.end() ? -1 : it->second.at("runs").get<int>();
}

const char* const kVoxelPasses[] = {"voxelize", "inject", "mips"};

TEST(StaticScene, PlaneSkipsTheVoxelPassesAfterTheFirstFrameWithTheSameImage) {
    const Render skipped = render("plane", "plane");
    const Render rebuilt = render("plane-rebuilt", "plane", {"--recompute-every-frame"});
    // What depends only on the scene (shadow map, voxel grid) is built in frame 0 only.
    for (const char* pass : {"shadow", "voxelize", "inject", "mips"}) {
        EXPECT_EQ(runs(skipped, pass), 0) << pass;
        EXPECT_EQ(skipped.passes.at(pass).at("median_ms").get<double>(), 0.0) << pass;
        EXPECT_EQ(runs(rebuilt, pass), int(kFrames - kWarmup)) << pass;
    }
    // The G-buffer and direct light (the camera stands still) in frames 0 and 1 only: then both G-buffer
    // copies hold the view, and the timed frames (1..5) reuse it from frame 2 on.
    for (const char* pass : {"gbuffer", "direct"}) {
        EXPECT_EQ(runs(skipped, pass), 1) << pass;
        EXPECT_EQ(runs(rebuilt, pass), int(kFrames - kWarmup)) << pass;
    }
    // The jittered trace and what follows it run every time.
    for (const char* pass : {"trace", "upsample", "composite"}) EXPECT_EQ(runs(skipped, pass), 5) << pass;

    // Bit for bit: the grid kept from frame 0 is the grid every frame would build.
    const ImageRgba32f a = readExr(skipped.dir / "final.exr"), b = readExr(rebuilt.dir / "final.exr");
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    size_t differing = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) differing += a.pixels[i] != b.pixels[i] ? 1 : 0;
    EXPECT_EQ(differing, 0u) << "values differing between reusing and recomputing the unchanged passes";
    // ...and the grid holds light: GI brightens the frame against GI off (so the comparison can fail).
    const Render off = render("plane-gi-off", "plane", {"--gi", "off"});
    const ImageRgba32f c = readExr(off.dir / "final.exr");
    double on = 0.0, without = 0.0;
    for (size_t i = 0; i < a.pixels.size(); i += 4) {
        on += test::luminance(a.pixels[i], a.pixels[i + 1], a.pixels[i + 2]);
        without += test::luminance(c.pixels[i], c.pixels[i + 1], c.pixels[i + 2]);
    }
    EXPECT_NE(on, without);
}

TEST(StaticScene, CameraCutRebuildsTheVoxelGridOnce) {
    const Render cut = render("plane-cut", "plane", {"--camera-cut", "3"});
    for (const char* pass : kVoxelPasses) EXPECT_EQ(runs(cut, pass), 1) << pass;
    // The new view's G-buffer: in the cut frame and the next (then reused), besides frame 1 before the cut.
    EXPECT_EQ(runs(cut, "gbuffer"), 3);
}

TEST(StaticScene, CornellsMovingCubeRebuildsTheVoxelGridEveryFrame) {
    const Render cornell = render("cornell", "cornell");
    for (const char* pass : kVoxelPasses) {
        EXPECT_EQ(runs(cornell, pass), int(kFrames - kWarmup)) << pass;
        EXPECT_GT(cornell.passes.at(pass).at("median_ms").get<double>(), 0.0) << pass;
    }
}

TEST(StaticScene, VoxelCacheOnAStaticSceneGivesTheSameImage) {
    const fs::path dir = test::freshOutputDir("static_scene/cache");
    const test::RunResult voxelize = test::runVct({"voxelize", "--scene", "plane", "--voxels", "32", "--out",
                                                   (dir / "plane.vdb").string(), "--validate"});
    ASSERT_TRUE(voxelize.exited() && voxelize.exitCode == 0) << voxelize.describe();
    const Render cached = render("plane-cached", "plane", {"--voxel-cache", (dir / "plane.vdb").string()});
    const Render computed = render("plane-computed", "plane");
    for (const char* pass : kVoxelPasses) EXPECT_EQ(runs(cached, pass), 0) << pass;
    const ImageRgba32f a = readExr(cached.dir / "final.exr"), b = readExr(computed.dir / "final.exr");
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    EXPECT_TRUE(a.pixels == b.pixels) << "the cached voxelization renders differently";
}

// ---- GI off: no indirect-light targets ----

TEST(GiOff, AuxWritesOnlyTheBuffersThatExist) {
    const Render off = render("gi-off-aux", "cornell", {"--gi", "off", "--aux"});
    for (const char* file :
         {"direct.exr", "normal.exr", "roughness.exr", "albedo.exr", "depth.exr", "final.exr"})
        EXPECT_TRUE(fs::is_regular_file(off.dir / file)) << file;
    for (const char* file :
         {"diffuse_indirect.exr", "specular_indirect.exr", "weight_sum.exr", "resample_mask.png"})
        EXPECT_FALSE(fs::exists(off.dir / file)) << file << " written with --gi off";
    for (const char* pass : kVoxelPasses) EXPECT_EQ(runs(off, pass), -1) << pass;
    const ImageRgba32f image = readExr(off.dir / "final.exr");
    EXPECT_EQ(test::countNonFinite(image.pixels), 0u);
}

TEST(GiOff, ViewsThatNeedGiAreOneLineUsageErrors) {
    const fs::path dir = test::freshOutputDir("static_scene/gi-off-views");
    for (const char* view : {"diffuse", "specular", "weights", "resample", "voxels"}) {
        const test::RunResult run = test::runVct({"render", "--gi", "off", "--size", "64x36", "--frames", "1",
                                                  "--view", view, "--out", dir.string()});
        ASSERT_TRUE(run.exited()) << run.describe();
        EXPECT_EQ(run.exitCode, 2) << view << "\n" << run.describe();
        EXPECT_NE(run.err.find("--gi"), std::string::npos) << run.err;
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
        EXPECT_FALSE(fs::exists(dir / "final.png")) << view << ": failed only after rendering";
    }
}

}  // namespace
}  // namespace vct
