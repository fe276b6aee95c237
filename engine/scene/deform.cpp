#include "scene/deform.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "lib/cpp_glsl.h"

namespace vct {

namespace glsl_deform {
using namespace glm;
#include "lib/deform.glsl"
}  // namespace glsl_deform

namespace {

[[noreturn]] void fail(const std::string& what) {
    throw Error(what);
}

std::string named(const std::string& kind, const std::string& name, size_t index) {
    return kind + " '" + (name.empty() ? "#" + std::to_string(index) : name) + "'";
}

bool finite(const glm::vec4& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

// A weights channel at time t (already wrapped): `count` weights, interpolated as Scene::evaluate does TRS
// channels (times before the first key clamp to it, after the last to the last).
std::vector<float> sampleWeights(const WeightsChannel& ch, float t) {
    const size_t n = ch.count;
    const bool cubic = ch.interpolation == Interpolation::CubicSpline;
    auto value = [&](size_t key, size_t i) { return ch.values[(cubic ? key * 3 + 1 : key) * n + i]; };
    std::vector<float> out(n);
    const auto& times = ch.times;
    size_t k = 0, k1 = 0;
    float u = 0.0f, dt = 0.0f;
    if (times.size() > 1 && t > times.front() && t < times.back()) {
        k1 = size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin());
        k = k1 - 1;
        dt = times[k1] - times[k];
        u = dt > 0.0f ? (t - times[k]) / dt : 0.0f;
    } else {
        k = k1 = (times.size() == 1 || t <= times.front()) ? 0 : times.size() - 1;
    }
    for (size_t i = 0; i < n; ++i) {
        if (k == k1 || ch.interpolation == Interpolation::Step) {
            out[i] = value(k, i);
        } else if (!cubic) {
            out[i] = value(k, i) + (value(k1, i) - value(k, i)) * u;
        } else {
            // Hermite spline with glTF's (in-tangent, value, out-tangent) blocks; tangents scale with dt.
            const float u2 = u * u, u3 = u2 * u;
            const float p0 = value(k, i), m0 = ch.values[(k * 3 + 2) * n + i] * dt;
            const float p1 = value(k1, i), m1 = ch.values[(k1 * 3) * n + i] * dt;
            out[i] = (2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * m0 + (-2 * u3 + 3 * u2) * p1 +
                     (u3 - u2) * m1;
        }
    }
    return out;
}

}  // namespace

uint32_t meshMorphTargets(const Scene& scene, int mesh) {
    if (mesh < 0 || size_t(mesh) >= scene.meshes.size()) return 0;
    uint32_t targets = 0;
    for (uint32_t p : scene.meshes[size_t(mesh)].primitives)
        if (p < scene.primitives.size()) targets = std::max(targets, scene.primitives[p].morphTargetCount);
    return targets;
}

std::vector<std::vector<float>> morphWeights(const Scene& scene, float timeSeconds) {
    std::vector<std::vector<float>> weights(scene.nodes.size());
    for (size_t n = 0; n < scene.nodes.size(); ++n) {
        const Node& node = scene.nodes[n];
        const uint32_t targets = meshMorphTargets(scene, node.mesh);
        if (targets == 0) continue;
        const std::vector<float>& given =
            !node.weights.empty() ? node.weights : scene.meshes[size_t(node.mesh)].weights;
        weights[n] = given;
        weights[n].resize(targets, 0.0f);
    }
    for (const Animation& anim : scene.animations) {
        float t = anim.duration > 0.0f ? std::fmod(timeSeconds, anim.duration) : 0.0f;
        if (t < 0.0f) t += anim.duration;
        for (const WeightsChannel& ch : anim.weightChannels) {
            if (ch.node < 0 || size_t(ch.node) >= weights.size() || ch.times.empty()) continue;
            std::vector<float>& w = weights[size_t(ch.node)];
            const size_t needed =
                ch.times.size() * ch.count * (ch.interpolation == Interpolation::CubicSpline ? 3 : 1);
            if (w.empty() || ch.count != w.size() || ch.values.size() < needed) continue;
            w = sampleWeights(ch, t);
        }
    }
    return weights;
}

std::vector<bool> weightAnimatedNodes(const Scene& scene) {
    std::vector<bool> animated(scene.nodes.size(), false);
    for (const Animation& anim : scene.animations)
        for (const WeightsChannel& ch : anim.weightChannels)
            if (ch.node >= 0 && size_t(ch.node) < animated.size()) animated[size_t(ch.node)] = true;
    return animated;
}

std::vector<glm::mat4> jointMatrices(const Scene& scene, int skin, const std::vector<glm::mat4>& world) {
    if (skin < 0 || size_t(skin) >= scene.skins.size()) return {};
    const Skin& s = scene.skins[size_t(skin)];
    std::vector<glm::mat4> out(s.joints.size(), glm::mat4(1.0f));
    for (size_t j = 0; j < s.joints.size(); ++j) {
        const int node = s.joints[j];
        const glm::mat4 jointWorld =
            node >= 0 && size_t(node) < world.size() ? world[size_t(node)] : glm::mat4(1.0f);
        out[j] = jointWorld * (j < s.inverseBindMatrices.size() ? s.inverseBindMatrices[j] : glm::mat4(1.0f));
    }
    return out;
}

std::vector<Vertex> deformPrimitive(const Scene& scene, const Instance& instance, uint32_t primitive,
                                    const std::vector<glm::mat4>& joints) {
    const Primitive& prim = scene.primitives[primitive];
    std::vector<Vertex> out(scene.vertices.begin() + prim.vertexOffset,
                            scene.vertices.begin() + prim.vertexOffset + prim.vertexCount);
    const bool skinned = instance.skin >= 0 && prim.skinVertexOffset >= 0;
    const uint32_t targets =
        std::min<uint32_t>(prim.morphTargetCount, uint32_t(instance.morphWeights.size()));
    // The order of skin.comp: targets in order, then the 8 influences in order.
    for (uint32_t v = 0; v < prim.vertexCount; ++v) {
        glm::vec3 dp(0.0f), dn(0.0f), dt(0.0f);
        for (uint32_t t = 0; t < targets; ++t) {
            const float w = instance.morphWeights[t];
            if (w == 0.0f) continue;
            const MorphDelta& d = scene.morphDeltas[prim.morphDeltaOffset + size_t(t) * prim.vertexCount + v];
            dp = glsl_deform::morphInfluence(dp, glm::vec3(d.position), w);
            dn = glsl_deform::morphInfluence(dn, glm::vec3(d.normal), w);
            dt = glsl_deform::morphInfluence(dt, glm::vec3(d.tangent), w);
        }
        glm::mat4 skin(0.0f);
        bool weighted = false;
        if (skinned) {
            const SkinVertex& s = scene.skinVertices[size_t(prim.skinVertexOffset) + v];
            for (int k = 0; k < 8; ++k) {
                const float w = k < 4 ? s.weights0[k] : s.weights1[k - 4];
                const uint32_t j = k < 4 ? s.joints0[k] : s.joints1[k - 4];
                if (!(w > 0.0f) || j >= joints.size()) continue;
                skin = glsl_deform::skinInfluence(skin, joints[j], w);
                weighted = true;
            }
        }
        const glsl_deform::DeformedVertex d = glsl_deform::deformVertex(
            out[v].position, out[v].normal, out[v].tangent, dp, dn, dt, skin, weighted);
        out[v].position = d.position;
        out[v].normal = d.normal;
        out[v].tangent = d.tangent;
    }
    return out;
}

Aabb deformedBounds(const Scene& scene, const Instance& instance, const std::vector<glm::mat4>& joints) {
    Aabb box;
    if (instance.mesh < 0 || size_t(instance.mesh) >= scene.meshes.size()) return box;
    for (uint32_t p : scene.meshes[size_t(instance.mesh)].primitives) {
        if (p >= scene.primitives.size()) continue;
        const Primitive& prim = scene.primitives[p];
        Aabb rest = prim.bounds;
        const uint32_t targets =
            std::min<uint32_t>(prim.morphTargetCount, uint32_t(instance.morphWeights.size()));
        if (!rest.empty() && targets > 0) {
            glm::vec3 lo(0.0f), hi(0.0f);
            for (uint32_t t = 0; t < targets; ++t) {
                const float w = instance.morphWeights[t];
                if (w == 0.0f) continue;
                Aabb delta;
                for (uint32_t v = 0; v < prim.vertexCount; ++v)
                    delta.extend(
                        glm::vec3(scene.morphDeltas[prim.morphDeltaOffset + size_t(t) * prim.vertexCount + v]
                                      .position));
                if (delta.empty()) continue;
                lo += glm::min(delta.min * w, delta.max * w);
                hi += glm::max(delta.min * w, delta.max * w);
            }
            rest = Aabb{rest.min + lo, rest.max + hi};
        }
        if (instance.skin >= 0 && prim.skinVertexOffset >= 0) {
            box.extend(rest);  // vertices without weights stay in the bind pose
            for (const glm::mat4& joint : joints) box.extend(rest.transformed(joint));
        } else {
            box.extend(rest.transformed(instance.world));
        }
    }
    return box;
}

void validateDeformation(const Scene& scene) {
    for (size_t s = 0; s < scene.skins.size(); ++s) {
        const Skin& skin = scene.skins[s];
        const std::string where = named("skin", skin.name, s) + ": ";
        if (skin.joints.empty()) fail(where + "has no joints");
        if (skin.inverseBindMatrices.size() != skin.joints.size())
            fail(where + std::to_string(skin.inverseBindMatrices.size()) + " inverse bind matrices for " +
                 std::to_string(skin.joints.size()) + " joints");
        for (size_t j = 0; j < skin.joints.size(); ++j) {
            if (skin.joints[j] < 0 || size_t(skin.joints[j]) >= scene.nodes.size())
                fail(where + "joint " + std::to_string(j) + " names node " + std::to_string(skin.joints[j]) +
                     ", out of range (" + std::to_string(scene.nodes.size()) + " nodes)");
            for (int c = 0; c < 4; ++c)
                if (!finite(skin.inverseBindMatrices[j][c]))
                    fail(where + "inverse bind matrix " + std::to_string(j) + " is not finite");
        }
    }
    for (size_t p = 0; p < scene.primitives.size(); ++p) {
        const Primitive& prim = scene.primitives[p];
        const std::string where = "primitive " + std::to_string(p) + ": ";
        if (prim.skinVertexOffset >= 0 &&
            size_t(prim.skinVertexOffset) + prim.vertexCount > scene.skinVertices.size())
            fail(where + "skin vertex range is past the end of the skin vertices");
        if (prim.morphTargetCount > 0) {
            const size_t end =
                size_t(prim.morphDeltaOffset) + size_t(prim.morphTargetCount) * prim.vertexCount;
            if (end > scene.morphDeltas.size())
                fail(where + "morph target range is past the end of the deltas");
            for (size_t d = prim.morphDeltaOffset; d < end; ++d) {
                const MorphDelta& delta = scene.morphDeltas[d];
                if (!finite(delta.position) || !finite(delta.normal) || !finite(delta.tangent))
                    fail(where + "a morph target delta is not finite");
            }
        }
        if (prim.skinVertexOffset >= 0)
            for (uint32_t v = 0; v < prim.vertexCount; ++v) {
                const SkinVertex& s = scene.skinVertices[size_t(prim.skinVertexOffset) + v];
                if (!finite(s.weights0) || !finite(s.weights1))
                    fail(where + "skin weights of vertex " + std::to_string(v) + " are not finite");
            }
    }
    for (size_t n = 0; n < scene.nodes.size(); ++n) {
        const Node& node = scene.nodes[n];
        const std::string where = named("node", node.name, n) + ": ";
        if (node.skin >= 0 && size_t(node.skin) >= scene.skins.size())
            fail(where + "skin index is out of range");
        if (node.mesh < 0 || size_t(node.mesh) >= scene.meshes.size()) continue;
        const uint32_t targets = meshMorphTargets(scene, node.mesh);
        if (!node.weights.empty() && node.weights.size() != targets)
            fail(where + std::to_string(node.weights.size()) + " morph weights for " +
                 std::to_string(targets) + " morph targets");
        for (float w : node.weights)
            if (!std::isfinite(w)) fail(where + "a morph weight is not finite");
        if (node.skin < 0) continue;
        const size_t joints = scene.skins[size_t(node.skin)].joints.size();
        for (uint32_t p : scene.meshes[size_t(node.mesh)].primitives)
            if (p < scene.primitives.size() && scene.primitives[p].skinVertexOffset >= 0 &&
                scene.primitives[p].maxJoint >= joints)
                fail(where + "its mesh names joint " + std::to_string(scene.primitives[p].maxJoint) +
                     ", but " + named("skin", scene.skins[size_t(node.skin)].name, size_t(node.skin)) +
                     " has " + std::to_string(joints) + " joints");
    }
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        const uint32_t targets = meshMorphTargets(scene, int(m));
        if (!mesh.weights.empty() && mesh.weights.size() != targets)
            fail(named("mesh", mesh.name, m) + ": " + std::to_string(mesh.weights.size()) + " weights for " +
                 std::to_string(targets) + " morph targets");
        for (float w : mesh.weights)
            if (!std::isfinite(w)) fail(named("mesh", mesh.name, m) + ": a morph weight is not finite");
    }
}

}  // namespace vct
