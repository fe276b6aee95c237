#include "scene/camera.h"

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"

namespace vct {

glm::vec3 CameraView::position() const {
    return glm::vec3(glm::inverse(view)[3]);
}

glm::mat4 CameraView::projection(float aspect) const {
    glm::mat4 proj = glm::perspective(yfov, aspect, znear, zfar);
    proj[1][1] *= -1.0f;  // Vulkan's framebuffer y points down
    return proj;
}

CameraView sceneCamera(const Scene& scene, float timeSeconds) {
    std::vector<glm::quat> rotations;
    const std::vector<glm::mat4> world = scene.evaluate(timeSeconds, &rotations);
    for (size_t n = 0; n < scene.nodes.size(); ++n) {
        if (scene.nodes[n].camera < 0) continue;
        const Camera& camera = scene.cameras[size_t(scene.nodes[n].camera)];
        CameraView view;
        // Cameras ignore the node's scale (glTF): rebuild the frame from its orthonormalised axes (from the
        // composed rotations where a zero scale left none).
        glm::mat4 frame = world[n];
        const glm::mat3 axes = worldAxes(world[n], rotations[n]);
        for (int axis = 0; axis < 3; ++axis) frame[axis] = glm::vec4(axes[axis], 0.0f);
        view.view = glm::inverse(frame);
        view.yfov = camera.yfov;
        view.znear = camera.znear;
        view.zfar = camera.zfar;
        return view;
    }
    throw Error("scene '" + scene.name + "' has no camera");
}

CameraView cutCamera(CameraView camera) {
    const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(25.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    const glm::mat4 step = glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, 0.0f, 0.0f));
    camera.view = step * turn * camera.view;  // applied in camera space
    return camera;
}

}  // namespace vct
