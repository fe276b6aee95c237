// The voxel grid: the shared math of shaders/lib/voxel.glsl on the CPU (triangle/box overlap, closest point,
// coordinate conversions, grid fitting, fixed-point accumulation, the voxel cosine), and the voxelize /
// inject / mips passes end to end through `vct render` on lavapipe.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "render/voxel_grid.h"
#include "test_util.h"

namespace vct {
namespace {

namespace g = vct::glsl;
using glm::vec3;
using glm::vec4;

const vec3 kCenter(0.5f), kHalf(0.5f);  // the unit voxel [0,1]³

bool overlaps(vec3 a, vec3 b, vec3 c) {
    return g::triangleBoxOverlap(kCenter, kHalf, a, b, c);
}

TEST(VoxelOverlap, TriangleInsideAndThrough) {
    EXPECT_TRUE(overlaps(vec3(0.2f), vec3(0.8f, 0.2f, 0.2f), vec3(0.2f, 0.8f, 0.2f)));
    // Crosses the box, no vertex inside.
    EXPECT_TRUE(overlaps(vec3(-1.0f, -1.0f, 0.5f), vec3(3.0f, -1.0f, 0.5f), vec3(-1.0f, 3.0f, 0.5f)));
}

TEST(VoxelOverlap, TouchingCountsAsOverlap) {
    // In the plane z = 1 (the box's top face), and one touching only at the corner (1,1,1).
    EXPECT_TRUE(overlaps(vec3(0.0f, 0.0f, 1.0f), vec3(1.0f, 0.0f, 1.0f), vec3(0.0f, 1.0f, 1.0f)));
    EXPECT_TRUE(overlaps(vec3(1.0f), vec3(2.0f, 1.0f, 1.0f), vec3(1.0f, 2.0f, 1.0f)));
}

TEST(VoxelOverlap, Separated) {
    // Above the box.
    EXPECT_FALSE(overlaps(vec3(0.0f, 0.0f, 1.01f), vec3(1.0f, 0.0f, 1.01f), vec3(0.0f, 1.0f, 1.01f)));
    // Bounding boxes overlap, but the plane x+y+z = 3.1 passes beyond the corner (1,1,1).
    EXPECT_FALSE(overlaps(vec3(3.1f, 0.0f, 0.0f), vec3(0.0f, 3.1f, 0.0f), vec3(0.0f, 0.0f, 3.1f)));
    // A thin vertical sliver along x+y = 2.2, beside the box's vertical edge at (1,1).
    EXPECT_FALSE(overlaps(vec3(2.2f, 0.0f, 0.5f), vec3(0.0f, 2.2f, 0.5f), vec3(2.2f, 0.0f, 0.6f)));
}

TEST(VoxelOverlap, HugeTriangle) {
    const float big = 1e6f;
    EXPECT_TRUE(overlaps(vec3(-big, -big, 0.5f), vec3(big, -big, 0.5f), vec3(0.0f, big, 0.5f)));
    EXPECT_FALSE(overlaps(vec3(-big, -big, 2.0f), vec3(big, -big, 2.0f), vec3(0.0f, big, 2.0f)));
}

TEST(VoxelOverlap, DegenerateTrianglesGiveNoNaN) {
    // A point inside, a point outside, a segment through the box, a segment beside it.
    EXPECT_TRUE(overlaps(vec3(0.5f), vec3(0.5f), vec3(0.5f)));
    EXPECT_FALSE(overlaps(vec3(2.0f), vec3(2.0f), vec3(2.0f)));
    EXPECT_TRUE(overlaps(vec3(-1.0f, 0.5f, 0.5f), vec3(2.0f, 0.5f, 0.5f), vec3(0.5f, 0.5f, 0.5f)));
    EXPECT_FALSE(overlaps(vec3(-1.0f, 1.5f, 0.5f), vec3(2.0f, 1.5f, 0.5f), vec3(0.5f, 1.5f, 0.5f)));
    for (vec3 p : {vec3(0.5f), vec3(3.0f, -2.0f, 7.0f)}) {
        const vec3 point = g::closestPointBarycentric(p, vec3(1.0f), vec3(1.0f), vec3(1.0f));
        const vec3 segment = g::closestPointBarycentric(p, vec3(0.0f), vec3(1.0f), vec3(2.0f));
        for (vec3 b : {point, segment}) {
            EXPECT_TRUE(std::isfinite(b.x) && std::isfinite(b.y) && std::isfinite(b.z));
            EXPECT_NEAR(b.x + b.y + b.z, 1.0f, 1e-5f);
        }
    }
}

bool holds(vec3 a, vec3 b, vec3 c) {
    return g::voxelHoldsTriangle(kCenter, a, b, c);
}

// A large triangle in the plane m·p = k (m = (1, 1, 1) scaled or an axis), made of three points of it.
std::array<vec3, 3> planeTriangle(vec3 m, float k) {
    // Two directions in the plane, far out, so that the triangle covers any voxel near the origin.
    const vec3 u = glm::normalize(glm::cross(m, std::abs(m.x) < 0.9f ? vec3(1, 0, 0) : vec3(0, 1, 0)));
    const vec3 v = glm::cross(glm::normalize(m), u);
    const vec3 o = m * (k / glm::dot(m, m));
    return {o - 100.0f * u - 100.0f * v, o + 200.0f * u - 100.0f * v, o - 100.0f * u + 200.0f * v};
}

TEST(VoxelHolds, AxisAlignedAndSinglyTiltedPlanesKeepEveryVoxelTheyTouch) {
    // The voxel's top face, and a plane tilted about z through the voxel's edge region (x + y = 1.9: touches).
    EXPECT_TRUE(holds(vec3(0.0f, 0.0f, 1.0f), vec3(1.0f, 0.0f, 1.0f), vec3(0.0f, 1.0f, 1.0f)));
    const auto tilted = planeTriangle(vec3(1.0f, 1.0f, 0.0f), 1.9f);
    EXPECT_TRUE(overlaps(tilted[0], tilted[1], tilted[2]));
    EXPECT_TRUE(holds(tilted[0], tilted[1], tilted[2]));
    // Separated stays separated.
    EXPECT_FALSE(holds(vec3(0.0f, 0.0f, 1.01f), vec3(1.0f, 0.0f, 1.01f), vec3(0.0f, 1.0f, 1.01f)));
}

TEST(VoxelHolds, ADoublyObliquePlaneDropsTheVoxelsItCutsAtACorner) {
    // x + y + z = k touches the unit voxel for k in [0, 3]; it is held for |k − 1.5| ≤ ½(3 − 1) = 1.
    for (const auto& [k, held] :
         {std::pair{1.5f, true}, {2.45f, true}, {2.55f, false}, {2.9f, false}, {0.45f, false}}) {
        const auto t = planeTriangle(vec3(1.0f), k);
        EXPECT_TRUE(overlaps(t[0], t[1], t[2])) << k;
        EXPECT_EQ(holds(t[0], t[1], t[2]), held) << k;
    }
}

// Over a 12³ block, the voxels that hold the plane x + 2y + 3z = k: every line of voxels along an axis still meets at
// least one (the plane stays closed to rays along the axes), and each column along the dominant axis z holds
// (|m_z| + |m_y|)/|m_z| = 5/3 of them on average, against 6/3 that it touches.
TEST(VoxelHolds, ADoublyObliquePlaneStaysClosedAlongEveryAxis) {
    const vec3 m(1.0f, 2.0f, 3.0f);
    const float k = 36.3f;  // through the block's middle
    const auto t = planeTriangle(m, k);
    constexpr int n = 12;
    std::vector<uint8_t> held(n * n * n), touched(n * n * n);
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const vec3 c = vec3(x, y, z) + 0.5f;
                held[size_t((z * n + y) * n + x)] = g::voxelHoldsTriangle(c, t[0], t[1], t[2]);
                touched[size_t((z * n + y) * n + x)] = g::triangleBoxOverlap(c, kHalf, t[0], t[1], t[2]);
            }
    // Lines along each axis whose plane crossing lies well inside the block.
    size_t lines = 0, open = 0;
    for (int axis = 0; axis < 3; ++axis)
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                vec3 mid(0.0f);
                const int a = (axis + 1) % 3, b = (axis + 2) % 3;
                mid[a] = float(i) + 0.5f;
                mid[b] = float(j) + 0.5f;
                const float crossing = (k - m[a] * mid[a] - m[b] * mid[b]) / m[axis];
                if (crossing < 1.0f || crossing > float(n - 1)) continue;
                ++lines;
                bool met = false;
                for (int s = 0; s < n; ++s) {
                    glm::ivec3 v(0);
                    v[axis] = s;
                    v[a] = i;
                    v[b] = j;
                    met = met || held[size_t((v.z * n + v.y) * n + v.x)];
                }
                open += !met;
            }
    EXPECT_GT(lines, 100u);
    EXPECT_EQ(open, 0u);
    size_t columns = 0, heldCount = 0, touchedCount = 0;
    for (int y = 2; y < n - 2; ++y)
        for (int x = 2; x < n - 2; ++x) {
            const float crossing = (k - m.x * (float(x) + 0.5f) - m.y * (float(y) + 0.5f)) / m.z;
            if (crossing < 2.0f || crossing > float(n - 2)) continue;
            ++columns;
            for (int z = 0; z < n; ++z) {
                heldCount += held[size_t((z * n + y) * n + x)];
                touchedCount += touched[size_t((z * n + y) * n + x)];
            }
        }
    ASSERT_GT(columns, 20u);
    EXPECT_NEAR(double(heldCount) / double(columns), 5.0 / 3.0, 0.15);
    EXPECT_NEAR(double(touchedCount) / double(columns), 6.0 / 3.0, 0.15);
}

