// The voxel GI against exact answers and the path-traced truth (issue 18, docs/design.md §5): an emissive
// furnace gathers its radiance at every voxel resolution; with albedo ρ the bounces follow the geometric
// series towards L_e/(1 − ρ) and never run away; cornell's indirect light per surface against the one-bounce
// and all-bounce references; light leaking through a one-voxel wall into a dark room.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "io/image_io.h"
#include "passes/voxel_bounce_pass.h"
#include "render/shader_math.h"
#include "report/image_metrics.h"
#include "scene/gltf_writer.h"
#include "scene_util.h"
#include "test_util.h"

namespace {

namespace fs = std::filesystem;
using namespace vct::test::scenes;

// Mean of an RGB buffer's luminance over the pixels where `mask` holds (all when null).
double meanLuminance(const vct::ImageRgba32f& image, const std::vector<bool>* mask = nullptr) {
    double sum = 0.0;
    size_t count = 0;
    for (size_t i = 0; i < size_t(image.width) * image.height; ++i) {
        if (mask && !(*mask)[i]) continue;
        const float* p = &image.pixels[i * 4];
        sum += vct::test::luminance(p[0], p[1], p[2]);
        ++count;
    }
    return count ? sum / double(count) : 0.0;
}

// Renders `scene` (a file) with vct, every pixel traced, `frames` frames of a still camera (the last at
// t = (frames − 1)/60 s); returns the output directory.
fs::path renderVct(const std::string& name, const std::string& scene, std::vector<std::string> extra,
                   int frames = 1) {
    const fs::path dir = vct::test::freshOutputDir("gi_truth/" + name);
    // One bounce unless the test asks for more (a later --bounces wins): the one-bounce references measure the
    // cone tracer itself, not the default's amortised gathers (docs/design.md §5.7).
    std::vector<std::string> args = {
        "render",        "--scene", scene,   "--size", "96x54",      "--frames",  std::to_string(frames),
        "--trace-scale", "1",       "--aux", "--out",  dir.string(), "--bounces", "1"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = vct::test::runVct(args);
    EXPECT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    const vct::ImageRgba32f final = vct::readExr(dir / "final.exr");
    EXPECT_EQ(vct::test::countNonFinite(final.pixels), 0u) << name;
    return dir;
}

// Writes `scene` with a camera at `position` turned by `rotation` (vertical field of view `yfov` radians) as a
// .glb in a directory of its own (ctest runs the tests in parallel, and a shared directory would be emptied
// under another test).
std::string sceneFile(const std::string& name, vct::Scene scene, glm::vec3 position, glm::quat rotation,
                      float yfov) {
    scene.cameras.push_back(vct::Camera{"inside", yfov, 0.01f, 10.0f, 0.0f});
    vct::Node camera;
    camera.name = "inside";
    camera.camera = 0;
    camera.translation = position;
    camera.rotation = rotation;
    scene.nodes.push_back(camera);
    scene.roots.push_back(int(scene.nodes.size() - 1));
    const fs::path path = vct::test::freshOutputDir("gi_truth/scene_" + name) / (name + ".glb");
    vct::writeGlb(scene, path);
    return path.string();
}

// The same, turned by `yaw` about y, with a 1.2 rad field of view.
std::string sceneFile(const std::string& name, vct::Scene scene, glm::vec3 position, float yaw) {
    return sceneFile(name, std::move(scene), position, glm::angleAxis(yaw, glm::vec3(0, 1, 0)), 1.2f);
}

// A closed emissive room (albedo ρ, emission L_e = 1) with a camera inside.
std::string furnaceFile(const std::string& name, float albedo) {
    return sceneFile(name, furnaceRoom(albedo, 1.0f), glm::vec3(0.2f, -0.1f, 0.6f), 0.4f);
}

TEST(VoxelGi, EmissiveFurnaceGathersItsRadianceAtEveryResolution) {
    // Walls of radiance 1, black: every pixel's demodulated diffuse indirect light (the cosine-weighted mean
    // radiance arriving) is exactly 1. Measured 0.990 at 32³ and 0.992 at 64³ since the samples are lifted clear of
    // the walls' coarser mips and read within the grid (lib/cone.glsl's coneSampleAt; 0.978 and 0.954 before); 0.970
    // and 0.957 with 0.5·d steps instead of 0.75·d before that: the step length changed it by < 1 % (0.786 and 0.776
    // before cones took samples past the grid's edge and renormalised at early termination: cone_trace.glsl).
    // Round 14, the coarser mip's whole reach cleared at any blend weight (docs/design.md §5.3): 0.996 and 0.999.
    const std::string file = furnaceFile("furnace_black", 0.0f);
    for (const char* voxels : {"32", "64"}) {
        const fs::path dir = renderVct(std::string("furnace_black_") + voxels, file, {"--voxels", voxels});
        const double diffuse = meanLuminance(vct::readExr(dir / "diffuse_indirect.exr"));
        std::printf("emissive furnace at %s^3: diffuse indirect %.4f (exact 1)\n", voxels, diffuse);
        EXPECT_NEAR(diffuse, 1.0, 0.02) << voxels;
    }
}

// The walls' reflectance for the light bounced in the grid (lib/voxel_specular.glsl's bouncedLightReflectance):
// with Lambertian voxels (--voxel-glossy off) the diffuse albedo ρ = 0.5, with glossy voxels ρ plus the specular
// layer's share at n·l = 2/3 (the furnace's roughness is 1), from the split-sum integral the DFG table holds.
double furnaceReflectance(bool glossy) {
    const glm::vec2 dfg =
        vct::glsl::integrateDFG(vct::glsl::BOUNCE_MEAN_COSINE, vct::glsl::alphaFromPerceptual(1.0f), 1024);
    return vct::glsl::bouncedLightReflectance(glm::vec3(0.5f), 0.0f, dfg, glossy).g;
}

TEST(VoxelGi, FurnaceBouncesFollowTheGeometricSeriesAndNeverRunAway) {
    // Albedo ρ = 0.5, emission 1, Lambertian voxels: with N bounces the walls send L_e·(1 + ρ + … + ρ^(N−1)), so
    // the gathered light is 1, 1.5, 1.75, …, 1.9922 at N = 8, and never above L_e/(1 − ρ) = 2. Measured at 32³:
    // 0.991, 1.486, 1.974 (1 % under, the furnace's own deficit above; 0.971, 1.450, 1.951 before the lifted
    // samples); round 14 0.997, 1.496, 1.991; round 17 0.993, 1.491, 1.983. Glossy voxels (the default) reflect
    // the specular layer's share of the bounced light too (ρ = 0.5083 at roughness 1): the same series with that
    // ρ, measured 0.993, 1.499, 2.015 against 1, 1.508, 2.025. Never above the limit L_e/(1 − ρ), taken from the
    // first bounce (which carries the furnace's own deficit).
    const std::string file = furnaceFile("furnace_grey", 0.5f);
    for (const bool glossy : {false, true}) {
        const double rho = furnaceReflectance(glossy);
        double one = 0.0;
        for (int bounces : {1, 2, 8}) {
            const fs::path dir =
                renderVct("furnace_grey_b" + std::to_string(bounces) + (glossy ? "_glossy" : ""), file,
                          {"--voxels", "32", "--bounces", std::to_string(bounces), "--voxel-glossy",
                           glossy ? "on" : "off"});
            const double diffuse = meanLuminance(vct::readExr(dir / "diffuse_indirect.exr"));
            const double exact = (1.0 - std::pow(rho, bounces)) / (1.0 - rho);
            if (bounces == 1) one = diffuse;
            std::printf(
                "furnace rho %.4f (glossy voxels %s), %d bounces: diffuse indirect %.4f (exact %.4f)\n", rho,
                glossy ? "on" : "off", bounces, diffuse, exact);
            EXPECT_NEAR(diffuse, exact, 0.02 * exact) << bounces << (glossy ? " glossy" : "");
            EXPECT_LT(diffuse, one / (1.0 - rho)) << "runs away";
        }
    }
}

// `--bounces all` (passes/voxel_bounce_pass.h): the first frame starts from four bounces (the whole grid
// gathers three times, as `--bounces 4` does: the same images bit for bit), then one slab of the grid gathers per
// frame, from the grid as the slabs before left it, and every inject adds what was gathered. The same furnace
// (ρ = 0.5, L_e = 1) converges to L_e/(1 − ρ) = 2 over the frames and stays there; with nothing moving the gathers
// stop after their settle frames (8 slabs × 18 rounds at 32³), so a static scene then does no voxel work.
// Measured at 32³: 1.858 after the first frame (four bounces: exact 1.875, less the furnace's 1 %), 1.934 after
// one round of the 8 slabs more, 1.981 after 9 rounds (73 frames) and 1.981 after 25 (201 frames, 144 of them with
// a gather): --bounces 8's 1.974, the furnace's 1 % deficit, never above 2. (Before the first frame's whole-grid
// gathers and the lifted samples, round 10: 1.580 after one round of 8 frames, 1.959 after 9.) Round 14 (the coarser
// mip's whole reach cleared at any blend weight): 1.874 after the first frame (exact 1.875), 1.950 after one round,
// 1.994 converged and settled; round 17 (the gathers read blended mips, docs/design.md §5.7): 1.876, 1.952, 1.996.
// The fixed cone set: turned cones keep a pixel history (design §5.5), which
// lags the grid's light while it grows (1.929 after one round, 1.985 converged) and is not what this measures.
// Lambertian voxels (--voxel-glossy off): their reflectance is the albedo ρ = 0.5 itself (furnaceReflectance).
TEST(VoxelGi, AllBouncesConvergeOverFramesToTheFurnaceLimitAndThenStop) {
    const std::string file = furnaceFile("furnace_grey_all", 0.5f);
    auto render = [&](const std::string& bounces, int frames) {
        const fs::path dir = renderVct("furnace_grey_" + bounces + "_" + std::to_string(frames), file,
                                       {"--voxels", "32", "--bounces", bounces, "--warmup", "0",
                                        "--cone-rotation", "off", "--voxel-glossy", "off"},
                                       frames);
        const double diffuse = meanLuminance(vct::readExr(dir / "diffuse_indirect.exr"));
        std::printf("furnace rho 0.5, %s bounces, %d frames: diffuse indirect %.4f (limit 2)\n",
                    bounces.c_str(), frames, diffuse);
        int gathers = -1;
        const nlohmann::json timings = nlohmann::json::parse(std::ifstream(dir / "timings.json"));
        for (const auto& pass : timings["passes"])
            if (pass["name"] == "bounce") gathers = pass["runs"].get<int>();
        return std::tuple{diffuse, gathers, dir};
    };
    const auto [first, firstGathers, firstDir] = render("all", 1);
    const auto [four, fourGathers, fourDir] = render("4", 1);
    const auto [oneRound, oneRoundGathers, oneRoundDir] = render("all", 9);
    const auto [converged, convergedGathers, convergedDir] = render("all", 73);
    const auto [settled, settledGathers, settledDir] = render("all", 201);
    // The first frame is `--bounces 4`'s, exactly.
    for (const char* image : {"final.exr", "diffuse_indirect.exr", "specular_indirect.exr"})
        EXPECT_TRUE(vct::test::readTextFile(firstDir / image) == vct::test::readTextFile(fourDir / image))
            << image << " differs from --bounces 4's";
    EXPECT_EQ(first, four);
    EXPECT_EQ(firstGathers, 1);
    EXPECT_NEAR(first, 1.874, 0.01);
    EXPECT_GT(first, 1.75) << "fewer than four bounces";
    // Exact: 1.875, five bounces 1.9375. The furnace's own error is ±1 % (round 17's blended gathers: 1.876).
    EXPECT_LT(first, 1.875 + 0.01) << "more than four bounces";
    EXPECT_EQ(oneRoundGathers, 9);
    EXPECT_NEAR(oneRound, 1.950, 0.01);
    EXPECT_GT(oneRound, first + 0.02) << "a round adds no bounce";
    EXPECT_NEAR(converged, 2.0, 0.06 * 2.0);
    EXPECT_GT(converged, oneRound + 0.03) << "the rounds after the first add no bounce";  // measured + 0.047
    EXPECT_LE(settled, 2.0) << "runs away";
    EXPECT_NEAR(settled, converged, 0.01 * converged) << "still changing after the gathers settled";
    // Gathers in the frames after the first (which is a change): the settle frames, then none.
    EXPECT_EQ(convergedGathers, 73);
    EXPECT_EQ(settledGathers, 8 * 18);
}

// `--bounces all`'s slabs (passes/voxel_bounce_pass.h): one round visits every voxel of the grid exactly once, in
// whole bricks, layer after layer along z. On a CPU device no slab holds more brick places than a 64³ layer (16 ×
// 16), so a frame's gather costs about the same at every resolution: rounds of 8, 16, 128 and 1024 slabs at 32³ to
// 256³. On a GPU a slab is a whole layer: N/4 slabs.
TEST(VoxelBounce, SlabsTileTheGridOnceARound) {
    struct Case {
        uint32_t n;
        bool cpu;
        uint32_t slabs, brickPlaces;  // per slab
    };
    for (const Case& c : {Case{32, true, 8, 64}, Case{64, true, 16, 256}, Case{128, true, 128, 256},
                          Case{256, true, 1024, 256}, Case{64, false, 16, 256}, Case{128, false, 32, 1024},
                          Case{256, false, 64, 4096}}) {
        const uint32_t n = c.n, bands = vct::VoxelBouncePass::bandsPerLayer(n, c.cpu);
        ASSERT_EQ(vct::VoxelBouncePass::slabCount(n, bands), c.slabs) << n;
        std::vector<uint8_t> visits(size_t(n) * n * n, 0);
        uint32_t lastZ = 0;
        for (uint32_t i = 0; i < c.slabs; ++i) {
            const vct::VoxelRegion r = vct::VoxelBouncePass::slab(n, bands, i);
            for (int axis = 0; axis < 3; ++axis) {
                EXPECT_EQ(r.min[axis] % VCT_VOXEL_BRICK, 0u) << n << " slab " << i;
                EXPECT_EQ(r.max[axis] % VCT_VOXEL_BRICK, 0u) << n << " slab " << i;
                EXPECT_LE(r.max[axis], n);
            }
            const glm::uvec3 bricks = (r.max - r.min) / uint32_t(VCT_VOXEL_BRICK);
            EXPECT_EQ(bricks.x * bricks.y * bricks.z, c.brickPlaces) << n << " slab " << i;
            EXPECT_GE(r.min.z, lastZ) << "slabs go along z: " << n << " slab " << i;
            lastZ = r.min.z;
            for (uint32_t z = r.min.z; z < r.max.z; ++z)
                for (uint32_t y = r.min.y; y < r.max.y; ++y)
                    for (uint32_t x = r.min.x; x < r.max.x; ++x) ++visits[(size_t(z) * n + y) * n + x];
        }
        EXPECT_EQ(std::count(visits.begin(), visits.end(), uint8_t(1)), std::ptrdiff_t(visits.size())) << n;
    }
}

// The closed black cube [−1, 1]³ with some faces emitting radiance 1, seen from its centre with a narrow view
// (0.6 rad) that holds only the face `floor` (y = −1) or the back wall (z = −1). `othersEmit`: that face is black
// and every other face emits, so it gathers exactly 1 (its whole hemisphere is emissive wall); else only that
// face emits, and it gathers exactly 0 (a plane cannot light itself).
std::string boxFaceFile(const std::string& name, bool floor, bool othersEmit) {
    vct::Scene scene = emptyScene(name, diffuseMaterial(0.0f, 0.0f));
    scene.materials.push_back(diffuseMaterial(0.0f, 1.0f));
    addClosedBox(scene, glm::vec3(-1.0f), glm::vec3(1.0f), 0);
    for (vct::Primitive& primitive : scene.primitives) {
        const bool isFace = floor ? primitive.bounds.max.y < -0.99f : primitive.bounds.max.z < -0.99f;
        primitive.material = isFace != othersEmit ? 1 : 0;
    }
    // Off-centre by a few cm, so that the face is not seen symmetric about a voxel boundary.
    return floor ? sceneFile(name, scene, {0.05f, 0.0f, 0.03f},
                             glm::angleAxis(-1.5707963f, glm::vec3(1, 0, 0)), 0.6f)
                 : sceneFile(name, scene, {0.05f, 0.03f, 0.5f}, glm::quat(1, 0, 0, 0), 0.6f);
}

TEST(VoxelGi, HowMuchASurfaceShadowsAndLightsItselfInAClosedBox) {
    // docs/design.md §5.6: how much of its own voxel layer a cone leaving a surface sees. A black face under
    // five emissive ones should gather 1; an emissive face under five black ones, 0. Measured (96x54, one frame,
    // every pixel traced), floor / back wall:
    //   fixed set     gathers 1:  32³ 1.000 / 1.000, 64³ 1.000 / 1.000, 128³ 1.000 / 1.000
    //                 gathers 0:  32³ 0.0008 / 0.0009, 64³ 0.0007 / 0.0009, 128³ 0.0006 / 0.0010
    //   jittered set  gathers 1:  32³ 0.999 / 0.999, 64³ 1.000 / 1.000, 128³ 1.000 / 1.000
    //                 gathers 0:  32³ 0.0005 / 0.0006, 64³ 0.0001 / 0.0002, 128³ 0.0000 / 0.0003
    // Before round 11 the fixed set gathered 0.970 / 0.973, 0.934 / 0.938, 0.843 / 0.872 and lit itself with 0.010 /
    // 0.009, 0.014 / 0.014, 0.039 / 0.028: the face's own voxels, read through the coarser level of the blend between
    // mips, whose voxels are twice the footprint the surface clearance allows; it grew as voxels got finer. Samples
    // lifted until that level's reach clears the surface, and past the grid read at a mip that keeps it out
    // (lib/cone.glsl's coneCoarseMipLift, coneSampleAt), keep the face out at every resolution: round 11 counted that
    // reach only in proportion below a quarter of the level's weight, and gathered 0.981 and lit itself with 0.010 at
    // every resolution; round 14 clears it at any weight. The jittered set's narrower footprints
    // (CONE_SURFACE_CLEARANCE_JITTERED) and farther start (CONE_START_OFFSET_JITTERED) keep its voxels out as well.
    // The bounds: gathered within 0.02 of the measured, self-lighting ≤ 0.005 (round 11's 0.010 fails).
    struct Expected {
        const char* voxels;
        double gathered, selfLit;
    };
    const Expected fixedSet[] = {{"32", 0.98, 0.005}, {"64", 0.98, 0.005}, {"128", 0.98, 0.005}};
    const Expected jitteredSet[] = {{"32", 0.98, 0.005}, {"64", 0.98, 0.005}, {"128", 0.98, 0.005}};
    for (bool floor : {true, false})
        for (bool othersEmit : {true, false}) {
            const std::string name =
                std::string(floor ? "box_floor" : "box_wall") + (othersEmit ? "_lit" : "_self");
            const std::string file = boxFaceFile(name, floor, othersEmit);
            for (bool jittered : {false, true})
                for (const Expected& e : jittered ? jitteredSet : fixedSet) {
                    const std::string run = name + (jittered ? "_jittered_" : "_fixed_") + e.voxels;
                    const fs::path dir = renderVct(
                        run, file, {"--voxels", e.voxels, "--cone-jitter", jittered ? "on" : "off"});
                    const double diffuse = meanLuminance(vct::readExr(dir / "diffuse_indirect.exr"));
                    std::printf("%s: diffuse indirect %.4f (exact %d)\n", run.c_str(), diffuse,
                                othersEmit ? 1 : 0);
                    if (othersEmit) {
                        EXPECT_GE(diffuse, e.gathered) << run;
                        EXPECT_LE(diffuse, 1.0 + 1e-3) << run;
                    } else {
                        EXPECT_LE(diffuse, e.selfLit) << run;
                        EXPECT_GE(diffuse, 0.0) << run;
                    }
                }
        }
}

TEST(VoxelGi, AClosedRoomLetsNoSkyIn) {
    // cornell is closed: in the truth none of its environment (a constant 0.03) reaches a surface inside. So the
    // indirect light with the sky 30× brighter, over what it is with the sky all but off, is what cones let in
    // through the room's walls, floor and ceiling. Cones close at the closure box (lib/cone_trace.glsl,
    // render/voxel_bricks.h's coneClosureBox), the room's own faces: measured 1.0053 for the whole image, the
    // 99th percentile of the pixels 1.124 (the gold sphere's near-mirror cones), with a few samples past the face
    // (rounds 18–21); 1.0000 and 1.000 with the face forced closed (round 22); 1.0005 and 1.019 ending on the
    // face's own read, which lets the sky in where the face has an opening (round 23,
    // ASkylightInAClosedRoomLetsTheSkyIn). Closing at the grid's faces alone, as until round 18 (cornell's floor
    // and ceiling lie 8 voxels inside the cubic grid): 1.0357 and 1.78.
    std::vector<double> indirect[2];
    const char* intensities[2] = {"0.001", "30"};
    for (int i = 0; i < 2; ++i) {
        const fs::path dir = renderVct(std::string("closed_room_sky_") + intensities[i], "cornell",
                                       {"--voxels", "64", "--environment-intensity", intensities[i]}, 8);
        const vct::ImageRgba32f final = vct::readExr(dir / "final.exr");
        const vct::ImageRgba32f direct = vct::readExr(dir / "direct.exr");
        for (size_t p = 0; p + 3 < final.pixels.size(); p += 4) {
            const glm::vec3 d(final.pixels[p] - direct.pixels[p], final.pixels[p + 1] - direct.pixels[p + 1],
                              final.pixels[p + 2] - direct.pixels[p + 2]);
            indirect[i].push_back(vct::test::luminance(d.x, d.y, d.z));
        }
    }
    ASSERT_EQ(indirect[0].size(), indirect[1].size());
    double sum[2] = {0.0, 0.0};
    std::vector<double> ratios;
    for (size_t p = 0; p < indirect[0].size(); ++p) {
        sum[0] += indirect[0][p];
        sum[1] += indirect[1][p];
        ratios.push_back(indirect[1][p] / std::max(indirect[0][p], 1e-4));
    }
    std::sort(ratios.begin(), ratios.end());
    const double whole = sum[1] / sum[0], percentile99 = ratios[ratios.size() * 99 / 100];
    std::printf("closed room, sky 30x over sky 0.001x: whole image %.4f, 99th percentile pixel %.3f\n", whole,
                percentile99);
    EXPECT_GT(sum[0], 0.0);
    EXPECT_LE(whole, 1.01);
    EXPECT_LE(percentile99, 1.05);
}

// vct compare --json of `image` against `reference`: the report's JSON.
nlohmann::json compareWith(const fs::path& reference, const fs::path& image) {
    const fs::path json = image / "compare.json";
    const auto r = vct::test::runVct({"compare", "--reference-dir", reference.string(), "--image-dir",
                                      image.string(), "--json", json.string()});
    EXPECT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    return nlohmann::json::parse(std::ifstream(json));
}

// `secondary`: the reference's --secondary (full: the truth; diffuse: without glossy-to-diffuse transport).
// `owner` names the test: each test renders its own references (ctest runs tests in parallel, and a directory
// two tests empty and fill at once is a race).
fs::path cornellReference(const std::string& owner, const std::string& bounces, int frame = 0,
                          const std::string& secondary = "full") {
    const fs::path dir = vct::test::freshOutputDir("gi_truth/" + owner + "_cornell_reference_" + bounces +
                                                   "_" + secondary + "_" + std::to_string(frame));
    const auto r = vct::test::runVct({"reference", "--scene", "cornell", "--size", "96x54", "--frame",
                                      std::to_string(frame), "--spp", "64", "--bounces", bounces,
                                      "--secondary", secondary, "--out", dir.string()});
    EXPECT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    return dir;
}

TEST(VoxelGi, CornellIndirectLightPerSurfaceAgainstThePathTracedTruth) {
    // One bounce, 64³, 96x54 against 64 spp (a few % noise), 8 frames (the last at t = 7/60 s, as the
    // reference), the three cone sets (docs/design.md §5.5). The fixed set (the default): measured 0.89 (red wall)
    // to 1.11 (green wall), the whole image 1.05. Turned per pixel and frame, averaged by the history: the whole
    // image 1.03. Jittered: 0.84 (floor, which then lacked a third of its glossy-bounce light: design §5.6) to 1.13
    // (red wall), 0.98; at 320x180 after 32 frames 0.85 to 1.11 (round 6).
    // Round 18's cones close at the room's floor and ceiling (design §5.6): light that leaked out through them now
    // stays in the room, the gold sphere's most. The whole image reads 1.080 (fixed), 1.081 (turned) and 1.074
    // (jittered), the excess on the surfaces that were bright before (blue cube 1.22–1.24, tall box 1.06–1.17,
    // back wall 1.12–1.15); its bound, 0.08 until then, is 0.09.
    // Round 21's lobes send their axis part where the reflection points, also behind a leaning averaged normal
    // (lib/voxel_specular.glsl): the floor gets the glossy light the sphere's flanks and the bumped back wall
    // reflect down, which the truth has (at 320x180 its glossy part went from 0.77x to 1.14x the truth's at 64³,
    // from 0.66x to 1.03x at 128³). The whole image reads 1.101 (fixed), 1.099 (turned) and 1.088 (jittered), the
    // floor 1.17 / 1.11 / 0.95 here; the bound is 0.11. Round 22's whole-mip cones count an object once
    // (lib/cone.glsl's coneCompositeNested; the jittered set's diffuse cones keep the fog composite, its specular
    // cone reads whole mips): 1.024 (fixed), 1.046 (turned) and 1.092 (jittered), every surface 0.87–1.22.
    // Round 28's voxels send part of their light out of the slabs behind an oblique normal (lib/voxel.glsl's
    // voxelFacing ramp), which the narrow footprints of the jittered set see most: 1.043 (fixed), 1.063 (turned) and
    // 1.130 (jittered), every surface 0.86–1.24 (the jittered set's blue cube 1.244, its back wall 1.214). The
    // whole-image bound is 0.11 for the fixed and turned sets, 0.14 for the jittered one.
    const fs::path reference = cornellReference("per_surface", "1", 7);
    const std::pair<const char*, const char*> sets[] = {
        {"fixed", "--cone-rotation"}, {"turned", "--cone-rotation"}, {"jittered", "--cone-jitter"}};
    for (const auto& [set, flag] : sets) {
        const nlohmann::json one = compareWith(
            reference, renderVct(std::string("cornell_b1_") + set, "cornell",
                                 {"--voxels", "64", flag, std::string(set) == "fixed" ? "off" : "on"}, 8));
        for (const auto& surface : one["surfaces"]) {
            const double ratio = surface["indirect"]["ratio"].get<double>();
            std::printf("one bounce, %s cones, %s: %.3f\n", set, surface["name"].get<std::string>().c_str(),
                        ratio);
            EXPECT_GE(ratio, 0.8) << surface["name"] << ", " << set << " cones";
            EXPECT_LE(ratio, 1.25) << surface["name"] << ", " << set << " cones";
        }
        const double whole = one["image"]["indirect"]["ratio"].get<double>();
        std::printf("one bounce, %s cones, whole image: %.3f\n", set, whole);
        EXPECT_NEAR(whole, 1.0, std::string(set) == "jittered" ? 0.14 : 0.11) << set << " cones";
    }

    // All bounces against --bounces 8: measured 0.990 of the full GI's indirect light with round 18's closure at the
    // room's floor and ceiling (the voxels' gathers leaked through them too); before it 0.943 (0.954 before round 11's cone
    // samples, which read more of the room through the grid's edge texels; 0.905 with the gathers leaving from the
    // voxels' centres; the voxels' gathers carry diffuse transport only; one bounce gives 0.36). Round 25's gathers
    // count a coverage once near a closed face (lib/cone_trace.glsl's CONE_MARCH_BLENDED_COVERAGE: the hall's
    // skylights): 0.978 → 0.962 (0.932 counting it once everywhere).
    const nlohmann::json all =
        compareWith(cornellReference("per_surface", "all"),
                    renderVct("cornell_b8", "cornell", {"--voxels", "64", "--bounces", "8"}));
    const double allWhole = all["image"]["indirect"]["ratio"].get<double>();
    std::printf("8 bounces against all bounces: %.3f\n", allWhole);
    EXPECT_GE(allWhole, 0.8);
    EXPECT_LE(allWhole, 1.15);

    // `--bounces all` (the default), its gathers amortised over 64 frames (4 rounds of the 16 slabs, one layer of
    // bricks each, at 64³, after the first frame's four bounces), against the full GI at the last frame: measured
    // 0.981 of it, every surface 0.91 (red wall) to 1.10 (blue cube) with round 18's closure; before it 0.927 of
    // it, every surface 0.86 (red wall) to 1.11 (blue cube); round 10's 0.925 (0.85 to 1.09) had neither
    // the first frame's four bounces nor round 11's cone samples; gathering from the voxels' centres 0.890, and
    // with 8 slabs (8 rounds) 0.906. At 320×180 against 256 spp: round 11's report. Round 22 (the pixels' whole-mip
    // cones count an object once; the gathers keep the fog composite): 0.966, every surface 0.91 to 1.07. Round 25
    // (the gathers count a coverage once near a closed face): 0.971 → 0.957, every surface 0.90 (floor, red wall) to
    // 1.07 (blue cube); 0.929 counting it once everywhere.
    const nlohmann::json amortised =
        compareWith(cornellReference("per_surface", "all", 63),
                    renderVct("cornell_ball", "cornell", {"--voxels", "64", "--bounces", "all"}, 64));
    for (const auto& surface : amortised["surfaces"]) {
        const double ratio = surface["indirect"]["ratio"].get<double>();
        std::printf("all bounces, %s: %.3f\n", surface["name"].get<std::string>().c_str(), ratio);
        EXPECT_GE(ratio, 0.7) << surface["name"];
        EXPECT_LE(ratio, 1.4) << surface["name"];
    }
    const double amortisedWhole = amortised["image"]["indirect"]["ratio"].get<double>();
    std::printf("all bounces (amortised) against all bounces: %.3f\n", amortisedWhole);
    EXPECT_NEAR(amortisedWhole, 1.0, 0.15);
}

TEST(VoxelGi, GlossyVoxelsCarryTheGlossyTransportAndLambertianOnesMatchTheTruthWithout) {
    // docs/design.md §5.11. Voxels of the diffuse albedo alone (--voxel-glossy off) against the reference whose
    // secondary vertices are Lambertian of that albedo: the cone tracer's own error, measured 0.86 (red wall) to
    // 1.18 (white box); the same voxels send the truth (glossy transport and all) too little light, the metal
    // sphere none. With the lobes (the default) the truth's extra light arrives: the whole image's indirect light
    // rises by the transport's share (measured 1.184x; the truth's 1.188x), the whole image 1.06 of the truth.
    // Since round 21's lobes (their axis part also behind a leaning normal, lib/voxel_specular.glsl): 1.203x, the
    // whole image 1.099 (the floor gets the glossy light the sphere's flanks reflect down); bound 0.11.
    const fs::path diffuseReference = cornellReference("glossy", "1", 7, "diffuse");
    const fs::path lambertianDir =
        renderVct("cornell_lambertian", "cornell", {"--voxels", "64", "--voxel-glossy", "off"}, 8);
    const nlohmann::json lambertian = compareWith(diffuseReference, lambertianDir);
    for (const auto& surface : lambertian["surfaces"]) {
        const double ratio = surface["indirect"]["ratio"].get<double>();
        std::printf("lambertian voxels against the diffuse-secondary truth, %s: %.3f\n",
                    surface["name"].get<std::string>().c_str(), ratio);
        EXPECT_GE(ratio, 0.8) << surface["name"];
        EXPECT_LE(ratio, 1.25) << surface["name"];
    }
    // The glossy transport's share of the truth, from the two references' indirect light: what the lobes must add.
    const fs::path truthReference = cornellReference("glossy", "1", 7);
    const nlohmann::json lambertianTruth = compareWith(truthReference, lambertianDir);
    const nlohmann::json glossy =
        compareWith(truthReference, renderVct("cornell_glossy", "cornell", {"--voxels", "64"}, 8));
    const double added = glossy["image"]["indirect"]["vct_sum"].get<double>() /
                         lambertianTruth["image"]["indirect"]["vct_sum"].get<double>();
    const double truthAdded = lambertianTruth["image"]["indirect"]["reference_sum"].get<double>() /
                              lambertian["image"]["indirect"]["reference_sum"].get<double>();
    std::printf(
        "indirect light with glossy voxels / without: %.3f (the truth with / without glossy transport: "
        "%.3f); whole image against the truth: %.3f\n",
        added, truthAdded, glossy["image"]["indirect"]["ratio"].get<double>());
    EXPECT_NEAR(added, truthAdded, 0.05);
    EXPECT_NEAR(glossy["image"]["indirect"]["ratio"].get<double>(), 1.0, 0.11);
}

// The mean diffuse indirect light vct renders of `file` at `voxels`³ with the sky all but off (one bounce, every pixel
// traced): what the leak tests compare, so that the sky leaking in at the grid's edge does not count.
double diffuseWithoutSky(const std::string& name, const std::string& file, const char* voxels) {
    const fs::path dir = renderVct(name, file, {"--voxels", voxels, "--environment-intensity", "0.001"});
    return meanLuminance(vct::readExr(dir / "diffuse_indirect.exr"));
}

TEST(VoxelGi, LightLeakingThroughAOneVoxelWallIsBounded) {
    // Two rooms sharing a wall of zero thickness (tests/scene_util.h, twoRooms): the left one lit by its
    // emissive ceiling, the right one dark, so every bit of indirect light in the right room leaked through
    // the wall. Each camera stands in its room's far half looking at the shared wall (yaw ±90°). Measured: the
    // dark room gets 0.062 (32³) and 0.065 (64³) of the lit room's diffuse indirect light, the lit room 0.21 and
    // 0.20; before the directional voxels (issue 18) 0.26 and 0.31, the lit room 0.097 and 0.072 (its own walls
    // faded in the mips). What leaks now crosses the ceiling both rooms share (docs/design.md §5.6). Round 11
    // (samples lifted clear of the surface's coarser mip, read within the grid): 0.052 and 0.050, the lit room
    // 0.20 and 0.19; round 14 (its whole reach at any blend weight) 0.050 and 0.050, the lit room 0.20 and 0.19.
    // The rooms have no light, so they get the loader's default light and its sky (issue 20), which also leaks
    // in through their outer walls at the grid's edge (64³: the dark room 0.0232 with the sky, 0.0119 with it ×
    // 0.001, leak 0.108 against 0.059): the sky is dimmed to 0.001 here so that this measures the leak between
    // the rooms, as before. Round 16 (the diffuse cones read the whole coarser mip, lib/cone.glsl's coneWholeMip):
    // 0.065 at 32³ and 0.048 at 64³, the lit room 0.20 and 0.19: at 32³ the coarser level, now read whole where
    // the blend weighed it in part, lets more through; at 64³ less. Round 21: 0.064 and 0.053, the lit room 0.23
    // and 0.22. Round 22 (the whole-mip cones count an object once, lib/cone.glsl's coneCompositeNested; docs/
    // design.md §5.3): 0.075 and 0.067, the lit room 0.23 and 0.22. The texel that leaks, holding the lit room's
    // ceiling beside the wall, now blocks the cone once where the fog composite counted the wall at several steps;
    // the bounds follow (they were 0.07 and 0.055), for the truth it gains elsewhere (+0.4 to +2.2 dB). Round 23
    // (a cone ends on the closed face it passes, read where its axis crossed it: lib/cone_trace.glsl's
    // closedFaceRead): 0.071 and 0.061, the lit room 0.23 and 0.23. Round 29 (the rooms are two closed regions
    // inside one closure box, render/voxel_regions.h, and a cone that crosses into the other ends on the wall):
    // 0.056 and 0.036, the lit room 0.23 and 0.23; what is left crosses in the coarse footprints.
    const std::pair<const char*, double> bounds[] = {{"32", 0.06}, {"64", 0.04}};
    const vct::Scene rooms = twoRooms(0.5f);
    const std::string litFile = sceneFile("rooms_lit", rooms, glm::vec3(-1.6f, 0.0f, 0.0f), -1.5708f);
    const std::string darkFile = sceneFile("rooms_dark", rooms, glm::vec3(1.6f, 0.0f, 0.0f), 1.5708f);
    for (const auto& [voxels, bound] : bounds) {
        const double lit = diffuseWithoutSky(std::string("rooms_lit_") + voxels, litFile, voxels);
        const double dark = diffuseWithoutSky(std::string("rooms_dark_") + voxels, darkFile, voxels);
        const double leak = dark / lit;
        std::printf("two rooms at %s^3: lit room %.4f, dark room %.4f: leak %.4f (exact 0)\n", voxels, lit,
                    dark, leak);
        EXPECT_GE(lit, 0.17) << "the lit room must be lit for the ratio to mean anything";
        EXPECT_LE(leak, bound) << voxels;
        EXPECT_TRUE(std::isfinite(leak));
    }
}

// The turns of the rooms below: about y (the walls stay vertical, their normals in one axis plane) and about an oblique
// axis (every wall's normal off every axis plane).
struct RoomTurn {
    const char* name;
    glm::quat rotation;
};
const RoomTurn kRoomTurns[] = {
    {"30 deg about y", glm::angleAxis(glm::radians(30.0f), glm::vec3(0, 1, 0))},
    {"45 deg about y", glm::angleAxis(glm::radians(45.0f), glm::vec3(0, 1, 0))},
    {"oblique", glm::angleAxis(glm::radians(20.0f), glm::vec3(1, 0, 0)) *
                    glm::angleAxis(glm::radians(30.0f), glm::vec3(0, 1, 0))},
};

// The emissive furnace of EmissiveFurnaceGathersItsRadianceAtEveryResolution turned: the truth does not change (every
// pixel gathers exactly 1), vct's voxels do. The room's walls are closed by the closure box only where they lie on the
// faces of an axis-aligned box (render/voxel_bricks.h's coneClosureBox); a turned wall is a staircase of voxels that a
// cone counting its coverage once (lib/cone.glsl's coneCompositeNested) passes in part: with the sky turned down to
// 0.001 and up to 1000, 6.0 % / 4.9 % of the room's cones reached it (30° / 45° about y, 64³). Since round 29 the room
// and what lies outside it are two closed regions of the static grid (render/voxel_regions.h), and a cone that
// crosses from one into the other ends on the wall (lib/cone_trace.glsl). Measured (32³ / 64³, the default sky): 30°
// about y 0.909 / 0.909, 45° 0.901 / 0.902, oblique 0.883 / 0.891; without the regions (`--voxel-regions off`, round
// 28's cones) 0.844 / 0.831, 0.851 / 0.831, 0.758 / 0.738. What is left is the slabs: a turned wall read obliquely
// through a slab behind its normal is dimmer (docs/design.md §5.2, §5.6). The bounds hold these measurements.
TEST(VoxelGi, TurnedEmissiveFurnaceGathersMostOfItsRadiance) {
    const std::pair<const char*, std::array<double, 3>> bounds[] = {{"32", {0.90, 0.89, 0.87}},
                                                                    {"64", {0.90, 0.89, 0.88}}};
    for (size_t turn = 0; turn < std::size(kRoomTurns); ++turn) {
        const glm::quat q = kRoomTurns[turn].rotation;
        vct::Scene room = furnaceRoom(0.0f, 1.0f);
        room.nodes[0].rotation = q;
        const std::string tag = "turned_furnace_" + std::to_string(turn);
        const std::string file = sceneFile(tag, room, q * glm::vec3(0.2f, -0.1f, 0.6f),
                                           q * glm::angleAxis(0.4f, glm::vec3(0, 1, 0)), 1.2f);
        for (const auto& [voxels, bound] : bounds) {
            // Validated: the region labels' volume and binding (render/voxel_grid.h) with the layer on.
            const fs::path dir = renderVct(tag + "_" + voxels, file, {"--voxels", voxels, "--validate"});
            const double diffuse = meanLuminance(vct::readExr(dir / "diffuse_indirect.exr"));
            std::printf("emissive furnace turned %s at %s^3: diffuse indirect %.4f (exact 1)\n",
                        kRoomTurns[turn].name, voxels, diffuse);
            EXPECT_GE(diffuse, bound[turn]) << kRoomTurns[turn].name << " " << voxels;
            EXPECT_LE(diffuse, 1.0 + 1e-3) << kRoomTurns[turn].name << " " << voxels;
            if (std::string(voxels) != "64") continue;
            // The regions are what closes it: off, the cones leak as before (0.831 / 0.831 / 0.738).
            const fs::path off = renderVct(tag + "_" + voxels + "_regions_off", file,
                                           {"--voxels", voxels, "--voxel-regions", "off"});
            const double leaking = meanLuminance(vct::readExr(off / "diffuse_indirect.exr"));
            std::printf("  without the regions: %.4f\n", leaking);
            EXPECT_LE(leaking, diffuse - 0.06) << kRoomTurns[turn].name;
        }
    }
}

// The two rooms of LightLeakingThroughAOneVoxelWallIsBounded turned: their shared wall of no thickness (and every
// other) is a staircase of voxels. Measured (round 29, the closed regions): the dark room gets (32³ / 64³) 0.068 /
// 0.049 of the lit room's diffuse light turned 30° about y, 0.069 / 0.041 turned 45°, 0.063 / 0.051 turned about the
// oblique axis; without the regions (round 28) 0.076 / 0.068, 0.076 / 0.057, 0.069 / 0.069. The lit room itself gathers
// 0.15–0.19 (0.12–0.14 without the regions, 0.23 unturned): TurnedEmissiveFurnaceGathersMostOfItsRadiance's slabs.
TEST(VoxelGi, LightLeakingThroughATurnedWallOfNoThicknessIsBounded) {
    const std::pair<const char*, double> bounds[] = {{"32", 0.075}, {"64", 0.055}};
    for (size_t turn = 0; turn < std::size(kRoomTurns); ++turn) {
        const glm::quat q = kRoomTurns[turn].rotation;
        vct::Scene rooms = twoRooms(0.5f);
        rooms.nodes[0].rotation = q;
        const std::string tag = "turned_rooms_" + std::to_string(turn);
        const std::string litFile = sceneFile(tag + "_lit", rooms, q * glm::vec3(-1.6f, 0.0f, 0.0f),
                                              q * glm::angleAxis(-1.5708f, glm::vec3(0, 1, 0)), 1.2f);
        const std::string darkFile = sceneFile(tag + "_dark", rooms, q * glm::vec3(1.6f, 0.0f, 0.0f),
                                               q * glm::angleAxis(1.5708f, glm::vec3(0, 1, 0)), 1.2f);
        for (const auto& [voxels, bound] : bounds) {
            const double lit = diffuseWithoutSky(tag + "_lit_" + voxels, litFile, voxels);
            const double dark = diffuseWithoutSky(tag + "_dark_" + voxels, darkFile, voxels);
            std::printf("two rooms turned %s at %s^3: lit room %.4f, dark room %.4f: leak %.4f (exact 0)\n",
                        kRoomTurns[turn].name, voxels, lit, dark, dark / lit);
            EXPECT_GE(lit, 0.15) << "the lit room must be lit for the ratio to mean anything";
            EXPECT_LE(dark / lit, bound) << kRoomTurns[turn].name << " " << voxels;
        }
    }
}

// The same room turned: the built-in cornell-turned is cornell turned 30° about y with its camera and light, so the
// truth is the same image. What vct renders differently is its grid's doing. Measured (one bounce, every pixel traced,
// 64³, 96×54, 8 frames): the turned room's mean diffuse indirect light as a share of the axis-aligned one's, and the
// PSNR of its demodulated diffuse and specular indirect light against it, with the closed regions and without.
TEST(VoxelGi, CornellTurnedRendersAsCornellDoes) {
    struct Measured {
        double ratio, diffusePsnr, specularPsnr;
    };
    auto measure = [](const char* regions) {
        const fs::path aligned = renderVct(std::string("invariance_cornell_") + regions, "cornell",
                                           {"--voxels", "64", "--voxel-regions", regions}, 8);
        const fs::path turned =
            renderVct(std::string("invariance_cornell_turned_") + regions, "cornell-turned",
                      {"--voxels", "64", "--voxel-regions", regions, "--validate"}, 8);
        Measured m;
        const vct::ImageRgba32f a = vct::readExr(aligned / "diffuse_indirect.exr");
        const vct::ImageRgba32f t = vct::readExr(turned / "diffuse_indirect.exr");
        m.ratio = meanLuminance(t) / meanLuminance(a);
        m.diffusePsnr = vct::compareImages(a, t).psnr;
        m.specularPsnr = vct::compareImages(vct::readExr(aligned / "specular_indirect.exr"),
                                            vct::readExr(turned / "specular_indirect.exr"))
                             .psnr;
        std::printf(
            "cornell turned against cornell, regions %s: diffuse indirect %.4f of it, PSNR diffuse %.2f dB, "
            "specular %.2f dB\n",
            regions, m.ratio, m.diffusePsnr, m.specularPsnr);
        return m;
    };
    // Measured: with the regions 0.950, 28.93 / 24.68 dB; without 0.833, 25.39 / 22.53 dB (the turned walls leak).
    const Measured on = measure("on"), off = measure("off");
    EXPECT_GE(on.ratio, 0.94);
    EXPECT_LE(on.ratio, 1.06);
    EXPECT_GE(on.diffusePsnr, 28.5);
    EXPECT_GE(on.specularPsnr, 24.3);
    // The regions are what closes it.
    EXPECT_GE(on.ratio - off.ratio, 0.1);
    EXPECT_GE(on.diffusePsnr - off.diffusePsnr, 3.0);
}

TEST(VoxelGi, LightLeakingThroughAWallOneVoxelThickBetweenTwoRoomsIsBounded) {
    // Two closed rooms (albedo 0.5) side by side along x, the left one lit by a spot light, the right one dark,
    // sharing a wall one voxel thick: its faces lie a quarter voxel into two neighbouring voxel layers, each
    // one-sided. Every bit of indirect light in the right room leaked through the wall (exact 0). The wall's faces
    // are inner faces of the rooms, not a closed room's outer faces (lib/voxel_sheet.glsl's outerWallFaceNormal), so
    // the lit face keeps its sideways light, which the mips average with the dark face's. Measured: the dark room gets
    // 0.0188 / 0.0194 of the lit room's diffuse indirect light (32³ / 64³), the same as with round 23's shaders and
    // with every face of such a wall one-slab. The same rooms sharing a wall of no thickness (a sheet) leak 3× more:
    // 0.0599 / 0.0578, the leak of LightLeakingThroughAOneVoxelWallIsBounded (0.07 / 0.06).
    const std::pair<const char*, double> bounds[] = {{"32", 0.025}, {"64", 0.025}};
    for (const auto& [voxels, bound] : bounds) {
        const int n = std::stoi(voxels);
        const float voxel = 4.0f / float(n - 2);
        double leak[2] = {0.0, 0.0};  // through the thick wall, through the wall of no thickness
        for (const bool thick : {true, false}) {
            // The bounds' 4 m along x put x = 0 on a voxel boundary (the grid is centred): the wall [−¾v, ¼v].
            const float wallLow = thick ? -0.75f * voxel : 0.0f, wallHigh = thick ? 0.25f * voxel : 0.0f;
            vct::Scene rooms = emptyScene("two rooms, thick wall", diffuseMaterial(0.5f, 0.0f));
            addClosedBox(rooms, {-2.0f, -1.0f, -1.0f}, {wallLow, 1.0f, 1.0f}, 0);
            addClosedBox(rooms, {wallHigh, -1.0f, -1.0f}, {2.0f, 1.0f, 1.0f}, 0);
            // A spot light (shadow-mapped: a point light is not, and would light the dark room through the wall)
            // under the lit room's ceiling, turned down: its 45° cone takes in the floor and the walls' lower parts.
            vct::Node& lamp = addLight(rooms, "lamp", vct::LightType::Spot, 20.0f);
            lamp.translation = glm::vec3(-1.0f, 0.9f, 0.0f);
            lamp.rotation = glm::angleAxis(-glm::half_pi<float>(), glm::vec3(1, 0, 0));  // −Z turned to −Y
            const std::string tag = std::string(thick ? "thick" : "thin") + "_wall_rooms_" + voxels;
            const std::string litFile =
                sceneFile(tag + "_lit", rooms, glm::vec3(-1.6f, 0.0f, 0.0f), -1.5708f);
            const std::string darkFile =
                sceneFile(tag + "_dark", rooms, glm::vec3(1.6f, 0.0f, 0.0f), 1.5708f);
            const double lit = diffuseWithoutSky(tag + "_lit", litFile, voxels);
            const double dark = diffuseWithoutSky(tag + "_dark", darkFile, voxels);
            double& through = leak[thick ? 0 : 1];
            through = dark / lit;
            std::printf("two spot-lit rooms, a wall %s at %s^3: lit room %.4f, dark room %.5f: leak %.4f\n",
                        thick ? "one voxel thick" : "of no thickness", voxels, lit, dark, through);
            EXPECT_GE(lit, 0.09)
                << "the lit room must be lit for the ratio to mean anything (measured 0.103-0.113)";
            EXPECT_TRUE(std::isfinite(through));
        }
        EXPECT_LE(leak[0], bound) << voxels;
        // The thick wall's sideways light adds no leak of its own: measured 0.31 / 0.34 of the thin wall's, and since
        // round 29's closed regions (render/voxel_regions.h), which end the cones that cross the wall of no
        // thickness (its leak 0.0599 / 0.0578 → 0.0447 / 0.0311) and leave the thick wall's as it was (0.0185 /
        // 0.0168: what crosses it is the coarse footprints), 0.41 / 0.54.
        EXPECT_LE(leak[0], 0.6 * leak[1]) << voxels;
    }
}

// A sun of `illuminance` straight above `scene`.
void addSunAbove(vct::Scene& scene, float illuminance) {
    vct::Node& sun = addLight(scene, "sun", vct::LightType::Directional, illuminance);
    sun.rotation = glm::angleAxis(-glm::half_pi<float>(), glm::vec3(1, 0, 0));  // −Z turned to −Y
}

// The mean diffuse indirect light in the room of `file` under its sunlit roof (the sky all but off, one bounce), over
// the roof's radiance; printed as `what`.
double roofLeak(const std::string& name, const std::string& file, const char* voxels, double roofRadiance,
                const char* what) {
    const double leak = diffuseWithoutSky(name, file, voxels) / roofRadiance;
    std::printf("%s at %s^3: the room's indirect light %.4f of the roof's radiance (exact 0)\n", what, voxels,
                leak);
    EXPECT_TRUE(std::isfinite(leak)) << name;
    return leak;
}

TEST(VoxelGi, ARoofOfNoThicknessLitFromAboveSendsNothingIntoTheRoomBelow) {
    // A closed room (albedo 0.5) whose ceiling is also the top face of a roof of no thickness (two quads in one
    // plane, facing up and down), under a sun straight above: no light gets into the room (exact 0). The roof's
    // plane lies inside a voxel layer at 32³ and 64³ (y = 2.05), so both faces fall in one voxel, whose normals
    // cancel. Until round 22 that voxel sent its sunlit face's light to every side (voxelCosine and voxelFacing for
    // |n̄| → 0): down into the room and, through its sideways slabs, to the room's cones that read it obliquely.
    // inject.comp now reads the sheet's plane from its neighbours (sheetAxis) and sends each face's light into the
    // slab on its own side only (sheetFacing; docs/design.md §5.6). Measured: the room's mean diffuse indirect
    // light over the roof's radiance (the sun's E·ρ/π) 0.138 / 0.135 before (32³ / 64³), 0.135 / 0.123 with the
    // sheet's sideways slabs still lit, 0.0033 / 0.0034 now.
    vct::Scene room = emptyScene("roofed room", diffuseMaterial(0.5f, 0.0f));
    addClosedBox(room, {-2.0f, 0.0f, -2.0f}, {2.0f, 2.05f, 2.0f}, 0);
    addQuad(room, glm::vec3(0.0f, 2.05f, 0.0f), glm::vec3(0, 0, 2), glm::vec3(2, 0, 0), 0);  // the roof, +y
    const float sunIlluminance = 3.0f;
    addSunAbove(room, sunIlluminance);
    const std::string file = sceneFile("roofed_room", room, glm::vec3(0.0f, 1.0f, 1.5f), 0.0f);
    const double roofRadiance = sunIlluminance * 0.5 / M_PI;
    // The roof is lit as meant (else no leak would mean nothing): seen from above (a view 2.9 × 1.6 m, all roof) it
    // shows that radiance, less the Fresnel share the BRDF's diffuse lobe gives up to its specular one (measured:
    // see the bounds).
    const std::string above = sceneFile("roofed_room_above", room, glm::vec3(0.0f, 4.0f, 0.0f),
                                        glm::angleAxis(-glm::half_pi<float>(), glm::vec3(1, 0, 0)), 0.8f);
    const double roofLit = meanLuminance(vct::readExr(
                               renderVct("roofed_room_above", above, {"--voxels", "32"}) / "direct.exr")) /
                           roofRadiance;
    std::printf("the roof seen from above: %.3f of its radiance\n", roofLit);
    EXPECT_GE(roofLit, 0.95);  // measured 0.985
    EXPECT_LE(roofLit, 1.0);
    const std::pair<const char*, double> bounds[] = {{"32", 0.01}, {"64", 0.01}};
    for (const auto& [voxels, bound] : bounds)
        EXPECT_LE(roofLeak(std::string("roofed_room_") + voxels, file, voxels, roofRadiance,
                           "a roof of no thickness"),
                  bound)
            << voxels;
    // The default (every bounce) under the sky: the roof's voxels gather the sky above and the dark room below
    // (voxel_bounce.comp gathers a sheet's two sides), and sent the mean to both sides: the room got 0.103 of the
    // roof's direct radiance (64³, 16 frames). Each side's gather now goes back out on its side alone (inject.comp,
    // lib/voxel_sheet.glsl): 0.0064. The same room with the sky all but off: 0.0041.
    const fs::path dir =
        renderVct("roofed_room_sky_all_bounces", file,
                  {"--voxels", "64", "--environment-intensity", "1", "--bounces", "all"}, 16);
    const double leak = meanLuminance(vct::readExr(dir / "diffuse_indirect.exr")) / roofRadiance;
    std::printf(
        "a roof of no thickness under the sky, every bounce: the room's indirect light %.4f (exact 0)\n",
        leak);
    EXPECT_LE(leak, 0.01);
}

TEST(VoxelGi, AThickRoofLitFromAboveSendsNothingIntoTheRoomBelow) {
    // The same closed room under a roof thicker than a voxel: the room's ceiling (facing down) and the roof's top
    // (facing up) in different voxel layers, each one-sided (|n̄| ≈ 1: no sheet), as the hall's 0.3 m roof at 64³ and
    // 128³. The exact answer is again 0. Two placements: one voxel thick, both faces a quarter voxel into neighbouring
    // layers; 1.5 voxels thick, the ceiling ¾ voxel into its layer and the top ¼ voxel into the layer past the next,
    // with an empty layer between. The top layer sent its sunlit face's light sideways too, as a one-sided voxel does
    // (a floor seen obliquely from above is lit), and every mip texel and trilinear read that holds both layers
    // averages their sideways slabs, which the room's cones read from below: the room got 0.0223 / 0.0216 of the
    // roof's radiance (one voxel thick, 32³ / 64³). The outer face of a closed room's wall now sends its light into
    // the slab on its own side only (lib/voxel_sheet.glsl, outerWallFaceNormal; docs/design.md §5.6): 0.0028 /
    // 0.0013. 1.5 voxels thick: 0.0218 / 0.0206 before, 0.0281 / 0.0291 while the inner face was looked for right
    // behind the outer one only, 0.0033 / 0.0015 now.
    // A roof closed by its four sides as well (a box, as modelled roofs are): the voxels along its top edges hold the
    // top and a side, their averaged normal 45° off the axes, and the rule above (an axis) left them out; they sent
    // their sunlit light to every side, and the room got 0.0036 / 0.0017 of the roof's radiance (32³ / 64³). The
    // shell's edges, and the voxels in it whose faces disagree, now send theirs out of the room alone as well
    // (outerWallFaceNormal): 0.0009 / 0.0005. The hall's sunlit roof edges and skylight rims lit its floor that way
    // (docs/design.md §5.6).
    struct Roof {
        const char* name;
        float thickness;      // in voxels
        float ceilingOffset;  // the ceiling at y = v·(2k + offset): its place in its layer
        bool sides;           // the roof's four side faces too
        double bounds[2];     // 32³, 64³
    };
    const Roof roofs[] = {{"one voxel thick", 1.0f, 1.5f, false, {0.004, 0.002}},
                          {"1.5 voxels thick", 1.5f, 3.0f, false, {0.005, 0.0025}},
                          {"one voxel thick, a box", 1.0f, 1.5f, true, {0.0015, 0.0008}}};
    const char* grids[2] = {"32", "64"};
    for (const Roof& roof : roofs)
        for (int g = 0; g < 2; ++g) {
            // The grid fits the room's 4 m to N − 2 voxels, centred on the room's height H = ceiling + t·v: y lies
            // at grid coordinate (y − H/2)/v + N/2, so the ceiling c = v·(2k + offset) lies at k + (offset − t)/2.
            const int n = std::stoi(grids[g]);
            const float voxel = 4.0f / float(n - 2);
            const int k = int(std::lround((2.0f / voxel - roof.ceilingOffset) / 2.0f));  // c ≈ 2 m
            const float ceiling = voxel * (2.0f * float(k) + roof.ceilingOffset);
            vct::Scene room = emptyScene("thick roofed room", diffuseMaterial(0.5f, 0.0f));
            addClosedBox(room, {-2.0f, 0.0f, -2.0f}, {2.0f, ceiling, 2.0f}, 0);
            const float top = ceiling + roof.thickness * voxel;
            addQuad(room, glm::vec3(0.0f, top, 0.0f), glm::vec3(0, 0, 2), glm::vec3(2, 0, 0), 0);
            if (roof.sides) {
                // Facing out (cross(u, v)): +x, −x, +z, −z.
                const float middle = 0.5f * (ceiling + top), half = 0.5f * (top - ceiling);
                addQuad(room, {2.0f, middle, 0.0f}, {0.0f, half, 0.0f}, {0.0f, 0.0f, 2.0f}, 0);
                addQuad(room, {-2.0f, middle, 0.0f}, {0.0f, 0.0f, 2.0f}, {0.0f, half, 0.0f}, 0);
                addQuad(room, {0.0f, middle, 2.0f}, {2.0f, 0.0f, 0.0f}, {0.0f, half, 0.0f}, 0);
                addQuad(room, {0.0f, middle, -2.0f}, {0.0f, half, 0.0f}, {2.0f, 0.0f, 0.0f}, 0);
            }
            const float sunIlluminance = 3.0f;
            addSunAbove(room, sunIlluminance);
            const std::string name = std::string("thick_roofed_room_") +
                                     (roof.thickness > 1.0f ? "15_" : (roof.sides ? "box_" : "1_")) +
                                     grids[g];
            const std::string file = sceneFile(name, room, glm::vec3(0.0f, 1.0f, 1.5f), 0.0f);
            EXPECT_LE(roofLeak(name, file, grids[g], sunIlluminance * 0.5 / M_PI, roof.name), roof.bounds[g])
                << roof.name << " " << grids[g];
        }
}

// A closed room (albedo 0.5, 4 m × `height` × 4 m) whose ceiling has a square hole of half-side `hole` in its
// middle, lit only by a point light too faint to matter, with a camera looking at the floor under the hole.
std::string skylitRoomFile(const std::string& name, float height, float hole) {
    vct::Scene room = emptyScene("skylit room", diffuseMaterial(0.5f, 0.0f));
    addClosedBox(room, {-2.0f, 0.0f, -2.0f}, {2.0f, height, 2.0f}, 0, /*leftOut: the ceiling*/ 3);
    // The ceiling around the hole [−hole, hole]², facing down (cross(x, z) = −y).
    const float strip = 0.5f * (2.0f - hole), stripCentre = 0.5f * (2.0f + hole);
    addQuad(room, {0.0f, height, -stripCentre}, {2.0f, 0.0f, 0.0f}, {0.0f, 0.0f, strip}, 0);
    addQuad(room, {0.0f, height, stripCentre}, {2.0f, 0.0f, 0.0f}, {0.0f, 0.0f, strip}, 0);
    addQuad(room, {-stripCentre, height, 0.0f}, {strip, 0.0f, 0.0f}, {0.0f, 0.0f, hole}, 0);
    addQuad(room, {stripCentre, height, 0.0f}, {strip, 0.0f, 0.0f}, {0.0f, 0.0f, hole}, 0);
    vct::Node& faint = addLight(room, "faint", vct::LightType::Point, 1e-4f);
    faint.translation = glm::vec3(0.0f, 0.5f * height, 0.0f);
    // Looking down at the floor under the hole from near the front wall.
    const float pitch = -std::atan2(0.75f * height, 1.9f) - 0.1f;
    return sceneFile(name, room, glm::vec3(0.0f, 0.75f * height, 1.9f),
                     glm::angleAxis(pitch, glm::vec3(1, 0, 0)), 1.2f);
}

TEST(VoxelGi, ASkylightInAClosedRoomLetsTheSkyIn) {
    // Skylit rooms (skylitRoomFile) under a constant sky (a scene with only a point light has the constant ambient
    // 0.03, × 30 here): the sky through the hole is all the indirect light there is. The hole is 4.8 % / 1.6 % of the
    // ceiling, so the ceiling still counts as a closed face of the cones' closure box (render/voxel_bricks.h,
    // kClosedFaceCoverage), and a cone that passes that face through the hole must see the sky, not a wall that is
    // not there. The image's mean diffuse indirect light against the path tracer's (one bounce, 256 spp).
    // Until round 23 a cone past a closed face was closed whatever the face's texel held, at a place that walked
    // along the face with the cone's later samples: the low room read 0.000 / 0.000 (32³ / 64³) and the tall one
    // 0.005 / 0.004 (round 21, which counted the face's texels a few times over: 0.024 / 0.025 and 0.069 /
    // 0.061). Now a cone ends on the face's layer where its axis crossed it (lib/cone_trace.glsl's
    // closedFaceRead): the low room 0.847 / 0.941, whose 0.875 m opening 0.6 m above the floor the cones resolve.
    // Round 24 reads the face on the texel boundary just beyond it, not the nearest one: at the coarse levels, whose
    // texels span this low room from floor to ceiling, the nearest boundary lay inside the room and the read took in
    // the floor (the hall's skylights let in 0.18 of the true sky that way): the low room 0.932 / 1.003. The tall
    // room's 0.5 m opening 2 m up is narrower than the cones' footprints there, whose coarse texels cover it with
    // the ceiling around it, and the cones read it mostly closed: 0.060 / 0.143 (a cone tracer's limit; the bounds
    // keep it from falling back to nothing at 64³).
    // The second bounce (--bounces 2 less one bounce, against the same difference of the path tracer's): the sky
    // that the voxels' gathers see through the hole, sent on by the floor and walls. The gathers counted the opacity
    // of every step (the fog), and the coarse texels that hold the ceiling and the hole closed them before they
    // reached the face's read: the low room's second bounce was 1.179 / 0.738 of the truth (32³ / 64³). They count a
    // coverage once near a closed face now (lib/cone_trace.glsl's CONE_MARCH_BLENDED_COVERAGE): 1.318 / 1.212,
    // bounded to [0.85, 1.45]. The tall room's (0.140 / 0.016) is only printed: its one bounce is already the cones'
    // limit.
    struct Room {
        const char* name;
        float height, hole;
        double bounds[2][2];  // per grid (32³, 64³): the ratio's lower and upper bound
        bool secondBounce;    // whether its second bounce is bounded
    };
    const Room rooms[] = {{"low", 0.6f, 0.4375f, {{0.88, 1.1}, {0.95, 1.1}}, true},
                          {"tall", 2.0f, 0.25f, {{0.03, 1.1}, {0.1, 1.1}}, false}};
    const std::vector<std::string> sky = {"--environment-intensity", "30"};
    for (const Room& room : rooms) {
        const std::string name = std::string("skylit_room_") + room.name;
        const std::string file = skylitRoomFile(name, room.height, room.hole);
        // The path tracer's mean diffuse indirect light with `bounces` bounces.
        const auto truthOf = [&](const char* bounces) {
            const fs::path reference =
                vct::test::freshOutputDir("gi_truth/" + name + "_reference_b" + bounces);
            std::vector<std::string> args = {"reference",       "--scene", file,        "--size", "96x54",
                                             "--spp",           "256",     "--bounces", bounces,  "--out",
                                             reference.string()};
            args.insert(args.end(), sky.begin(), sky.end());
            const auto r = vct::test::runVct(args);
            EXPECT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
            return meanLuminance(vct::readExr(reference / "diffuse_indirect.exr"));
        };
        const double truth = truthOf("1");
        ASSERT_GT(truth, 0.0);
        // The second bounce: the sky the voxels' gathers see through the hole, sent on by the walls and floor.
        const double truth2 = truthOf("2") - truth;
        ASSERT_GT(truth2, 0.0);
        for (int grid = 0; grid < 2; ++grid) {
            const std::string voxels = grid == 0 ? "32" : "64";
            std::vector<std::string> extra = {"--voxels", voxels};
            extra.insert(extra.end(), sky.begin(), sky.end());
            const fs::path dir = renderVct(name + "_" + voxels, file, extra);
            const double one = meanLuminance(vct::readExr(dir / "diffuse_indirect.exr"));
            const double ratio = one / truth;
            std::printf("a skylight in the %s room at %s^3: diffuse indirect %.3f of the truth\n", room.name,
                        voxels.c_str(), ratio);
            EXPECT_GE(ratio, room.bounds[grid][0]) << room.name << " " << voxels;
            EXPECT_LE(ratio, room.bounds[grid][1]) << room.name << " " << voxels;
            extra.insert(extra.end(), {"--bounces", "2"});
            const fs::path dir2 = renderVct(name + "_b2_" + voxels, file, extra);
            const double second = (meanLuminance(vct::readExr(dir2 / "diffuse_indirect.exr")) - one) / truth2;
            std::printf("a skylight in the %s room at %s^3: the second bounce %.3f of the truth\n", room.name,
                        voxels.c_str(), second);
            EXPECT_TRUE(std::isfinite(second)) << room.name << " " << voxels;
            if (room.secondBounce) {
                EXPECT_GE(second, 0.85) << room.name << " " << voxels;
                EXPECT_LE(second, 1.45) << room.name << " " << voxels;
            }
        }
    }
}

}  // namespace
