// The path-traced reference (engine/reference/): analytic cases where the answer is known exactly (furnace,
// open floor under a uniform sky, a lit plane alone), its statistics (error ∝ 1/√spp, the reported noise
// matches the difference of two seeds, determinism), its direct light against vct's direct pass, and bad
// input.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "io/image_io.h"
#include "reference/path_tracer.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_writer.h"
#include "scene_util.h"
#include "test_util.h"

namespace {

namespace fs = std::filesystem;
using namespace vct::test;
using namespace vct::test::scenes;
using vct::reference::PathTracer;
using vct::reference::ReferenceImages;
using vct::reference::ReferenceSettings;
using vct::reference::SecondaryBrdf;

// A floor of 200 × 200 units at y = 0, facing up.
vct::Scene openFloor() {
    vct::Scene scene = emptyScene("floor", diffuseMaterial(0.8f, 0.0f));
    addQuad(scene, glm::vec3(0.0f), glm::vec3(0, 0, 100), glm::vec3(100, 0, 0), 0);
    return scene;
}

vct::CameraView lookAt(glm::vec3 eye, glm::vec3 target) {
    vct::CameraView camera;
    camera.view = glm::lookAt(eye, target, glm::vec3(0, 1, 0));
    camera.yfov = 1.0f;
    camera.znear = 0.01f;
    camera.zfar = 100.0f;
    return camera;
}

ReferenceSettings smallSettings(int bounces, uint32_t size = 24) {
    ReferenceSettings settings;
    settings.width = size;
    settings.height = size;
    settings.bounces = bounces;
    return settings;
}

struct ImageStats {
    glm::dvec3 mean{0.0};
    double meanStd = 0.0;  // standard deviation of the mean's luminance, from the per-pixel variances
    size_t pixels = 0;
};

// Mean over the pixels whose centre hits a surface, and its noise from the reported per-pixel variances.
ImageStats surfaceMean(const ReferenceImages& images, const vct::reference::EstimateImage& image) {
    ImageStats stats;
    double variance = 0.0;
    for (size_t p = 0; p < image.mean.size(); ++p) {
        if (images.surfaceId[p] < 0) continue;
        stats.mean += glm::dvec3(image.mean[p]);
        variance += 0.2126 * 0.2126 * image.variance[p].r + 0.7152 * 0.7152 * image.variance[p].g +
                    0.0722 * 0.0722 * image.variance[p].b;
        ++stats.pixels;
    }
    stats.mean /= double(std::max<size_t>(stats.pixels, 1));
    stats.meanStd = std::sqrt(variance) / double(std::max<size_t>(stats.pixels, 1));
    return stats;
}

void expectAllFinite(const ReferenceImages& images) {
    for (const auto* image :
         {&images.final, &images.direct, &images.diffuseIndirect, &images.specularIndirect})
        for (size_t p = 0; p < image->mean.size(); ++p)
            for (int c = 0; c < 3; ++c) {
                ASSERT_TRUE(std::isfinite(image->mean[p][c]) && image->mean[p][c] >= 0.0f) << "pixel " << p;
                ASSERT_TRUE(std::isfinite(image->variance[p][c])) << "pixel " << p;
            }
}

// ---- analytic cases ----

// A closed room whose walls emit L_e and reflect Lambertian albedo ρ (the diffuse secondary BRDF): the
// incoming radiance D is L_e with one bounce, L_e(1 + ρ) with two, L_e/(1 − ρ) with all (geometric series).
TEST(Reference, FurnaceGivesTheGeometricSeries) {
    const float albedo = 0.5f, emission = 1.0f;
    const vct::Scene scene = furnaceRoom(albedo, emission);
    const vct::CameraView camera = lookAt(glm::vec3(0.1f, 0.2f, 0.3f), glm::vec3(0.3f, 0.0f, -1.0f));
    for (int bounces : {1, 2}) {
        ReferenceSettings settings = smallSettings(bounces);
        settings.secondary = SecondaryBrdf::Diffuse;
        PathTracer tracer(scene, 0.0f, camera, settings);
        tracer.addSamples(4);
        const ReferenceImages images = tracer.images();
        expectAllFinite(images);
        const double expected = bounces == 1 ? emission : emission * (1.0 + albedo);
        // Every path has the same value: exact up to float rounding, in every pixel.
        for (size_t p = 0; p < images.diffuseIndirect.mean.size(); ++p)
            ASSERT_NEAR(images.diffuseIndirect.mean[p].g, expected, 1e-5 * expected) << "bounces " << bounces;
        // The specular lobe's estimate normalised by its albedo from the DFG table: L_e up to the table's
        // interpolation (measured within 0.6 %).
        const ImageStats specular = surfaceMean(images, images.specularIndirect);
        EXPECT_NEAR(specular.mean.g, expected, 0.015 * expected) << "bounces " << bounces;
    }
    ReferenceSettings settings = smallSettings(vct::reference::kUnlimitedBounces);
    settings.secondary = SecondaryBrdf::Diffuse;
    PathTracer tracer(scene, 0.0f, camera, settings);
    tracer.addSamples(64);
    const ReferenceImages images = tracer.images();
    expectAllFinite(images);
    const ImageStats diffuse = surfaceMean(images, images.diffuseIndirect);
    const double expected = emission / (1.0 - albedo);
    // Russian roulette makes it noisy but unbiased: within 4 standard deviations of its own reported noise.
    EXPECT_NEAR(diffuse.mean.g, expected, 4.0 * diffuse.meanStd) << "noise " << diffuse.meanStd;
    EXPECT_LT(diffuse.meanStd, 0.01 * expected);  // and that noise is small (measured 0.3 %)
}

// Under a uniform environment L an open floor sees the sky in every direction above it: D = L (irradiance
// πL), with any number of bounces (nothing sends light back); S = L up to the DFG table.
TEST(Reference, OpenFloorUnderUniformSkyGetsItsAnalyticIrradiance) {
    const vct::Scene scene = openFloor();
    const vct::CameraView camera = lookAt(glm::vec3(0.0f, 2.0f, 3.0f), glm::vec3(0.0f, 0.0f, -2.0f));
    for (int bounces : {1, vct::reference::kUnlimitedBounces}) {
        ReferenceSettings settings = smallSettings(bounces);
        settings.environment = glm::vec3(0.5f);
        PathTracer tracer(scene, 0.0f, camera, settings);
        tracer.addSamples(8);
        const ReferenceImages images = tracer.images();
        expectAllFinite(images);
        size_t floorPixels = 0;
        for (size_t p = 0; p < images.surfaceId.size(); ++p) {
            if (images.surfaceId[p] < 0) continue;
            ++floorPixels;
            ASSERT_NEAR(images.diffuseIndirect.mean[p].r, 0.5f, 1e-6f);
            ASSERT_FLOAT_EQ(images.direct.mean[p].r, 0.0f);  // no light, no emission
        }
        EXPECT_GT(floorPixels, images.surfaceId.size() / 3);  // the floor fills a good part of the view
        const ImageStats specular = surfaceMean(images, images.specularIndirect);
        EXPECT_NEAR(specular.mean.r, 0.5, 0.5 * 0.015);
    }
}

// A lit plane alone receives no indirect light but the environment's: with a black sky, exactly none.
TEST(Reference, LitPlaneAloneGetsNoIndirectLight) {
    vct::Scene scene = openFloor();
    vct::Node& sun = addLight(scene, "sun", vct::LightType::Directional, 3.0f);
    sun.rotation = glm::angleAxis(glm::radians(-60.0f), glm::vec3(1, 0, 0));  // -Z tilted down
    const vct::CameraView camera = lookAt(glm::vec3(0.0f, 2.0f, 3.0f), glm::vec3(0.0f, 0.0f, -2.0f));
    for (float sky : {0.0f, 0.2f}) {
        ReferenceSettings settings = smallSettings(vct::reference::kUnlimitedBounces);
        settings.environment = glm::vec3(sky);
        PathTracer tracer(scene, 0.0f, camera, settings);
        tracer.addSamples(8);
        const ReferenceImages images = tracer.images();
        expectAllFinite(images);
        const ImageStats direct = surfaceMean(images, images.direct);
        EXPECT_GT(direct.mean.r, 0.3);  // the sun lights it
        for (size_t p = 0; p < images.surfaceId.size(); ++p) {
            if (images.surfaceId[p] < 0) continue;
            ASSERT_NEAR(images.diffuseIndirect.mean[p].r, sky, 1e-6f);
        }
    }
}

// ---- statistics and determinism ----

double meanSquaredDifference(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
    double sum = 0.0;
    for (size_t p = 0; p < a.size(); ++p)
        for (int c = 0; c < 3; ++c) sum += double(a[p][c] - b[p][c]) * double(a[p][c] - b[p][c]);
    return sum / double(3 * a.size());
}

double meanVariance(const std::vector<glm::vec3>& variance) {
    double sum = 0.0;
    for (const glm::vec3& v : variance) sum += double(v.r) + v.g + v.b;
    return sum / double(3 * variance.size());
}

vct::CameraView cornellCamera(const vct::Scene& scene) {
    return vct::sceneCamera(scene, 0.0f);
}

// The furnace room without emission, lit by a point light under its ceiling: every estimate has a bounded,
// moderate variance (rough walls, no highlights), so that sample statistics converge quickly.
vct::Scene litRoom() {
    vct::Scene scene = furnaceRoom(0.6f, 0.0f);
    addLight(scene, "bulb", vct::LightType::Point, 2.0f).translation = glm::vec3(0.2f, 0.8f, -0.3f);
    return scene;
}

TEST(Reference, SameSeedSameImageWhateverTheThreadsAndTheSplit) {
    const vct::Scene scene = vct::loadScene("cornell");
    ReferenceSettings settings = smallSettings(1, 16);
    settings.threads = 1;
    PathTracer one(scene, 0.0f, cornellCamera(scene), settings);
    one.addSamples(6);
    settings.threads = 2;
    PathTracer split(scene, 0.0f, cornellCamera(scene), settings);
    split.addSamples(2);
    split.addSamples(4);
    const ReferenceImages a = one.images(), b = split.images();
    EXPECT_EQ(a.final.mean, b.final.mean);
    EXPECT_EQ(a.specularIndirect.variance, b.specularIndirect.variance);
    EXPECT_EQ(a.surfaceId, b.surfaceId);
}

// Two seeds differ by the noise each reports: E[(A − B)²] = var_A + var_B. And sixteen times the samples cut
// the mean squared error sixteenfold (error ∝ 1/√spp).
TEST(Reference, NoiseIsWhatItReportsAndFallsAsOneOverRootSpp) {
    const vct::Scene scene = litRoom();
    const vct::CameraView camera = lookAt(glm::vec3(0.1f, -0.2f, 0.6f), glm::vec3(-0.2f, 0.0f, -1.0f));
    auto render = [&](uint64_t seed, uint32_t spp) {
        ReferenceSettings settings = smallSettings(1, 32);
        settings.seed = seed;
        PathTracer tracer(scene, 0.0f, camera, settings);
        tracer.addSamples(spp);
        return tracer.images();
    };
    const ReferenceImages a = render(1, 64), b = render(2, 64);
    for (const auto& [name, image] : {std::pair{"final", &ReferenceImages::final},
                                      std::pair{"diffuse", &ReferenceImages::diffuseIndirect},
                                      std::pair{"specular", &ReferenceImages::specularIndirect}}) {
        const double difference = meanSquaredDifference((a.*image).mean, (b.*image).mean);
        const double reported = meanVariance((a.*image).variance) + meanVariance((b.*image).variance);
        EXPECT_NEAR(difference / reported, 1.0, 0.1) << name << ": " << difference << " vs " << reported;
    }
    // MSE against a converged image, less that image's own variance.
    const ReferenceImages truth = render(7, 2048);
    const ReferenceImages low = render(3, 8), high = render(4, 128);
    const double truthVariance = meanVariance(truth.diffuseIndirect.variance);
    const double lowError =
        meanSquaredDifference(low.diffuseIndirect.mean, truth.diffuseIndirect.mean) - truthVariance;
    const double highError =
        meanSquaredDifference(high.diffuseIndirect.mean, truth.diffuseIndirect.mean) - truthVariance;
    EXPECT_NEAR(lowError / highError, 16.0, 16.0 * 0.15) << lowError << " vs " << highError;
}

// ---- against vct, through the program ----

struct Exr {
    vct::ImageRgba32f image;
    float at(size_t pixel, int channel) const { return image.pixels[4 * pixel + size_t(channel)]; }
};

// Mean relative difference of the reference's direct light from vct's on diffuse-dominated pixels (perceptual
// roughness ≥ minRoughness in vct's G-buffer) inside a surface (the 3×3 neighbourhood sees the same surface),
// returned as Σ reference / Σ vct over those pixels; `count` is how many there were.
double directRatio(const fs::path& vctDir, const fs::path& refDir, float minRoughness, size_t& count) {
    const Exr vctDirect{vct::readExr(vctDir / "direct.exr")};
    const Exr roughness{vct::readExr(vctDir / "roughness.exr")};
    const Exr refDirect{vct::readExr(refDir / "direct.exr")};
    const Exr ids{vct::readExr(refDir / "surface_id.exr")};
    const int w = int(ids.image.width), h = int(ids.image.height);
    double sumRef = 0.0, sumVct = 0.0;
    count = 0;
    for (int y = 1; y + 1 < h; ++y)
        for (int x = 1; x + 1 < w; ++x) {
            const size_t p = size_t(y) * size_t(w) + size_t(x);
            const float id = ids.at(p, 0);
            if (id < 0.0f || roughness.at(p, 0) < minRoughness) continue;
            bool interior = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    interior = interior && ids.at(p + size_t(dy * w + dx), 0) == id;
            if (!interior) continue;
            for (int c = 0; c < 3; ++c) {
                sumRef += refDirect.at(p, c);
                sumVct += vctDirect.at(p, c);
            }
            ++count;
        }
    return sumVct > 0.0 ? sumRef / sumVct : 0.0;
}

void expectDirectAgrees(const std::string& scene, const std::string& tag, const std::string& size,
                        float minRoughness, double margin, const std::vector<std::string>& vctFlags = {},
                        const std::vector<std::string>& commonFlags = {}) {
    const fs::path vctDir = freshOutputDir("reference/" + tag + "-vct");
    const fs::path refDir = freshOutputDir("reference/" + tag + "-reference");
    std::vector<std::string> renderArgs = {"render",     "--scene", scene,           "--size", size,
                                           "--frames",   "1",       "--trace-scale", "1",      "--aux",
                                           "--validate", "--out",   vctDir.string()};
    renderArgs.insert(renderArgs.end(), vctFlags.begin(), vctFlags.end());
    renderArgs.insert(renderArgs.end(), commonFlags.begin(), commonFlags.end());
    const RunResult render = runVct(renderArgs);
    ASSERT_EQ(render.exitCode, 0) << render.describe();
    std::vector<std::string> referenceArgs = {"reference", "--scene", scene,          "--size",
                                              size,        "--spp",   "32",           "--bounces",
                                              "0",         "--out",   refDir.string()};
    referenceArgs.insert(referenceArgs.end(), commonFlags.begin(), commonFlags.end());
    const RunResult reference = runVct(referenceArgs);
    ASSERT_EQ(reference.exitCode, 0) << reference.describe();
    size_t count = 0;
    const double ratio = directRatio(vctDir, refDir, minRoughness, count);
    std::printf("%s: direct light, reference / vct = %.4f over %zu pixels\n", tag.c_str(), ratio, count);
    EXPECT_GT(count, 300u) << "too few diffuse-dominated pixels to compare";
    EXPECT_NEAR(ratio, 1.0, margin) << count << " pixels";
    const nlohmann::json json = nlohmann::json::parse(readTextFile(refDir / "reference.json"));
    EXPECT_EQ(json["spp"], 32);
    EXPECT_GT(json["rays_per_second"].get<double>(), 1e4);
}

// The direct light is the one thing both renderers compute the same way (up to vct's shadow map and
// mip-mapped textures): calibrates the reference's light, camera, BRDF and materials against vct's.
TEST(Reference, DirectLightMatchesVctOnCornell) {
    expectDirectAgrees("cornell", "cornell", "96x54", 0.8f, 0.03);
}

TEST(Reference, DirectLightMatchesVctOnATexturedModel) {
    const fs::path model = fs::path(VCT_SHARED_SCENES) / "DamagedHelmet" / "glTF" / "DamagedHelmet.gltf";
    if (!fs::exists(model)) GTEST_SKIP() << "no " << model << " (shared scenes not available)";
    // Seen from close up (a pixel covers a few texels, so the material at a pixel's centre stands for the
    // pixel), and against vct's unfiltered-material mode: Toksvig and specular AA widen the visor's lobes
    // into a highlight that the reference, integrating the level-0 normal map over each pixel, does not show.
    const fs::path dir = freshOutputDir("reference/helmet-camera");
    writeTextFile(dir / "close.camera.json",
                  R"({"keys": [{"time": 0, "position": [0.3, 0.2, 1.9], "target": [0.0, 0.1, 0.0]}]})");
    expectDirectAgrees(model.string(), "helmet", "240x135", 0.5f, 0.05,
                       {"--toksvig", "off", "--specular-aa", "off", "--texture-lod0"},
                       {"--camera-path", (dir / "close.camera.json").string()});
}

// Vertex colours (COLOR_0) multiply the base colour in the reference as in vct's G-buffer: on a room whose back
// wall has vertex colours the two direct lights agree, and the reference's direct light is the one it computes
// for the same wall with the colour in its base colour factor instead.
TEST(Reference, DirectLightMatchesVctWithVertexColors) {
    const fs::path dir = freshOutputDir("reference/vertex-color-scenes");
    const glm::vec4 color(0.9f, 0.45f, 0.2f, 1.0f);
    const glm::vec3 base(0.8f, 0.7f, 0.9f);
    vct::writeGlb(vertexColorRoom(true, color, base), dir / "colored.glb");
    vct::writeGlb(vertexColorRoom(false, color, base), dir / "factor.glb");
    // Measured: reference / vct = 1.0001 over 2840 pixels; against the factor scene 1.2e-7 at most.
    expectDirectAgrees((dir / "colored.glb").string(), "vertex-colors", "96x54", 0.8f, 0.01);
    const fs::path factorDir = freshOutputDir("reference/vertex-colors-factor");
    const RunResult reference =
        runVct({"reference", "--scene", (dir / "factor.glb").string(), "--size", "96x54", "--spp", "32",
                "--bounces", "0", "--out", factorDir.string()});
    ASSERT_EQ(reference.exitCode, 0) << reference.describe();
    const Exr colored{
        vct::readExr(fs::path(VCT_TEST_OUTPUT) / "reference/vertex-colors-reference/direct.exr")};
    const Exr factor{vct::readExr(factorDir / "direct.exr")};
    ASSERT_EQ(colored.image.pixels.size(), factor.image.pixels.size());
    double maxRelative = 0.0, sum = 0.0;
    for (size_t i = 0; i < factor.image.pixels.size(); ++i) {
        const double a = colored.image.pixels[i], b = factor.image.pixels[i];
        maxRelative = std::max(maxRelative, std::abs(a - b) / std::max(b, 1e-3));
        sum += b;
    }
    std::printf("vertex colours: reference direct light against the factor scene's, max relative %.2e\n",
                maxRelative);
    EXPECT_GT(sum, 0.0);
    EXPECT_LE(maxRelative, 1e-6);
}

// ---- bad input: the loader's one-line errors ----

void expectOneLineError(const std::vector<std::string>& args, int exitCode, const std::string& mention) {
    const RunResult run = runVct(args);
    EXPECT_EQ(run.exitCode, exitCode) << run.describe();
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.describe();
    EXPECT_NE(run.err.find(mention), std::string::npos) << run.describe();
}

TEST(Reference, BadInputEndsInOneLine) {
    const fs::path dir = freshOutputDir("reference/bad");
    const std::string out = (dir / "out").string();
    expectOneLineError({"reference", "--scene", (dir / "missing.gltf").string(), "--out", out}, 1,
                       "missing.gltf");
    writeTextFile(dir / "broken.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [");
    expectOneLineError({"reference", "--scene", (dir / "broken.gltf").string(), "--out", out}, 1,
                       "broken.gltf");
    expectOneLineError({"reference", "--bounces", "many", "--out", out}, 2, "--bounces");
    expectOneLineError({"reference", "--spp", "0", "--out", out}, 2, "--spp");
    expectOneLineError({"reference", "--secondary", "glossy", "--out", out}, 2, "--secondary");
    expectOneLineError({"reference", "--size", "16384x16384", "--spp", "1024", "--out", out}, 2, "samples");
    writeTextFile(dir / "file", "x");
    expectOneLineError({"reference", "--size", "8x8", "--spp", "1", "--out", (dir / "file").string()}, 2,
                       "--out");
}

}  // namespace
