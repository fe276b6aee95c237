// The demo's controls, scripts and timers on the CPU; and `vct demo --script` under xvfb-run on lavapipe:
// the issue's acceptance run (weights, trace scale, resample view, adaptive, camera cut), the split view's
// honesty (each side bit for bit the frame of its configuration alone), camera paths (demo = render, and
// reproducible), recording, scene loading errors, shader hot reload, and every live setting under validation;
// the path-traced reference on side B (its worker thread on the CPU, and in the window).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <thread>

#include "app/demo/demo_controls.h"
#include "app/demo/demo_reference.h"
#include "app/demo/demo_script.h"
#include "app/demo/demo_timers.h"
#include "core/error.h"
#include "io/image_io.h"
#include "scene/builtin_scenes.h"
#include "scene/camera_path.h"
#include "test_util.h"

namespace vct {
namespace {

// ---- CPU: controls, scripts, timers ----

TEST(DemoControls, OptionsUseTheCommandLineNamesAndChecks) {
    DemoControls c;
    applyOption(c, "weights", "normal");
    applyOption(c, "trace-scale", "2");
    applyOption(c, "beta", "35");
    applyOption(c, "tau", "0.5");
    applyOption(c, "adaptive", "off");
    applyOption(c, "temporal", "false");
    applyOption(c, "view", "resample");
    EXPECT_EQ(c.settings.weights, RenderSettings::Weights::Normal);
    EXPECT_EQ(c.settings.traceScale, 2u);
    EXPECT_FLOAT_EQ(c.settings.beta, 35.0f);
    EXPECT_FLOAT_EQ(resampleThreshold(c.settings), 0.5f);
    EXPECT_FALSE(c.settings.adaptive);
    EXPECT_FALSE(c.settings.temporal);
    EXPECT_EQ(c.view, AuxView::Resample);
    EXPECT_EQ(settingText(c.settings, "weights"), "normal");
    EXPECT_EQ(settingText(c.settings, "trace-scale"), "2");
    EXPECT_THROW(applyOption(c, "trace-scale", "3"), UsageError);
    EXPECT_THROW(applyOption(c, "beta", "nan"), UsageError);
    EXPECT_THROW(applyOption(c, "weights", "lobe"), UsageError);
    EXPECT_THROW(applyOption(c, "no-such-option", "1"), UsageError);
    EXPECT_THROW(applyOption(c, "b-view", "final"), UsageError);  // not a render setting
    EXPECT_EQ(c.settings.traceScale, 2u);                         // a refused value changes nothing
}

TEST(DemoControls, SideBIsSideAWithItsOverrides) {
    DemoControls c;
    applyOption(c, "b-weights", "bilinear");
    applyOption(c, "b-trace-scale", "1");
    applyOption(c, "beta", "40");  // A's change reaches B where B does not override it
    const RenderSettings b = c.settingsB();
    EXPECT_EQ(b.weights, RenderSettings::Weights::Bilinear);
    EXPECT_EQ(b.traceScale, 1u);
    EXPECT_FLOAT_EQ(b.beta, 40.0f);
    EXPECT_EQ(c.settings.weights, RenderSettings::Weights::Sg);
    EXPECT_THROW(applyOption(c, "b-weights", "x"), UsageError);
    EXPECT_EQ(c.settingsB().weights, RenderSettings::Weights::Bilinear);
}

TEST(DemoControls, ActionsAreOneShotFlags) {
    DemoControls c;
    applyOption(c, "camera-cut", "on");
    applyOption(c, "screenshot-ui", "a.png");
    applyOption(c, "scene", "plane");
    EXPECT_TRUE(c.cameraCut);
    EXPECT_EQ(c.screenshot, "a.png");
    EXPECT_TRUE(c.screenshotUi);
    EXPECT_EQ(c.openScene, "plane");
    EXPECT_THROW(applyOption(c, "screenshot", ""), UsageError);
}

TEST(DemoControls, SplitSourceAndReferenceBounces) {
    DemoControls c;
    EXPECT_EQ(c.splitSource, SplitSource::Vct);
    EXPECT_EQ(c.referenceBounces, reference::kUnlimitedBounces);  // what vct's default converges to
    applyOption(c, "split", "on");
    EXPECT_TRUE(c.rendersB());
    EXPECT_FALSE(c.showsReference());
    applyOption(c, "split-source", "reference");
    EXPECT_FALSE(c.rendersB());  // no second vct renderer while B is the reference
    EXPECT_TRUE(c.showsReference());
    applyOption(c, "reference-bounces", "all");
    EXPECT_EQ(c.referenceBounces, reference::kUnlimitedBounces);
    EXPECT_EQ(referenceBouncesText(c.referenceBounces), "all");
    applyOption(c, "reference-bounces", "3");
    EXPECT_EQ(referenceBouncesText(c.referenceBounces), "3");
    for (const char* bad : {"65", "-1", "1.5", "", "some"})
        EXPECT_THROW(applyOption(c, "reference-bounces", bad), UsageError) << bad;
    EXPECT_THROW(applyOption(c, "split-source", "truth"), UsageError);
    EXPECT_EQ(c.referenceBounces, 3);
    EXPECT_STREQ(splitSourceName(c.splitSource), "reference");
    applyOption(c, "split", "off");
    EXPECT_FALSE(c.showsReference());
    EXPECT_FALSE(c.rendersB());
}

TEST(DemoScript, ParsesStepsInFrameOrderKeepingFileOrderWithinAFrame) {
    const DemoScript script = parseDemoScript(
        R"([{"frame": 5, "screenshot": "b.png", "ui": true},
            {"frame": 2, "set": {"split": true, "b-weights": "sg", "trace-scale": 2, "beta": 12.5}},
            {"frame": 5, "set": {"camera-cut": true}}])",
        "test");
    ASSERT_EQ(script.steps.size(), 3u);
    EXPECT_EQ(script.steps[0].frame, 2u);
    const std::vector<std::pair<std::string, std::string>> expected = {
        {"split", "on"}, {"b-weights", "sg"}, {"trace-scale", "2"}, {"beta", "12.5"}};
    EXPECT_EQ(script.steps[0].options, expected);
    EXPECT_EQ(script.steps[1].options[0], std::make_pair(std::string("screenshot-ui"), std::string("b.png")));
    EXPECT_EQ(script.steps[2].options[0].first, "camera-cut");
    EXPECT_EQ(script.lastFrame(), 5u);
}

