// Materials as the G-buffer pass evaluates them (shaders/lib/surface.glsl), on the CPU for the path-traced
// reference: the same glTF metallic-roughness factors and textures, the same tangent-space normal mapping,
// the same clamps. Textures are read at level 0 with bilinear filtering (sRGB decoded per texel before
// filtering, as the GPU's sRGB formats do); the reference integrates over each pixel instead of relying on
// mips, so it applies neither Toksvig roughness nor geometric specular AA: those approximate the very
// filtering it does.
#pragma once

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace vct::reference {

// Interpolated vertex data at a hit, in world space, before the material.
struct SurfaceGeometry {
    glm::vec3 position{0.0f};
    glm::vec3 faceNormal{0.0f, 0.0f,
                         1.0f};  // unit geometric normal of the triangle, towards the ray's origin
    bool frontFacing = true;     // the ray sees the triangle's counter-clockwise (front) side
    glm::vec3 normal{0.0f};      // interpolated vertex normal (not normalised; may be zero)
    glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f};  // xyz interpolated, w the bitangent sign
    glm::vec2 uv{0.0f};
    // Interpolated COLOR_0, which multiplies the base colour (alpha too); exactly white where the primitive
    // has none (as gbuffer.frag, which multiplies only where it has one).
    glm::vec4 color{1.0f};
};

// What the G-buffer would hold at the hit, plus the geometry the tracer needs.
struct SurfacePoint {
    glm::vec3 position{0.0f};
    glm::vec3 faceNormal{0.0f, 0.0f, 1.0f};  // as in SurfaceGeometry
    glm::vec3 normal{0.0f, 0.0f, 1.0f};      // unit shading normal (normal-mapped)
    glm::vec3 baseColor{1.0f};
    float metallic = 0.0f;
    float perceptualRoughness = 1.0f;
    glm::vec3 emission{0.0f};
    float occlusion = 1.0f;
};

class MaterialEvaluator {
  public:
    explicit MaterialEvaluator(const Scene& scene);
    // Texture `index` (−1: the default texel the GPU scene binds, white or a flat normal) at uv, in linear
    // values (sRGB textures decoded).
    glm::vec4 sampleTexture(int index, bool normalSlot, glm::vec2 uv) const;
    // Base colour alpha (factor × texture × the vertex colour's alpha), for alpha-masked materials.
    float alpha(uint32_t material, glm::vec2 uv, float vertexAlpha = 1.0f) const;
    // True where an alpha-masked material discards the fragment (as gbuffer.frag does).
    bool discards(uint32_t material, glm::vec2 uv, float vertexAlpha = 1.0f) const;
    SurfacePoint evaluate(uint32_t material, const SurfaceGeometry& geometry) const;

  private:
    const Scene& scene_;
    float srgbToLinearTable_[256];
};

}  // namespace vct::reference
