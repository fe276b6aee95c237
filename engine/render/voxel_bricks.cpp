#include "render/voxel_bricks.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "lib/shared.h"

namespace vct {

namespace {

constexpr int kBrick = VCT_VOXEL_BRICK;

// The bricks whose block (voxels bB .. bB + B on each axis, the apron included) holds a voxel of [lo, hi].
struct BrickRange {
    glm::ivec3 min, max;  // inclusive
};
BrickRange bricksHolding(glm::ivec3 lo, glm::ivec3 hi, int bricksPerAxis) {
    // Voxel v is in brick v / B and, on a brick's lower face (v % B == 0), in the apron of the one below: the first
    // brick is (lo − 1) / B (lo ≥ 0; C++ division truncates, so lo = 0 gives brick 0).
    return {glm::max((lo - 1) / kBrick, glm::ivec3(0)), glm::min(hi / kBrick, glm::ivec3(bricksPerAxis - 1))};
}

// The bricks holding the voxels of voxel-space box [low, high] widened by one voxel, inside the N³ grid; false when
// the box misses the grid (or is not finite).
bool bricksAround(glm::vec3 low, glm::vec3 high, int n, int bricksPerAxis, BrickRange& range) {
    const glm::vec3 huge(1e30f);  // also false for NaN
    if (!glm::all(glm::lessThan(glm::abs(low), huge)) || !glm::all(glm::lessThan(glm::abs(high), huge)) ||
        !glm::all(glm::greaterThan(high, glm::vec3(-1.0f))) ||
        !glm::all(glm::lessThan(low, glm::vec3(float(n) + 1.0f))))
        return false;
    const glm::ivec3 lo = glm::max(glm::ivec3(glm::floor(low)) - 1, glm::ivec3(0));
    const glm::ivec3 hi = glm::min(glm::ivec3(glm::floor(high)) + 1, glm::ivec3(n - 1));
    if (glm::any(glm::greaterThan(lo, hi))) return false;
    range = bricksHolding(lo, hi, bricksPerAxis);
    return true;
}

// Samples of the animation for moving instances' bounds (as voxelSceneBounds).
constexpr int kAnimationSamples = 32;

}  // namespace

std::vector<uint32_t> BrickLayout::table() const {
    std::vector<uint32_t> out = map;
    out.reserve(map.size() + bricks.size());
    for (const glm::uvec3& b : bricks) out.push_back(b.x | (b.y << 10) | (b.z << 20));
    return out;
}

double BrickLayout::occupancy() const {
    return map.empty() ? 0.0 : double(bricks.size()) / double(map.size());
}

glm::uvec2 brickAtlasShape(uint32_t count) {
    const uint32_t blocks = std::max(count, 1u);
    uint32_t side = uint32_t(std::ceil(std::cbrt(double(blocks))));
    while (side > 1 && uint64_t(side - 1) * (side - 1) * (side - 1) >= blocks) --side;  // cbrt's rounding
    while (uint64_t(side) * side * side < blocks) ++side;
    const uint32_t layers = (blocks + side * side - 1) / (side * side);
    return {side, layers};
}

BrickLayout allocateBricks(const Scene& scene, glm::vec4 originSize, uint32_t resolution) {
    BrickLayout layout;
    layout.resolution = resolution;
    const int perAxis = int(resolution) / kBrick;
    layout.bricksPerAxis = uint32_t(perAxis);
    std::vector<uint8_t> needed(size_t(perAxis) * perAxis * perAxis, 0);
    auto mark = [&](glm::ivec3 b) { needed[glsl::brickLinearIndex(b, perAxis)] = 1; };
    const glm::vec3 origin(originSize);
    const float voxelSize = originSize.w;
    const int n = int(resolution);

    // Static triangles: the voxelizer's loop (shaders/voxelize.comp) visits the voxels of the triangle's bounds
    // and keeps those its box overlaps; a brick's block holds such a voxel only if the block's box overlaps the
    // triangle too. The test's box is widened a little for the CPU's and GPU's rounding.
    constexpr float kSlack = 1e-3f;
    const glm::vec3 blockHalf(0.5f * float(kBrick + 1) + kSlack);
    forEachStaticTriangle(scene, originSize, [&](glm::vec3 p0, glm::vec3 p1, glm::vec3 p2) {
        BrickRange range;
        if (!bricksAround(glm::min(p0, glm::min(p1, p2)), glm::max(p0, glm::max(p1, p2)), n, perAxis, range))
            return;
        for (int z = range.min.z; z <= range.max.z; ++z)
            for (int y = range.min.y; y <= range.max.y; ++y)
                for (int x = range.min.x; x <= range.max.x; ++x) {
                    const glm::vec3 centre = glm::vec3(x, y, z) * float(kBrick) + 0.5f * float(kBrick + 1);
                    if (glsl::triangleBoxOverlap(centre, blockHalf, p0, p1, p2)) mark(glm::ivec3(x, y, z));
                }
    });

    // Moving instances: every brick within a voxel of the box around their bounds at two consecutive sampled times
    // (what they sweep between the samples, for motion along a line; a fast object would otherwise jump over
    // bricks between samples, and its voxels there would have no storage).
    auto markBox = [&](const Aabb& box) {
        BrickRange range;
        if (!bricksAround((box.min - origin) / voxelSize, (box.max - origin) / voxelSize, n, perAxis, range))
            return;
        for (int z = range.min.z; z <= range.max.z; ++z)
            for (int y = range.min.y; y <= range.max.y; ++y)
                for (int x = range.min.x; x <= range.max.x; ++x) mark(glm::ivec3(x, y, z));
    };
    float duration = 0.0f;
    for (const Animation& animation : scene.animations) duration = std::max(duration, animation.duration);
    std::vector<Aabb> previous;  // each instance's bounds at the last sample (empty: not moving)
    for (int s = 0; s <= (duration > 0.0f ? kAnimationSamples : 0); ++s) {
        const std::vector<Instance> instances =
            scene.instances(duration * float(s) / float(kAnimationSamples));
        previous.resize(instances.size());
        for (size_t i = 0; i < instances.size(); ++i) {
            const Instance& instance = instances[i];
            if (!instance.moving || instance.bounds.empty()) continue;
            Aabb swept = instance.bounds;
            swept.extend(previous[i]);
            markBox(swept);
            previous[i] = instance.bounds;
        }
    }

    layout.map.assign(needed.size(), VCT_BRICK_NONE);
    for (int z = 0; z < perAxis; ++z)
        for (int y = 0; y < perAxis; ++y)
            for (int x = 0; x < perAxis; ++x) {
                const uint32_t i = glsl::brickLinearIndex(glm::ivec3(x, y, z), perAxis);
                if (!needed[i]) continue;
                layout.map[i] = uint32_t(layout.bricks.size());
                layout.bricks.push_back(glm::uvec3(x, y, z));
            }
    const glm::uvec2 shape = brickAtlasShape(layout.brickCount());
    layout.atlasSide = shape.x;
    layout.atlasLayers = shape.y;
    return layout;
}

std::array<double, 6> closureFacesBrickCoverage(const BrickLayout& layout, glm::vec4 originSize,
                                                const Aabb& content) {
    std::array<double, 6> coverage{};
    if (content.empty() || layout.bricksPerAxis == 0) return coverage;
    const glm::vec3 origin(originSize);
    const float voxelSize = originSize.w;
    const int perAxis = int(layout.bricksPerAxis);
    const auto brickOf = [&](float world, int axis) {
        const int voxel = int(std::floor((world - origin[axis]) / voxelSize));
        return std::clamp(voxel, 0, int(layout.resolution) - 1) / kBrick;
    };
    for (int face = 0; face < 6; ++face) {
        const int axis = face / 2, u = (axis + 1) % 3, v = (axis + 2) % 3;
        const int uLast = brickOf(content.max[u], u), vLast = brickOf(content.max[v], v);
        glm::ivec3 b(0);
        b[axis] = brickOf(face % 2 == 0 ? content.min[axis] : content.max[axis], axis);
        uint64_t covered = 0, total = 0;
        for (b[v] = brickOf(content.min[v], v); b[v] <= vLast; ++b[v])
            for (b[u] = brickOf(content.min[u], u); b[u] <= uLast; ++b[u]) {
                ++total;
                covered += layout.map[glsl::brickLinearIndex(b, perAxis)] != VCT_BRICK_NONE ? 1 : 0;
            }
        coverage[size_t(face)] = total ? double(covered) / double(total) : 0.0;
    }
    return coverage;
}

std::array<double, 6> closureFacesInPlaneShare(const Scene& scene, glm::vec4 originSize, const Aabb& content,
                                               std::array<bool, 6> faces) {
    std::array<double, 6> share{};
    if (content.empty() || !std::any_of(faces.begin(), faces.end(), [](bool f) { return f; })) return share;
    const glm::vec3 lo = (content.min - glm::vec3(originSize)) / originSize.w;
    const glm::vec3 hi = (content.max - glm::vec3(originSize)) / originSize.w;
    // The cells of each face: the voxel columns across it that the content's extent on its two other axes reaches
    // (a bound on a voxel boundary, to rounding, adds no column beyond it).
    constexpr float kRounding = 1e-3f;
    const glm::ivec3 first(glm::floor(lo + kRounding));
    const glm::ivec3 count = glm::max(glm::ivec3(glm::ceil(hi - kRounding)) - first, glm::ivec3(1));
    std::array<std::vector<uint8_t>, 6> cells;
    for (int face = 0; face < 6; ++face) {
        const int axis = face / 2, u = (axis + 1) % 3, v = (axis + 2) % 3;
        if (faces[size_t(face)]) cells[size_t(face)].assign(size_t(count[u]) * size_t(count[v]), 0);
    }
    forEachStaticTriangle(scene, originSize, [&](glm::vec3 p0, glm::vec3 p1, glm::vec3 p2) {
        const glm::vec3 low = glm::min(p0, glm::min(p1, p2)), high = glm::max(p0, glm::max(p1, p2));
        const float huge = 1e7f;  // voxel units; also false for NaN
        if (!glm::all(glm::lessThan(glm::abs(low), glm::vec3(huge))) ||
            !glm::all(glm::lessThan(glm::abs(high), glm::vec3(huge))))
            return;
        for (int face = 0; face < 6; ++face) {
            if (!faces[size_t(face)]) continue;
            const int axis = face / 2, u = (axis + 1) % 3, v = (axis + 2) % 3;
            const float plane = face % 2 == 0 ? lo[axis] : hi[axis];
            // A cell is the voxel column across the face, kClosedFacePlaneTolerance voxels either side of its plane.
            glm::vec3 half(0.5f);
            half[axis] = float(kClosedFacePlaneTolerance);
            if (low[axis] > plane + half[axis] || high[axis] < plane - half[axis]) continue;
            const int u0 = std::max(int(std::floor(low[u])) - first[u], 0);
            const int u1 = std::min(int(std::floor(high[u])) - first[u], count[u] - 1);
            const int v0 = std::max(int(std::floor(low[v])) - first[v], 0);
            const int v1 = std::min(int(std::floor(high[v])) - first[v], count[v] - 1);
            for (int j = v0; j <= v1; ++j)
                for (int i = u0; i <= u1; ++i) {
                    uint8_t& cell = cells[size_t(face)][size_t(j) * size_t(count[u]) + size_t(i)];
                    if (cell) continue;
                    glm::vec3 centre;
                    centre[axis] = plane;
                    centre[u] = float(first[u] + i) + 0.5f;
                    centre[v] = float(first[v] + j) + 0.5f;
                    cell = glsl::triangleBoxOverlap(centre, half, p0, p1, p2) ? 1 : 0;
                }
        }
    });
    for (int face = 0; face < 6; ++face) {
        const std::vector<uint8_t>& c = cells[size_t(face)];
        if (!c.empty())
            share[size_t(face)] = double(std::count(c.begin(), c.end(), uint8_t(1))) / double(c.size());
    }
    return share;
}

ConeClosureBox coneClosureBox(const Scene& scene, const BrickLayout& layout, glm::vec4 originSize,
                              const Aabb& content) {
    const glm::vec3 origin(originSize);
    ConeClosureBox box{origin, origin + glm::vec3(originSize.w * float(layout.resolution))};
    if (content.empty() || layout.bricksPerAxis == 0) return box;
    const std::array<double, 6> bricks = closureFacesBrickCoverage(layout, originSize, content);
    std::array<bool, 6> covered{};
    for (int face = 0; face < 6; ++face) covered[size_t(face)] = bricks[size_t(face)] >= kClosedFaceCoverage;
    // The in-plane test only where the bricks cover the face (most sides of most scenes fail that first).
    const std::array<double, 6> inPlane = closureFacesInPlaneShare(scene, originSize, content, covered);
    for (int face = 0; face < 6; ++face) {
        if (!covered[size_t(face)] || inPlane[size_t(face)] < kClosedFaceInPlaneShare) continue;
        const int axis = face / 2;
        if (face % 2 == 0)
            box.min[axis] = content.min[axis];
        else
            box.max[axis] = content.max[axis];
    }
    return box;
}

}  // namespace vct