TEST(DemoScript, BadStepsAreErrorsNamingTheStep) {
    auto message = [](const std::string& text) {
        try {
            parseDemoScript(text, "s.json");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message(R"({"frame": 1})").find("list of steps"), std::string::npos);
    EXPECT_NE(message(R"([{"set": {}}])").find("step 0"), std::string::npos);
    EXPECT_NE(message(R"([{"frame": 0}, {"frame": 1, "set": {"weights": "x"}}])").find("step 1: weights"),
              std::string::npos);
    EXPECT_NE(message(R"([{"frame": 0, "bogus": 1}])").find("unknown key 'bogus'"), std::string::npos);
    EXPECT_NE(message("[").find("not valid JSON"), std::string::npos);
}

TEST(DemoTimers, RollingMediansPerPassAndFrame) {
    RollingTimers timers(3);
    timers.add({{"trace", 1.0}, {"upsample", 2.0}});
    timers.add({{"trace", 3.0}, {"upsample", 2.0}});
    timers.add({{"trace", 2.0}, {"upsample", 4.0}});
    timers.add({{"trace", 10.0}});  // the first frame leaves the window
    const auto bars = timers.medians();
    ASSERT_EQ(bars.size(), 2u);
    EXPECT_EQ(bars[0].name, "trace");
    EXPECT_DOUBLE_EQ(bars[0].medianMs, 3.0);
    EXPECT_DOUBLE_EQ(bars[1].medianMs, 3.0);        // (2 + 4) / 2 over the frames that had it
    EXPECT_DOUBLE_EQ(timers.frameMedianMs(), 6.0);  // sums 5, 6, 10
    History history(2);
    for (float v : {1.0f, 5.0f, 3.0f}) history.push(v);
    EXPECT_EQ(history.values(), (std::vector<float>{5.0f, 3.0f}));
    EXPECT_FLOAT_EQ(history.max(), 5.0f);
}

// ---- the reference's worker (CPU) ----

ReferenceRequest referenceRequest(std::shared_ptr<const Scene> scene, uint32_t width, uint32_t height) {
    ReferenceRequest request;
    request.camera = sceneCamera(*scene, 0.0f);
    request.scene = std::move(scene);
    request.width = width;
    request.height = height;
    return request;
}

// Lockstep (scripted runs): one pass per update, waited for; a camera move restarts, a new time rebuilds, and
// what it shows is the tracer's own mean, bit for bit.
TEST(DemoReference, LockstepAddsOnePassPerFrameAndRestartsOnChanges) {
    auto scene = std::make_shared<const Scene>(loadScene("cornell"));
    ReferenceRequest request = referenceRequest(scene, 32, 18);
    DemoReference worker(1);
    ReferenceSnapshot snapshot;
    for (uint32_t frame = 0; frame < 4; ++frame) {
        EXPECT_EQ(worker.update(request, true), frame == 0);
        worker.waitForFrame();
        snapshot = worker.snapshot();
        ASSERT_TRUE(snapshot.images) << snapshot.state;
        EXPECT_EQ(snapshot.samplesPerPixel, frame + 1);
        EXPECT_EQ(snapshot.images->samplesPerPixel, frame + 1);
        EXPECT_TRUE(snapshot.current);
        EXPECT_FALSE(snapshot.failed);
    }
    EXPECT_GT(snapshot.raysPerSecond, 0.0);
    EXPECT_EQ(snapshot.threads, 1u);
    reference::ReferenceSettings settings;
    settings.width = 32;
    settings.height = 18;
    settings.threads = 1;
    reference::PathTracer tracer(*scene, 0.0f, request.camera, settings);
    tracer.addSamples(4);
    EXPECT_TRUE(snapshot.images->final.mean == tracer.images().final.mean);

    request.camera = cutCamera(request.camera);  // a camera move: restart
    EXPECT_TRUE(worker.update(request, true));
    worker.waitForFrame();
    EXPECT_EQ(worker.snapshot().samplesPerPixel, 1u);
    EXPECT_FALSE(worker.update(request, true));
    worker.waitForFrame();
    EXPECT_EQ(worker.snapshot().samplesPerPixel, 2u);
    request.timeSeconds = 0.5f;  // the animation moved: a new tracer at the new time
    EXPECT_TRUE(worker.update(request, true));
    worker.waitForFrame();
    EXPECT_EQ(worker.snapshot().samplesPerPixel, 1u);
    request.bounces = reference::kUnlimitedBounces;
    EXPECT_TRUE(worker.update(request, true));
    worker.waitForFrame();
    EXPECT_EQ(worker.snapshot().samplesPerPixel, 1u);
    EXPECT_TRUE(worker.snapshot().current);
}

// The clock runs whenever the animation is not paused; a scene that stands still at the new time (plane has
// no animation) keeps its tracer converging.
TEST(DemoReference, ATimeStepThatMovesNothingKeepsConverging) {
    auto scene = std::make_shared<const Scene>(loadScene("plane"));
    ASSERT_TRUE(scene->animations.empty());
    ReferenceRequest request = referenceRequest(scene, 16, 9);
    DemoReference worker(1);
    EXPECT_TRUE(worker.update(request, true));
    worker.waitForFrame();
    request.timeSeconds = 1.0f / 60.0f;
    EXPECT_FALSE(worker.update(request, true));
    worker.waitForFrame();
    EXPECT_EQ(worker.snapshot().samplesPerPixel, 2u);
    EXPECT_TRUE(worker.snapshot().current);
}

// Interactive: update never waits; the worker converges on its own, a camera move makes the image shown
// stale at once, and destroying it mid-pass cancels, joins and frees the scene it kept alive.
TEST(DemoReference, ConvergesOnItsOwnThreadAndStopsCleanly) {
    auto scene = std::make_shared<const Scene>(loadScene("cornell"));
    const std::weak_ptr<const Scene> weak = scene;
    ReferenceRequest request = referenceRequest(scene, 64, 36);
    scene.reset();  // the request (and then the worker) holds the only share
    auto worker = std::make_unique<DemoReference>(1);
    auto waitFor = [&](const char* what, auto done) {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
        ReferenceSnapshot s = worker->snapshot();
        while (!done(s) && std::chrono::steady_clock::now() < deadline) {
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
            s = worker->snapshot();
        }
        EXPECT_TRUE(done(s)) << what << ": " << s.samplesPerPixel << " spp, " << s.state;
        return s;
    };
    worker->update(request, false);
    // No further update: the passes come from the worker alone.
    const ReferenceSnapshot converging =
        waitFor("converging", [](const ReferenceSnapshot& s) { return s.current && s.samplesPerPixel >= 3; });
    ASSERT_TRUE(converging.images);
    EXPECT_EQ(converging.images->width, 64u);
    request.camera = cutCamera(request.camera);
    EXPECT_TRUE(worker->update(request, false));
    EXPECT_FALSE(worker->snapshot().current) << "the image of the previous camera counts as current";
    waitFor("restarted", [](const ReferenceSnapshot& s) { return s.current && s.samplesPerPixel >= 1; });
    // Passes that take a while (640x360, every bounce): destroyed inside one, the worker cancels it.
    request.width = 640;
    request.height = 360;
    request.bounces = reference::kUnlimitedBounces;
    auto start = std::chrono::steady_clock::now();
    EXPECT_TRUE(worker->update(request, false));
    waitFor("a long pass", [](const ReferenceSnapshot& s) { return s.current && s.samplesPerPixel >= 1; });
    auto since = [](std::chrono::steady_clock::time_point t) {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    };
    const double passSeconds = since(start);  // with the scene build: at least one pass
    std::this_thread::sleep_for(std::chrono::duration<double>(passSeconds / 4));
    request.scene.reset();
    EXPECT_FALSE(weak.expired()) << "the worker's tracer must keep its scene alive";
    start = std::chrono::steady_clock::now();
    worker.reset();  // it would not stop on its own before 65536 spp
    const double stopSeconds = since(start);
    std::printf("first pass at 640x360 %.3f s, stopped in %.4f s\n", passSeconds, stopSeconds);
    EXPECT_TRUE(weak.expired()) << "the scene outlived the worker";
    EXPECT_LT(stopSeconds, passSeconds / 2) << "stopping the worker did not cancel its pass";
}

// ---- the demo window under xvfb-run ----

constexpr const char* kXvfbRun = "/usr/bin/xvfb-run";

// `vct demo` at 160x90 with 32^3 voxels in a virtual X display, validation on.
test::RunResult runDemo(std::vector<std::string> args) {
    std::vector<std::string> all = {
        "-a", "-s",        "-screen 0 640x480x24", VCT_BINARY, "demo", "--size", "160x90", "--voxels",
        "32", "--validate"};
    all.insert(all.end(), args.begin(), args.end());
    return test::runProcess(kXvfbRun, all, std::chrono::seconds(300));
}

#define REQUIRE_XVFB() \
    if (access(kXvfbRun, X_OK) != 0) GTEST_SKIP() << "xvfb-run not installed (scripts/install-deps.sh)"

void expectClean(const test::RunResult& run) {
    ASSERT_TRUE(run.exited() && run.exitCode == 0) << run.describe();
    EXPECT_EQ(run.err.find("alidation"), std::string::npos) << run.err;
}

std::filesystem::path writeScript(const std::filesystem::path& dir, const nlohmann::json& steps) {
    const std::filesystem::path file = dir / "script.json";
    test::writeTextFile(file, steps.dump(1));
    return file;
}

// Mean absolute difference per channel (0..255) and the fraction of pixels that differ at all.
struct Difference {
    double mean = 0.0;
    double changed = 0.0;
};

Difference difference(const ImageRgba8& a, const ImageRgba8& b) {
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    Difference d;
    const size_t pixels = size_t(a.width) * a.height;
    if (a.pixels.size() != b.pixels.size() || pixels == 0) return d;
    size_t changed = 0;
    for (size_t i = 0; i < pixels; ++i) {
        bool differs = false;
        for (size_t c = 0; c < 3; ++c) {
            const int delta = std::abs(int(a.pixels[i * 4 + c]) - int(b.pixels[i * 4 + c]));
            d.mean += delta;
            differs |= delta > 0;
        }
        changed += differs ? 1 : 0;
    }
    d.mean /= double(pixels * 3);
    d.changed = double(changed) / double(pixels);
    return d;
}

size_t redPixels(const ImageRgba8& image) {
    size_t count = 0;
    for (size_t i = 0; i + 3 < image.pixels.size(); i += 4)
        count += image.pixels[i] == 255 && image.pixels[i + 1] == 0 && image.pixels[i + 2] == 0;
    return count;
}

TEST(DemoWindow, ScriptedAcceptanceRun) {
    REQUIRE_XVFB();
    const std::filesystem::path dir = test::freshOutputDir("demo/acceptance");
    auto shot = [&](const std::string& name) { return (dir / (name + ".png")).string(); };
    // Steps 1-2 with the animation paused: the only change between two screenshots is the setting, measured
    // against the change between two screenshots of the same setting 16 frames apart (one jitter cycle), the
    // first after two cycles (after one the history was still settling: noise 0.0132 levels on lavapipe, 0.0017
    // after two). One bounce, so that the light stands still: the default's gathers would still be converging
    // (design §5.7). The fixed cone set: the default turned cones' noise in a still view would hide the changes.
    // Steps 3-5 with the cube moving, as in Tokuyoshi 2015 Fig. 8.
    const nlohmann::json steps = {{{"frame", 0},
                                   {"set",
                                    {{"pause", "on"},
                                     {"weights", "sg"},
                                     {"trace-scale", 4},
                                     {"bounces", 1},
                                     {"cone-rotation", "off"}}}},
                                  {{"frame", 32}, {"screenshot", shot("0-sg")}},
                                  {{"frame", 48}, {"screenshot", shot("0-sg-again")}},
                                  {{"frame", 49}, {"set", {{"weights", "normal"}}}},
                                  {{"frame", 64}, {"screenshot", shot("1-normal")}},
                                  {{"frame", 65}, {"set", {{"trace-scale", 2}}}},
                                  {{"frame", 80}, {"screenshot", shot("2-scale2")}},
                                  {{"frame", 81}, {"set", {{"view", "resample"}, {"pause", "off"}}}},
                                  {{"frame", 88}, {"screenshot", shot("3-resample")}},
                                  {{"frame", 89}, {"set", {{"adaptive", "off"}}}},
                                  {{"frame", 96}, {"screenshot", shot("4-adaptive-off")}},
                                  {{"frame", 97}, {"set", {{"camera-cut", true}}}},
                                  {{"frame", 98}, {"screenshot", shot("5-cut")}},
                                  {{"frame", 99}, {"screenshot", shot("6-ui")}, {"ui", true}}};
    const test::RunResult run = runDemo({"--script", writeScript(dir, steps).string()});
    expectClean(run);
    auto load = [&](const std::string& name) { return readPng(shot(name)); };
    const ImageRgba8 sg = load("0-sg"), sgAgain = load("0-sg-again"), normal = load("1-normal"),
                     scale2 = load("2-scale2"), resample = load("3-resample"),
                     adaptiveOff = load("4-adaptive-off"), cut = load("5-cut"), ui = load("6-ui");
    ASSERT_EQ(sg.width, 160u);
    ASSERT_EQ(sg.height, 90u);
    const double noise = difference(sg, sgAgain).mean;
    // Paused, both guides converge towards the traced pixels (pixel-own samples dominate the history), so the
    // switch changes little but clearly more than the noise: measured mean 0.038 levels against noise 0.0017.
    const double weightsChange = difference(sgAgain, normal).mean;
    EXPECT_GT(weightsChange, 3.0 * noise) << "weights sg -> normal changed nothing";
    EXPECT_GT(weightsChange, 0.015) << "weights sg -> normal changed nothing";
    EXPECT_GT(difference(normal, scale2).mean, 2.0 * noise + 0.05) << "trace scale 4 -> 2 changed nothing";
    EXPECT_EQ(redPixels(scale2), 0u);
    // A measured minimum, so the view cannot pass on an empty mask: 3 red pixels at this frame (lavapipe).
    std::printf("resample view: %zu re-traced (red) pixels\n", size_t(redPixels(resample)));
    EXPECT_GE(redPixels(resample), 2u)
        << "the resample view shows (almost) no re-traced pixels around the moving cube";
    EXPECT_EQ(redPixels(adaptiveOff), 0u) << "adaptive off still re-traces";
    EXPECT_GT(difference(adaptiveOff, cut).changed, 0.5) << "the camera cut did not change the view";
    EXPECT_GT(difference(cut, ui).changed, 0.05) << "the panel is not drawn in a screenshot with ui";
    for (const char* line :
         {"frame 49: weights normal", "frame 65: trace-scale 2", "frame 97: camera-cut on"})
        EXPECT_NE(run.out.find(line), std::string::npos) << line << "\n" << run.out;
}

// The split view composes two real frames: left of the wipe bit for bit the frame of configuration A alone,
// right of it the frame of configuration B alone.
TEST(DemoWindow, SplitViewSidesAreTheirConfigurationsFrames) {
    REQUIRE_XVFB();
    const std::filesystem::path dir = test::freshOutputDir("demo/split");
    auto runWith = [&](const std::string& name, const nlohmann::json& set) {
        const nlohmann::json steps = {{{"frame", 0}, {"set", set}},
                                      {{"frame", 12}, {"screenshot", name + ".png"}}};  // beside the script
        std::filesystem::create_directories(dir / name);
        const test::RunResult run = runDemo({"--script", writeScript(dir / name, steps).string()});
        expectClean(run);
        return std::make_pair(readPng(dir / name / (name + ".png")), run.out);
    };
    const auto [sg, outSg] = runWith("sg", {{"weights", "sg"}});
    const auto [normal, outNormal] = runWith("normal", {{"weights", "normal"}});
    const auto [split, outSplit] =
        runWith("split", {{"split", "on"}, {"wipe", 0.5}, {"b-weights", "normal"}});
    ASSERT_EQ(split.pixels.size(), sg.pixels.size());
    const uint32_t wipe = 80;  // 0.5 of 160
    size_t leftDiff = 0, rightDiff = 0, sidesDiffer = 0;
    for (uint32_t y = 0; y < split.height; ++y)
        for (uint32_t x = 0; x < split.width; ++x)
            for (uint32_t c = 0; c < 4; ++c) {
                const size_t i = (size_t(y) * split.width + x) * 4 + c;
                (x < wipe ? leftDiff : rightDiff) += split.pixels[i] != (x < wipe ? sg : normal).pixels[i];
                sidesDiffer += sg.pixels[i] != normal.pixels[i];
            }
    EXPECT_EQ(leftDiff, 0u) << "left of the wipe is not the sg frame";
    EXPECT_EQ(rightDiff, 0u) << "right of the wipe is not the normal frame";
    EXPECT_GT(sidesDiffer, 0u) << "sg and normal frames are identical: the test shows nothing";
    EXPECT_NE(outSplit.find("renderer B (split view)"), std::string::npos) << outSplit;
}

// Mean luminance (0..1 of the sRGB bytes) of the columns [x0, x1).
double meanLuminance(const ImageRgba8& image, uint32_t x0, uint32_t x1) {
    double sum = 0.0;
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = x0; x < x1; ++x) {
            const uint8_t* p = &image.pixels[(size_t(y) * image.width + x) * 4];
            sum += test::luminance(p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f);
        }
    return sum / (double(image.height) * (x1 - x0));
}

