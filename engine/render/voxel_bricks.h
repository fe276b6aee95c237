// Sparse voxel storage (docs/design.md §5.10, shaders/lib/voxel_bricks.glsl): which bricks of VCT_VOXEL_BRICK³
// voxels get storage, and where. Computed once per grid on the CPU from the scene: every brick a static triangle
// can write (the voxelizer's own overlap test, on the brick's block with its apron) and every brick moving
// geometry can reach over the animation. The voxel passes never write outside them.
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <type_traits>
#include <vector>

#include "lib/shared.h"
#include "scene/scene.h"

// The voxel math of the shaders (shaders/lib/voxel.glsl, voxel_bricks.glsl) as C++, in namespace vct::glsl like
// render/shader_math.h (include guards keep the two compatible in one translation unit).
#include "lib/cpp_glsl.h"
namespace vct::glsl {
using namespace glm;
#include "lib/voxel.glsl"
#include "lib/voxel_bricks.glsl"
}  // namespace vct::glsl

namespace vct {

struct BrickLayout {
    uint32_t resolution = 0;     // N
    uint32_t bricksPerAxis = 0;  // N / VCT_VOXEL_BRICK
    // (N / VCT_VOXEL_BRICK)³ entries, brickLinearIndex order: the brick's index k, or VCT_BRICK_NONE.
    std::vector<uint32_t> map;
    std::vector<glm::uvec3> bricks;  // the allocated bricks' coordinates, k order (linear order)
    uint32_t atlasSide = 1;          // blocks per atlas row and column (lib/voxel_bricks.glsl)
    uint32_t atlasLayers = 1;        // layers of atlasSide² blocks

    uint32_t brickCount() const { return uint32_t(bricks.size()); }
    // What the shaders' brick table holds: the map, then each allocated brick packed x | y << 10 | z << 20.
    std::vector<uint32_t> table() const;
    // Share of the grid's bricks that have storage (0..1).
    double occupancy() const;
};

// The bricks the scene needs in the grid (origin, voxel size) of N³ voxels: those whose block (the brick and its
// apron) a static triangle overlaps, and those within a voxel of a moving instance's bounds at any time of the
// animation (sampled as voxelSceneBounds samples it).
BrickLayout allocateBricks(const Scene& scene, glm::vec4 originSize, uint32_t resolution);

// The atlas shape (side, layers) for `count` bricks: the smallest cube-like arrangement.
glm::uvec2 brickAtlasShape(uint32_t count);

// Calls visit(p0, p1, p2) with each triangle of the static instances at t = 0, in the voxel units of the grid at
// originSize (origin xyz, voxel size w), not snapped; visit(p0, p1, p2, instance, primitive, v) when it takes them too,
// v the triangle's three vertex indices into Scene::vertices.
template <typename Visit>
void forEachStaticTriangle(const Scene& scene, glm::vec4 originSize, Visit&& visit) {
    const glm::vec3 origin(originSize);
    const float voxelSize = originSize.w;
    for (const Instance& instance : scene.instances(0.0f)) {
        if (instance.moving || instance.mesh < 0) continue;
        for (uint32_t primitiveIndex : scene.meshes[size_t(instance.mesh)].primitives) {
            const Primitive& primitive = scene.primitives[primitiveIndex];
            for (uint32_t t = 0; t + 2 < primitive.indexCount; t += 3) {
                glm::vec3 p[3];
                glm::uvec3 vertex(0u);
                bool inside = true;  // the loader checks indices; a scene built in code might not
                for (int k = 0; k < 3; ++k) {
                    const int64_t v = int64_t(scene.indices[primitive.firstIndex + t + uint32_t(k)]) +
                                      primitive.vertexOffset;
                    inside = inside && v >= 0 && size_t(v) < scene.vertices.size();
                    if (!inside) break;
                    vertex[k] = uint32_t(v);
                    const glm::vec3 world =
                        glm::vec3(instance.world * glm::vec4(scene.vertices[size_t(v)].position, 1.0f));
                    p[k] = (world - origin) / voxelSize;
                }
                if (!inside) continue;
                if constexpr (std::is_invocable_v<Visit, glm::vec3, glm::vec3, glm::vec3, const Instance&,
                                                  const Primitive&, glm::uvec3>)
                    visit(p[0], p[1], p[2], instance, primitive, vertex);
                else
                    visit(p[0], p[1], p[2]);
            }
        }
    }
}

// Where cones close (shaders/lib/cone_trace.glsl's traceCone): a box whose every side is the face of `content` (what
// was voxelized) where geometry covers that face, as a closed room's floor, walls and ceiling do, and the grid's
// face elsewhere. The grid is a cube about the content's largest extent, so a room lower than it is wide has empty
// voxels below its floor and above its ceiling: a cone crossing either obliquely (a thin layer is opaque only in
// the slab across it) met nothing more there and saw the sky. A face counts as covered when
//  - at least kClosedFaceCoverage of the bricks of its layer, over the content's extent, have storage (what the
//    voxelizer writes; an opening narrower than a brick, a skylight among its rims, leaves it covered), and
//  - static geometry lies in the face's plane: a static triangle comes within kClosedFacePlaneTolerance voxels of
//    it in at least kClosedFaceInPlaneShare of the voxel columns across it. A convex object touches its box along
//    a line or at points, while the bricks of the face's layer, 8 voxels deep, hold its curved surface; a moving,
//    skinned or morphed object has bricks for all its bounds and never closes a side (a fixed box cannot follow
//    it). By bricks alone a lone skinned cylinder closed all six sides and its cones ended on its own box, 0.89× of
//    a white sky (round 26; docs/design.md §5.3).
//    Shares measured (tests/voxel_bricks_test.cpp, ConeClosure): rooms' faces ≥ 0.938 (the hall's roof with its
//    skylights), convex objects 8 voxels across or more ≤ 0.75. A room turned 1° off the grid's axes keeps its sides
//    closed at 64³ (0.935) but not at 128³ (0.460), nor turned 2° (0.468 at 64³): its cones then close at the grid.
struct ConeClosureBox {
    glm::vec3 min, max;
};
constexpr double kClosedFaceCoverage = 0.95;
constexpr double kClosedFaceInPlaneShare = 0.85;
constexpr double kClosedFacePlaneTolerance = 1.0;
ConeClosureBox coneClosureBox(const Scene& scene, const BrickLayout& layout, glm::vec4 originSize,
                              const Aabb& content);
// Per face of `content` (−x, +x, −y, +y, −z, +z): the share of the bricks of its layer, over the content's extent
// on the two other axes, that have storage.
std::array<double, 6> closureFacesBrickCoverage(const BrickLayout& layout, glm::vec4 originSize,
                                                const Aabb& content);
// Per face of `content` marked in `faces` (0 for the others): the share of the voxel columns across it, over the
// content's extent on the two other axes, in which a static triangle comes within kClosedFacePlaneTolerance voxels of
// the face's plane.
std::array<double, 6> closureFacesInPlaneShare(const Scene& scene, glm::vec4 originSize, const Aabb& content,
                                               std::array<bool, 6> faces);

}  // namespace vct
