#include "app/demo/fly_camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace vct {

FlyCamera::FlyCamera(const CameraView& start, float speed) : start_(start), speed_(speed) {
    const glm::mat4 cameraToWorld = glm::inverse(start.view);
    position_ = glm::vec3(cameraToWorld[3]);
    const glm::vec3 f = glm::normalize(-glm::vec3(cameraToWorld[2]));  // the camera looks along its -Z
    pitch_ = std::clamp(std::asin(std::clamp(f.y, -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
    // Straight up/down leaves no heading in f; atan2(0, 0) = 0 is as good a yaw as any.
    yaw_ = std::atan2(-f.x, -f.z);
}

glm::vec3 FlyCamera::forward() const {
    return {-std::sin(yaw_) * std::cos(pitch_), std::sin(pitch_), -std::cos(yaw_) * std::cos(pitch_)};
}

void FlyCamera::update(const FlyInput& input) {
    // An idle frame keeps the pose, and with it the exact start view.
    if (input.look == glm::vec2(0.0f) && (input.move == glm::vec3(0.0f) || input.dt == 0.0f)) return;
    moved_ = true;
    yaw_ -= input.look.x;
    pitch_ = std::clamp(pitch_ + input.look.y, -kMaxPitch, kMaxPitch);
    // Keep yaw bounded so float precision does not drift after long sessions of turning one way.
    yaw_ = std::remainder(yaw_, 2.0f * glm::pi<float>());

    const glm::vec3 f = forward();
    // Strafing stays horizontal and Q/E move along world up, so looking down does not make "right" sink.
    const glm::vec3 right(std::cos(yaw_), 0.0f, -std::sin(yaw_));
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    glm::vec3 direction = right * input.move.x + up * input.move.y + f * input.move.z;
    // Diagonals are not faster than straight moves.
    if (glm::length(direction) > 1.0f) direction = glm::normalize(direction);
    position_ += direction * speed_ * (input.fast ? kFastFactor : 1.0f) * input.dt;
}

CameraView FlyCamera::view() const {
    // Rebuilding the start view from yaw/pitch would differ from it by rounding; return it as given.
    if (!moved_) return start_;
    CameraView v = start_;
    v.view = glm::lookAt(position_, position_ + forward(), glm::vec3(0.0f, 1.0f, 0.0f));
    return v;
}

}  // namespace vct
