// The shadow map's 3×3 PCF as four bilinear taps (shaders/lib/shadow_pcf.glsl, what direct.comp samples) against
// the nine bilinear taps it replaced, on the CPU through the same header: a bilinear depth-compare tap is
// emulated on a grid of compare results with clamp-to-edge addressing, as a sampler2DShadow with linear
// filtering evaluates it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "lib/cpp_glsl.h"

// Included here, not in render/shader_math.h: nothing on the CPU but this test uses the PCF taps.
namespace pcf {
using namespace glm;
#include "lib/shadow_pcf.glsl"
}  // namespace pcf

namespace {

using namespace glm;
using pcf::PcfTaps;
using pcf::pcfTaps;

// Compare results (1 lit, 0 shadowed) of a size×size shadow map.
struct CompareGrid {
    int size;
    std::vector<float> lit;
    float at(int x, int y) const {
        x = std::clamp(x, 0, size - 1);
        y = std::clamp(y, 0, size - 1);
        return lit[size_t(y * size + x)];
    }
    // A bilinear compare tap at t (texel-centre units).
    float bilinear(vec2 t) const {
        const int x = int(std::floor(t.x)), y = int(std::floor(t.y));
        const float fx = t.x - float(x), fy = t.y - float(y);
        return (1 - fx) * (1 - fy) * at(x, y) + fx * (1 - fy) * at(x + 1, y) + (1 - fx) * fy * at(x, y + 1) +
               fx * fy * at(x + 1, y + 1);
    }
    float nineTaps(vec2 t) const {
        float sum = 0;
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x) sum += bilinear(t + vec2(x, y));
        return sum / 9;
    }
    float fourTaps(vec2 t) const {
        const PcfTaps taps = pcfTaps(t);
        return (taps.firstWeight.x * taps.firstWeight.y * bilinear(taps.first) +
                taps.lastWeight.x * taps.firstWeight.y * bilinear(vec2(taps.last.x, taps.first.y)) +
                taps.firstWeight.x * taps.lastWeight.y * bilinear(vec2(taps.first.x, taps.last.y)) +
                taps.lastWeight.x * taps.lastWeight.y * bilinear(taps.last)) /
               9;
    }
};

TEST(ShadowPcf, TapsByHand) {
    // f = 0.5: both pairs weighted 1.5, taps 2/3 and 1/3 of the way along their pairs.
    const PcfTaps half = pcfTaps(vec2(10.5f, 3.5f));
    EXPECT_FLOAT_EQ(half.firstWeight.x, 1.5f);
    EXPECT_FLOAT_EQ(half.lastWeight.y, 1.5f);
    EXPECT_FLOAT_EQ(half.first.x, 9.0f + 2.0f / 3.0f);
    EXPECT_FLOAT_EQ(half.last.x, 11.0f + 1.0f / 3.0f);
    // f = 0 (on a texel centre): texels −1, 0, +1 weigh 1 each; the last tap sits on texel +1.
    const PcfTaps centre = pcfTaps(vec2(7.0f, 7.0f));
    EXPECT_FLOAT_EQ(centre.firstWeight.x, 2.0f);
    EXPECT_FLOAT_EQ(centre.first.x, 6.5f);
    EXPECT_FLOAT_EQ(centre.lastWeight.x, 1.0f);
    EXPECT_FLOAT_EQ(centre.last.x, 8.0f);
}

// Random maps of lit/shadowed texels (and an edge, and the map's border): the four taps give the nine taps'
// visibility to float rounding (measured: ≤ 4.8e-7; asserted 1e-5), and a wholly lit map gives 1 (to 1e-6).
TEST(ShadowPcf, FourTapsEqualNineTaps) {
    std::mt19937 rng(19);
    std::uniform_real_distribution<float> position(-1.0f, 17.0f);
    CompareGrid random{16, std::vector<float>(256)};
    for (float& lit : random.lit) lit = float(rng() & 1u);
    CompareGrid edge{16, std::vector<float>(256)};
    for (int i = 0; i < 256; ++i) edge.lit[size_t(i)] = (i % 16) + (i / 16) < 15 ? 1.0f : 0.0f;
    CompareGrid allLit{16, std::vector<float>(256, 1.0f)};
    float maxDifference = 0;
    int partial = 0;
    for (int i = 0; i < 4000; ++i) {
        const vec2 t(position(rng), position(rng));
        for (const CompareGrid* grid : {&random, &edge}) {
            const float nine = grid->nineTaps(t);
            maxDifference = std::max(maxDifference, std::abs(grid->fourTaps(t) - nine));
            partial += nine > 0.01f && nine < 0.99f;
        }
        EXPECT_NEAR(allLit.fourTaps(t), 1.0f, 1e-6f);
    }
    EXPECT_LE(maxDifference, 1e-5f);
    // Penumbrae, not only wholly lit or shadowed positions (measured: 5032 of 8000).
    EXPECT_GE(partial, 4000);
}

}  // namespace
