// The vertex of every mesh: what the scene holds (scene/scene.h) and what graphics pipelines read in vertex
// binding 0 (vk/pipeline.cpp), so both layers see one layout.
#pragma once

#include <glm/glm.hpp>

namespace vct {

// Interleaved vertex as uploaded to the GPU (48 bytes). tangent.w is the bitangent sign (glTF convention:
// bitangent = cross(normal, tangent.xyz) * tangent.w).
struct Vertex {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    glm::vec2 uv{0.0f};
    glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f};
};
static_assert(sizeof(Vertex) == 48);

}  // namespace vct
