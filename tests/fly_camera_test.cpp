// The demo's fly camera: starting pose, turning, pitch clamp, moving in the camera's frame.
#include "app/demo/fly_camera.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

namespace vct {
namespace {

constexpr float kEps = 1e-4f;

void expectNear(const glm::vec3& a, const glm::vec3& b) {
    EXPECT_NEAR(a.x, b.x, kEps);
    EXPECT_NEAR(a.y, b.y, kEps);
    EXPECT_NEAR(a.z, b.z, kEps);
}

CameraView lookingAt(const glm::vec3& eye, const glm::vec3& target) {
    CameraView view;
    view.view = glm::lookAt(eye, target, glm::vec3(0, 1, 0));
    view.yfov = 0.6f;
    view.znear = 0.1f;
    view.zfar = 50.0f;
    return view;
}

TEST(FlyCamera, StartsAtTheGivenViewAndReproducesIt) {
    const CameraView start = lookingAt({1, 2, 3}, {0, 1, -1});
    FlyCamera camera(start, 1.0f);
    expectNear(camera.position(), {1, 2, 3});
    expectNear(camera.forward(), glm::normalize(glm::vec3(-1, -1, -4)));
    const CameraView view = camera.view();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(view.view[c][r], start.view[c][r], kEps);
    EXPECT_FLOAT_EQ(view.yfov, 0.6f);
    EXPECT_FLOAT_EQ(view.znear, 0.1f);
    EXPECT_FLOAT_EQ(view.zfar, 50.0f);
}

TEST(FlyCamera, KeepsTheStartViewExactlyUntilItMoves) {
    CameraView start = lookingAt({1, 2, 3}, {0, 1, -1});
    start.view = glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(0, 0, 1)) * start.view;  // rolled
    FlyCamera camera(start, 1.0f);
    FlyInput idle;
    idle.dt = 0.1f;
    camera.update(idle);
    EXPECT_EQ(camera.view().view, start.view);
    FlyInput turn;
    turn.look.x = 0.1f;
    camera.update(turn);
    EXPECT_NE(camera.view().view, start.view);
    // The roll is gone: the camera's x axis is level.
    EXPECT_NEAR(glm::inverse(camera.view().view)[0].y, 0.0f, kEps);
}

TEST(FlyCamera, LookingRightTurnsClockwiseSeenFromAbove) {
    FlyCamera camera(lookingAt({0, 0, 0}, {0, 0, -1}), 1.0f);
    FlyInput input;
    input.look.x = glm::half_pi<float>();
    camera.update(input);
    expectNear(camera.forward(), {1, 0, 0});
    expectNear(camera.position(), {0, 0, 0});
}

TEST(FlyCamera, PitchIsClamped) {
    FlyCamera camera(lookingAt({0, 0, 0}, {0, 0, -1}), 1.0f);
    FlyInput input;
    input.look.y = 10.0f;
    camera.update(input);
    EXPECT_FLOAT_EQ(camera.pitch(), FlyCamera::kMaxPitch);
    input.look.y = -20.0f;
    camera.update(input);
    EXPECT_FLOAT_EQ(camera.pitch(), -FlyCamera::kMaxPitch);
    // The view stays a proper rotation even at the clamp.
    const glm::mat3 rotation(camera.view().view);
    EXPECT_NEAR(glm::determinant(rotation), 1.0f, kEps);
}

TEST(FlyCamera, MovesInTheCameraFrameAtItsSpeed) {
    FlyCamera camera(lookingAt({0, 0, 0}, {-1, 0, 0}), 2.0f);  // facing -X: right is -Z
    FlyInput input;
    input.dt = 0.5f;
    input.move = {0, 0, 1};
    camera.update(input);
    expectNear(camera.position(), {-1, 0, 0});
    input.move = {1, 0, 0};
    camera.update(input);
    expectNear(camera.position(), {-1, 0, -1});
    input.move = {0, 1, 0};
    input.fast = true;
    camera.update(input);
    expectNear(camera.position(), {-1, FlyCamera::kFastFactor, -1});
}

TEST(FlyCamera, StrafeStaysLevelWhenLookingDown) {
    FlyCamera camera(lookingAt({0, 5, 0}, {0, 0, -1}), 1.0f);
    FlyInput input;
    input.dt = 1.0f;
    input.move = {1, 0, 0};
    camera.update(input);
    expectNear(camera.position(), {1, 5, 0});
}

TEST(FlyCamera, DiagonalMovesAreNotFaster) {
    FlyCamera camera(lookingAt({0, 0, 0}, {0, 0, -1}), 1.0f);
    FlyInput input;
    input.dt = 1.0f;
    input.move = {1, 0, 1};
    camera.update(input);
    EXPECT_NEAR(glm::length(camera.position()), 1.0f, kEps);
}

}  // namespace
}  // namespace vct