// Bytes that differ in the columns [x0, x1).
size_t differingBytes(const ImageRgba8& a, const ImageRgba8& b, uint32_t x0, uint32_t x1) {
    if (a.width != b.width || a.height != b.height) return ~size_t(0);
    size_t count = 0;
    for (uint32_t y = 0; y < a.height; ++y)
        for (uint32_t x = x0; x < x1; ++x)
            for (uint32_t c = 0; c < 4; ++c) {
                const size_t i = (size_t(y) * a.width + x) * 4 + c;
                count += a.pixels[i] != b.pixels[i];
            }
    return count;
}

// Side B as the path-traced reference (split-source reference), the animation paused: one pass per frame in a
// scripted run, so B at frame 15 is `vct reference --spp 16` bit for bit; a camera cut restarts it (spp back
// down); switching the source, a scene load and the split view off stop its worker, under validation.
TEST(DemoWindow, SplitViewShowsThePathTracedReferenceConvergingAndRestarting) {
    REQUIRE_XVFB();
    const std::filesystem::path dir = test::freshOutputDir("demo/reference");
    auto shot = [&](const std::string& name) { return (dir / (name + ".png")).string(); };
    const nlohmann::json steps = {
        {{"frame", 0}, {"set", {{"pause", "on"}, {"split", "on"}, {"split-source", "reference"}}}},
        {{"frame", 7}, {"screenshot", shot("0-8spp")}},
        {{"frame", 15}, {"screenshot", shot("1-16spp")}},
        {{"frame", 16}, {"set", {{"camera-cut", true}}}},
        {{"frame", 18}, {"screenshot", shot("2-cut")}},
        {{"frame", 19}, {"set", {{"split-source", "vct"}}}},
        {{"frame", 20}, {"screenshot", shot("3-vct")}},
        {{"frame", 21}, {"set", {{"split-source", "reference"}, {"reference-bounces", "all"}}}},
        {{"frame", 22}, {"set", {{"scene", "plane"}}}},
        {{"frame", 25}, {"screenshot", shot("4-plane")}},
        {{"frame", 26}, {"set", {{"split", "off"}}}}};
    const auto start = std::chrono::steady_clock::now();
    const test::RunResult run = runDemo({"--script", writeScript(dir, steps).string()});
    std::printf("demo run: %.1f s\n",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    expectClean(run);
    // The spp of what B showed at each screenshot: growing one per frame, down again after the cut and the
    // scene load.
    for (const char* line : {"frame 7: reference 8 spp,", "frame 15: reference 16 spp,",
                             "frame 18: reference 3 spp,", "frame 25: reference 4 spp,"})
        EXPECT_NE(run.out.find(line), std::string::npos) << line << "\n" << run.out;
    EXPECT_EQ(run.out.find("frame 20: reference"), std::string::npos) << "B is vct again at frame 20";
    EXPECT_NE(run.out.find("loaded plane"), std::string::npos) << run.out;

    const test::RunResult reference =
        test::runVct({"reference", "--size", "160x90", "--spp", "16", "--frame", "0", "--threads", "1",
                      "--bounces", "all", "--out", (dir / "reference").string()});
    ASSERT_TRUE(reference.exited() && reference.exitCode == 0) << reference.describe();
    const ImageRgba8 truth = readPng(dir / "reference" / "final.png");
    const ImageRgba8 at8 = readPng(shot("0-8spp")), at16 = readPng(shot("1-16spp")),
                     cut = readPng(shot("2-cut")), vct = readPng(shot("3-vct")),
                     plane = readPng(shot("4-plane"));
    ASSERT_EQ(at16.width, 160u);
    const uint32_t wipe = 80, w = 160;  // the default wipe, 0.5
    EXPECT_EQ(differingBytes(at16, truth, wipe, w), 0u) << "B is not the reference's 16 spp image";
    EXPECT_GT(differingBytes(at16, truth, 0, wipe), 0u) << "A is the reference too";
    const double luminance8 = meanLuminance(at8, wipe, w), luminance16 = meanLuminance(at16, wipe, w);
    std::printf("B mean luminance: %.4f at 8 spp, %.4f at 16 spp, %.4f after the cut, %.4f on plane\n",
                luminance8, luminance16, meanLuminance(cut, wipe, w), meanLuminance(plane, wipe, w));
    EXPECT_GT(luminance8, 0.1) << "B is (nearly) black";
    EXPECT_GT(luminance16, 0.1) << "B is (nearly) black";
    EXPECT_GT(meanLuminance(cut, wipe, w), 0.1) << "B is (nearly) black after the cut";
    EXPECT_GT(meanLuminance(plane, wipe, w), 0.05) << "B is (nearly) black on plane";
    EXPECT_GT(differingBytes(at8, at16, wipe, w), 0u) << "B did not change from 8 to 16 spp";
    EXPECT_GT(difference(at16, cut).changed, 0.5) << "the cut did not change B";
    EXPECT_GT(differingBytes(vct, truth, wipe, w), 0u)
        << "B still shows the reference after split-source vct";
}

std::filesystem::path writeCameraPath(const std::filesystem::path& dir) {
    const std::filesystem::path file = dir / "path.camera.json";
    test::writeTextFile(file, R"({"scene": "cornell", "keys": [
        {"time": 0.0, "position": [0.0, 2.0, 1.9], "target": [0.0, 0.75, -1.2]},
        {"time": 0.1, "position": [0.4, 1.8, 1.7], "target": [0.0, 0.75, -1.2]},
        {"time": 0.2, "position": [0.8, 1.6, 1.4], "target": [-0.2, 0.6, -1.2]}]})");
    return file;
}

