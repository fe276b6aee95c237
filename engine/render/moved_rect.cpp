#include "render/moved_rect.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vct {

namespace {

// Above this share of the target a rectangle saves little and the whole target is recomputed.
constexpr double kMaxRectShare = 0.5;

}  // namespace

std::optional<TexelRect> movedRect(const glm::mat4& viewProj, const Aabb& moved, glm::uvec2 size) {
    if (moved.empty()) return TexelRect{};
    const glm::vec2 extent(size);
    glm::vec2 low(std::numeric_limits<float>::max()), high(-std::numeric_limits<float>::max());
    for (int c = 0; c < 8; ++c) {
        const glm::vec3 corner((c & 1) ? moved.max.x : moved.min.x, (c & 2) ? moved.max.y : moved.min.y,
                               (c & 4) ? moved.max.z : moved.min.z);
        const glm::vec4 clip = viewProj * glm::vec4(corner, 1.0f);
        // At or behind the eye the projection is not the bounds' hull any more (and NaN fails the test too).
        if (!(clip.w > 1e-6f)) return std::nullopt;
        // The viewport's mapping (render/scene_draw.cpp): texel coordinates (ndc + 1)/2 · size on both axes.
        const glm::vec2 texel = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * extent;
        if (!std::isfinite(texel.x) || !std::isfinite(texel.y)) return std::nullopt;
        low = glm::min(low, texel);
        high = glm::max(high, texel);
    }
    // One texel of margin, then clamped to the target (in float first: a far corner may project anywhere).
    const glm::vec2 from = glm::clamp(glm::floor(low) - 1.0f, glm::vec2(0.0f), extent);
    const glm::vec2 to = glm::clamp(glm::ceil(high) + 1.0f, glm::vec2(0.0f), extent);
    const TexelRect rect{glm::ivec2(from), glm::ivec2(to)};
    if (rect.empty()) return TexelRect{};
    if (double(rect.area()) > kMaxRectShare * double(size.x) * double(size.y)) return std::nullopt;
    return rect;
}

}  // namespace vct
