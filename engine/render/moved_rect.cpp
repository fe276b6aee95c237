#include "render/moved_rect.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vct {

ViewInputs viewInputsOf(const gpu::FrameUniforms& u) {
    ViewInputs view{};
    view.cameraPosition = glm::vec4(u.cameraPosition, 0.0f);
    view.imageSize = glm::vec4(u.imageSize, u.texelSize);
    view.flags = u.flags;
    return view;
}

std::optional<TexelRect> movedRect(const glm::mat4& viewProj, const Aabb& moved, glm::uvec2 size,
                                   double maxShare) {
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
    if (double(rect.area()) > maxShare * double(size.x) * double(size.y)) return std::nullopt;
    return rect;
}

std::optional<TexelRect> shadowReadersRect(const glm::mat4& viewProj, glm::uvec2 size,
                                           const glm::mat4& lightViewProj, const TexelRect& texels,
                                           glm::uvec2 shadowSize, const Aabb& surfaces, float normalOffset) {
    if (texels.empty() || surfaces.empty()) return TexelRect{};
    // The lookup's point q is the surface point p pushed along its normal by 1.5 × the offset (a tenth more for the
    // shader's rounding): q lies within `reach` of the surfaces, p within `reach` of the column that q lies in.
    const float reach = 1.65f * normalOffset;
    const Aabb points{surfaces.min - reach, surfaces.max + reach};
    // The points' depth range in the light's clip space, of those in front of it (a lookup behind the light reads
    // nothing; one at depth ≥ 1 neither). Depth grows with the distance along the light's view axis, which is
    // linear in the world: its extremes over a box are at corners.
    float depthLow = std::numeric_limits<float>::max(), depthHigh = -std::numeric_limits<float>::max();
    bool behind = false;
    for (int c = 0; c < 8; ++c) {
        const glm::vec3 corner((c & 1) ? points.max.x : points.min.x, (c & 2) ? points.max.y : points.min.y,
                               (c & 4) ? points.max.z : points.min.z);
        const glm::vec4 clip = lightViewProj * glm::vec4(corner, 1.0f);
        if (!std::isfinite(clip.w) || !std::isfinite(clip.z)) return std::nullopt;
        if (!(clip.w > 1e-6f)) {
            behind = true;
            continue;
        }
        const float depth = clip.z / clip.w;
        depthLow = std::min(depthLow, depth);
        depthHigh = std::max(depthHigh, depth);
    }
    if (depthLow > depthHigh) return TexelRect{};  // every point behind the light
    depthHigh = std::min(depthHigh, 1.0f);
    // A lookup reads the texels ⌊t⌋ − 1 … ⌊t⌋ + 2, t = uv · size − 0.5: it reads `texels` for t in
    // [min − 2, max + 1), uv in [(min − 1.5), (max + 1.5)) / size; a texel more either side for rounding.
    const glm::vec2 extent(shadowSize);
    const glm::vec2 ndcLow = (glm::vec2(texels.min) - 2.5f) / extent * 2.0f - 1.0f;
    const glm::vec2 ndcHigh = (glm::vec2(texels.max) + 2.5f) / extent * 2.0f - 1.0f;
    const glm::mat4 lightToWorld = glm::inverse(lightViewProj);
    Aabb column;
    auto add = [&](const glm::vec4& homogeneous) {
        const glm::vec3 p = glm::vec3(homogeneous) / homogeneous.w;
        column.extend(p);
        return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
    };
    for (int c = 0; c < 8; ++c) {
        // Points reaching behind a perspective light: the column is the pyramid from its eye (the point that
        // projects to w = 0, clip (0, 0, 1, 0)) to the far depth, not cut at a near depth.
        if (behind && (c & 4) == 0) continue;
        const glm::vec4 ndc((c & 1) ? ndcHigh.x : ndcLow.x, (c & 2) ? ndcHigh.y : ndcLow.y,
                            (c & 4) ? depthHigh : depthLow, 1.0f);
        if (!add(lightToWorld * ndc)) return std::nullopt;
    }
    if (behind && !add(lightToWorld * glm::vec4(0.0f, 0.0f, 1.0f, 0.0f))) return std::nullopt;
    return movedRect(viewProj, Aabb{column.min - reach, column.max + reach}, size, 1.0);
}

}  // namespace vct
