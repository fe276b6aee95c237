// Textures made in code for the built-in scenes, so the project needs no binary assets. All come with
// their full mip chain (buildMipChain).
#pragma once

#include <cstdint>
#include <string>

#include "scene/scene.h"

namespace vct {

// Tangent-space normal map of an "egg-crate" height field h = sin(2πx/P)·sin(2πy/P) with P = `period`
// texels (size must be a multiple of period so the map tiles). `slope` is the largest |dh/dx| in
// tangent-space units (0.8 ≈ 39°). A period of a few texels makes the normals of one texel footprint
// disagree as soon as the map is minified, which is what the Toksvig mips must capture.
Texture makeBumpNormalMap(const std::string& name, uint32_t size, uint32_t period, float slope);

// glTF metallicRoughness texture (G = roughness, B = metallic, R = 1 as unused occlusion) with `bands`
// vertical stripes whose roughness steps linearly from minRoughness (left, u = 0) to maxRoughness (right).
Texture makeRoughnessStripes(const std::string& name, uint32_t size, uint32_t bands, float minRoughness,
                             float maxRoughness, float metallic);

}  // namespace vct
