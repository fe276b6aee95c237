// The vertex of every mesh: what the scene holds (scene/scene.h) and what graphics pipelines read in vertex
// binding 0 (vk/pipeline.cpp), so both layers see one layout. Shaders that read vertices as floats (voxelize,
// skin, the G-buffer's previous positions) step by VCT_FLOATS_PER_VERTEX (shaders/lib/shared.h).
#pragma once

#include <glm/glm.hpp>

namespace vct {

// Interleaved vertex as uploaded to the GPU (64 bytes). tangent.w is the bitangent sign (glTF convention:
// bitangent = cross(normal, tangent.xyz) * tangent.w). color is glTF COLOR_0 (linear RGBA; alpha 1 for a VEC3
// accessor), white where the file has none; it multiplies the base colour only of primitives that have it
// (Primitive::hasColors), so meshes without COLOR_0 shade exactly as they would without the attribute.
struct Vertex {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    glm::vec2 uv{0.0f};
    glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f};
    glm::vec4 color{1.0f};
};
static_assert(sizeof(Vertex) == 64);

}  // namespace vct