// `render --camera-path` twice: the same final.exr bit for bit (a moving camera can be measured).
TEST(CameraPathRender, TwoRunsGiveIdenticalFinalExr) {
    const std::filesystem::path dir = test::freshOutputDir("demo/path-render");
    const std::string path = writeCameraPath(dir).string();
    std::vector<std::vector<float>> images;
    for (const char* name : {"a", "b"}) {
        const test::RunResult run =
            test::runVct({"render", "--size", "160x90", "--voxels", "32", "--frames", "14", "--camera-path",
                          path, "--out", (dir / name).string(), "--validate"});
        ASSERT_TRUE(run.exited() && run.exitCode == 0) << run.describe();
        images.push_back(readExr(dir / name / "final.exr").pixels);
    }
    ASSERT_FALSE(images[0].empty());
    EXPECT_TRUE(images[0] == images[1]) << "two renders of the same camera path differ";
}

// The demo plays the same path through the same frames: its screenshot is render's final.png.
TEST(DemoWindow, CameraPathMatchesRender) {
    REQUIRE_XVFB();
    const std::filesystem::path dir = test::freshOutputDir("demo/path-demo");
    const std::string path = writeCameraPath(dir).string();
    const test::RunResult render =
        test::runVct({"render", "--size", "160x90", "--voxels", "32", "--frames", "14", "--camera-path", path,
                      "--out", (dir / "render").string()});
    ASSERT_TRUE(render.exited() && render.exitCode == 0) << render.describe();
    const test::RunResult demo =
        runDemo({"--camera-path", path, "--frames", "14", "--screenshot", (dir / "demo.png").string()});
    expectClean(demo);
    const ImageRgba8 a = readPng(dir / "render" / "final.png"), b = readPng(dir / "demo.png");
    EXPECT_TRUE(a.pixels == b.pixels) << "mean difference " << difference(a, b).mean;
}

