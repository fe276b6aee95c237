// Small skinned and morphed glTF files made in code for the skin tests (tests/skin_test.cpp,
// tests/skin_gpu_test.cpp), on hostile_util.h's document + buffer: a two-bone strip whose deformed vertices
// are known by hand, and a triangle with one morph target.
#pragma once

#include <cstring>
#include <string>
#include <vector>

#include "hostile_util.h"

namespace vct::skin_test {

using hostile::GltfScene;
using json = nlohmann::json;

constexpr int kFloat = 5126, kUnsignedByte = 5121, kUnsignedShort = 5123;

// Appends `data` to buffer 0 (4-byte aligned) as a new bufferView and accessor; returns the accessor index.
inline int addAccessor(GltfScene& s, const void* data, size_t bytes, int componentType, size_t count,
                       const std::string& type, bool normalized = false) {
    while (s.bin.size() % 4) s.bin.push_back(0);
    const size_t offset = s.bin.size();
    const auto* p = static_cast<const unsigned char*>(data);
    s.bin.insert(s.bin.end(), p, p + bytes);
    s.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
    json accessor = {{"bufferView", s.doc["bufferViews"].size() - 1},
                     {"componentType", componentType},
                     {"count", count},
                     {"type", type}};
    if (normalized) accessor["normalized"] = true;
    s.doc["accessors"].push_back(accessor);
    s.doc["buffers"][0]["byteLength"] = s.bin.size();
    return int(s.doc["accessors"].size()) - 1;
}

inline int addFloats(GltfScene& s, const std::vector<float>& values, const std::string& type) {
    const size_t components = type == "SCALAR" ? 1
                              : type == "VEC2" ? 2
                              : type == "VEC3" ? 3
                              : type == "VEC4" ? 4
                                               : 16;
    return addAccessor(s, values.data(), values.size() * 4, kFloat, values.size() / components, type);
}

inline GltfScene emptyScene() {
    GltfScene s;
    s.texture = false;
    s.doc = {{"asset", {{"version", "2.0"}}},
             {"scene", 0},
             {"buffers", {{{"uri", "scene.bin"}, {"byteLength", 0}}}},
             {"bufferViews", json::array()},
             {"accessors", json::array()}};
    return s;
}

// Rows of the strip: x = 0, 0.5, 1, 1.5, 2 at y = 0 (vertices 0-4) and y = 0.2 (5-9), z = 0, normal +z.
constexpr int kStripColumns = 5;
inline float stripX(int column) {
    return 0.5f * float(column);
}

struct StripOptions {
    bool secondSet = false;    // joint 1's influence in JOINTS_1/WEIGHTS_1 (JOINTS_0 holds joint 0's)
    bool quantised = false;    // unsigned byte joints and normalized unsigned byte weights
    float weightScale = 1.0f;  // weights that do not sum to 1 (the loader renormalises)
    bool zeroWeights = false;  // every weight 0: the bind pose, with a note
    uint32_t badJoint = 0;     // > 0: vertex 4 names this joint (out of range for 2 joints)
    bool nanInverseBind = false;
    bool colors = false;  // COLOR_0 (normalized unsigned byte VEC4, a different colour per vertex)
};

// A strip skinned by two joints: joint 0 (node 1) at the origin, joint 1 (node 2, its child) at x = 1, whose
// rotation about z is animated: 0° at t = 0, 90° at t = 1 s, 0° at t = 2 s (LINEAR). Columns x < 1 follow
// joint 0, x = 1 both half, x > 1 joint 1. At t = 1 s a vertex (x, y) of joint 1 goes to (1 - y, x - 1).
inline GltfScene twoBoneStrip(const StripOptions& o = {}) {
    GltfScene s = emptyScene();
    std::vector<float> positions, normals;
    for (float y : {0.0f, 0.2f})
        for (int c = 0; c < kStripColumns; ++c) {
            positions.insert(positions.end(), {stripX(c), y, 0.0f});
            normals.insert(normals.end(), {0.0f, 0.0f, 1.0f});
        }
    std::vector<uint16_t> indices;
    for (uint16_t c = 0; c + 1 < kStripColumns; ++c) {
        const uint16_t a = c, b = uint16_t(c + 1), d = uint16_t(c + kStripColumns),
                       e = uint16_t(c + 1 + kStripColumns);
        indices.insert(indices.end(), {a, b, e, a, e, d});
    }
    // Per vertex: (joint, weight) of joint 0 and of joint 1.
    std::vector<uint8_t> joints0, joints1;
    std::vector<float> weights0, weights1;
    for (int v = 0; v < 2 * kStripColumns; ++v) {
        const float x = stripX(v % kStripColumns);
        float w1 = x < 1.0f ? 0.0f : x > 1.0f ? 1.0f : 0.5f;
        float w0 = 1.0f - w1;
        if (o.zeroWeights) w0 = w1 = 0.0f;
        w0 *= o.weightScale;
        w1 *= o.weightScale;
        const uint8_t j1 = (o.badJoint > 0 && v == 4) ? uint8_t(o.badJoint) : uint8_t(1);
        if (o.secondSet) {
            joints0.insert(joints0.end(), {0, 0, 0, 0});
            weights0.insert(weights0.end(), {w0, 0, 0, 0});
            joints1.insert(joints1.end(), {j1, 0, 0, 0});
            weights1.insert(weights1.end(), {w1, 0, 0, 0});
        } else {
            joints0.insert(joints0.end(), {0, j1, 0, 0});
            weights0.insert(weights0.end(), {w0, w1, 0, 0});
        }
    }
    auto addJoints = [&](const std::vector<uint8_t>& j) {
        if (o.quantised) return addAccessor(s, j.data(), j.size(), kUnsignedByte, j.size() / 4, "VEC4");
        std::vector<uint16_t> wide(j.begin(), j.end());
        return addAccessor(s, wide.data(), wide.size() * 2, kUnsignedShort, wide.size() / 4, "VEC4");
    };
    auto addWeights = [&](const std::vector<float>& w) {
        if (!o.quantised) return addFloats(s, w, "VEC4");
        std::vector<uint8_t> q;
        for (float f : w) q.push_back(uint8_t(std::lround(std::min(f, 1.0f) * 255.0f)));
        return addAccessor(s, q.data(), q.size(), kUnsignedByte, q.size() / 4, "VEC4", true);
    };
    json attributes = {{"POSITION", addFloats(s, positions, "VEC3")},
                       {"NORMAL", addFloats(s, normals, "VEC3")},
                       {"JOINTS_0", addJoints(joints0)},
                       {"WEIGHTS_0", addWeights(weights0)}};
    if (o.secondSet) {
        attributes["JOINTS_1"] = addJoints(joints1);
        attributes["WEIGHTS_1"] = addWeights(weights1);
    }
    if (o.colors) {
        std::vector<uint8_t> colors;
        for (int v = 0; v < 2 * kStripColumns; ++v)
            colors.insert(colors.end(), {uint8_t(40 + 20 * v), uint8_t(250 - 10 * v), uint8_t(7 * v), 255});
        attributes["COLOR_0"] =
            addAccessor(s, colors.data(), colors.size(), kUnsignedByte, colors.size() / 4, "VEC4", true);
    }
    s.doc["accessors"][0]["min"] = {0, 0, 0};
    s.doc["accessors"][0]["max"] = {2, 0.2, 0};
    const int indexAccessor =
        addAccessor(s, indices.data(), indices.size() * 2, kUnsignedShort, indices.size(), "SCALAR");
    // Inverse bind matrices (column-major): joint 0 identity, joint 1 a translation by -1 along x.
    std::vector<float> inverseBind = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0,  0, 0, 1,
                                      1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1, 0, 0, 1};
    if (o.nanInverseBind) inverseBind[17] = std::nanf("");
    const int inverseBindAccessor = addFloats(s, inverseBind, "MAT4");
    const float h = std::sqrt(0.5f);
    const int times = addFloats(s, {0.0f, 1.0f, 2.0f}, "SCALAR");
    const int rotations = addFloats(s, {0, 0, 0, 1, 0, 0, h, h, 0, 0, 0, 1}, "VEC4");
    s.doc["meshes"] = {
        {{"name", "strip"},
         {"primitives", {{{"attributes", attributes}, {"indices", indexAccessor}, {"material", 0}}}}}};
    s.doc["materials"] = {{{"name", "grey"}, {"doubleSided", true}}};
    s.doc["nodes"] = {{{"name", "strip"}, {"mesh", 0}, {"skin", 0}},
                      {{"name", "root"}, {"children", {2}}},
                      {{"name", "tip"}, {"translation", {1, 0, 0}}}};
    s.doc["scenes"] = {{{"nodes", {0, 1}}}};
    s.doc["skins"] = {{{"name", "bones"},
                       {"joints", {1, 2}},
                       {"inverseBindMatrices", inverseBindAccessor},
                       {"skeleton", 1}}};
    json sampler = {{"input", times}, {"output", rotations}, {"interpolation", "LINEAR"}};
    json channel = {{"sampler", 0}, {"target", {{"node", 2}, {"path", "rotation"}}}};
    json animation = {
        {"name", "bend"}, {"samplers", json::array({sampler})}, {"channels", json::array({channel})}};
    s.doc["animations"] = json::array({animation});
    return s;
}

