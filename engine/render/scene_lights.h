// The scene's punctual lights in world space at one time, as the shaders read them (GpuLight): the one
// conversion from glTF lights on nodes, shared by the GPU scene and the path-traced reference.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <vector>

#include "lib/shared.h"
#include "scene/scene.h"

namespace vct {

// One GpuLight per node with a light, in node order. `world` and `worldRotations` are Scene::evaluate's
// output for the same time.
std::vector<gpu::GpuLight> sceneLights(const Scene& scene, const std::vector<glm::mat4>& world,
                                       const std::vector<glm::quat>& worldRotations);

}  // namespace vct
