// Which texels of the shadow map a frame must redraw when only instances moved (docs/design.md §5.8): the light-space
// rectangle of their bounds before and after the move. Outside it the map holds what the last frame drew, the
// same depths a whole redraw gives, so the shadow pass clears and redraws only inside it.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>

#include "scene/scene.h"

namespace vct {

// Texels [min, max) of the shadow map.
struct ShadowRect {
    glm::ivec2 min{0}, max{0};
    bool empty() const { return min.x >= max.x || min.y >= max.y; }
};

// The texels whose depth the move of `moved` (world bounds, before and after) can change in a `size`² map drawn
// with `lightViewProj`, with a texel of margin: the bounding rectangle of the corners' projections, which holds
// the projection of everything inside the bounds while every corner is in front of the light. Empty when nothing
// moved or the bounds project outside the map; nullopt when the whole map must be redrawn instead: a corner at or
// behind a perspective light's eye, a non-finite projection, or a rectangle over half the map (it saves little).
std::optional<ShadowRect> shadowUpdateRect(const glm::mat4& lightViewProj, const Aabb& moved, uint32_t size);

}  // namespace vct
