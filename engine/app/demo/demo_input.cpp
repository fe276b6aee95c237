#include "app/demo/demo_input.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace vct {

namespace {
constexpr float kLookRadiansPerPixel = 0.004f;
constexpr double kWipeGrabPixels = 8.0;
}  // namespace

DemoInput::DemoInput(GLFWwindow* window) : window_(window) {
    // A key pressed and released between two polls (Esc at a few fps on a CPU device) still counts.
    glfwSetInputMode(window, GLFW_STICKY_KEYS, GLFW_TRUE);
}

bool DemoInput::down(int key) const {
    return glfwGetKey(window_, key) == GLFW_PRESS;
}

bool DemoInput::pressed(int key) {
    const bool now = down(key);
    const bool was = std::exchange(wasDown_[key], now);
    return now && !was;
}

float DemoInput::dragWipe(float wipe, bool split, bool mouseEnabled) {
    const bool button = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    int width = 0, height = 0;
    glfwGetWindowSize(window_, &width, &height);
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(window_, &x, &y);
    if (!button || !split || width <= 0) {
        draggingWipe_ = false;
    } else if (!draggingWipe_ && !wasDragging_ && mouseEnabled) {
        // A new press: it grabs the wipe when it lands on it.
        draggingWipe_ = std::abs(x - double(wipe) * width) <= kWipeGrabPixels;
    }
    return draggingWipe_ ? float(std::clamp(x / width, 0.0, 1.0)) : -1.0f;
}

FlyInput DemoInput::fly(float dt, bool keysEnabled, bool mouseEnabled) {
    FlyInput input;
    input.dt = dt;
    if (keysEnabled) {
        auto axis = [&](int positive, int negative) { return float(down(positive)) - float(down(negative)); };
        input.move.x = axis(GLFW_KEY_D, GLFW_KEY_A);
        input.move.y = axis(GLFW_KEY_E, GLFW_KEY_Q);
        input.move.z = axis(GLFW_KEY_W, GLFW_KEY_S);
        input.fast = down(GLFW_KEY_LEFT_SHIFT) || down(GLFW_KEY_RIGHT_SHIFT);
    }
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(window_, &x, &y);
    const bool dragging = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS ||
                          glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    // Only motion while a button stays held turns the camera, so a click does not jump the view; a drag that
    // began on the panel or the wipe never does.
    if (dragging && wasDragging_ && mouseEnabled && !draggingWipe_)
        input.look = glm::vec2(float(x - lastX_), float(lastY_ - y)) * kLookRadiansPerPixel;
    wasDragging_ = dragging;
    lastX_ = x;
    lastY_ = y;
    return input;
}

}  // namespace vct