// The strip's vertex v at t = 1 s, by hand: joint 1 turns (x, y) by 90° about the pivot (1, 0), to
// (1 - y, x - 1); half-weighted vertices average the two images.
inline glm::vec3 stripExpectedAtOneSecond(int v) {
    const float x = stripX(v % kStripColumns), y = v < kStripColumns ? 0.0f : 0.2f;
    const glm::vec3 byJoint0(x, y, 0.0f), byJoint1(1.0f - y, x - 1.0f, 0.0f);
    if (x < 1.0f) return byJoint0;
    if (x > 1.0f) return byJoint1;
    return 0.5f * byJoint0 + 0.5f * byJoint1;
}

enum class WeightSource { MeshDefault, NodeOverride, Linear, Step, CubicSpline };

// A triangle (0,0,0), (1,0,0), (0,1,0) with normal +z and one morph target: position deltas (0,0,2),
// (0,0,4), (0,0,0), normal deltas (1,0,0). The weight is 0.5 at the time `morphHalfTime` says (mesh default
// 0.5; node weights 0.5 over a mesh default of 0; LINEAR 0 → 1 over 2 s; STEP 0, 0.5, 1 at 0, 1, 2 s; CUBICSPLINE 0 → 1 over 2 s,
// zero tangents). `sparse`: the position deltas as a sparse accessor without bufferView (only vertex 1 moves).
inline GltfScene morphTriangle(WeightSource source = WeightSource::MeshDefault, bool sparse = false) {
    GltfScene s = emptyScene();
    const int position = addFloats(s, {0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    s.doc["accessors"][position]["min"] = {0, 0, 0};
    s.doc["accessors"][position]["max"] = {1, 1, 0};
    const int normal = addFloats(s, {0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    int delta = 0;
    if (sparse) {
        const uint8_t index = 1;
        const float value[3] = {0, 0, 4};
        const int indexView = int(s.doc["bufferViews"].size());
        addAccessor(s, &index, 1, kUnsignedByte, 1, "SCALAR");
        const int valueView = int(s.doc["bufferViews"].size());
        addAccessor(s, value, 12, kFloat, 1, "VEC3");
        s.doc["accessors"].push_back(
            {{"componentType", kFloat},
             {"count", 3},
             {"type", "VEC3"},
             {"sparse",
              {{"count", 1},
               {"indices", {{"bufferView", indexView}, {"componentType", kUnsignedByte}}},
               {"values", {{"bufferView", valueView}}}}}});
        delta = int(s.doc["accessors"].size()) - 1;
    } else {
        delta = addFloats(s, {0, 0, 2, 0, 0, 4, 0, 0, 0}, "VEC3");
    }
    const int normalDelta = addFloats(s, {1, 0, 0, 1, 0, 0, 1, 0, 0}, "VEC3");
    s.doc["meshes"] = {{{"name", "morph"},
                        {"primitives",
                         {{{"attributes", {{"POSITION", position}, {"NORMAL", normal}}},
                           {"targets", {{{"POSITION", delta}, {"NORMAL", normalDelta}}}}}}},
                        {"weights", {source == WeightSource::MeshDefault ? 0.5 : 0.0}}}};
    s.doc["nodes"] = {{{"name", "triangle"}, {"mesh", 0}}};
    if (source == WeightSource::NodeOverride) s.doc["nodes"][0]["weights"] = {0.5};
    s.doc["scenes"] = {{{"nodes", {0}}}};
    auto animate = [&](const std::vector<float>& times, const std::vector<float>& values,
                       const char* interpolation) {
        const int in = addFloats(s, times, "SCALAR"), out = addFloats(s, values, "SCALAR");
        json sampler = {{"input", in}, {"output", out}, {"interpolation", interpolation}};
        json channel = {{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}};
        s.doc["animations"] =
            json::array({json{{"samplers", json::array({sampler})}, {"channels", json::array({channel})}}});
    };
    if (source == WeightSource::Linear) animate({0, 2}, {0, 1}, "LINEAR");
    if (source == WeightSource::Step) animate({0, 1, 2}, {0, 0.5f, 1}, "STEP");
    if (source == WeightSource::CubicSpline) animate({0, 2}, {0, 0, 0, 0, 1, 0}, "CUBICSPLINE");
    return s;
}

// When morphTriangle's weight is 0.5 (STEP holds key 1's 0.5 through [1, 2)).
inline float morphHalfTime(WeightSource source) {
    return source == WeightSource::Step ? 1.5f : 1.0f;
}

}  // namespace vct::skin_test