TEST(VoxelClosestPoint, InteriorAndVertex) {
    const vec3 a(0.0f), b(1.0f, 0.0f, 0.0f), c(0.0f, 1.0f, 0.0f);
    const vec3 inside = g::closestPointBarycentric(vec3(0.25f, 0.25f, 3.0f), a, b, c);
    EXPECT_NEAR(inside.y, 0.25f, 1e-6f);
    EXPECT_NEAR(inside.z, 0.25f, 1e-6f);
    const vec3 corner = g::closestPointBarycentric(vec3(2.0f, -1.0f, 0.0f), a, b, c);
    EXPECT_NEAR(corner.y, 1.0f, 1e-6f);
}

TEST(VoxelCoordinates, WorldVoxelRoundTrip) {
    const vec4 grid(-2.0f, 1.0f, 3.0f, 0.25f);
    const vec3 p(0.3f, 1.7f, 4.1f);
    const vec3 v = g::voxelFromWorld(p, grid);
    const vec3 back = g::worldFromVoxel(v, grid);
    EXPECT_NEAR(back.x, p.x, 1e-5f);
    EXPECT_NEAR(back.y, p.y, 1e-5f);
    EXPECT_NEAR(back.z, p.z, 1e-5f);
    // Texel centre of voxel i at origin + (i + 0.5)·size; its UVW is (i + 0.5) / N.
    const vec3 center = g::voxelCenterWorld(glm::ivec3(3, 0, 7), grid);
    EXPECT_NEAR(center.x, -2.0f + 3.5f * 0.25f, 1e-6f);
    EXPECT_NEAR(center.z, 3.0f + 7.5f * 0.25f, 1e-6f);
    const vec3 uvw = g::voxelUvw(center, grid, 16.0f);
    EXPECT_NEAR(uvw.x, 3.5f / 16.0f, 1e-6f);
    EXPECT_NEAR(uvw.y, 0.5f / 16.0f, 1e-6f);
    EXPECT_EQ(g::voxelLinearIndex(glm::ivec3(1, 2, 3), 4), 1u + 4u * (2u + 4u * 3u));
}

