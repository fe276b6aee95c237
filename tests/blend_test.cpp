// Blended surfaces (glTF alphaMode BLEND: the blend pass, docs/design.md §2.6) on lavapipe, in process under
// validation, against analytic expectations. The scenes are layers of large quads facing the camera (they fill
// the frame), written as .glb by the project's writer and loaded back: emissive metal-black layers (albedo 0,
// F0 0) under a zero-intensity light and a black environment with GI off, so every pixel is exactly its
// emission composited "over": a·front + (1 − a)·back; two blended layers in either submission order; alpha 0
// (the background exactly) and alpha 1 (the opaque result); a lit layer against the opaque render; GI on
// (finite, validation clean); and the path-traced reference's stochastic transparency against the same sums.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>

#include "passes/blend_pass.h"
#include "reference/path_tracer.h"
#include "render/renderer.h"
#include "scene/gltf_loader.h"
#include "scene/gltf_writer.h"
#include "scene_util.h"
#include "test_util.h"
#include "validated_context.h"
#include "vk/context.h"

namespace vct {
namespace {

namespace fs = std::filesystem;

constexpr uint32_t kWidth = 64, kHeight = 36;

vk::Context& context() {
    return test::validatedContext();
}

// One quad of the scene: facing +z (the camera) at depth z, spanning ±20 in x and y.
struct Layer {
    float z;
    glm::vec3 emission;
    float alpha;
    AlphaMode mode = AlphaMode::Blend;
    glm::vec3 baseColor{0.0f};  // with metallic 1 for black, metallic 0 otherwise
};

// The layers in the order given (the scene's submission order), and one directional light travelling along
// −z of `lightIntensity` (0: nothing lit; the loader would add a default light to a scene without one).
Scene layeredScene(const std::string& name, const std::vector<Layer>& layers, float lightIntensity = 0.0f) {
    Scene scene = test::scenes::emptyScene(name, test::scenes::diffuseMaterial(1.0f, 0.0f));
    scene.materials.clear();
    for (const Layer& layer : layers) {
        Material m;
        m.name = "layer " + std::to_string(scene.materials.size());
        const bool black = layer.baseColor == glm::vec3(0.0f);
        m.baseColorFactor = glm::vec4(layer.baseColor, layer.alpha);
        m.metallicFactor = black ? 1.0f : 0.0f;
        m.roughnessFactor = black ? 1.0f : 0.6f;
        m.emissiveFactor = layer.emission;
        m.alphaMode = layer.mode;
        scene.materials.push_back(m);
        test::scenes::addQuad(scene, glm::vec3(0.0f, 0.0f, layer.z), glm::vec3(20, 0, 0), glm::vec3(0, 20, 0),
                              uint32_t(scene.materials.size() - 1));
    }
    test::scenes::addLight(scene, "light", LightType::Directional, lightIntensity);
    // Through the project's writer and loader, as a file would come.
    const fs::path dir = test::freshOutputDir("blend/" + name);
    writeGlb(scene, dir / "scene.glb");
    return loadGltf((dir / "scene.glb").string());
}

CameraView camera() {
    CameraView view;
    view.view = glm::lookAt(glm::vec3(0.3f, 0.2f, 4.0f), glm::vec3(0.0f), glm::vec3(0, 1, 0));
    view.yfov = 0.8f;
    view.znear = 0.05f;
    view.zfar = 50.0f;
    return view;
}

RenderSettings settings(bool gi) {
    RenderSettings s;
    s.width = kWidth;
    s.height = kHeight;
    s.gi = gi;
    s.voxelResolution = 32;
    s.environmentIntensity = 0.0f;  // black: every pixel is what its layers emit and reflect
    return s;
}

struct Render {
    std::vector<glm::vec3> hdr;  // per pixel
    bool blendPass = false;      // whether the renderer ran one
};

Render render(const Scene& scene, bool gi = false, uint32_t frames = 1) {
    Renderer renderer(context(), scene, settings(gi));
    for (uint32_t i = 0; i < frames; ++i) {
        FrameInput input;
        input.camera = camera();
        input.cut = i == 0;
        renderer.render(input);
    }
    const std::vector<float> rgba = renderer.readFinalHdr();
    Render result;
    for (size_t p = 0; p < rgba.size() / 4; ++p)
        result.hdr.emplace_back(rgba[4 * p], rgba[4 * p + 1], rgba[4 * p + 2]);
    result.blendPass = renderer.targets().blend;
    return result;
}

// Largest difference from `expected` over every pixel and channel, relative to max(|expected|, 0.05);
// printed, so that the margins below can be checked against what is measured.
float worstRelative(const Render& image, const std::vector<glm::vec3>& expected, const std::string& what) {
    float worst = 0.0f;
    for (size_t p = 0; p < image.hdr.size(); ++p)
        for (int c = 0; c < 3; ++c) {
            const float e = expected[p][c], v = image.hdr[p][c];
            if (!std::isfinite(v)) return INFINITY;
            worst = std::max(worst, std::abs(v - e) / std::max(std::abs(e), 0.05f));
        }
    std::printf("  %s: worst relative difference %.3g\n", what.c_str(), double(worst));
    return worst;
}

std::vector<glm::vec3> uniform(glm::vec3 value) {
    return std::vector<glm::vec3>(size_t(kWidth) * kHeight, value);
}

glm::vec3 over(float alpha, glm::vec3 front, glm::vec3 back) {
    return alpha * front + (1.0f - alpha) * back;
}

const glm::vec3 kFront(0.9f, 0.3f, 0.1f), kMiddle(0.1f, 0.8f, 0.3f), kBack(0.2f, 0.5f, 0.8f);

// a·front + (1 − a)·back at every pixel, for alphas from 0 to 1. Measured (lavapipe): 2.4e-4 … 6.5e-4
// relative at most (both layers pass through RGBA16F images: direct and the transparent layer).
TEST(Blend, OneLayerOverAnOpaqueBackgroundIsTheOverSum) {
    const uint32_t before = vk::validationMessageCount();
    for (float alpha : {0.0f, 0.25f, 0.5f, 0.8f, 1.0f}) {
        const Scene scene = layeredScene("one-" + std::to_string(int(alpha * 100)),
                                         {{0.0f, kBack, 1.0f, AlphaMode::Opaque}, {1.0f, kFront, alpha}});
        const Render image = render(scene);
        EXPECT_TRUE(image.blendPass);
        EXPECT_LE(worstRelative(image, uniform(over(alpha, kFront, kBack)), "alpha " + std::to_string(alpha)),
                  1e-3f)
            << "alpha " << alpha;
    }
    EXPECT_EQ(vk::validationMessageCount(), before);
}

// Alpha 0 shows the background exactly (bit for bit the render without the layer); alpha 1 equals the layer
// drawn opaque (measured: identical; the bound allows RGBA16F rounding).
TEST(Blend, AlphaZeroIsTheBackgroundAndAlphaOneTheOpaqueLayer) {
    const uint32_t before = vk::validationMessageCount();
    const Render background = render(layeredScene("background", {{0.0f, kBack, 1.0f, AlphaMode::Opaque}}));
    EXPECT_FALSE(background.blendPass);  // no blended surface: no blend pass
    const Render zero =
        render(layeredScene("alpha-zero", {{0.0f, kBack, 1.0f, AlphaMode::Opaque}, {1.0f, kFront, 0.0f}}));
    EXPECT_EQ(zero.hdr, background.hdr);
    const Render opaque = render(layeredScene(
        "opaque", {{0.0f, kBack, 1.0f, AlphaMode::Opaque}, {1.0f, kFront, 1.0f, AlphaMode::Opaque}}));
    const Render one =
        render(layeredScene("alpha-one", {{0.0f, kBack, 1.0f, AlphaMode::Opaque}, {1.0f, kFront, 1.0f}}));
    EXPECT_LE(worstRelative(one, opaque.hdr, "alpha 1 vs opaque"), 5e-4f);
    EXPECT_EQ(vk::validationMessageCount(), before);
}

// Two blended layers over an opaque one, submitted in either order: the pass sorts them back to front, so
// both give a1·E1 + (1 − a1)·(a2·E2 + (1 − a2)·E_b). With the depths swapped the other order is right; the
// two sums differ by far more than the tolerance, so the order is what is tested. Measured 3.2e-5 and 5.5e-4.
TEST(Blend, TwoLayersCompositeBackToFrontWhateverTheSubmissionOrder) {
    const uint32_t before = vk::validationMessageCount();
    const float a1 = 0.5f, a2 = 0.6f;
    const Layer back{0.0f, kBack, 1.0f, AlphaMode::Opaque};
    const glm::vec3 nearFirst = over(a1, kFront, over(a2, kMiddle, kBack));    // kFront nearest
    const glm::vec3 middleFirst = over(a2, kMiddle, over(a1, kFront, kBack));  // kMiddle nearest
    ASSERT_GT(glm::length(nearFirst - middleFirst), 0.1f);
    for (bool frontSubmittedFirst : {true, false}) {
        const Layer front{1.0f, kFront, a1}, middle{0.5f, kMiddle, a2};
        const std::string order = frontSubmittedFirst ? "front-first" : "middle-first";
        const Scene scene =
            layeredScene("two-" + order, frontSubmittedFirst ? std::vector<Layer>{back, front, middle}
                                                             : std::vector<Layer>{back, middle, front});
        EXPECT_LE(worstRelative(render(scene), uniform(nearFirst), order), 1e-3f) << order;
        // The same layers with their depths exchanged.
        const Layer swappedFront{0.5f, kFront, a1}, swappedMiddle{1.0f, kMiddle, a2};
        const Scene swapped = layeredScene(
            "swapped-" + order, frontSubmittedFirst ? std::vector<Layer>{back, swappedFront, swappedMiddle}
                                                    : std::vector<Layer>{back, swappedMiddle, swappedFront});
        EXPECT_LE(worstRelative(render(swapped), uniform(middleFirst), "swapped " + order), 1e-3f) << order;
    }
    EXPECT_EQ(vk::validationMessageCount(), before);
}

// A lit layer (base colour 0.8, 0.4, 0.2: exact in the G-buffer's 8 bits; one directional light): the blended
// pixel is a·(the layer drawn opaque) + (1 − a)·(the background with the layer at alpha 0). The forward pass
// shades what the G-buffer path shades, to its storage rounding (normal RGBA16F): measured 6.2e-4.
TEST(Blend, LitLayerMatchesTheOpaqueShadingComposited) {
    const uint32_t before = vk::validationMessageCount();
    const glm::vec3 base(0.8f, 0.4f, 0.2f);
    const float alpha = 0.4f, light = 3.0f;
    const Layer back{0.0f, kBack, 1.0f, AlphaMode::Opaque};
    auto lit = [&](float a, AlphaMode mode) {
        return render(
            layeredScene("lit-" + std::to_string(int(a * 100)) + (mode == AlphaMode::Blend ? "b" : "o"),
                         {back, {1.0f, glm::vec3(0.0f), a, mode, base}}, light));
    };
    const Render opaque = lit(1.0f, AlphaMode::Opaque), background = lit(0.0f, AlphaMode::Blend);
    const Render blended = lit(alpha, AlphaMode::Blend);
    std::vector<glm::vec3> expected;
    for (size_t p = 0; p < opaque.hdr.size(); ++p)
        expected.push_back(over(alpha, opaque.hdr[p], background.hdr[p]));
    EXPECT_GT(glm::length(opaque.hdr[0] - background.hdr[0]), 0.1f);  // the layer shows
    EXPECT_LE(worstRelative(blended, expected, "lit"), 1e-3f);
    EXPECT_EQ(vk::validationMessageCount(), before);
}

// GI on: the blended layers trace their own cones at their fragments (and are voxelized by their alpha).
// Finite, validation clean, and still the emission composited: the layers reflect almost nothing (albedo 0,
// F0 0: at most the DFG bias times what the cones see, and their cones leave towards the empty +z side).
// Measured 7.5e-5.
TEST(Blend, GiOnIsFiniteAndCloseToTheOverSum) {
    const uint32_t before = vk::validationMessageCount();
    const Scene scene = layeredScene(
        "gi", {{0.0f, kBack, 1.0f, AlphaMode::Opaque}, {1.0f, kFront, 0.5f}, {0.5f, kMiddle, 0.6f}});
    const Render image = render(scene, true, 3);
    EXPECT_LE(worstRelative(image, uniform(over(0.5f, kFront, over(0.6f, kMiddle, kBack))), "gi on"), 1e-3f);
    EXPECT_EQ(vk::validationMessageCount(), before);
}

// Voxelized with opacity from alpha: the voxels of a blended layer alone hold its alpha in the albedo volume's
// alpha (8 bits after the accumulator's 1/1023 steps), those of the opaque layer 1. Measured: 0.3 ± 0.0020 (half
// an 8-bit step) and 1 exactly, 961 voxels each.
TEST(Blend, VoxelOpacityIsTheLayersAlpha) {
    const uint32_t before = vk::validationMessageCount();
    const float alpha = 0.3f;
    const Scene scene =
        layeredScene("voxels", {{-8.0f, kBack, 1.0f, AlphaMode::Opaque}, {0.0f, kFront, alpha}});
    Renderer renderer(context(), scene, settings(true));
    FrameInput input;
    input.camera = camera();
    input.cut = true;
    renderer.render(input);
    VoxelGrid& grid = *renderer.voxelGrid();
    size_t blended = 0, opaque = 0;
    float worst = 0.0f;
    for (const glm::vec4& voxel : grid.readVolume(grid.albedo())) {
        if (voxel.a <= 0.0f) continue;
        const bool isOpaque = voxel.a > 0.65f;
        ++(isOpaque ? opaque : blended);
        worst = std::max(worst, std::abs(voxel.a - (isOpaque ? 1.0f : alpha)));
    }
    std::printf("  %zu blended voxels, %zu opaque, worst opacity error %.4f\n", blended, opaque,
                double(worst));
    EXPECT_GT(blended, 100u);
    EXPECT_GT(opaque, 100u);
    EXPECT_LE(worst, 1.5f / 255.0f);
    EXPECT_EQ(vk::validationMessageCount(), before);
}

// The back-to-front order is by the view depth of each primitive's bounds centre.
TEST(Blend, DrawsAreOrderedFarthestFirst) {
    const Scene scene = layeredScene("order", {{0.0f, kBack, 1.0f, AlphaMode::Opaque},
                                               {1.0f, kFront, 0.5f},
                                               {-1.0f, kMiddle, 0.5f},
                                               {0.5f, kMiddle, 0.5f}});
    Renderer renderer(context(), scene, settings(false));
    const std::vector<DrawItem> order = blendedDrawsBackToFront(renderer.gpuScene(), camera().view);
    ASSERT_EQ(order.size(), 3u);  // the opaque layer is not among them
    EXPECT_EQ(order[0].meshPrimitive, 2u);
    EXPECT_EQ(order[1].meshPrimitive, 3u);
    EXPECT_EQ(order[2].meshPrimitive, 1u);
}

// The path-traced reference passes through a blended surface with probability 1 − alpha: its direct image
// (emission of the first surface a camera ray keeps) converges to the same over sum. Over 24² pixels × 64
// samples, the mean's noise is at most 0.5·|E_f − E_b|/√36864 = 0.0018 per channel: the bound is 3 of those
// (measured: 0.0015 from the sum, vct within 1e-4 of it).
TEST(Blend, ReferenceStochasticTransparencyAgreesWithVct) {
    const float alpha = 0.5f;
    const Scene scene =
        layeredScene("reference", {{0.0f, kBack, 1.0f, AlphaMode::Opaque}, {1.0f, kFront, alpha}});
    reference::ReferenceSettings rs;
    rs.width = rs.height = 24;
    rs.environment = glm::vec3(0.0f);
    rs.threads = 2;
    reference::PathTracer tracer(scene, 0.0f, camera(), rs);
    tracer.addSamples(64);
    const reference::ReferenceImages images = tracer.images();
    glm::dvec3 mean(0.0);
    for (const glm::vec3& v : images.direct.mean) mean += glm::dvec3(v);
    mean /= double(images.direct.mean.size());
    const glm::vec3 expected = over(alpha, kFront, kBack);
    const Render vct = render(scene);
    glm::dvec3 vctMean(0.0);
    for (const glm::vec3& v : vct.hdr) vctMean += glm::dvec3(v);
    vctMean /= double(vct.hdr.size());
    std::printf("  reference %.4f %.4f %.4f, vct %.4f %.4f %.4f, expected %.4f %.4f %.4f\n", mean.r, mean.g,
                mean.b, vctMean.r, vctMean.g, vctMean.b, double(expected.r), double(expected.g),
                double(expected.b));
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(mean[c], expected[c], 0.0055) << "channel " << c;
        EXPECT_NEAR(vctMean[c], expected[c], 1e-3) << "channel " << c;
    }
}

}  // namespace
}  // namespace vct
