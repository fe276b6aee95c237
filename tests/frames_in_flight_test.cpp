// Two frames in flight (render/renderer.h): the CPU writes frame k + 1's uniforms, instance transforms, lights
// and joint matrices while lavapipe (whose queue runs on threads of its own) may still run frame k. Rendered
// with one and with two frames in flight, the same frames must give the same images bit for bit: the moving
// cube of cornell (instance buffer), the two-bone strip (joint matrices) and a point light that moves (light
// buffer). The last frame's image carries every earlier frame through the temporal history, and the
// re-trace count and the per-pass timings must be those of every frame, collected in order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "render/renderer.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"
#include "skin_util.h"
#include "validated_context.h"
#include "vk/context.h"

namespace vct {
namespace {

vk::Context& context() {
    return test::validatedContext();
}

struct FramesRun {
    std::vector<float> finalImage;    // the last frame's linear HDR final
    std::vector<float> indirect;      // its demodulated diffuse indirect light
    std::vector<float> resampled;     // the re-traced fraction after each finished frame
    size_t timedFrames = 0;           // frames in the timer's statistics
    std::vector<std::string> passes;  // the passes the timer saw, in order
    std::vector<size_t> passSamples;  // samples per pass
};

constexpr uint32_t kFrames = 12, kWarmup = 2;

FramesRun renderFrames(const Scene& scene, uint32_t framesInFlight) {
    RenderSettings settings;
    settings.width = 96;
    settings.height = 54;
    settings.voxelResolution = 32;
    Renderer renderer(context(), scene, settings, framesInFlight);
    FramesRun run;
    for (uint32_t frame = 0; frame < kFrames; ++frame) {
        renderer.render(fixedStepFrame(scene, frame, kWarmup));
        run.resampled.push_back(renderer.resampledFraction());
    }
    renderer.finishFrames();
    run.finalImage = renderer.readFinalHdr();
    run.indirect = renderer.readIndirect().diffuse;
    run.timedFrames = renderer.timer().frameStats().samples;
    for (const vk::PassTiming& pass : renderer.timer().passStats()) {
        run.passes.push_back(pass.name);
        run.passSamples.push_back(pass.samples);
    }
    return run;
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// cornell with its point-light variant: the light moves along x, so the light buffer changes every frame.
Scene cornellWithMovingLight() {
    Scene scene = loadScene("cornell");
    for (Node& node : scene.nodes) {
        if (node.light < 0) continue;
        Animation animation;
        animation.name = "light sweep";
        AnimationChannel channel;
        channel.node = int(&node - scene.nodes.data());
        channel.path = AnimationPath::Translation;
        channel.times = {0.0f, 1.0f};
        const glm::vec3 t = node.translation;
        channel.values = {glm::vec4(t.x - 0.3f, t.y, t.z, 0.0f), glm::vec4(t.x + 0.3f, t.y, t.z, 0.0f)};
        animation.channels.push_back(channel);
        animation.duration = 1.0f;
        scene.animations.push_back(animation);
        break;
    }
    return scene;
}

Scene sceneNamed(const std::string& name) {
    if (name == "strip")
        return loadGltf(
            hostile::writeGltf(test::freshOutputDir("frames_in_flight/strip"), skin_test::twoBoneStrip())
                .string());
    if (name == "cornell-moving-light") return cornellWithMovingLight();
    return loadScene(name);
}

class FramesInFlight : public testing::TestWithParam<std::string> {};

TEST_P(FramesInFlight, TwoInFlightRenderTheSameFramesAsOne) {
    const uint32_t before = vk::validationMessageCount();
    const Scene scene = sceneNamed(GetParam());
    const FramesRun one = renderFrames(scene, 1);
    const FramesRun two = renderFrames(scene, 2);
    EXPECT_TRUE(sameBits(one.finalImage, two.finalImage)) << "final.exr of the last frame differs";
    EXPECT_TRUE(sameBits(one.indirect, two.indirect)) << "indirect light of the last frame differs";
    // Every recorded frame timed once, in both: frames kWarmup .. kFrames − 1.
    EXPECT_EQ(one.timedFrames, kFrames - kWarmup);
    EXPECT_EQ(two.timedFrames, kFrames - kWarmup);
    EXPECT_EQ(one.passes, two.passes);
    EXPECT_EQ(one.passSamples, two.passSamples);
    // Two in flight report the re-trace fraction of the last finished frame: render(k) waits for frame k − 2
    // (nothing before the first two has finished).
    ASSERT_EQ(two.resampled.size(), one.resampled.size());
    EXPECT_EQ(two.resampled[0], 0.0f);
    EXPECT_EQ(two.resampled[1], 0.0f);
    for (size_t k = 2; k < one.resampled.size(); ++k) EXPECT_EQ(two.resampled[k], one.resampled[k - 2]) << k;
    EXPECT_GT(*std::max_element(one.resampled.begin(), one.resampled.end()), 0.0f) << "nothing re-traced";
    EXPECT_EQ(vk::validationMessageCount(), before);
}

INSTANTIATE_TEST_SUITE_P(Scenes, FramesInFlight, testing::Values("cornell", "strip", "cornell-moving-light"),
                         [](const testing::TestParamInfo<std::string>& param) {
                             std::string name = param.param;
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

}  // namespace
}  // namespace vct