TEST(DemoWindow, RecordsACameraPathThatLoads) {
    REQUIRE_XVFB();
    const std::filesystem::path dir = test::freshOutputDir("demo/record");
    const std::filesystem::path recorded = dir / "recorded.camera.json";
    const nlohmann::json steps = {{{"frame", 2}, {"set", {{"record", true}}}},
                                  {{"frame", 12}, {"set", {{"camera-cut", true}}}},
                                  {{"frame", 40}, {"set", {{"record", true}}}}};
    const test::RunResult run =
        runDemo({"--script", writeScript(dir, steps).string(), "--record-path", recorded.string()});
    expectClean(run);
    const CameraPath path = loadCameraPath(recorded);
    ASSERT_GE(path.keys.size(), 2u);
    EXPECT_NE(path.keys.front().position, path.keys.back().position) << "the cut is not in the recording";
    EXPECT_EQ(path.scene, "cornell");
}

TEST(DemoWindow, BadSceneFileKeepsThePreviousSceneAndAGoodOneLoads) {
    REQUIRE_XVFB();
    const std::filesystem::path dir = test::freshOutputDir("demo/scenes");
    test::writeTextFile(dir / "broken.gltf", "{ not json");
    const nlohmann::json steps = {{{"frame", 1}, {"set", {{"scene", (dir / "broken.gltf").string()}}}},
                                  {{"frame", 3}, {"set", {{"scene", "plane"}}}},
                                  {{"frame", 6}, {"screenshot", (dir / "plane.png").string()}}};
    const test::RunResult run = runDemo({"--script", writeScript(dir, steps).string()});
    expectClean(run);
    EXPECT_NE(run.err.find("broken.gltf"), std::string::npos) << run.err;
    EXPECT_NE(run.out.find("loaded plane"), std::string::npos) << run.out;
    EXPECT_TRUE(std::filesystem::exists(dir / "plane.png"));
}