TEST(VoxelGridFit, CubeCoversBoundsWithPadding) {
    const vec3 lo(-1.0f, 0.0f, -3.0f), hi(1.0f, 2.0f, 5.0f);
    const vec4 grid = g::voxelGridFit(lo, hi, 64.0f);
    const vec3 gridMax = vec3(grid) + 64.0f * grid.w;
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_LE(grid[axis] + grid.w * 0.99f, lo[axis]);  // at least ~one voxel free below
        EXPECT_GE(gridMax[axis] - grid.w * 0.99f, hi[axis]);
    }
    EXPECT_NEAR(grid.w, 8.0f / 62.0f, 1e-6f);
}

TEST(VoxelGridFit, FlatSceneStaysValid) {
    // Zero extent on y (a plane), and a single point: positive, finite voxel size, bounds inside the grid.
    const std::pair<vec3, vec3> cases[] = {{vec3(-1.0f, 0.0f, -1.0f), vec3(1.0f, 0.0f, 1.0f)},
                                           {vec3(2.0f), vec3(2.0f)}};
    for (const auto& [lo, hi] : cases) {
        const vec4 grid = g::voxelGridFit(lo, hi, 32.0f);
        EXPECT_GT(grid.w, 0.0f);
        EXPECT_TRUE(std::isfinite(grid.x) && std::isfinite(grid.y) && std::isfinite(grid.z) &&
                    std::isfinite(grid.w));
        const vec3 v = g::voxelFromWorld(0.5f * (lo + hi), grid);
        for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(v[axis], 16.0f, 1e-3f);  // centred
    }
}

