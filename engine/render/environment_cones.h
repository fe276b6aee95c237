// The environment as a cone sees it (docs/design.md §5.9): for each cone aperture, the mean radiance over the
// spherical cap of that half-angle about every direction, stored as layers of one equirectangular size.
//
// Why not the map's mip chain: a mip texel is a box in (azimuth, polar angle), not a cone. Near the poles its
// box is a sector: the zenith read at level 5 of a 256-wide map (the 60° diffuse cone's) returned the mean of
// one 45° × 45° sector of the sky's cap, the one towards the sun, so a surface facing up read its central cone
// 1.5× too bright and its six-cone sky light 1.08× the exact irradiance (0.99× from caps).
//
// Layer k holds caps of half-angle θ_k = π·2^k / width (lib/environment.glsl's environmentMip: the cone whose
// half-angle is θ reads layer log2(θ·width/π), between two layers linearly); layer 0 is the map itself at that
// width (a texel's half-width is π/width). The last layer's cap is the whole sphere. A map wider than
// kEnvironmentConeWidth is filtered from its full resolution into that width: cones narrower than a texel of it
// (0.7°) read it at that width, while the background keeps the full map.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "render/environment.h"

namespace vct {

// The widest the layers are (a cap of θ_1 = 1.4° then spans a texel).
constexpr uint32_t kEnvironmentConeWidth = 256;

struct EnvironmentConeLayers {
    uint32_t width = 0, height = 0, count = 0;
    std::vector<glm::vec3> texels;  // layer by layer, each row by row from the zenith (lib/environment.glsl)

    const glm::vec3& texel(uint32_t layer, uint32_t x, uint32_t y) const {
        return texels[(size_t(layer) * height + y) * width + x];
    }
};

// The layers of `map` (its rotation is applied at lookup, as for the map).
EnvironmentConeLayers environmentConeLayers(const EnvironmentMap& map);

// The CPU twin of lib/environment_sample.glsl's environmentCone: the layers read along unit `dir` (turned back
// by `rotation`) for a cone of half-angle atan(tanHalfAngle), filtered as the GPU sampler does (linear, u
// repeated, v and the layer clamped).
glm::vec3 sampleEnvironmentCone(const EnvironmentConeLayers& layers, glm::vec3 dir, float tanHalfAngle,
                                float rotation);

}  // namespace vct
