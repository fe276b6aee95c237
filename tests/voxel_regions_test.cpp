// Closed regions of the static voxel grid (render/voxel_regions.h, docs/design.md §5.6), on the CPU: which scenes
// need them, what gets a label, and that the region a cone starts in and the one beyond a turned wall differ.
#include "render/voxel_regions.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <glm/gtc/quaternion.hpp>
#include <limits>

#include "render/voxel_grid.h"
#include "scene/builtin_scenes.h"
#include "scene_util.h"

namespace vct {
namespace {

namespace g = vct::glsl;

struct Labelled {
    VoxelRegions regions;
    glm::vec4 grid;  // origin, voxel size
};

// The regions a VoxelGrid of `scene` at n³ labels (its bounds, bricks and closure box).
Labelled regionsOf(const Scene& scene, uint32_t n) {
    const Aabb bounds = voxelSceneBounds(scene);
    const glm::vec4 grid = g::voxelGridFit(bounds.min, bounds.max, float(n));
    const BrickLayout bricks = allocateBricks(scene, grid, n);
    return {labelVoxelRegions(scene, grid, n, coneClosureBox(scene, bricks, grid, bounds)), grid};
}

// The label of the voxel holding world point p.
uint32_t labelAt(const Labelled& l, glm::vec3 p) {
    const glm::ivec3 v(glm::floor((p - glm::vec3(l.grid)) / l.grid.w));
    return l.regions.labels[g::voxelLinearIndex(v, int(l.regions.resolution))];
}

// A static scene turned by q about the origin (its one root node).
Scene turned(Scene scene, glm::quat q) {
    scene.nodes[0].rotation = q;
    return scene;
}

TEST(VoxelRegions, RoomsTheClosureBoxClosesAndOpenScenesNeedNone) {
    for (uint32_t n : {32u, 64u, 128u}) {
        // cornell: the room's walls are its closure box's faces; the outside never reaches into the box.
        const Labelled cornell = regionsOf(*makeBuiltinScene("cornell"), n);
        EXPECT_FALSE(cornell.regions.needed()) << n << ": " << cornell.regions.summary();
        EXPECT_EQ(cornell.regions.lightRegionsInClosure, 1u) << n;
        // The room and what lies outside it are apart all the same.
        const uint32_t room = labelAt(cornell, glm::vec3(0.0f, 1.5f, 0.0f));
        EXPECT_NE(room, 0u) << n;
        EXPECT_NE(room, cornell.regions.labels[0]) << n;  // the grid's corner, outside
        // The courtyard and the hall are open: one region light comes from (the box and the columns are closed
        // objects: faced away from, not lit).
        for (const char* name : {"courtyard", "hall"}) {
            const Labelled open = regionsOf(*makeBuiltinScene(name), n);
            EXPECT_FALSE(open.regions.needed()) << name << " " << n << ": " << open.regions.summary();
            EXPECT_EQ(open.regions.lightRegionsInClosure, 1u) << name << " " << n;
        }
    }
}

TEST(VoxelRegions, ATurnedRoomIsARegionApartFromWhatLiesOutside) {
    const glm::quat turns[] = {glm::angleAxis(glm::radians(30.0f), glm::vec3(0, 1, 0)),
                               glm::angleAxis(glm::radians(20.0f), glm::vec3(1, 0, 0)) *
                                   glm::angleAxis(glm::radians(30.0f), glm::vec3(0, 1, 0))};
    for (const glm::quat& q : turns)
        for (uint32_t n : {32u, 64u, 128u}) {
            const Labelled room = regionsOf(turned(test::scenes::furnaceRoom(0.0f, 1.0f), q), n);
            std::printf("turned furnace room at %u³: %s\n", n, room.regions.summary().c_str());
            EXPECT_TRUE(room.regions.needed()) << n;
            EXPECT_EQ(room.regions.lightRegionsInClosure, 2u) << n;
            // Its centre and the grid's corner: two labelled regions.
            const uint32_t inside = labelAt(room, glm::vec3(0.0f)), outside = room.regions.labels[0];
            EXPECT_NE(inside, 0u) << n;
            EXPECT_NE(outside, 0u) << n;
            EXPECT_NE(inside, outside) << n;
            // Just inside a wall (0.9 of the half-width along a turned axis) is still the room; just beyond the wall
            // (1.1) is outside, on the far side of the staircase of voxels.
            for (const glm::vec3 axis : {glm::vec3(1, 0, 0), glm::vec3(0, 0, 1), glm::vec3(0, 1, 0)}) {
                const float voxel = room.grid.w;
                EXPECT_EQ(labelAt(room, q * (axis * (1.0f - 1.5f * voxel))), inside) << n;
                EXPECT_EQ(labelAt(room, q * (axis * (1.0f + 1.5f * voxel))), outside) << n;
            }
        }
    // The built-in cornell-turned: the room and the outside.
    for (uint32_t n : {32u, 64u, 128u}) {
        const Labelled room = regionsOf(*makeBuiltinScene("cornell-turned"), n);
        EXPECT_TRUE(room.regions.needed()) << n << ": " << room.regions.summary();
        EXPECT_EQ(room.regions.lightRegionsInClosure, 2u) << n;
    }
    // Two rooms side by side sharing a wall of no thickness, turned: two lit rooms and the outside.
    for (uint32_t n : {32u, 64u}) {
        const Labelled rooms = regionsOf(turned(test::scenes::twoRooms(0.5f), turns[0]), n);
        EXPECT_TRUE(rooms.regions.needed()) << n;
        EXPECT_EQ(rooms.regions.lightRegionsInClosure, 3u) << n;
        const uint32_t left = labelAt(rooms, turns[0] * glm::vec3(-1.0f, 0, 0));
        const uint32_t right = labelAt(rooms, turns[0] * glm::vec3(1.0f, 0, 0));
        EXPECT_NE(left, 0u);
        EXPECT_NE(right, 0u);
        EXPECT_NE(left, right) << n;
    }
}

TEST(VoxelRegions, PocketsSmallerThanTheMinimumGetNoLabel) {
    // A closed box 0.2 m across inside the 2 m furnace room: 2 voxels inside at 32³ (a pocket, unlabelled), 7 at 128³
    // (a closed object of 343 voxels: labelled, not lit).
    Scene scene = test::scenes::furnaceRoom(0.5f, 0.0f);
    test::scenes::addClosedBox(scene, glm::vec3(-0.1f), glm::vec3(0.1f), 0);
    const Labelled small = regionsOf(scene, 32);
    EXPECT_EQ(labelAt(small, glm::vec3(0.0f)), 0u) << small.regions.summary();
    const Labelled large = regionsOf(scene, 128);
    EXPECT_NE(labelAt(large, glm::vec3(0.0f)), 0u) << large.regions.summary();
    EXPECT_NE(labelAt(large, glm::vec3(0.0f)), labelAt(large, glm::vec3(0.5f)));
}

TEST(VoxelRegions, NonFiniteAndFarAwayTrianglesHoldNoVoxel) {
    // Three quads in a 2 m grid of 32³: one at 1e29 m (beyond int), one with NaN corners, one degenerate (a point).
    Scene scene = test::scenes::emptyScene("hostile", test::scenes::diffuseMaterial(0.5f, 0.0f));
    test::scenes::addQuad(scene, glm::vec3(1e29f), glm::vec3(1e29f, 0, 0), glm::vec3(0, 1e29f, 0), 0);
    test::scenes::addQuad(scene, glm::vec3(0.0f), glm::vec3(0.5f, 0, 0), glm::vec3(0, 0.5f, 0), 0);
    for (size_t k = scene.vertices.size() - 4; k < scene.vertices.size(); ++k)
        scene.vertices[k].position.x = std::numeric_limits<float>::quiet_NaN();
    test::scenes::addQuad(scene, glm::vec3(0.25f), glm::vec3(0.0f), glm::vec3(0.0f), 0);
    const glm::vec4 grid(-1.0f, -1.0f, -1.0f, 2.0f / 32.0f);
    const std::vector<uint8_t> surface = staticSurfaceVoxels(scene, grid, 32);
    size_t held = 0;
    for (uint8_t v : surface) held += v;
    // The point holds the voxels it lies in (at most 8, on a corner: 0.25 m is 20 voxels in); nothing else.
    EXPECT_GE(held, 1u);
    EXPECT_LE(held, 8u);
    const VoxelRegions regions =
        labelVoxelRegions(scene, grid, 32, ConeClosureBox{glm::vec3(-1.0f), glm::vec3(1.0f)});
    EXPECT_EQ(regions.labels.size(), size_t(32 * 32 * 32));
    EXPECT_FALSE(regions.needed()) << regions.summary();
}

}  // namespace
}  // namespace vct
