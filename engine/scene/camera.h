// The camera a frame is seen from: a view matrix and a perspective lens (the scene's own cameras, keyframed
// paths in scene/camera_path.h, the demo's fly camera).
#pragma once

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace vct {

struct CameraView {
    glm::mat4 view{1.0f};  // world → camera (camera looks along -Z)
    float yfov = 0.8f;
    float znear = 0.05f;
    float zfar = 100.0f;

    glm::vec3 position() const;
    // Vulkan clip space: depth 0..1, y pointing down in the image.
    glm::mat4 projection(float aspect) const;
};

// The view after a camera cut (`render --camera-cut`, the demo's cut): the camera turned 25° about the
// vertical axis through itself and moved a little to the side, so most of the image changes but the scene
// stays in view.
CameraView cutCamera(CameraView camera);

// The scene's first camera at time t (the loader guarantees one exists).
CameraView sceneCamera(const Scene& scene, float timeSeconds);

}  // namespace vct
