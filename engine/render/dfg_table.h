// The split-sum DFG table (Karis 2013) for prefiltered (cone-traced) specular, computed at start-up on the
// CPU through the very function the shaders use (integrateDFG in shaders/lib/brdf.glsl).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace vct {

// size × size texels of (scale, bias), ∫ f_s (n·l) dω ≈ F0·scale + bias. Row-major, index = row * size + col:
//   col → n·v                 = (col + 0.5) / size
//   row → perceptual roughness = (row + 0.5) / size   (α = roughness²; perceptual spreads the rows evenly)
// so as a texture of width = height = size (RG16F or RG32F, linear filter, clamp to edge) it is sampled at
// uv = (n·v, perceptualRoughness). Returns an empty table for size 0.
std::vector<glm::vec2> makeDfgTable(uint32_t size, uint32_t sampleCount = 1024);

}  // namespace vct
