#include "scene/camera_path.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "scene/input_limits.h"
#include "scene/scene.h"

namespace vct {

namespace {

using nlohmann::json;

// A JSON number that is a finite float; `what` names it in the error.
float finiteNumber(const json& value, const std::string& what) {
    if (!value.is_number()) throw Error(what + " is not a number");
    const double number = value.get<double>();
    if (!std::isfinite(number) || std::fabs(number) > 1e30) throw Error(what + " is not a finite number");
    return float(number);
}

glm::vec3 finiteVec3(const json& value, const std::string& what) {
    if (!value.is_array() || value.size() != 3) throw Error(what + " is not an array of 3 numbers");
    return {finiteNumber(value[0], what), finiteNumber(value[1], what), finiteNumber(value[2], what)};
}

// Uniform Catmull-Rom between p1 and p2 at s in [0, 1].
glm::vec3 catmullRom(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& p3,
                     float s) {
    const float s2 = s * s, s3 = s2 * s;
    return 0.5f * (2.0f * p1 + (p2 - p0) * s + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * s2 +
                   (3.0f * p1 - p0 - 3.0f * p2 + p3) * s3);
}

// A view matrix looking from `eye` at `target`; an up vector that is not parallel to the view direction.
glm::mat4 lookAtView(const glm::vec3& eye, const glm::vec3& target) {
    const glm::vec3 forward = glm::normalize(target - eye);
    const glm::vec3 up =
        std::fabs(forward.y) > 0.999f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    return glm::lookAt(eye, target, up);
}

}  // namespace

float CameraPath::duration() const {
    return keys.empty() ? 0.0f : keys.back().time - keys.front().time;
}

CameraView CameraPath::evaluate(float timeSeconds, const CameraView& lens) const {
    CameraView view = lens;
    if (yfov) view.yfov = *yfov;
    if (znear) view.znear = *znear;
    if (zfar) view.zfar = *zfar;
    if (keys.empty()) return view;
    float t = timeSeconds;
    const float span = duration();
    if (loop && span > 0.0f)
        t = keys.front().time + std::fmod(std::fmod(t - keys.front().time, span) + span, span);
    if (t <= keys.front().time || keys.size() == 1) {
        view.view = lookAtView(keys.front().position, keys.front().target);
        return view;
    }
    if (t >= keys.back().time) {
        view.view = lookAtView(keys.back().position, keys.back().target);
        return view;
    }
    size_t i = 0;
    while (keys[i + 1].time < t) ++i;
    const CameraKey& k1 = keys[i];
    const CameraKey& k2 = keys[i + 1];
    const CameraKey& k0 = i > 0 ? keys[i - 1] : k1;
    const CameraKey& k3 = i + 2 < keys.size() ? keys[i + 2] : k2;
    const float s = (t - k1.time) / (k2.time - k1.time);
    const glm::vec3 eye = catmullRom(k0.position, k1.position, k2.position, k3.position, s);
    glm::vec3 target = catmullRom(k0.target, k1.target, k2.target, k3.target, s);
    // Splines of distinct keys can still meet between them: keep the previous key's direction then.
    if (glm::length(target - eye) < 1e-6f) target = eye + (k1.target - k1.position);
    view.view = lookAtView(eye, target);
    return view;
}

CameraPath loadCameraPath(const std::filesystem::path& file) {
    const std::string name = "camera path '" + file.string() + "': ";
    // The checked read every input file goes through (no blocking on a FIFO, the size bounded on the open
    // file).
    const FileRead read = readRegularFile(file, uint64_t(1) << 24);
    if (!read.error.empty()) throw Error(name + read.error);
    json root;
    try {
        root = json::parse(read.bytes.begin(), read.bytes.end());
    } catch (const json::exception& e) {
        throw Error(name + "not valid JSON (" + std::string(e.what()) + ")");
    }
    try {
        if (!root.is_object()) throw Error("not a JSON object");
        CameraPath path;
        if (root.contains("scene")) {
            if (!root["scene"].is_string()) throw Error("\"scene\" is not a string");
            path.scene = root["scene"].get<std::string>();
        }
        if (root.contains("loop")) {
            if (!root["loop"].is_boolean()) throw Error("\"loop\" is not true or false");
            path.loop = root["loop"].get<bool>();
        }
        if (root.contains("yfov")) {
            path.yfov = finiteNumber(root["yfov"], "\"yfov\"");
            if (!(*path.yfov > 1e-3f && *path.yfov < 3.1f))
                throw Error("\"yfov\" is not in (0.001, 3.1) radians");
        }
        if (root.contains("znear")) path.znear = finiteNumber(root["znear"], "\"znear\"");
        if (root.contains("zfar")) path.zfar = finiteNumber(root["zfar"], "\"zfar\"");
        if (path.znear && !(*path.znear > 0.0f)) throw Error("\"znear\" is not positive");
        if (path.zfar && !(*path.zfar > path.znear.value_or(0.0f)))
            throw Error("\"zfar\" is not beyond znear");
        if (path.znear && path.zfar && *path.zfar / *path.znear > kMaxCameraDepthRatio)
            throw Error("\"zfar\" / \"znear\" is " + numberText(*path.zfar / *path.znear) +
                        ", more than the " + numberText(kMaxCameraDepthRatio) + " float depth resolves");
        if (!root.contains("keys") || !root["keys"].is_array() || root["keys"].empty())
            throw Error("\"keys\" is missing or empty");
        if (root["keys"].size() > 100000) throw Error("more than 100000 keys");
        for (size_t k = 0; k < root["keys"].size(); ++k) {
            const json& key = root["keys"][k];
            const std::string where = "key " + std::to_string(k) + ": ";
            if (!key.is_object() || !key.contains("time") || !key.contains("position") ||
                !key.contains("target"))
                throw Error(where + "needs \"time\", \"position\" and \"target\"");
            CameraKey parsed;
            parsed.time = finiteNumber(key["time"], where + "\"time\"");
            parsed.position = finiteVec3(key["position"], where + "\"position\"");
            parsed.target = finiteVec3(key["target"], where + "\"target\"");
            if (glm::length(parsed.target - parsed.position) < 1e-6f)
                throw Error(where + "target equals position");
            if (!path.keys.empty() && !(parsed.time > path.keys.back().time))
                throw Error(where + "time does not increase");
            path.keys.push_back(parsed);
        }
        return path;
    } catch (const Error& e) {
        throw Error(name + e.what());
    }
}

void saveCameraPath(const CameraPath& path, const std::filesystem::path& file) {
    json root;
    if (!path.scene.empty()) root["scene"] = path.scene;
    if (path.yfov) root["yfov"] = *path.yfov;
    if (path.znear) root["znear"] = *path.znear;
    if (path.zfar) root["zfar"] = *path.zfar;
    root["loop"] = path.loop;
    root["keys"] = json::array();
    for (const CameraKey& key : path.keys)
        root["keys"].push_back({{"time", key.time},
                                {"position", {key.position.x, key.position.y, key.position.z}},
                                {"target", {key.target.x, key.target.y, key.target.z}}});
    writeFileReplacing(file, root.dump(2) + "\n");
}

void checkCameraPathForScene(const CameraPath& path, const Scene& scene, const std::filesystem::path& file) {
    const std::string name = "camera path '" + file.string() + "': ";
    const Aabb box = scene.bounds();
    if (box.empty()) return;
    for (size_t k = 0; k < path.keys.size(); ++k) {
        const CameraKey& key = path.keys[k];
        const CameraView view = path.evaluate(key.time, sceneCamera(scene, key.time));
        const std::string where = name + "key " + std::to_string(k) + ": ";
        if (!(view.znear > 0.0f) || !(view.zfar > view.znear) ||
            view.zfar / view.znear > kMaxCameraDepthRatio)
            throw Error(where + "depth range " + numberText(view.znear) + " .. " + numberText(view.zfar) +
                        " is not 0 < znear < zfar <= " + numberText(kMaxCameraDepthRatio) + " x znear");
        // Nearest and farthest distance from the camera to the scene's box.
        const glm::vec3 nearest = glm::clamp(key.position, box.min, box.max);
        const double dmin = glm::length(glm::dvec3(key.position) - glm::dvec3(nearest));
        double dmax = 0.0;
        for (int c = 0; c < 8; ++c) {
            const glm::dvec3 corner(c & 1 ? box.max.x : box.min.x, c & 2 ? box.max.y : box.min.y,
                                    c & 4 ? box.max.z : box.min.z);
            dmax = std::max(dmax, glm::length(corner - glm::dvec3(key.position)));
        }
        if (double(view.znear) >= dmax || double(view.zfar) <= dmin)
            throw Error(where + "its depth range " + numberText(view.znear) + " .. " + numberText(view.zfar) +
                        " excludes the whole scene (" + numberText(dmin) + " .. " + numberText(dmax) +
                        " away): the image would be empty");
    }
}

CameraKey cameraKey(const CameraView& camera, float timeSeconds) {
    const glm::mat4 frame = glm::inverse(camera.view);
    CameraKey key;
    key.time = timeSeconds;
    key.position = glm::vec3(frame[3]);
    key.target = key.position - glm::normalize(glm::vec3(frame[2]));  // the camera looks along −Z
    return key;
}

}  // namespace vct
