#include "render/voxel_regions.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "lib/shared.h"

namespace vct {

namespace {

constexpr int kBrick = VCT_VOXEL_BRICK;

size_t linearIndex(glm::ivec3 v, int n) {
    return size_t(glsl::voxelLinearIndex(v, n));
}

bool insideGrid(glm::ivec3 v, int n) {
    return glm::all(glm::greaterThanEqual(v, glm::ivec3(0))) && glm::all(glm::lessThan(v, glm::ivec3(n)));
}

// Calls visit(voxel, m) for every voxel that holds a static triangle of the scene, as the voxelizer decides it
// (shaders/voxelize.comp: snapped vertices, voxelHoldsTriangle over the voxels of the triangle's bounds), once per
// triangle it holds: m the unit direction the triangle faces (its shading normals, transformed as normals are: the
// winding is not reliable, the renderer culls no faces; 0 where they cancel).
template <typename Visit>
void forEachStaticSurfaceVoxel(const Scene& scene, glm::vec4 originSize, int n, Visit&& visit) {
    // A large oblique triangle's bounds hold far more voxels than it does: whole bricks its box misses are skipped.
    const glm::vec3 brickHalf(0.5f * float(kBrick) + 1e-3f);
    forEachStaticTriangle(
        scene, originSize,
        [&](glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, const Instance& instance, const Primitive&,
            glm::uvec3 vertex) {
            const glm::vec3 a = glsl::voxelSnap(p0), b = glsl::voxelSnap(p1), c = glsl::voxelSnap(p2);
            const glm::vec3 low = glm::min(a, glm::min(b, c)), high = glm::max(a, glm::max(b, c));
            const glm::vec3 huge(1e30f);  // also false for NaN
            if (!glm::all(glm::lessThan(glm::abs(low), huge)) ||
                !glm::all(glm::lessThan(glm::abs(high), huge)))
                return;
            // Clamped before the conversion to int: a far-away vertex (below 1e30) would overflow it.
            const glm::vec3 edge = glm::vec3(float(n));
            const glm::ivec3 lo =
                glm::max(glm::ivec3(glm::floor(glm::clamp(low, glm::vec3(-1.0f), edge))), 0);
            const glm::ivec3 hi =
                glm::min(glm::ivec3(glm::floor(glm::clamp(high, glm::vec3(-1.0f), edge))), glm::ivec3(n - 1));
            if (glm::any(glm::greaterThan(lo, hi))) return;
            const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(instance.world)));
            glm::vec3 m = normalMatrix * (scene.vertices[vertex.x].normal + scene.vertices[vertex.y].normal +
                                          scene.vertices[vertex.z].normal);
            const float length = glm::length(m);
            m = length > 0.0f && std::isfinite(length) ? m / length : glm::vec3(0.0f);
            for (int bz = lo.z / kBrick; bz <= hi.z / kBrick; ++bz)
                for (int by = lo.y / kBrick; by <= hi.y / kBrick; ++by)
                    for (int bx = lo.x / kBrick; bx <= hi.x / kBrick; ++bx) {
                        const glm::ivec3 first = glm::ivec3(bx, by, bz) * kBrick;
                        if (!glsl::triangleBoxOverlap(glm::vec3(first) + 0.5f * float(kBrick), brickHalf, a,
                                                      b, c))
                            continue;
                        const glm::ivec3 from = glm::max(first, lo), to = glm::min(first + kBrick - 1, hi);
                        for (int z = from.z; z <= to.z; ++z)
                            for (int y = from.y; y <= to.y; ++y)
                                for (int x = from.x; x <= to.x; ++x)
                                    if (glsl::voxelHoldsTriangle(glm::vec3(x, y, z) + 0.5f, a, b, c))
                                        visit(glm::ivec3(x, y, z), m);
                    }
        });
}

}  // namespace

std::string VoxelRegions::summary() const {
    return std::to_string(components) + " regions of empty voxels, " + std::to_string(labelled) +
           " labelled, " + std::to_string(lightRegionsInClosure) + " open or lit inside the closure box: " +
           (needed() ? "cones end where they pass into another region" : "not needed");
}

std::vector<uint8_t> staticSurfaceVoxels(const Scene& scene, glm::vec4 originSize, uint32_t resolution) {
    const int n = int(resolution);
    std::vector<uint8_t> surface(size_t(n) * n * n, 0);
    forEachStaticSurfaceVoxel(scene, originSize, n,
                              [&](glm::ivec3 voxel, glm::vec3) { surface[linearIndex(voxel, n)] = 1; });
    return surface;
}