TEST(VoxelAccumulation, FixedPointAveragesAndSignedSums) {
    // Two normals that cancel plus one that does not: wrapping uint sums give the signed average.
    const uint32_t sum =
        g::voxelEncodeSigned(-1.0f) + g::voxelEncodeSigned(0.5f) + g::voxelEncodeSigned(-0.2f);
    EXPECT_NEAR(g::voxelDecodeSigned(sum, 3), (-1.0f + 0.5f - 0.2f) / 3.0f, 2e-3f);
    EXPECT_NEAR(g::voxelDecodeUnit(g::voxelEncodeUnit(0.3f) + g::voxelEncodeUnit(0.9f), 2), 0.6f, 1e-3f);
    EXPECT_NEAR(g::voxelDecodeEmission(g::voxelEncodeEmission(12.5f), 1), 12.5f, 1e-2f);
    EXPECT_EQ(g::voxelEncodeUnit(-3.0f), 0u);  // clamped, never wraps
}

TEST(VoxelCosine, OneSidedTwoSidedAndAmbiguous) {
    const vec3 l(0.0f, 0.0f, 1.0f);
    EXPECT_NEAR(g::voxelCosine(vec3(0.0f, 0.0f, 1.0f), l), 1.0f, 1e-6f);
    EXPECT_NEAR(g::voxelCosine(vec3(0.0f, 0.0f, -1.0f), l), 0.0f, 1e-6f);  // lit from behind: dark
    EXPECT_NEAR(g::voxelCosine(vec3(0.0f), l), 0.5f, 1e-6f);               // no direction left
    const float thinWall = g::voxelCosine(vec3(0.0f, 0.0f, -0.1f), l);     // both sides, barely agreeing
    EXPECT_GT(thinWall, 0.8f);
    EXPECT_TRUE(std::isfinite(thinWall));
}

// The share of a voxel's light a slab sends (lib/voxel.glsl's voxelFacing): on the axes the step it was before round
// 28 (1 in front and beside, 0 straight behind), between them 1 + n̂·ω behind, and two-sided as n̄ shortens.
TEST(VoxelFacing, StepOnTheAxesRampBehindAnObliqueNormal) {
    const vec3 up(0.0f, 0.0f, 1.0f);
    EXPECT_EQ(g::voxelFacing(up, vec3(0.0f, 0.0f, 1.0f)), 1.0f);
    EXPECT_EQ(g::voxelFacing(up, vec3(1.0f, 0.0f, 0.0f)), 1.0f);   // beside
    EXPECT_EQ(g::voxelFacing(up, vec3(0.0f, 0.0f, -1.0f)), 0.0f);  // straight behind
    // A wall turned 30° about y, normal (0.87, 0, 0.5): the light it sends towards +x is whole, towards −z half
    // (n̂·ω = −0.5), towards −x 0.13 (n̂·ω = −0.87).
    const vec3 turned(std::cos(glm::radians(30.0f)), 0.0f, std::sin(glm::radians(30.0f)));
    EXPECT_EQ(g::voxelFacing(turned, vec3(1.0f, 0.0f, 0.0f)), 1.0f);
    EXPECT_NEAR(g::voxelFacing(turned, vec3(0.0f, 0.0f, -1.0f)), 0.5f, 1e-6f);
    EXPECT_NEAR(g::voxelFacing(turned, vec3(-1.0f, 0.0f, 0.0f)), 1.0f - std::cos(glm::radians(30.0f)), 1e-6f);
    // Two-sided as the averaged normal shortens; no direction left: every side.
    EXPECT_NEAR(g::voxelFacing(0.5f * up, vec3(0.0f, 0.0f, -1.0f)), 0.5f, 1e-6f);
    EXPECT_EQ(g::voxelFacing(vec3(0.0f), vec3(0.0f, 0.0f, -1.0f)), 1.0f);
}

