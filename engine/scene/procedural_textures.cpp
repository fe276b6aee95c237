#include "scene/procedural_textures.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>

namespace vct {

namespace {

uint8_t unorm8(float v) {
    return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

Texture blank(const std::string& name, TextureKind kind, uint32_t size) {
    Texture tex;
    tex.name = name;
    tex.kind = kind;
    tex.width = tex.height = size;
    tex.mips.emplace_back(size_t(size) * size * 4, uint8_t(255));
    return tex;
}

}  // namespace

Texture makeBumpNormalMap(const std::string& name, uint32_t size, uint32_t period, float slope) {
    Texture tex = blank(name, TextureKind::Normal, size);
    const float k = glm::two_pi<float>() / float(period);
    for (uint32_t row = 0; row < size; ++row) {
        for (uint32_t col = 0; col < size; ++col) {
            // Height derivatives at the texel centre, scaled so that max |dh/dcol| = slope.
            float x = k * (float(col) + 0.5f), y = k * (float(row) + 0.5f);
            float dhdcol = slope * std::cos(x) * std::sin(y);
            float dhdrow = slope * std::sin(x) * std::cos(y);
            // Tangent space: +X = increasing column, +Y = "up" in the image = decreasing row (glTF), so
            // n ∝ (-dh/dx, -dh/dy, 1) becomes (-dh/dcol, +dh/drow, 1).
            glm::vec3 n = glm::normalize(glm::vec3(-dhdcol, dhdrow, 1.0f));
            uint8_t* texel = &tex.mips[0][(size_t(row) * size + col) * 4];
            texel[0] = unorm8(n.x * 0.5f + 0.5f);
            texel[1] = unorm8(n.y * 0.5f + 0.5f);
            texel[2] = unorm8(n.z * 0.5f + 0.5f);
        }
    }
    buildMipChain(tex);
    return tex;
}

Texture makeRoughnessStripes(const std::string& name, uint32_t size, uint32_t bands, float minRoughness,
                             float maxRoughness, float metallic) {
    Texture tex = blank(name, TextureKind::Linear, size);
    tex.wrapS = tex.wrapT =
        TextureWrap::ClampToEdge;  // one set of stripes across the surface, no wrap-around
    for (uint32_t row = 0; row < size; ++row) {
        for (uint32_t col = 0; col < size; ++col) {
            uint32_t band = std::min(bands - 1, col * bands / size);
            float t = bands > 1 ? float(band) / float(bands - 1) : 0.0f;
            uint8_t* texel = &tex.mips[0][(size_t(row) * size + col) * 4];
            texel[1] = unorm8(minRoughness + t * (maxRoughness - minRoughness));
            texel[2] = unorm8(metallic);
        }
    }
    buildMipChain(tex);
    return tex;
}

}  // namespace vct
