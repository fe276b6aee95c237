// The demo window's keyboard and mouse, read by polling: fly-camera motion, one-press keys, and dragging the
// split view's wipe. Input the panel takes (ImGui wants the mouse or keyboard) does not reach the camera.
#pragma once

#include <map>

#include "app/demo/fly_camera.h"

struct GLFWwindow;

namespace vct {

class DemoInput {
  public:
    explicit DemoInput(GLFWwindow* window);

    // This frame's camera motion; none when `enabled` is false (the panel has the input), though the cursor
    // is still followed so that the next drag does not jump.
    FlyInput fly(float dt, bool keysEnabled, bool mouseEnabled);
    // True once per press of `key` (GLFW_KEY_*); sticky keys keep presses shorter than a frame.
    bool pressed(int key);
    // The split view's wipe: while a drag that started within a few pixels of it lasts, the cursor's x as a
    // fraction of the window width (else a negative value). Such a drag does not turn the camera.
    float dragWipe(float wipe, bool split, bool mouseEnabled);

  private:
    bool down(int key) const;
    GLFWwindow* window_;
    std::map<int, bool> wasDown_;
    bool wasDragging_ = false;
    bool draggingWipe_ = false;
    double lastX_ = 0.0, lastY_ = 0.0;
};

}  // namespace vct