// One mip texel of a direction slab (voxel_mips.comp): each pair of children along the slab's direction
// composited front over back, the four pairs averaged, premultiplied.
TEST(VoxelMips, PremultipliedAverageOfPairsCompositedFrontToBack) {
    const vec4 lit(2.0f, 1.0f, 0.0f, 1.0f), empty(0.0f);
    // One lit voxel among eight: the average keeps its colour and a quarter of the opacity per pair covered.
    const vec4 m = g::voxelAverage4(g::voxelOver(lit, empty), g::voxelOver(empty, empty),
                                    g::voxelOver(empty, empty), g::voxelOver(empty, empty));
    EXPECT_NEAR(m.a, 0.25f, 1e-6f);
    EXPECT_NEAR(m.r / m.a, 2.0f, 1e-5f);  // un-premultiplied colour is the lit voxel's
    // An opaque voxel in front hides the one behind; behind empty space, the back one shows.
    const vec4 dark(0.0f, 0.0f, 0.0f, 1.0f);
    EXPECT_EQ(g::voxelOver(dark, lit), dark);
    EXPECT_EQ(g::voxelOver(empty, lit), lit);
    // A one-voxel wall across the direction stays opaque at the next mip; one along it covers half.
    EXPECT_NEAR(g::voxelAverage4(g::voxelOver(dark, empty), g::voxelOver(dark, empty),
                                 g::voxelOver(dark, empty), g::voxelOver(dark, empty))
                    .a,
                1.0f, 1e-6f);
    EXPECT_NEAR(g::voxelAverage4(g::voxelOver(dark, dark), g::voxelOver(dark, dark),
                                 g::voxelOver(empty, empty), g::voxelOver(empty, empty))
                    .a,
                0.5f, 1e-6f);
}

// ---- the passes on the GPU (lavapipe): cornell with a 32³ grid, validation on ----

TEST(VoxelPasses, CornellTimingsListVoxelPasses) {
    const auto dir = test::freshOutputDir("voxel_passes");
    const test::RunResult run = test::runVct({"render", "--scene", "cornell", "--size", "160x90", "--frames",
                                              "4", "--voxels", "32", "--validate", "--out", dir.string()});
    ASSERT_TRUE(run.exited()) << run.describe();
    ASSERT_EQ(run.exitCode, 0) << run.describe();
    std::ifstream file(dir / "timings.json");
    ASSERT_TRUE(file) << "no timings.json";
    const nlohmann::json timings = nlohmann::json::parse(file);
    std::set<std::string> seen;
    for (const auto& pass : timings.at("passes")) {
        const std::string name = pass.at("name");
        if (name != "voxelize" && name != "inject" && name != "mips") continue;
        seen.insert(name);
        EXPECT_GT(pass.at("median_ms").get<double>(), 0.0) << name;
    }
    EXPECT_EQ(seen, (std::set<std::string>{"voxelize", "inject", "mips"}));
}

TEST(VoxelPasses, BadResolutionIsAUsageError) {
    const auto dir = test::freshOutputDir("voxel_bad");
    const test::RunResult run =
        test::runVct({"render", "--frames", "1", "--voxels", "48", "--out", dir.string()});
    ASSERT_TRUE(run.exited()) << run.describe();
    EXPECT_EQ(run.exitCode, 2) << run.describe();
}

}  // namespace
}  // namespace vct
