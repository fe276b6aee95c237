#include "reference/material_eval.h"

#include <algorithm>
#include <cmath>

#include "render/shader_math.h"

namespace vct::reference {

namespace {

// Unit vector or, when v is degenerate (zero or not finite), the fallback: lib/surface.glsl's safeNormalize.
glm::vec3 safeNormalize(glm::vec3 v, glm::vec3 fallback) {
    const float len2 = glm::dot(v, v);
    return (len2 > 1e-20f && std::isfinite(len2)) ? v / std::sqrt(len2) : fallback;
}

// Texel coordinate under a sampler wrap mode.
int wrapCoordinate(int i, int size, TextureWrap wrap) {
    switch (wrap) {
        case TextureWrap::ClampToEdge:
            return std::clamp(i, 0, size - 1);
        case TextureWrap::MirroredRepeat: {
            const int period = 2 * size;
            int m = i % period;
            if (m < 0) m += period;
            return m < size ? m : period - 1 - m;
        }
        case TextureWrap::Repeat:
        default: {
            int m = i % size;
            return m < 0 ? m + size : m;
        }
    }
}

}  // namespace

MaterialEvaluator::MaterialEvaluator(const Scene& scene) : scene_(scene) {
    for (int i = 0; i < 256; ++i) srgbToLinearTable_[i] = glsl::srgbToLinear(float(i) / 255.0f);
}

glm::vec4 MaterialEvaluator::sampleTexture(int index, bool normalSlot, glm::vec2 uv) const {
    // What lib/surface.glsl reads where a material has no texture (materialTextureOr): white, and the flat
    // normal's texel (VCT_FLAT_NORMAL_TEXEL).
    if (index < 0 || size_t(index) >= scene_.textures.size() || scene_.textures[size_t(index)].mips.empty()) {
        constexpr float flat = float(VCT_FLAT_NORMAL_TEXEL) / 255.0f;
        return normalSlot ? glm::vec4(flat, flat, 1.0f, 1.0f) : glm::vec4(1.0f);
    }
    const Texture& texture = scene_.textures[size_t(index)];
    const int w = int(texture.width), h = int(texture.height);
    const std::vector<uint8_t>& texels = texture.mips[0];
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = glm::vec2(0.0f);
    // Texel centres at (i + 0.5) / size; keep the coordinate in a range where int conversion is exact.
    const float x = std::fmod(uv.x, 4096.0f) * float(w) - 0.5f;
    const float y = std::fmod(uv.y, 4096.0f) * float(h) - 0.5f;
    const float fx = std::floor(x), fy = std::floor(y);
    const float tx = x - fx, ty = y - fy;
    const bool srgb = texture.kind == TextureKind::Color;
    auto texel = [&](int i, int j) {
        const size_t offset = (size_t(wrapCoordinate(j, h, texture.wrapT)) * size_t(w) +
                               size_t(wrapCoordinate(i, w, texture.wrapS))) *
                              4;
        const uint8_t* p = &texels[offset];
        if (srgb)
            return glm::vec4(srgbToLinearTable_[p[0]], srgbToLinearTable_[p[1]], srgbToLinearTable_[p[2]],
                             float(p[3]) / 255.0f);
        return glm::vec4(p[0], p[1], p[2], p[3]) / 255.0f;
    };
    const int i = int(fx), j = int(fy);
    return glm::mix(glm::mix(texel(i, j), texel(i + 1, j), tx),
                    glm::mix(texel(i, j + 1), texel(i + 1, j + 1), tx), ty);
}

float MaterialEvaluator::alpha(uint32_t material, glm::vec2 uv, float vertexAlpha) const {
    const Material& m = scene_.materials[material];
    return m.baseColorFactor.a * sampleTexture(m.baseColorTexture, false, uv).a * vertexAlpha;
}

bool MaterialEvaluator::discards(uint32_t material, glm::vec2 uv, float vertexAlpha) const {
    const Material& m = scene_.materials[material];
    return m.alphaMode == AlphaMode::Mask && alpha(material, uv, vertexAlpha) < m.alphaCutoff;
}

SurfacePoint MaterialEvaluator::evaluate(uint32_t materialIndex, const SurfaceGeometry& g) const {
    const Material& material = scene_.materials[materialIndex];
    SurfacePoint s;
    s.position = g.position;
    s.faceNormal = g.faceNormal;
    const glm::vec4 baseColor =
        material.baseColorFactor * sampleTexture(material.baseColorTexture, false, g.uv) * g.color;

    // lib/surface.glsl, step for step: the geometric frame, back faces seeing the flipped normal.
    glm::vec3 normal = safeNormalize(g.normal, g.frontFacing ? g.faceNormal : -g.faceNormal);
    const glm::vec3 inTangent = glm::vec3(g.tangent);
    glm::vec3 tangent = inTangent - normal * glm::dot(normal, inTangent);
    tangent = safeNormalize(tangent, std::abs(normal.x) < 0.9f
                                         ? glm::normalize(glm::cross(normal, glm::vec3(1, 0, 0)))
                                         : glm::normalize(glm::cross(normal, glm::vec3(0, 1, 0))));
    const float handedness = g.tangent.w < 0.0f ? -1.0f : 1.0f;
    if (!g.frontFacing) normal = -normal;
    const glm::vec3 bitangent = glm::cross(normal, tangent) * handedness;
    const glm::vec3 mapped = glm::vec3(sampleTexture(material.normalTexture, true, g.uv)) * 2.0f - 1.0f;
    const glm::vec3 scaled = glm::vec3(glm::vec2(mapped) * material.normalScale, mapped.z);
    s.normal = safeNormalize(tangent * scaled.x + bitangent * scaled.y + normal * scaled.z, normal);

    const glm::vec4 mr = sampleTexture(material.metallicRoughnessTexture, false, g.uv);
    s.metallic = std::clamp(material.metallicFactor * mr.b, 0.0f, 1.0f);
    s.perceptualRoughness = std::clamp(material.roughnessFactor * mr.g, 0.0f, 1.0f);
    s.emission = material.emissiveFactor * glm::vec3(sampleTexture(material.emissiveTexture, false, g.uv));
    s.occlusion =
        1.0f + material.occlusionStrength * (sampleTexture(material.occlusionTexture, false, g.uv).r - 1.0f);
    s.baseColor = glm::clamp(glm::vec3(baseColor), 0.0f, 1.0f);
    return s;
}

}  // namespace vct::reference
