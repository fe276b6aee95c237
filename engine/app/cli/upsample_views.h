// What the upsampling shows (Tokuyoshi 2015 Fig. 8; docs/design.md §6.6): the pixels re-traced at full resolution
// in red over the frame, and the per-pixel sum of upsampling weights as a heat map; their --aux files.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "render/renderer.h"

namespace vct {

// RGBA8: the final frame with the pixels the resample pass re-traced this frame in red.
std::vector<uint8_t> resampleOverlay(Renderer& renderer);

// RGBA8: min(diffuse, specular) sum of weights as a heat map, log scale from 0 (black) through τ (blue) to
// the history cap A_max (white); background pixels grey.
std::vector<uint8_t> weightHeatMap(Renderer& renderer);

// weight_sum.exr (r: diffuse, g: specular sum of weights, b: 1 where re-traced) and resample_mask.png
// (white where re-traced); nothing when GI is off. Returns the names written.
std::vector<std::string> writeUpsampleAux(Renderer& renderer, const std::filesystem::path& dir);

}  // namespace vct
