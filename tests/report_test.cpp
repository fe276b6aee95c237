// The speed-against-error report (issue 9): convergence of the static view to the every-pixel trace, the
// report and study modes of `vct benchmark` (structure, finite errors every frame, recovery after a cut),
// camera paths.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "io/image_io.h"
#include "report/image_metrics.h"
#include "scene/camera_path.h"
#include "test_util.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kReportScenes = std::string(VCT_SCENES_DIR) + "/report_scenes.json";

fs::path render(const std::string& name, std::vector<std::string> extra) {
    const fs::path dir = vct::test::freshOutputDir("report/" + name);
    // One bounce: the upsampling converges to the every-pixel trace of a light that stands still, which the
    // default's amortised gathers (docs/design.md §5.7) are not within 64 frames.
    std::vector<std::string> args = {"render",     "--scene", "cornell",    "--size",    "160x90",
                                     "--voxels",   "32",      "--frames",   "64",        "--aux",
                                     "--validate", "--out",   dir.string(), "--bounces", "1"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = vct::test::runVct(args);
    EXPECT_TRUE(r.exited() && r.exitCode == 0) << name << ": " << r.describe();
    return dir;
}

double psnr(const fs::path& reference, const fs::path& image) {
    return vct::compareImages(vct::readExr(reference), vct::readExr(image)).psnr;
}

TEST(Report, StaticViewConvergesToTheEveryPixelTrace) {
    // Static camera, 64 frames (every jitter offset 4 times), defaults (scale 4, sg, temporal, adaptive)
    // against trace scale 1 of the same frame. Before pixel-own samples counted more than interpolated ones
    // the history converged to the B-spline blur: diffuse 37.1 dB, specular 39.5 dB at 320x180 (41.9 and 44.4
    // after); measured here (160x90, 32³): 41.5 dB and 41.2 dB with adaptive off, a little more with it. The
    // tracer that converges to the path-traced truth (directional voxels, surface-clear footprints: issue 18)
    // gives a sharper indirect signal, which the history converges to a little less closely: 39.6 dB and
    // 39.0 dB (final sRGB still above 40 dB); with rough lobes from the diffuse cones and 0.75·d steps
    // 38.96 dB and 39.37 dB (final 40.35 dB).
    // With the diffuse cones turned per pixel and frame (the default, docs/design.md §5.5) the two differ by
    // the turns' noise, which trace scale 1's history (γ = 0.8: about 9 frames) and scale 4's (an own sample
    // every 16 frames) average differently: 31.07 dB diffuse, 42.49 dB specular, 32.13 dB final. That is not
    // the upsampling's error, so both run with the fixed cone set.
    // Glossy voxels (the default, docs/design.md §5.11) make the indirect signal sharper where glossy surfaces
    // light others, and the history converges to it less closely: 38.25 dB diffuse, 40.47 dB specular, 39.34 dB
    // final (Lambertian voxels, --voxel-glossy off: 39.68, 39.43, 40.95; the tree before them: 38.96, 39.37,
    // 40.35). The upsampling is the same code in both; the margins above hold on the Lambertian signal, and the
    // default's are its own measurement less 0.25 dB. With round 11's cone samples (lifted clear of the surface's
    // coarser mip and read within the grid, docs/design.md §5.3): 37.86 / 41.38 / 39.16 dB (Lambertian 39.51 /
    // 38.52 / 40.94; before them on this machine 38.10 / 41.05 / 39.21 and 39.70 / 39.39 / 40.95). Round 14 clears the
    // coarser mip's whole reach at any blend weight (a lit surface no longer lights itself through it): the every-pixel
    // trace keeps more detail (the back wall's reflections; its specular part against the path tracer 1.17 → 0.95 at
    // 64³), which the same upsampling converges to less closely: 36.35 / 39.82 / 37.26 dB (Lambertian 39.66 / 37.68 /
    // 40.89). Round 17's specular cone reads whole mips (design §5.3): its every-pixel trace steps where ⌈m⌉ does,
    // which the upsampling converges to less closely with glossy voxels (specular 39.83 → 38.55 dB, final 39.09 →
    // 38.83) and more closely without (37.70 → 38.85, final 41.30 → 40.95); diffuse unchanged (41.99 and 39.26).
    // Round 18's cones close at a room's floor and ceiling (design §5.6), and light that leaked out through them
    // stays in the room: Lambertian 42.68 / 38.57 / 40.82 dB, glossy 40.00 / 38.26 / 38.75 dB.
    // The margins are each measurement less about 0.25 dB.
    // On the H200 (round 20) the same code measured the diffuse part lower: Lambertian 42.30 / 38.59 / 40.83 dB,
    // glossy 39.69 / 38.28 / 38.76 dB. Neither the pixel layout nor anisotropic filtering (its two per-device
    // defaults that reach this image) moves lavapipe's figures, so the 0.3–0.4 dB is the hardware's arithmetic
    // (its texture filter's fixed-point weights, say); a GPU's diffuse margins are the H200's less 0.25 dB.
    // Round 21's lobes light the floor with the glossy light its neighbours reflect down (lib/voxel_specular.glsl):
    // glossy 39.71 / 39.04 / 38.41 dB (Lambertian unchanged). On a GPU the glossy diffuse margin is an estimate, not
    // measured since: the H200's figure taken 0.31 dB below lavapipe's as in round 20 (39.40), less 0.25.
    // Round 28 (voxelHoldsTriangle, the ramped voxelFacing): Lambertian 44.19 / 38.73 / 41.15 dB, glossy 43.20 / 38.43
    // / 40.15 dB; the margins are these less 0.25 dB, the GPU's diffuse ones 0.35 dB below lavapipe's as in round 20
    // (an estimate, not measured on a GPU since).
    struct Case {
        const char* glossy;
        double diffuse, specular, display;  // lowest PSNRs allowed
        double gpuDiffuse;                  // the diffuse part's on a GPU
    };
    for (const Case& c : {Case{"off", 43.9, 38.45, 40.9, 43.55}, Case{"on", 42.95, 38.15, 39.9, 42.6}}) {
        const std::string suffix = std::string("_glossy_") + c.glossy;
        const fs::path reference = render("converge_s1" + suffix, {"--trace-scale", "1", "--cone-rotation",
                                                                   "off", "--voxel-glossy", c.glossy});
        const std::string device =
            json::parse(std::ifstream(reference / "timings.json")).value("device", std::string());
        const bool cpuDevice = device.find("llvmpipe") != std::string::npos;
        const fs::path upsampled =
            render("converge_s4" + suffix, {"--cone-rotation", "off", "--voxel-glossy", c.glossy});
        const double diffuse = psnr(reference / "diffuse_indirect.exr", upsampled / "diffuse_indirect.exr");
        const double specular =
            psnr(reference / "specular_indirect.exr", upsampled / "specular_indirect.exr");
        const double display = vct::compareToneMapped(vct::readExr(reference / "final.exr"),
                                                      vct::readExr(upsampled / "final.exr"), 1.0f)
                                   .psnr;
        std::printf(
            "static cornell, glossy voxels %s, scale 4 vs 1 after 64 frames: diffuse %.2f dB, specular "
            "%.2f dB, final sRGB %.2f dB\n",
            c.glossy, diffuse, specular, display);
        EXPECT_GE(diffuse, cpuDevice ? c.diffuse : c.gpuDiffuse) << c.glossy << " on " << device;
        EXPECT_GE(specular, c.specular) << c.glossy;
        EXPECT_GE(display, c.display) << c.glossy;
    }
}

TEST(Report, ToneMappedPsnrUsesPeakOneNotTheHdrPeak) {
    // A 1x2 image whose reference holds a light (1000) and a grey pixel; the image is off by 0.1 on the grey
    // one.
    const vct::ImageRgba32f reference{2, 1, {1000, 1000, 1000, 1, 0.5f, 0.5f, 0.5f, 1}};
    const vct::ImageRgba32f image{2, 1, {1000, 1000, 1000, 1, 0.6f, 0.6f, 0.6f, 1}};
    const vct::ImageError hdr = vct::compareImages(reference, image);
    const vct::ImageError display = vct::compareToneMapped(reference, image, 1.0f);
    // HDR peak 1000: MSE 0.005 reads 83 dB, which says nothing about what is seen.
    EXPECT_NEAR(hdr.psnr, 10.0 * std::log10(1000.0 * 1000.0 / 0.005),
                1e-4);  // 0.6f − 0.5f is not 0.1 exactly
    // Display: ACES + sRGB of 0.5 and 0.6 differ by ~0.035, half the pixels: ~32 dB with peak 1.
    EXPECT_GT(display.psnr, 28.0);
    EXPECT_LT(display.psnr, 36.0);
}

TEST(Report, ReportModeMeasuresEveryConfigurationEveryFrame) {
    // One bounce: the cut's check needs a light that stands still. With the default's gathers converging over the
    // first rounds (docs/design.md §5.7), the history lags the rising light and the frame before the cut measured
    // worse than the cut itself (26.8 against 35.0 dB).
    const fs::path dir = vct::test::freshOutputDir("report/report_mode");
    const auto r = vct::test::runVct(
        {"benchmark", "--mode",     "report",     "--report-scenes", kReportScenes, "--scenes",
         "cornell",   "--cameras",  "static,cut", "--size",          "64x36",       "--voxels",
         "32",        "--frames",   "12",         "--warmup",        "2",           "--block",
         "4",         "--validate", "--out",      dir.string(),      "--bounces",   "1"});
    ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    const json report = json::parse(std::ifstream(dir / "report.json"));
    ASSERT_EQ(report["runs"].size(), 2u);
    for (const json& run : report["runs"]) {
        // The reference, then scales 2 and 4 x three weights x adaptive off/on.
        ASSERT_EQ(run["configs"].size(), 13u) << run["camera"];
        EXPECT_EQ(run["configs"][0]["name"], "reference");
        for (size_t i = 1; i < run["configs"].size(); ++i) {
            const json& c = run["configs"][i];
            for (const char* curve :
                 {"diffuse_psnr", "specular_psnr", "final_srgb_psnr", "resampled_fraction"}) {
                ASSERT_EQ(c["curves"][curve].size(), 12u) << c["name"] << " " << curve;
                for (const json& v : c["curves"][curve])
                    EXPECT_TRUE(std::isfinite(v.get<double>())) << c["name"];
            }
            for (const char* buffer : {"diffuse", "specular", "final_hdr", "final_srgb"})
                EXPECT_EQ(c["error"][buffer]["non_finite"], 0) << c["name"];
            EXPECT_GT(c["frame_median_ms"].get<double>(), 0.0);
        }
    }
    // The cut: in frame 6 the view jumps. Without adaptive re-tracing the pixels whose history is lost are
    // interpolated from the scale-4 trace, and the frame drops below the one before it; the re-tracing fills them
    // with their own samples (the frame after the cut is then about as good as the one before: lavapipe 35.58 dB
    // before, 35.42 at the cut; the H200 35.10 and 35.16, which is why this no longer asks the cut to be worse);
    // and the history brings it back within the 5 frames after (sg + adaptive at scale 4).
    // Measured (lavapipe, final sRGB PSNR, frames 5 / 6 / 11): sg 31.98 / 29.24 / 33.72, sg + adaptive 35.58 /
    // 35.42 / 38.02. The margins are about half of each measured gap.
    const json& cut = report["runs"][1];
    EXPECT_EQ(cut["cut_frame"], 6);
    const auto curveOf = [&](const std::string& name) {
        for (const json& c : cut["configs"])
            if (c["name"] == name) return c["curves"]["final_srgb_psnr"];
        ADD_FAILURE() << "no configuration " << name;
        return json::array({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
    };
    const json sg = curveOf("s4 sg"), adaptive = curveOf("s4 sg+adaptive");
    const double before = sg[5].get<double>(), atCut = sg[6].get<double>();
    const double adaptiveBefore = adaptive[5].get<double>(), adaptiveAtCut = adaptive[6].get<double>(),
                 adaptiveAfter = adaptive[11].get<double>();
    std::printf(
        "cut: final sRGB PSNR, sg %.2f dB before, %.2f at the cut; sg + adaptive %.2f before, %.2f at the "
        "cut, %.2f five frames later\n",
        before, atCut, adaptiveBefore, adaptiveAtCut, adaptiveAfter);
    EXPECT_LE(atCut, before - 1.3);                 // measured 2.74 dB lower
    EXPECT_GE(adaptiveAtCut, atCut + 3.0);          // measured 6.18 dB higher
    EXPECT_GE(adaptiveAfter, adaptiveAtCut + 1.3);  // measured 2.60 dB higher
    EXPECT_TRUE(fs::is_regular_file(dir / "report.md"));
}

TEST(Report, DumpedLastFramesLoadBackAgainstAPathTracedReference) {
    // --dump-last: the static camera's last frame of every configuration, as vct render --aux writes it,
    // measured by vct compare --reference-dir against a tiny path-traced reference of that frame (what
    // benchmarks/report.sh does at full size). Only that the files are there and the metrics finite: no
    // accuracy numbers at 48x27 and 4 spp.
    const fs::path dir = vct::test::freshOutputDir("report/dump_last");
    const fs::path dump = dir / "last";
    std::vector<std::string> args = {"benchmark", "--mode", "report", "--report-scenes", kReportScenes};
    for (const char* flag : {"--scenes cornell", "--cameras static,cut", "--size 48x27", "--voxels 32",
                             "--frames 4", "--warmup 1", "--block 2"}) {
        const std::string text = flag;
        args.push_back(text.substr(0, text.find(' ')));
        args.push_back(text.substr(text.find(' ') + 1));
    }
    args.insert(args.end(), {"--dump-last", dump.string(), "--out", (dir / "report").string()});
    const auto r = vct::test::runVct(args);
    ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    const json manifest = json::parse(std::ifstream(dump / "manifest.json"));
    // Only the report mode has last frames to dump.
    const auto other = vct::test::runVct({"benchmark", "--mode", "scenes", "--dump-last",
                                          (dir / "x").string(), "--out", (dir / "scenes").string()});
    ASSERT_TRUE(other.exited());
    EXPECT_EQ(other.exitCode, 2) << other.describe();
    EXPECT_NE(other.err.find("--dump-last"), std::string::npos) << other.err;
    EXPECT_EQ(manifest["frame"], 3);
    EXPECT_EQ(manifest["width"], 48);
    EXPECT_EQ(manifest["height"], 27);
    ASSERT_EQ(manifest["scenes"].size(), 1u);  // the static camera only, not the cut
    const json& scene = manifest["scenes"][0];
    EXPECT_EQ(scene["name"], "cornell");
    EXPECT_EQ(scene["scene"], "cornell");
    EXPECT_TRUE(scene["camera_path"].is_null());
    ASSERT_EQ(scene["configs"].size(), 13u);
    EXPECT_EQ(scene["configs"][0]["name"], "reference");
    EXPECT_EQ(scene["configs"][0]["trace_scale"], 1);
    const json report = json::parse(std::ifstream(dir / "report" / "report.json"));
    ASSERT_EQ(report["runs"].size(), 2u);
    EXPECT_EQ(report["runs"][0]["last_frame"]["frame"], 3);
    EXPECT_FALSE(report["runs"][1].contains("last_frame")) << "the cut camera is not dumped";

    const fs::path reference = dir / "reference";
    const auto ref = vct::test::runVct({"reference", "--scene", "cornell", "--size", "48x27", "--frame", "3",
                                        "--spp", "4", "--out", reference.string()});
    ASSERT_TRUE(ref.exited() && ref.exitCode == 0) << ref.describe();
    fs::create_directories(dir / "truth");
    std::set<std::string> dirs;
    for (const json& config : scene["configs"]) {
        const std::string name = config["dir"].get<std::string>();
        EXPECT_TRUE(dirs.insert(name).second) << "two configurations share " << name;
        const fs::path images = dump / scene["dir"].get<std::string>() / name;
        for (const char* file : {"final.exr", "direct.exr", "diffuse_indirect.exr", "specular_indirect.exr"})
            ASSERT_TRUE(fs::is_regular_file(images / file)) << images / file;
        const fs::path out = dir / "truth" / (name + ".json");
        const auto c = vct::test::runVct({"compare", "--reference-dir", reference.string(), "--image-dir",
                                          images.string(), "--json", out.string()});
        ASSERT_TRUE(c.exited() && c.exitCode == 0) << name << ": " << c.describe();
        const json truth = json::parse(std::ifstream(out));
        for (const char* light : {"final", "indirect"})
            for (const char* metric : {"psnr_srgb", "rel_mse"}) {
                const json& v = truth["errors"][light][metric];
                EXPECT_TRUE(v.is_number() && std::isfinite(v.get<double>()))
                    << name << " " << light << " " << metric;
            }
        const json& ratio = truth["image"]["indirect"]["ratio"];
        EXPECT_TRUE(ratio.is_number() && std::isfinite(ratio.get<double>())) << name;
    }

    // The every-pixel trace's dump is the frame vct render --frames 4 ends on (the frame vct reference
    // --frame 3 renders).
    const fs::path rendered = dir / "render_s1";
    // The report runs the fixed cone set (app/bench/benchmark_command.cpp), so vct render does too.
    const auto s1 =
        vct::test::runVct({"render", "--scene", "cornell", "--size", "48x27", "--voxels", "32", "--frames",
                           "4", "--trace-scale", "1", "--cone-rotation", "off", "--out", rendered.string()});
    ASSERT_TRUE(s1.exited() && s1.exitCode == 0) << s1.describe();
    const vct::ImageError same = vct::compareImages(vct::readExr(rendered / "final.exr"),
                                                    vct::readExr(dump / "cornell/reference/final.exr"));
    EXPECT_TRUE(same.mse < 1e-8) << "every-pixel dump against vct render: MSE " << same.mse;
}

TEST(Report, StudyModeFindsOptimaPerMaterialClass) {
    const fs::path dir = vct::test::freshOutputDir("report/study_mode");
    const auto r = vct::test::runVct({"benchmark", "--mode", "study", "--report-scenes", kReportScenes,
                                      "--scenes", "cornell", "--size", "48x27", "--voxels", "32",
                                      "--validate", "--out", dir.string()});
    ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    const json study = json::parse(std::ifstream(dir / "study.json"));
    ASSERT_EQ(study["scenes"].size(), 1u);
    std::set<std::string> classes;
    for (const json& c : study["scenes"][0]["classes"]) {
        classes.insert(c["class"].get<std::string>());
        EXPECT_GT(c["pixels"].get<double>(), 0.0);
        ASSERT_EQ(c["sg_specular_mse"].size(), study["betas"].size());
        ASSERT_EQ(c["sg_specular_mse"][0].size(), study["kappas"].size());
        ASSERT_EQ(c["normal_specular_mse"].size(), study["sigmas"].size());
        double lowest = 1e300;
        for (const json& row : c["sg_specular_mse"])
            for (const json& v : row) {
                EXPECT_TRUE(std::isfinite(v.get<double>()));
                lowest = std::min(lowest, v.get<double>());
            }
        EXPECT_EQ(c["sg_optimum"]["mse"].get<double>(), lowest) << c["class"];
    }
    // cornell has all three: the gold sphere, the striped glossy floor, the rough walls.
    for (const char* name : {"all", "metal", "glossy dielectric", "rough dielectric"})
        EXPECT_TRUE(classes.count(name)) << name;
}

TEST(Report, CameraPathFilesLoadAndMove) {
    for (const char* name : {"cornell", "plane", "DamagedHelmet"}) {
        const vct::CameraPath path =
            vct::loadCameraPath(std::string(VCT_SCENES_DIR) + "/" + name + ".camera.json");
        ASSERT_GE(path.keys.size(), 2u) << name;
        // The report's 64 frames (1.07 s) stay on the path and the camera moves between them.
        const vct::CameraView lens;
        const glm::vec3 a = path.evaluate(0.0f, lens).position(),
                        b = path.evaluate(63.0f / 60.0f, lens).position();
        EXPECT_GT(glm::length(b - a), 0.1f) << name;
        EXPECT_LE(63.0f / 60.0f, path.duration()) << name;
    }
    // Bad files: one error naming the file.
    const fs::path dir = vct::test::freshOutputDir("report/bad_path");
    vct::test::writeTextFile(dir / "bad.json",
                             R"({"keys": [{"time": 0, "position": [0, 0, 0], "target": [0, 0, 0]}]})");
    try {
        vct::loadCameraPath(dir / "bad.json");
        ADD_FAILURE() << "accepted a key whose target equals its position";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
    }
    const auto r = vct::test::runVct({"render", "--size", "32x18", "--frames", "1", "--camera-path",
                                      (dir / "missing.json").string(), "--out", (dir / "out").string()});
    EXPECT_TRUE(r.exited() && r.exitCode == 1) << r.describe();
}

}  // namespace
