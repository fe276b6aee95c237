// Skinned and morphed meshes on the CPU: the joint matrices and morph weights of a frame, the deformed
// vertices (with the very math skin.comp runs on the GPU: shaders/lib/deform.glsl), and bounds that hold the
// deformed shape. The path-traced reference builds its geometry from deformPrimitive; the GPU's deformed
// buffer is tested against it (tests/skin_test.cpp).
#pragma once

#include <vector>

#include "scene/scene.h"

namespace vct {

// Number of morph targets of a mesh (every primitive of a mesh has the same number: the loader checks it).
uint32_t meshMorphTargets(const Scene& scene, int mesh);

// Every node's morph weights at time t (animations loop as in Scene::evaluate): its "weights" channel's value,
// else the node's weights, else its mesh's, else zeros; one per target of the node's mesh (empty for nodes
// without a morphed mesh).
std::vector<std::vector<float>> morphWeights(const Scene& scene, float timeSeconds);

// Nodes whose morph weights are animated (a "weights" channel targets them).
std::vector<bool> weightAnimatedNodes(const Scene& scene);

// The skin's joint matrices for node world matrices `world` (Scene::evaluate): world[joint] × inverse bind.
std::vector<glm::mat4> jointMatrices(const Scene& scene, int skin, const std::vector<glm::mat4>& world);

// One primitive of `instance` deformed: its vertexCount vertices with morphed and skinned position, normal
// and tangent (uv as at rest), in the instance's space (world space for a skinned instance, whose world is
// identity). `joints`: jointMatrices of the instance's skin (ignored without one).
std::vector<Vertex> deformPrimitive(const Scene& scene, const Instance& instance, uint32_t primitive,
                                    const std::vector<glm::mat4>& joints);

// Bounds of the instance's deformed mesh in world space: each skin joint's matrix applied to the morphed rest
// bounds (a skinned vertex is a convex combination of those images) with the rest bounds themselves (for
// vertices without weights); the morphed rest bounds add each target's delta bounds times its weight.
Aabb deformedBounds(const Scene& scene, const Instance& instance, const std::vector<glm::mat4>& joints);

// Throws vct::Error naming the first problem of the scene's skins and morph targets (indices out of range,
// non-finite matrices, deltas or weights, weight counts that do not match the targets).
void validateDeformation(const Scene& scene);

}  // namespace vct
