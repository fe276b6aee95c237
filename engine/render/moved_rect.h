// Which texels of a raster target a frame must recompute when only instances moved (docs/design.md §5.8): the
// rectangle where their bounds, before and after the move, project. Outside it the target holds what the last
// frame computed there, the same values a whole recomputation gives. The shadow pass redraws only this rectangle
// of the shadow map (the light's projection), the direct pass only the pixels in it (the camera's) and those
// whose shadow lookup reads the shadow map's.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>

#include "lib/shared.h"
#include "scene/scene.h"

namespace vct {

// Texels [min, max) of a target.
struct TexelRect {
    glm::ivec2 min{0}, max{0};
    bool empty() const { return min.x >= max.x || min.y >= max.y; }
    bool contains(glm::ivec2 texel) const {
        return texel.x >= min.x && texel.y >= min.y && texel.x < max.x && texel.y < max.y;
    }
    uint64_t area() const { return empty() ? 0 : uint64_t(max.x - min.x) * uint64_t(max.y - min.y); }
};

// The view a pass's last run used, as the frame uniforms hold it: a run that keeps that run's results outside a
// rectangle needs the same. Part of each pass's own record of what it read (compared bytewise): no implicit
// padding, and viewInputsOf zeroes the rest.
struct ViewInputs {
    glm::vec4 cameraPosition;  // w: 0
    glm::vec4 imageSize;       // xy: the size, zw: the texel size
    uint32_t flags;            // VCT_FLAG_*
    uint32_t padding[3];
};
ViewInputs viewInputsOf(const gpu::FrameUniforms& u);

// The texels of a `size` target drawn with `viewProj` (and the viewport of render/scene_draw.cpp) that the move of
// `moved` (world bounds, before and after) can change, with a texel of margin: the bounding rectangle of the
// corners' projections, which holds the projection of everything inside the bounds while every corner is in
// front of the eye. Empty when nothing moved or the bounds project outside the target; nullopt when the whole
// target must be recomputed instead: a corner at or behind a perspective eye, a non-finite projection, or a
// rectangle over `maxShare` of the target (a redraw under a rectangle over half of it saves little).
std::optional<TexelRect> movedRect(const glm::mat4& viewProj, const Aabb& moved, glm::uvec2 size,
                                   double maxShare = 0.5);

// The pixels of a `size` target drawn with `viewProj` whose shadow lookup (lib/shadow_lookup.glsl: the point
// pushed `normalOffset` along its normal, projected with `lightViewProj`, its 3×3 PCF reading the 4×4 texels from
// ⌊t⌋ − 1) can read a texel of `texels` in a `shadowSize` map, for surface points within `surfaces`: where the
// column of the light's clip space over those texels, cut to the surfaces' depth range in it, projects, widened
// by the offset (surfaces reaching behind a perspective light: the pyramid from its eye). Empty when `texels` is
// or no surface is in front of the light; nullopt when that cannot be bounded (a non-finite projection, the
// column reaching behind the camera). A dispatch over any part of the image saves the rest: no share is too large.
std::optional<TexelRect> shadowReadersRect(const glm::mat4& viewProj, glm::uvec2 size,
                                           const glm::mat4& lightViewProj, const TexelRect& texels,
                                           glm::uvec2 shadowSize, const Aabb& surfaces, float normalOffset);

}  // namespace vct
