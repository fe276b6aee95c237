// The rectangle of a raster target that moved instances can change (render/moved_rect.h): it holds the projection
// of the moved bounds with a texel of margin, is empty when nothing moved or the bounds fall outside the target,
// and asks for the whole target where a rectangle cannot be trusted (a corner behind a perspective eye, NaN) or
// saves little.
#include "render/moved_rect.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <random>

namespace vct {
namespace {

constexpr uint32_t kSize = 2048;

// A sun straight down over a 20 m square: world x, z ∈ [−10, 10] fill the map.
glm::mat4 sunDown() {
    const glm::mat4 view = glm::lookAt(glm::vec3(0, 20, 0), glm::vec3(0), glm::vec3(0, 0, 1));
    return glm::ortho(-10.0f, 10.0f, -10.0f, 10.0f, 1.0f, 40.0f) * view;
}

// Texel coordinates of a world point, as the rasterizer places it.
glm::vec2 texelOf(const glm::mat4& m, glm::vec3 p) {
    const glm::vec4 clip = m * glm::vec4(p, 1.0f);
    return (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * float(kSize);
}

TEST(MovedRect, RectangleHoldsTheMovedBoundsWithATexelOfMargin) {
    const glm::mat4 m = sunDown();
    const Aabb moved = Aabb{glm::vec3(1.0f, 0.0f, 2.0f), glm::vec3(2.0f, 1.0f, 2.5f)};
    const std::optional<TexelRect> rect = movedRect(m, moved, glm::uvec2(kSize));
    ASSERT_TRUE(rect);
    ASSERT_FALSE(rect->empty());
    // Every point of the bounds (a grid of them, corners included) lands inside, a texel in from the edge.
    for (float x = 1.0f; x <= 2.0f; x += 0.25f)
        for (float y = 0.0f; y <= 1.0f; y += 0.5f)
            for (float z = 2.0f; z <= 2.5f; z += 0.125f) {
                const glm::vec2 t = texelOf(m, glm::vec3(x, y, z));
                EXPECT_GE(t.x, float(rect->min.x + 1));
                EXPECT_GE(t.y, float(rect->min.y + 1));
                EXPECT_LE(t.x, float(rect->max.x - 1));
                EXPECT_LE(t.y, float(rect->max.y - 1));
            }
    // And no more than that: 1 m × 0.5 m is 102.4 × 51.2 texels, plus at most 2 + 2 per axis.
    EXPECT_LE(rect->max.x - rect->min.x, 107);
    EXPECT_LE(rect->max.y - rect->min.y, 56);
}

TEST(MovedRect, NothingMovedOrMovedOutsideTheMapRedrawsNothing) {
    const glm::mat4 m = sunDown();
    const std::optional<TexelRect> none = movedRect(m, Aabb{}, glm::uvec2(kSize));
    ASSERT_TRUE(none);
    EXPECT_TRUE(none->empty());
    const std::optional<TexelRect> outside =
        movedRect(m, Aabb{glm::vec3(30.0f, 0.0f, 0.0f), glm::vec3(31.0f, 1.0f, 1.0f)}, glm::uvec2(kSize));
    ASSERT_TRUE(outside);
    EXPECT_TRUE(outside->empty());
}

TEST(MovedRect, PartlyOutsideIsClampedToTheMap) {
    const std::optional<TexelRect> rect = movedRect(
        sunDown(), Aabb{glm::vec3(9.5f, 0.0f, -1.0f), glm::vec3(12.0f, 1.0f, 0.0f)}, glm::uvec2(kSize));
    ASSERT_TRUE(rect);
    ASSERT_FALSE(rect->empty());
    EXPECT_GE(rect->min.x, 0);
    EXPECT_GE(rect->min.y, 0);
    EXPECT_LE(rect->max.x, int(kSize));
    EXPECT_LE(rect->max.y, int(kSize));
}

TEST(MovedRect, WholeMapWhereARectangleCannotBeTrustedOrSavesLittle) {
    // A spot light at the origin looking down −z: a box reaching behind it.
    const glm::mat4 spot = glm::perspective(1.0f, 1.0f, 0.01f, 50.0f) *
                           glm::lookAt(glm::vec3(0.0f), glm::vec3(0, 0, -1), glm::vec3(0, 1, 0));
    EXPECT_FALSE(movedRect(spot, Aabb{glm::vec3(-1, -1, -2), glm::vec3(1, 1, 1)}, glm::uvec2(kSize)));
    // In front of it the rectangle is fine.
    EXPECT_TRUE(movedRect(spot, Aabb{glm::vec3(-0.1f, -0.1f, -5.0f), glm::vec3(0.1f, 0.1f, -4.0f)},
                          glm::uvec2(kSize)));
    // A NaN projection.
    glm::mat4 broken = sunDown();
    broken[0][0] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(movedRect(broken, Aabb{glm::vec3(0.0f), glm::vec3(1.0f)}, glm::uvec2(kSize)));
    // Bounds over most of the map.
    EXPECT_FALSE(movedRect(sunDown(), Aabb{glm::vec3(-9, 0, -9), glm::vec3(9, 1, 9)}, glm::uvec2(kSize)));
}

TEST(MovedRect, ACameraTargetIsNotSquare) {
    // A camera at z = 5 looking at the origin, 640×360: a small box at the centre lands at the centre.
    const glm::mat4 camera = glm::perspective(1.0f, 640.0f / 360.0f, 0.1f, 100.0f) *
                             glm::lookAt(glm::vec3(0, 0, 5), glm::vec3(0.0f), glm::vec3(0, 1, 0));
    const std::optional<TexelRect> rect =
        movedRect(camera, Aabb{glm::vec3(-0.05f), glm::vec3(0.05f)}, glm::uvec2(640, 360));
    ASSERT_TRUE(rect);
    ASSERT_FALSE(rect->empty());
    EXPECT_TRUE(rect->contains(glm::ivec2(320, 180)));
    EXPECT_FALSE(rect->contains(glm::ivec2(10, 10)));
    EXPECT_LE(rect->max.x, 640);
    EXPECT_LE(rect->max.y, 360);
}

// lib/shadow_lookup.glsl's test, on the CPU: whether the lookup at p (normal n) reads a texel of `rect`.
bool lookupReads(const glm::mat4& light, glm::vec3 p, glm::vec3 n, float offset, const TexelRect& rect) {
    const glm::vec4 clip = light * glm::vec4(p + n * offset * 1.5f, 1.0f);
    if (clip.w <= 0.0f) return false;
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    const glm::vec2 uv = glm::vec2(ndc) * 0.5f + 0.5f;
    if (uv.x < 0.0f || uv.y < 0.0f || uv.x > 1.0f || uv.y > 1.0f || ndc.z >= 1.0f) return false;
    const glm::vec2 t = uv * float(kSize) - 0.5f;
    const glm::ivec2 first = glm::ivec2(glm::floor(t)) - 1, last = first + 3;
    return first.x < rect.max.x && first.y < rect.max.y && last.x >= rect.min.x && last.y >= rect.min.y;
}

// Every surface point whose shadow lookup reads the redrawn texels projects into the rectangle: points drawn at
// random in the surfaces' bounds with random normals, under the sun and under a spot light, the camera looking on.
// The rectangle is no larger than needed by more than the column's slant: measured below.
TEST(ShadowReadersRect, HoldsEveryPixelWhoseLookupReadsTheTexels) {
    const glm::mat4 camera = glm::perspective(1.0f, 640.0f / 360.0f, 0.1f, 100.0f) *
                             glm::lookAt(glm::vec3(0, 6, 14), glm::vec3(0.0f), glm::vec3(0, 1, 0));
    const glm::uvec2 size(640, 360);
    const glm::mat4 spot = glm::perspective(1.2f, 1.0f, 0.5f, 40.0f) *
                           glm::lookAt(glm::vec3(2, 12, 1), glm::vec3(0.0f), glm::vec3(0, 0, 1));
    const Aabb low{glm::vec3(-5, 0, -5), glm::vec3(5, 3, 5)};
    // A room whose ceiling is above the spot light: the column is the pyramid from the light's eye.
    const Aabb room{glm::vec3(-5, 0, -5), glm::vec3(5, 14, 5)};
    const TexelRect texels{glm::ivec2(1000, 980), glm::ivec2(1060, 1050)};
    const float offset = 20.0f / kSize;
    for (const auto& [light, surfaces] :
         {std::pair{sunDown(), low}, std::pair{spot, low}, std::pair{spot, room}}) {
        const std::optional<TexelRect> rect =
            shadowReadersRect(camera, size, light, texels, glm::uvec2(kSize), surfaces, offset);
        ASSERT_TRUE(rect);
        ASSERT_FALSE(rect->empty());
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        int reading = 0;
        for (int i = 0; i < 400000; ++i) {
            const glm::vec3 p =
                glm::mix(surfaces.min, surfaces.max, glm::vec3(unit(rng), unit(rng), unit(rng)));
            const float z = 2.0f * unit(rng) - 1.0f, phi = 6.2831853f * unit(rng);
            const float s = std::sqrt(1.0f - z * z);
            const glm::vec3 n(s * std::cos(phi), z, s * std::sin(phi));
            if (!lookupReads(light, p, n, offset, texels)) continue;
            const glm::vec4 clip = camera * glm::vec4(p, 1.0f);
            const glm::ivec2 pixel(glm::floor((glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(size)));
            if (!TexelRect{glm::ivec2(0), glm::ivec2(size)}.contains(pixel)) continue;  // off the image
            ++reading;
            EXPECT_TRUE(rect->contains(pixel)) << pixel.x << " " << pixel.y;
        }
        std::printf("%d points in the image read the texels; rectangle %d..%d × %d..%d\n", reading,
                    rect->min.x, rect->max.x, rect->min.y, rect->max.y);
        EXPECT_GT(reading, 100);  // the test sees points that read the texels
        // A column of 60 × 70 texels (0.6 × 0.7 m under the sun) over 3 m of height: a narrow part of the image.
        EXPECT_LE(double(rect->area()), 0.12 * size.x * size.y);
    }
    // Nothing redrawn, or every surface behind the light: nothing to recompute.
    for (const auto& [redrawn, surfaces] :
         {std::pair{TexelRect{}, low}, std::pair{texels, Aabb{glm::vec3(-5, 13, -5), glm::vec3(5, 14, 5)}}}) {
        const std::optional<TexelRect> none =
            shadowReadersRect(camera, size, spot, redrawn, glm::uvec2(kSize), surfaces, offset);
        ASSERT_TRUE(none);
        EXPECT_TRUE(none->empty());
    }
}

}  // namespace
}  // namespace vct
