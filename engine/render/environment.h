// The environment (docs/design.md §5.9): the radiance arriving from directions no surface occludes, as an
// equirectangular map (lib/environment.glsl: layout) with a mip chain prefiltered by solid angle. One map per
// renderer, made once: a procedural clear sky (render/sky_model.h) lit by the scene's directional light, an
// HDR file (--environment), or a constant. The GPU copy is render/gpu_environment.h; the path-traced
// reference reads and importance-samples this one (render/environment_sampler.h).
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "render/settings.h"
#include "scene/scene.h"

namespace vct {

struct EnvironmentMap {
    std::string description;  // what it is, for the startup line and timings.json ("sky, turbidity 3, ...")
    float rotation = 0.0f;    // radians about +y: looked up at the direction turned back (equirectUv)
    // Level 0 first, then each level half the size of the one before (at least 1), down to 1×1: the sizes a
    // Vulkan mip chain has. Row 0 is the zenith (lib/environment.glsl).
    std::vector<uint32_t> widths, heights;
    std::vector<std::vector<glm::vec3>> levels;

    uint32_t width() const { return widths.empty() ? 0 : widths[0]; }
    uint32_t height() const { return heights.empty() ? 0 : heights[0]; }
    const glm::vec3& texel(size_t level, uint32_t x, uint32_t y) const {
        return levels[level][size_t(y) * widths[level] + x];
    }
    // The radiance of the level-0 texel that direction `dir` falls in (piecewise constant: what the
    // reference's sampling pdf is made of).
    glm::vec3 radiance(glm::vec3 dir) const;
    // The solid-angle-weighted mean radiance: the 1×1 level.
    glm::vec3 meanRadiance() const { return levels.back()[0]; }
};

// Solid angle of a texel in row y of a map of the given size: (2π / width) · (cos θ0 − cos θ1).
double equirectTexelSolidAngle(uint32_t y, uint32_t width, uint32_t height);

// Level 0 given (width × height texels in `levels[0]`), the chain below it: each texel of level l + 1 is the
// solid-angle-weighted mean of the level-l texels it covers (2×2, or 2×1 / 1×2 once a side is 1), so every
// level holds the same integral ∫ L dω (exactly where the sides are powers of two).
void buildEnvironmentMips(EnvironmentMap& map);

// A uniform environment of radiance `radiance` (a 1×1 map).
EnvironmentMap constantEnvironment(glm::vec3 radiance);

// An equirectangular HDR image: OpenEXR (.exr, io/image_io) or Radiance RGBE (.hdr). Throws Error naming the
// file and the problem (unreadable, not 2:1, non-finite or negative texels, too large).
EnvironmentMap loadEnvironmentMap(const std::filesystem::path& path);

// The renderer's and the reference's environment for `scene` at t = 0 (docs/design.md §5.9):
//   --environment FILE: the map, × --environment-intensity, turned by --environment-rotation;
//   else the scene's first directional light as the sun: the procedural sky of --sky-turbidity without a sun
//   disc (the light stands for the sun's direct light; the sky holds the rest), scaled by the light;
//   else (only point and spot lights: a closed room such as cornell) the constant `ambient`.
// Every case × intensity.
EnvironmentMap sceneEnvironment(const Scene& scene, const RenderSettings& settings);

}  // namespace vct
