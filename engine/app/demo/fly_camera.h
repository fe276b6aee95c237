// A free-flying camera for the demo window, kept free of GLFW so its math is unit-tested: yaw about world +Y,
// pitch clamped short of straight up/down (where yaw would become meaningless), and moves in the camera's
// frame.
#pragma once

#include <glm/glm.hpp>

#include "scene/camera.h"

namespace vct {

struct FlyInput {
    glm::vec3 move{0.0f};  // x: right, y: world up, z: forward; each in [-1, 1] (keys held)
    glm::vec2 look{0.0f};  // radians this frame; x > 0 turns right, y > 0 looks up
    float dt = 0.0f;       // seconds this frame
    bool fast = false;     // Shift: kFastFactor times the speed
};

class FlyCamera {
  public:
    static constexpr float kFastFactor = 4.0f;
    static constexpr float kMaxPitch = 1.55f;  // ≈ 89°

    // Starts where `start` is, looking the same way, keeping its lens; `speed` is in world units per second.
    // Until the first turn or move, view() is `start` exactly (so scripted demo frames match `vct render`);
    // after that any roll of `start` is dropped.
    FlyCamera(const CameraView& start, float speed);

    void update(const FlyInput& input);
    CameraView view() const;

    glm::vec3 position() const { return position_; }
    glm::vec3 forward() const;
    float yaw() const { return yaw_; }
    float pitch() const { return pitch_; }
    float speed() const { return speed_; }

  private:
    CameraView start_;  // also the lens (yfov, znear, zfar) kept after moving
    bool moved_ = false;
    glm::vec3 position_{0.0f};
    float yaw_ = 0.0f;    // 0 looks along -Z; positive turns left (counter-clockwise seen from above)
    float pitch_ = 0.0f;  // 0 is level; positive looks up
    float speed_;
};

}  // namespace vct