VoxelRegions labelVoxelRegions(const Scene& scene, glm::vec4 originSize, uint32_t resolution,
                               const ConeClosureBox& closure) {
    const int n = int(resolution);
    const size_t count = size_t(n) * n * n;
    const std::vector<uint8_t> surface = staticSurfaceVoxels(scene, originSize, resolution);

    // 6-connected components of the empty voxels: union-find over one pass in linear order, each voxel joined to
    // its −x, −y and −z neighbours (a set's root is its first voxel in that order), then a second pass that numbers
    // the roots as they come and gives every voxel its root's number. Memory-order passes: a breadth-first fill took
    // 1.25 s at 256³, this 0.2 s.
    constexpr uint32_t kNone = ~0u;
    std::vector<uint32_t> parent(count, kNone);
    auto find = [&](uint32_t i) {
        while (parent[i] != i) {
            parent[i] = parent[parent[i]];  // path halving
            i = parent[i];
        }
        return i;
    };
    auto unite = [&](uint32_t a, uint32_t b) {
        a = find(a);
        b = find(b);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
    };
    const uint32_t row = uint32_t(n), slice = uint32_t(n) * uint32_t(n);
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const uint32_t i = uint32_t(linearIndex({x, y, z}, n));
                if (surface[i]) continue;
                parent[i] = i;
                if (x > 0 && !surface[i - 1]) unite(i, i - 1);
                if (y > 0 && !surface[i - row]) unite(i, i - row);
                if (z > 0 && !surface[i - slice]) unite(i, i - slice);
            }
    std::vector<uint32_t> component(count, kNone);
    std::vector<uint32_t> size;
    std::vector<uint8_t> open;  // touches the grid's border
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const uint32_t i = uint32_t(linearIndex({x, y, z}, n));
                if (surface[i]) continue;
                const uint32_t root = find(i);
                if (root == i) {
                    component[i] = uint32_t(size.size());
                    size.push_back(0);
                    open.push_back(0);
                } else {
                    component[i] = component[root];  // the root comes first in this order
                }
                const uint32_t id = component[i];
                ++size[id];
                if (x == 0 || y == 0 || z == 0 || x == n - 1 || y == n - 1 || z == n - 1) open[id] = 1;
            }
    parent = {};
    const uint32_t components = uint32_t(size.size());

    // Lit: static surfaces face into it more than away from it. Each voxel that holds a surface looks one and a half
    // (else two and a half) voxels out along the surface's normal, in front and behind. A room's interior is faced by
    // its walls; a closed object's interior is faced away from by its sides, and faced only where it rests on a
    // floor (the floor under it). Double-sided materials too: their normals still say which side is the outside
    // (MetalRoughSpheresNoTextures' spheres, double-sided, counted on both sides made 98 lit regions at 128³).
    std::vector<uint64_t> front(components, 0), back(components, 0);
    forEachStaticSurfaceVoxel(scene, originSize, n, [&](glm::ivec3 voxel, glm::vec3 m) {
        if (m == glm::vec3(0.0f)) return;
        for (const float side : {1.0f, -1.0f})
            for (const float distance : {1.5f, 2.5f}) {
                const glm::ivec3 v(glm::floor(glm::vec3(voxel) + 0.5f + side * distance * m));
                if (!insideGrid(v, n)) break;
                const uint32_t id = component[linearIndex(v, n)];
                if (id == kNone) continue;
                ++(side > 0.0f ? front : back)[id];
                break;
            }
    });
    std::vector<uint8_t> lit(components, 0);
    for (uint32_t id = 0; id < components; ++id) lit[id] = front[id] > back[id] ? 1 : 0;

    // Inside the closure box: a voxel centre within it, in the grid's voxel units.
    const glm::vec3 origin(originSize);
    const glm::vec3 boxMin = (closure.min - origin) / originSize.w,
                    boxMax = (closure.max - origin) / originSize.w;
    std::vector<uint8_t> inClosure(components, 0);
    const glm::vec3 edge = glm::vec3(float(n));
    const glm::ivec3 lo =
        glm::clamp(glm::ivec3(glm::floor(glm::clamp(boxMin, glm::vec3(0.0f), edge))), 0, n - 1);
    const glm::ivec3 hi =
        glm::clamp(glm::ivec3(glm::floor(glm::clamp(boxMax, glm::vec3(0.0f), edge))), 0, n - 1);
    for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
            for (int x = lo.x; x <= hi.x; ++x) {
                const glm::vec3 centre = glm::vec3(x, y, z) + 0.5f;
                if (glm::any(glm::lessThan(centre, boxMin)) || glm::any(glm::greaterThan(centre, boxMax)))
                    continue;
                const uint32_t id = component[linearIndex({x, y, z}, n)];
                if (id != kNone) inClosure[id] = 1;
            }

    VoxelRegions regions;
    regions.resolution = resolution;
    regions.components = components;
    // Labels, the regions light comes from first, then by size; pockets too small keep 0.
    std::vector<uint32_t> order(components);
    std::iota(order.begin(), order.end(), 0u);
    auto matters = [&](uint32_t id) { return (open[id] || lit[id]) ? 1 : 0; };
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        return matters(a) != matters(b) ? matters(a) > matters(b) : size[a] > size[b];
    });
    std::vector<uint8_t> label(components, 0);
    for (uint32_t id : order) {
        if (size[id] < kMinRegionVoxels || regions.labelled >= kMaxRegionLabels) continue;
        label[id] = uint8_t(++regions.labelled);
        if (matters(id) && inClosure[id]) ++regions.lightRegionsInClosure;
    }
    regions.labels.resize(count, 0);
    for (size_t i = 0; i < count; ++i)
        if (component[i] != kNone) regions.labels[i] = label[component[i]];
    return regions;
}

}  // namespace vct
