// Keyframed camera paths (scenes/*.camera.json): the moving camera of benchmarks, headless renders and the
// demo's recorded flights. A path with one key is a fixed view.
//
// File format (JSON):
//   {"scene": "cornell",                      // optional: the scene the path was made for (informational)
//    "yfov": 0.8, "znear": 0.05, "zfar": 100, // optional: lens; absent fields keep the scene camera's
//    "loop": false,                           // optional: wrap time past the last key (default: hold it)
//    "keys": [{"time": 0.0, "position": [x, y, z], "target": [x, y, z]}, ...]}
// Times are seconds, strictly increasing; positions and targets are finite and distinct at each key. Between
// keys position and target follow a uniform Catmull-Rom spline (C1, through every key), so a
// recorded flight replays smoothly; the up vector is +Y.
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "scene/camera.h"

namespace vct {

struct CameraKey {
    float time = 0.0f;
    glm::vec3 position{0.0f};
    glm::vec3 target{0.0f, 0.0f, -1.0f};
};

struct CameraPath {
    std::string scene;
    std::optional<float> yfov, znear, zfar;
    bool loop = false;
    std::vector<CameraKey> keys;

    // Seconds from the first key to the last.
    float duration() const;
    // The camera at `timeSeconds`; the lens comes from the path where it sets one, else from `lens`.
    CameraView evaluate(float timeSeconds, const CameraView& lens) const;
};

struct Scene;

// The largest zfar / znear a path may ask for (float depth resolves no more; as glTF cameras are fitted).
inline constexpr float kMaxCameraDepthRatio = 1e6f;

// Reads and checks a path file; throws Error naming the file and the problem.
CameraPath loadCameraPath(const std::filesystem::path& file);
// Checks a path against the scene it is played in: at every key the depth range (the path's lens, else the
// scene camera's) is one float can resolve and does not exclude the whole scene. Throws Error naming `file`.
void checkCameraPathForScene(const CameraPath& path, const Scene& scene, const std::filesystem::path& file);
// Writes a path file (the demo's recorder); throws Error when the file cannot be written.
void saveCameraPath(const CameraPath& path, const std::filesystem::path& file);
// A key looking from the camera's position along its view direction (the demo records these).
CameraKey cameraKey(const CameraView& camera, float timeSeconds);

}  // namespace vct
