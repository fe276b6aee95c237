// Model only what the scene needs: when nothing moved and no light changed, frames after the first skip the
// voxel grid's passes (voxelize, inject, mips) and the image stays the one that rebuilding the grid every
// frame gives; a camera cut and a moving object still rebuild it. And with GI off the frame allocates none
// of the indirect-light targets: the views and --aux files that need them say so or are left out.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/image_io.h"
#include "scene/gltf_writer.h"
#include "scene_util.h"
#include "test_util.h"

namespace vct {
namespace {

namespace fs = std::filesystem;

constexpr uint32_t kFrames = 6, kWarmup = 1;  // 5 timed frames, all after the first

struct Render {
    fs::path dir;
    std::map<std::string, nlohmann::json> passes;  // timings.json's passes by name
    nlohmann::json shadowMap;     // timings.json's shadow_map: texels, redrawn in the last frame
    bool directPartial = false;   // timings.json's direct.partial_last_frame
    nlohmann::json gbuffer;       // timings.json's gbuffer: pixels, redrawn in the last frame
    double directDispatched = 0;  // timings.json's direct.dispatched_pixels_last_frame
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
    r.shadowMap = timings.at("shadow_map");
    r.directPartial = timings.at("direct").at("partial_last_frame").get<bool>();
    r.gbuffer = timings.at("gbuffer");
    r.directDispatched = timings.at("direct").at("dispatched_pixels_last_frame").get<double>();
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

// A cube flying 2.5 m above a 10 m floor under a sun 45° off vertical: its shadow falls 2.5 m beside it, far
// outside the voxels it occupies, so only the shadow sweep (render/voxel_update.cpp) updates the floor voxels
// whose light its move changes. Written as a .glb for `vct render`.
std::string flyingCubeFile() {
    using namespace test::scenes;
    Scene scene = emptyScene("floor", diffuseMaterial(0.8f, 0.0f));
    addQuad(scene, glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 5.0f), glm::vec3(5.0f, 0.0f, 0.0f), 0);  // faces +y
    scene.meshes.push_back({"cube", {}});
    std::swap(scene.meshes[0], scene.meshes[1]);  // addQuad appends to mesh 0: the cube's, for now
    addClosedBox(scene, glm::vec3(-0.3f), glm::vec3(0.3f), 0);
    std::swap(scene.meshes[0], scene.meshes[1]);
    // addClosedBox faces inwards; the cube is seen from outside: flip each quad's winding.
    for (uint32_t p : scene.meshes[1].primitives) {
        const Primitive& primitive = scene.primitives[p];
        std::swap(scene.indices[primitive.firstIndex + 1], scene.indices[primitive.firstIndex + 2]);
        std::swap(scene.indices[primitive.firstIndex + 4], scene.indices[primitive.firstIndex + 5]);
        for (uint32_t v = 0; v < 4; ++v) scene.vertices[size_t(primitive.vertexOffset) + v].normal *= -1.0f;
    }
    Node cube;
    cube.name = "flying cube";
    cube.mesh = 1;
    scene.nodes.push_back(cube);
    scene.roots.push_back(int(scene.nodes.size() - 1));
    AnimationChannel fly{
        int(scene.nodes.size() - 1), AnimationPath::Translation, Interpolation::Linear, {}, {}};
    fly.times = {0.0f, 1.0f};
    fly.values = {{-2.0f, 2.5f, 0.0f, 0.0f}, {2.0f, 2.5f, 0.0f, 0.0f}};
    scene.animations.push_back(Animation{"fly", {fly}, 1.0f});
    Node& sun = addLight(scene, "sun", LightType::Directional, 3.0f);
    sun.rotation =
        glm::angleAxis(glm::radians(-45.0f), glm::vec3(1, 0, 0));  // -Z turned 45° down, towards -z
    scene.cameras.push_back(Camera{"above", 1.0f, 0.05f, 50.0f, 0.0f});
    Node camera;
    camera.name = "above";
    camera.camera = int(scene.cameras.size() - 1);
    camera.translation = glm::vec3(7.0f, 7.0f, 3.0f);  // from the side: the shadow is not behind the cube
    camera.rotation = glm::quatLookAtRH(glm::normalize(glm::vec3(0.0f, 0.0f, -1.0f) - camera.translation),
                                        glm::vec3(0, 1, 0));
    scene.nodes.push_back(camera);
    scene.roots.push_back(int(scene.nodes.size() - 1));
    const fs::path path = test::freshOutputDir("static_scene/flying_cube_scene") / "flying_cube.glb";
    writeGlb(scene, path);
    return path.string();
}

// Pay only for what moved: a moving object's frames resolve, inject and filter only the voxels it touched
// before and after its move and those its shadow may have changed (render/voxel_update.h), and every buffer is
// bit for bit what updating the whole grid every frame gives. Long enough for the object to cross many voxels:
// cornell's cube 0.8 m (11 voxels of 64³) in 48 frames, the hall's 4.8 m (8 voxels of 32³ at 1.27 m), the
// flying cube 3.1 m (20 voxels of 64³) with its shadow 2.5 m away (only the shadow sweep keeps that one right:
// without it 3927 values of final.exr differ). With the default's every bounce (round 10): the slab gathers run
// alike in both, so this holds with them too.
TEST(StaticScene, MovingObjectsUpdateOnlyTheirVoxelsWithTheSameImages) {
    const std::string flying = flyingCubeFile();
    for (const auto& [scene, voxels] : {std::pair{std::string("cornell"), "64"},
                                        std::pair{std::string("hall"), "32"}, std::pair{flying, "64"}}) {
        const std::vector<std::string> common = {"--frames", "48", "--voxels", voxels, "--aux"};
        std::vector<std::string> full = common;
        full.push_back("--recompute-every-frame");
        const std::string name = fs::path(scene).stem().string();
        const Render region = render(name + "-region", scene, common);
        const Render whole = render(name + "-whole", scene, full);
        for (const char* buffer : {"final", "direct", "diffuse_indirect", "specular_indirect", "normal",
                                   "roughness", "albedo", "depth"}) {
            const std::string file = std::string(buffer) + ".exr";
            const ImageRgba32f a = readExr(region.dir / file), b = readExr(whole.dir / file);
            ASSERT_EQ(a.pixels.size(), b.pixels.size()) << scene << " " << file;
            size_t differing = 0;
            for (size_t i = 0; i < a.pixels.size(); ++i) differing += a.pixels[i] != b.pixels[i] ? 1 : 0;
            EXPECT_EQ(differing, 0u) << scene << " " << file
                                     << ": values differing from updating every voxel";
        }
        for (const char* pass : kVoxelPasses) EXPECT_GT(runs(region, pass), 0) << scene << " " << pass;
        // The shadow map too was redrawn only where the object was and is, with the same images: measured
        // 15 748 of 4 194 304 texels (0.38 %) for cornell's cube, 18 980 (0.45 %) for the hall's object and
        // 12 054 (0.29 %) for the flying cube; the whole map every frame with --recompute-every-frame.
        const double texels = whole.shadowMap.at("texels").get<double>();
        EXPECT_EQ(whole.shadowMap.at("redrawn_texels_last_frame").get<double>(), texels) << scene;
        const double redrawn = region.shadowMap.at("redrawn_texels_last_frame").get<double>();
        std::printf("%s: %.0f of %.0f shadow-map texels redrawn in the last frame\n", name.c_str(), redrawn,
                    texels);
        EXPECT_GT(redrawn, 0.0) << scene;
        EXPECT_LE(redrawn, 0.01 * texels) << scene;
        // And the direct light only where the object projects and where its shadow lookup reads those texels.
        EXPECT_TRUE(region.directPartial) << scene;
        EXPECT_FALSE(whole.directPartial) << scene;
        // Dispatched: the pixels where the cube projects and where the light's column over the redrawn texels
        // does (cornell: 3 344 of 14 400, 23 %); the hall's sun slants that column over more than half the image,
        // which is then dispatched whole, as every pixel is with --recompute-every-frame.
        const double pixels = whole.gbuffer.at("pixels").get<double>();
        EXPECT_EQ(whole.directDispatched, pixels) << scene;
        if (scene == "cornell") {
            EXPECT_GT(region.directDispatched, 0.0);
            EXPECT_LE(region.directDispatched, 0.25 * pixels);
        }
        // And the G-buffer only in the rectangle where the object was and is (over the two frames its targets'
        // drawings are apart: depth and normal swap with their history copies), its edges on 2×2 quads: measured
        // 400, 352 and 196 of 14 400 pixels (2.8 %, 2.4 %, 1.4 %). With edges on odd pixels the hall's roughness
        // (and so final.exr) differed in 3 values.
        EXPECT_EQ(whole.gbuffer.at("redrawn_pixels_last_frame").get<double>(), pixels) << scene;
        const double gbufferRedrawn = region.gbuffer.at("redrawn_pixels_last_frame").get<double>();
        std::printf("%s: %.0f of %.0f G-buffer pixels redrawn in the last frame\n", name.c_str(),
                    gbufferRedrawn, pixels);
        EXPECT_GT(gbufferRedrawn, 0.0) << scene;
        EXPECT_LE(gbufferRedrawn, 0.04 * pixels) << scene;
    }
}

// The same on the shared animated models (skipped without ../shared): a skinned mesh and node animation, whose
// moved bounds cover a large part of the shadow map (measured at frame 29: RiggedSimple 1 841 234 texels, 44 %;
// BoxAnimated 1 254 682, 30 %), and the same images as updating everything every frame.
TEST(StaticScene, AnimatedGltfModelsUpdateOnlyWhatMovedWithTheSameImages) {
    for (const char* model : {"RiggedSimple", "BoxAnimated"}) {
        VCT_REQUIRE_SHARED(model);
        const std::vector<std::string> common = {"--frames", "30", "--aux"};
        std::vector<std::string> full = common;
        full.push_back("--recompute-every-frame");
        const std::string scene = test::sharedModel(model).string();
        const Render region = render(std::string(model) + "-region", scene, common);
        const Render whole = render(std::string(model) + "-whole", scene, full);
        for (const char* buffer : {"final", "direct", "diffuse_indirect", "normal", "roughness", "depth"}) {
            const std::string file = std::string(buffer) + ".exr";
            const ImageRgba32f a = readExr(region.dir / file), b = readExr(whole.dir / file);
            ASSERT_EQ(a.pixels.size(), b.pixels.size()) << model << " " << file;
            size_t differing = 0;
            for (size_t i = 0; i < a.pixels.size(); ++i) differing += a.pixels[i] != b.pixels[i] ? 1 : 0;
            EXPECT_EQ(differing, 0u) << model << " " << file;
        }
        const double texels = whole.shadowMap.at("texels").get<double>();
        const double redrawn = region.shadowMap.at("redrawn_texels_last_frame").get<double>();
        EXPECT_GT(redrawn, 0.0) << model;
        EXPECT_LE(redrawn, 0.5 * texels) << model;
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