TEST(DemoWindow, ShaderHotReloadRebuildsAndACompileErrorKeepsTheOldPipelines) {
    REQUIRE_XVFB();
    const std::filesystem::path dir = test::freshOutputDir("demo/reload");
    const nlohmann::json steps = {{{"frame", 1}, {"set", {{"hot-reload", true}}}},
                                  {{"frame", 3}, {"screenshot", (dir / "after.png").string()}}};
    const std::string script = writeScript(dir, steps).string();
    const test::RunResult good = runDemo({"--script", script});
    expectClean(good);
    EXPECT_NE(good.out.find("hot reload:"), std::string::npos) << good.out;

    // A copy of the shaders with one broken: the reload fails, says why, and the frames go on.
    const std::filesystem::path broken = dir / "shaders";
    std::filesystem::copy(VCT_SHADER_SOURCE_DIR, broken, std::filesystem::copy_options::recursive);
    {
        std::ofstream out(broken / "composite.comp", std::ios::app);
        out << "\nthis is not glsl;\n";
    }
    setenv("VCT_SHADER_SOURCE_DIR", broken.c_str(), 1);
    const test::RunResult bad = runDemo({"--script", script});
    unsetenv("VCT_SHADER_SOURCE_DIR");
    ASSERT_TRUE(bad.exited() && bad.exitCode == 0) << bad.describe();
    EXPECT_NE(bad.err.find("shader compile failed, old pipelines kept"), std::string::npos) << bad.err;
    EXPECT_NE(bad.err.find("composite.comp"), std::string::npos) << bad.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "after.png"));
}

