// The environment as the cones read it (render/environment_cones.h, docs/design.md §5.9): each layer holds the
// mean over a cap of its half-angle, a constant map stays exact, and under the default sky the cones' estimates of
// an open surface's light (the six diffuse cones; the specular cone with the diffuse cones' share of a rough lobe)
// come within the margins measured of the exact integrals over the map.
#include "render/environment_cones.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "render/shader_math.h"
#include "scene_util.h"

namespace {

namespace g = vct::glsl;
using glm::vec2;
using glm::vec3;

const vct::EnvironmentMap& defaultSky() {
    // The default light's direction (scene/scene.cpp's addDefaultLight), reversed: the sun.
    static const vct::EnvironmentMap map = vct::sceneEnvironment(
        vct::test::scenes::sceneWithSun(-glm::vec3(-0.3f, -1.0f, -0.6f), 3.0f), vct::RenderSettings{});
    return map;
}

vec3 texelDirection(const vct::EnvironmentMap& map, uint32_t x, uint32_t y) {
    return g::equirectDirection(
        vec2((float(x) + 0.5f) / float(map.width()), (float(y) + 0.5f) / float(map.height())), 0.0f);
}

// The exact weighted mean of level 0 over the sphere: Σ weight(d)·L·ω / Σ weight(d)·ω over its texels.
template <typename Weight>
vec3 weightedMean(const vct::EnvironmentMap& map, Weight weight) {
    glm::dvec3 sum(0.0);
    double total = 0.0;
    for (uint32_t y = 0; y < map.height(); ++y) {
        const double omega = vct::equirectTexelSolidAngle(y, map.width(), map.height());
        for (uint32_t x = 0; x < map.width(); ++x) {
            const double w = weight(texelDirection(map, x, y)) * omega;
            sum += w * glm::dvec3(map.texel(0, x, y));
            total += w;
        }
    }
    return vec3(sum / total);
}

// A width × height map of radiance c everywhere, with its mips.
vct::EnvironmentMap uniformMap(uint32_t width, uint32_t height, vec3 c) {
    vct::EnvironmentMap map;
    map.widths = {width};
    map.heights = {height};
    map.levels = {std::vector<vec3>(size_t(width) * height, c)};
    vct::buildEnvironmentMips(map);
    return map;
}

// The normals and views of the open-sky sweeps: up, four sides, a diagonal, down; head-on to grazing, four azimuths.
const vec3 kNormals[] = {
    {0, 1, 0}, {0, 0, 1}, {1, 0, 0}, {0, 0, -1}, {-1, 0, 0}, {0.57735f, 0.57735f, 0.57735f}, {0, -1, 0}};

// The six diffuse cones' estimate of the cosine-weighted mean radiance, averaged over eight turns of the set (the
// trace turns it per pixel and frame).
vec3 sixConeEstimate(const vct::EnvironmentConeLayers& layers, vec3 n) {
    vec3 sum(0.0f);
    for (int turn = 0; turn < 8; ++turn)
        for (int i = 0; i < g::DIFFUSE_CONE_COUNT; ++i)
            sum +=
                g::diffuseConeWeight(i) *
                vct::sampleEnvironmentCone(layers, g::turnedDiffuseConeDirection(n, i, float(turn) * 0.157f),
                                           g::DIFFUSE_CONE_TAN_HALF, 0.0f);
    return sum / 8.0f;
}

// The demodulated specular light of an open surface as the trace estimates it: the specular cone read at its
// environment aperture, a rough lobe's rest from the six diffuse cones (lib/cone.glsl's specularFromCones).
vec3 specularEstimate(const vct::EnvironmentConeLayers& layers, vec3 n, vec3 v, float alpha) {
    const float nov = glm::dot(n, v);
    const vec3 xi = g::specularConeDirection(n, v);
    vec3 sum(0.0f);
    for (int turn = 0; turn < 8; ++turn) {
        vec3 directions[g::DIFFUSE_CONE_COUNT], cones[g::DIFFUSE_CONE_COUNT];
        for (int i = 0; i < g::DIFFUSE_CONE_COUNT; ++i) {
            directions[i] = g::turnedDiffuseConeDirection(n, i, float(turn) * 0.157f);
            cones[i] = vct::sampleEnvironmentCone(layers, directions[i], g::DIFFUSE_CONE_TAN_HALF, 0.0f);
        }
        const vec3 specular =
            vct::sampleEnvironmentCone(layers, xi, g::specularEnvironmentTanHalf(alpha, nov), 0.0f);
        sum += g::specularFromCones(n, nov, alpha, xi, g::specularLobeInverseSharpness(alpha, nov), specular,
                                    directions, cones);
    }
    return sum / 8.0f;
}

// What the path-traced reference's demodulated specular light converges to on an open surface: ∫ f_s (n·l) L dω /
// ∫ f_s (n·l) dω, by GGX half-vector importance sampling (weights G_vis·4(v·h)(n·l)/(n·h)), with Schlick's Fresnel
// for F0 = 0.04 (a dielectric, whose Fresnel favours grazing light).
vec3 ggxSpecular(const vct::EnvironmentMap& map, vec3 n, vec3 v, float alpha) {
    const vec3 t = g::coneTangent(n), b = g::coneBitangent(n);
    const float nov = glm::dot(n, v);
    constexpr uint32_t kSamples = 4096;
    glm::dvec3 sum(0.0);
    double total = 0.0;
    for (uint32_t i = 0; i < kSamples; ++i) {
        const vec3 local = g::importanceSampleGGX(g::hammersley(i, kSamples), alpha);
        const vec3 h = glm::normalize(t * local.x + b * local.y + n * local.z);
        const vec3 l = 2.0f * glm::dot(v, h) * h - v;
        const float nol = glm::dot(n, l), noh = glm::dot(n, h), voh = glm::dot(v, h);
        if (nol <= 0.0f || noh <= 0.0f) continue;
        const double w = double(g::V_SmithGGXCorrelated(nov, nol, alpha)) * nol * 4.0 * voh / noh *
                         g::F_Schlick(0.04f, voh);
        sum += w * glm::dvec3(map.radiance(l));
        total += w;
    }
    return vec3(sum / total);
}

TEST(EnvironmentCones, EachLayerHoldsTheCapMeanOfTheMap) {
    const vct::EnvironmentMap& map = defaultSky();
    const vct::EnvironmentConeLayers layers = vct::environmentConeLayers(map);
    ASSERT_EQ(layers.width, map.width());  // the sky is 256 wide: layer 0 is level 0
    ASSERT_EQ(layers.count, 9u);           // caps up to π
    double worst = 0.0;
    for (uint32_t k : {1u, 3u, 5u, 7u, 8u})
        for (uint32_t y : {0u, 1u, 20u, 63u, 64u, 100u, 127u})
            for (uint32_t x : {0u, 77u, 200u}) {
                const vec3 d = texelDirection(map, x, y);
                // The builder's cap: θ_k, a hair wider so that texel centres exactly θ_k away count in.
                const double cosCap = std::cos(
                    std::min(3.14159265358979 * double(1u << k) / map.width(), 3.14159265358979) * 1.0001);
                // Every texel centre inside the cap, from level 0 (the layers take a coarser level for wide caps).
                const vec3 exact = weightedMean(map, [&](vec3 w) {
                    return glm::dot(glm::dvec3(w), glm::dvec3(d)) >= cosCap ? 1.0 : 0.0;
                });
                const double error =
                    std::abs(g::luminance(layers.texel(k, x, y)) / g::luminance(exact) - 1.0);
                worst = std::max(worst, error);
                EXPECT_LT(error, 0.025) << "layer " << k << " texel " << x << ", " << y;
            }
    std::printf("largest relative difference from the exact cap mean: %.4f\n", worst);
}

TEST(EnvironmentCones, AConstantMapReadsItsConstantAtEveryAperture) {
    const vec3 c(0.3f, 0.5f, 0.7f);
    const vct::EnvironmentConeLayers single = vct::environmentConeLayers(vct::constantEnvironment(c));
    EXPECT_EQ(single.count, 1u);
    const vct::EnvironmentConeLayers layers = vct::environmentConeLayers(uniformMap(64, 32, c));
    EXPECT_EQ(layers.count, 7u);
    // A file's size need not be a power of two: 1000 × 500 halves to 500, 250 (the layers' size), 125, 62, …
    const vct::EnvironmentConeLayers oddLayers = vct::environmentConeLayers(uniformMap(1000, 500, c));
    EXPECT_EQ(oddLayers.width, 250u);
    EXPECT_EQ(oddLayers.height, 125u);
    EXPECT_EQ(oddLayers.count, 9u);
    for (const auto* l : {&single, &layers, &oddLayers})
        for (float tanHalf : {0.0f, 0.01f, 0.3f, 0.577f, 1.0f, 50.0f})
            for (vec3 d : kNormals) {
                const vec3 read = vct::sampleEnvironmentCone(*l, d, tanHalf, 1.0f);
                EXPECT_NEAR(read.x, c.x, 1e-6f);
                EXPECT_NEAR(read.y, c.y, 1e-6f);
                EXPECT_NEAR(read.z, c.z, 1e-6f);
            }
}

TEST(EnvironmentCones, TheWidestLayerIsTheMapsMean) {
    const vct::EnvironmentMap& map = defaultSky();
    const vct::EnvironmentConeLayers layers = vct::environmentConeLayers(map);
    const float mean = g::luminance(map.meanRadiance());
    for (uint32_t y = 0; y < layers.height; y += 9)
        for (uint32_t x = 0; x < layers.width; x += 13)
            EXPECT_NEAR(g::luminance(layers.texel(layers.count - 1, x, y)) / mean, 1.0f, 1e-4f)
                << x << ", " << y;
}

// The six cones' sky light against the exact cosine-weighted mean. Measured (eight turns): 0.925 (the diagonal)
// to 1.021, facing up 0.975, rms 0.033. The map's own mips read the zenith as one 45° sector of the sky's cap, the
// one towards the sun: a surface facing up got 1.081, the diagonal 0.888, rms 0.056.
TEST(EnvironmentCones, SixConesUnderTheSkyGetItsIrradiance) {
    const vct::EnvironmentMap& map = defaultSky();
    const vct::EnvironmentConeLayers layers = vct::environmentConeLayers(map);
    double squares = 0.0;
    for (vec3 n : kNormals) {
        const vec3 exact = weightedMean(map, [&](vec3 d) { return std::max(double(glm::dot(d, n)), 0.0); });
        const double ratio = g::luminance(sixConeEstimate(layers, n)) / g::luminance(exact);
        std::printf("normal (%.2f %.2f %.2f): six cones / exact %.4f\n", n.x, n.y, n.z, ratio);
        EXPECT_GT(ratio, 0.915) << n.x << " " << n.y << " " << n.z;
        EXPECT_LT(ratio, 1.025) << n.x << " " << n.y << " " << n.z;
        squares += (ratio - 1.0) * (ratio - 1.0);
    }
    const double rms = std::sqrt(squares / double(std::size(kNormals)));
    std::printf("rms %.4f\n", rms);
    EXPECT_LT(rms, 0.037);
    // Facing up: the bug the layers fix.
    const vec3 up(0, 1, 0);
    const vec3 exactUp = weightedMean(map, [&](vec3 d) { return std::max(double(d.y), 0.0); });
    EXPECT_NEAR(g::luminance(sixConeEstimate(layers, up)) / g::luminance(exactUp), 1.0, 0.03);
}

// The specular estimate of an open surface against the GGX integral, rms over 7 normals × 4 view angles × 4
// azimuths per roughness. Measured: 0.007 / 0.032 / 0.061 / 0.105 / 0.075 at perceptual roughness 0.2 / 0.4 / 0.6 /
// 0.8 / 1.0. With the cone's own aperture instead of the lobe's equivalent cap (and the map's mips): 0.016 / 0.074 /
// 0.121 / 0.111 / 0.092; at 1.0 with the diffuse cones weighted by the lobe alone, also where the specular cone
// covers their tiles, 0.097. At 0.8 and above one cone (or six) cannot follow the lobe's shape: the cosine and
// Fresnel tilt it, and its tails reach the horizon.
TEST(EnvironmentCones, OpenSkySpecularFollowsTheGgxIntegral) {
    const vct::EnvironmentMap& map = defaultSky();
    const vct::EnvironmentConeLayers layers = vct::environmentConeLayers(map);
    const struct {
        float roughness, rms;
    } bounds[] = {{0.2f, 0.01f}, {0.4f, 0.035f}, {0.6f, 0.065f}, {0.8f, 0.11f}, {1.0f, 0.08f}};
    for (const auto& bound : bounds) {
        const float alpha = g::alphaFromPerceptual(bound.roughness);
        double squares = 0.0;
        int count = 0;
        for (vec3 n : kNormals) {
            const vec3 t = g::coneTangent(n), b = g::coneBitangent(n);
            for (float viewAngle : {0.0f, 30.0f, 60.0f, 80.0f})
                for (float azimuth : {0.0f, 90.0f, 180.0f, 270.0f}) {
                    const float th = glm::radians(viewAngle), ph = glm::radians(azimuth);
                    const vec3 v = glm::normalize(n * std::cos(th) +
                                                  std::sin(th) * (t * std::cos(ph) + b * std::sin(ph)));
                    const double ratio = g::luminance(specularEstimate(layers, n, v, alpha)) /
                                         g::luminance(ggxSpecular(map, n, v, alpha));
                    ASSERT_TRUE(std::isfinite(ratio));
                    squares += (ratio - 1.0) * (ratio - 1.0);
                    ++count;
                }
        }
        const double rms = std::sqrt(squares / count);
        std::printf("roughness %.1f: rms %.3f\n", double(bound.roughness), rms);
        EXPECT_LT(rms, bound.rms) << "roughness " << bound.roughness;
    }
}

// The specular cone's environment aperture: 0 for a mirror, the lobe's whole equivalent cap while the cone stands for
// all of the lobe (wider than the cone's half-maximum aperture: the tails), and finite for every roughness and view.
TEST(EnvironmentCones, SpecularEnvironmentApertureCoversTheLobe) {
    EXPECT_EQ(g::specularEnvironmentTanHalf(0.0f, 1.0f), 0.0f);
    float last = 0.0f;
    for (float roughness = 0.05f; roughness <= 1.0f; roughness += 0.05f) {
        const float alpha = g::alphaFromPerceptual(roughness);
        const float tanHalf = g::specularEnvironmentTanHalf(alpha, 1.0f);
        ASSERT_TRUE(std::isfinite(tanHalf)) << roughness;
        if (g::specularConeShare(alpha, 1.0f) >= 1.0f) {
            EXPECT_GT(tanHalf, 1.3f * g::specularConeTanHalf(alpha)) << roughness;
            EXPECT_GE(tanHalf, last) << roughness;
        }
        last = tanHalf;
        for (float nov : {0.0f, 1e-5f, 0.3f, 1.0f}) {
            const float t = g::specularEnvironmentTanHalf(alpha, nov);
            EXPECT_TRUE(std::isfinite(t) && t >= 0.0f) << roughness << " " << nov;
        }
    }
}

// A diffuse cone's tile outside the specular cone (the rest of a rough lobe, lib/cone.glsl): none of it while the tile
// (a cap of 30°) lies inside the specular cone's 45°, all of it from 75° off its axis, rising between.
TEST(EnvironmentCones, DiffuseTilesCountOutsideTheSpecularCone) {
    EXPECT_EQ(g::diffuseTileOutsideSpecularCone(1.0f), 0.0f);
    EXPECT_EQ(g::diffuseTileOutsideSpecularCone(std::cos(glm::radians(14.9f))), 0.0f);
    EXPECT_NEAR(g::diffuseTileOutsideSpecularCone(std::cos(glm::radians(45.0f))), 0.5f, 1e-4f);
    EXPECT_EQ(g::diffuseTileOutsideSpecularCone(std::cos(glm::radians(75.1f))), 1.0f);
    EXPECT_EQ(g::diffuseTileOutsideSpecularCone(-1.0f), 1.0f);
    EXPECT_EQ(g::diffuseTileOutsideSpecularCone(1.5f), 0.0f);  // rounding past 1: clamped, no NaN
    float last = 0.0f;
    for (float angle = 0.0f; angle <= 180.0f; angle += 1.0f) {
        const float share = g::diffuseTileOutsideSpecularCone(std::cos(glm::radians(angle)));
        EXPECT_GE(share, last) << angle;
        last = share;
    }
}

}  // namespace
