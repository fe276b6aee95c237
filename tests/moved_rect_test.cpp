// The rectangle of a raster target that moved instances can change (render/moved_rect.h): it holds the projection
// of the moved bounds with a texel of margin, is empty when nothing moved or the bounds fall outside the target,
// and asks for the whole target where a rectangle cannot be trusted (a corner behind a perspective eye, NaN) or
// saves little.
#include "render/moved_rect.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

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

}  // namespace
}  // namespace vct