// Every live setting and view, changed between frames, under the validation layer.
TEST(DemoWindow, EverySettingAndViewChangesLiveWithoutValidationMessages) {
    REQUIRE_XVFB();
    const std::filesystem::path dir = test::freshOutputDir("demo/all");
    // clang-format off
    const std::vector<std::pair<std::string, nlohmann::json>> changes = {
        {"beta", 5}, {"kappa", 300}, {"sigma-n", 0.3},
        {"gamma", 0.5}, {"tau", 1.0}, {"temporal", "off"},
        {"temporal", "on"}, {"toksvig", "off"}, {"specular-aa", "off"},
        {"exposure", 2.5}, {"anisotropy", 2}, {"weights", "bilinear"},
        {"trace-scale", 1}, {"view", "weights"}, {"trace-scale", 2},
        {"view", "weights"}, {"view", "diffuse"}, {"view", "specular"},
        {"view", "normals"}, {"view", "roughness"}, {"view", "direct"},
        {"view", "voxels"}, {"voxel-mip", 2}, {"voxels", 64},
        {"gi", "off"}, {"view", "resample"}, {"gi", "on"},
        {"split", "on"}, {"b-trace-scale", 1}, {"b-gi", "off"},
        {"wipe", 0.3}, {"split-source", "reference"}, {"view", "specular"},
        {"reference-bounces", "all"}, {"exposure", 1.5}, {"step", true},
        {"split-source", "vct"}, {"view", "final"}, {"reset-history", true},
        {"step", true}, {"pause", "on"}, {"panel", "off"}};
    // clang-format on
    nlohmann::json steps = nlohmann::json::array();
    uint32_t frame = 1;
    for (const auto& [name, value] : changes) steps.push_back({{"frame", frame++}, {"set", {{name, value}}}});
    steps.push_back({{"frame", frame}, {"screenshot", (dir / "last.png").string()}, {"ui", true}});
    const test::RunResult run = runDemo({"--script", writeScript(dir, steps).string()});
    expectClean(run);
    EXPECT_TRUE(std::filesystem::exists(dir / "last.png"));
}

}  // namespace
}  // namespace vct
