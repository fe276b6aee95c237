// Scene evaluation (animation, instances, bounds), default camera/light, validation and mip chains.
#include "scene/scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "scene/deform.h"
#include "scene/input_limits.h"

namespace vct {

namespace {
// The brightest light (colour x intensity) vct renders: the shaders divide by the squared distance (at least
// 1e-8), and light sums over bounces and pixels must stay far inside float.
constexpr float kMaxLightPower = 1e20f;
}  // namespace

Aabb Aabb::transformed(const glm::mat4& m) const {
    Aabb out;
    if (empty()) return out;
    for (int i = 0; i < 8; ++i) {
        glm::vec3 corner((i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z);
        out.extend(glm::vec3(m * glm::vec4(corner, 1.0f)));
    }
    return out;
}

glm::mat4 Node::localMatrix() const {
    if (matrix) return *matrix;
    return glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation) *
           glm::scale(glm::mat4(1.0f), scale);
}

namespace {

bool finite(const glm::vec2& v) {
    return std::isfinite(v.x) && std::isfinite(v.y);
}
bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool finite(const glm::vec4& v) {
    return finite(glm::vec3(v)) && std::isfinite(v.w);
}

glm::quat toQuat(const glm::vec4& xyzw) {
    return glm::quat(xyzw.w, xyzw.x, xyzw.y, xyzw.z);
}

// glTF stores unit quaternions, but interpolated or quantised ones drift; a zero one becomes identity.
glm::quat normalizedQuat(const glm::quat& q) {
    float len = glm::length(q);
    return len > 1e-12f && std::isfinite(len) ? q / len : glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
}

// Samples a channel at time t (already wrapped into the animation's range). Returns vec3 in xyz for
// T/S and a quaternion as x,y,z,w for R. Times before the first key clamp to it, after the last to the last.
glm::vec4 sampleChannel(const AnimationChannel& ch, float t) {
    const auto& times = ch.times;
    bool cubic = ch.interpolation == Interpolation::CubicSpline;
    auto value = [&](size_t key) { return ch.values[cubic ? key * 3 + 1 : key]; };
    if (times.size() == 1 || t <= times.front()) return value(0);
    if (t >= times.back()) return value(times.size() - 1);
    // First key strictly after t; the segment is [k, k+1].
    size_t k1 = static_cast<size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
    size_t k = k1 - 1;
    float dt = times[k1] - times[k];
    float u = dt > 0.0f ? (t - times[k]) / dt : 0.0f;
    bool rotation = ch.path == AnimationPath::Rotation;
    switch (ch.interpolation) {
        case Interpolation::Step:
            return value(k);
        case Interpolation::Linear:
            if (rotation) {
                glm::quat q =
                    glm::slerp(normalizedQuat(toQuat(value(k))), normalizedQuat(toQuat(value(k1))), u);
                return glm::vec4(q.x, q.y, q.z, q.w);
            }
            return glm::mix(value(k), value(k1), u);
        case Interpolation::CubicSpline: {
            // Hermite spline with glTF's (in-tangent, value, out-tangent) triples; tangents scale with dt.
            float u2 = u * u, u3 = u2 * u;
            glm::vec4 p0 = ch.values[k * 3 + 1], m0 = ch.values[k * 3 + 2] * dt;
            glm::vec4 p1 = ch.values[k1 * 3 + 1], m1 = ch.values[k1 * 3 + 0] * dt;
            return (2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * m0 + (-2 * u3 + 3 * u2) * p1 +
                   (u3 - u2) * m1;
        }
    }
    return value(k);
}

// Nodes in an order where every parent precedes its children; each node at most once, so a
// malformed hierarchy (cycle, shared child) cannot loop forever.
std::vector<int> topologicalOrder(const std::vector<Node>& nodes, const std::vector<int>& starts) {
    std::vector<int> order;
    std::vector<char> seen(nodes.size(), 0);
    std::vector<int> stack(starts.rbegin(), starts.rend());
    while (!stack.empty()) {
        int n = stack.back();
        stack.pop_back();
        if (n < 0 || static_cast<size_t>(n) >= nodes.size() || seen[static_cast<size_t>(n)]) continue;
        seen[static_cast<size_t>(n)] = 1;
        order.push_back(n);
        const auto& children = nodes[static_cast<size_t>(n)].children;
        stack.insert(stack.end(), children.rbegin(), children.rend());
    }
    return order;
}

std::vector<int> parentlessNodes(const std::vector<Node>& nodes) {
    std::vector<int> out;
    for (size_t i = 0; i < nodes.size(); ++i)
        if (nodes[i].parent < 0) out.push_back(static_cast<int>(i));
    return out;
}

// The rotation of a node matrix (its columns orthonormalised), identity where the matrix has none left
// (a zero scale).
glm::quat matrixRotation(const glm::mat4& m) {
    glm::mat3 axes(m);
    for (int c = 0; c < 3; ++c) {
        const float length = glm::length(axes[c]);
        if (!(length > 1e-30f) || !std::isfinite(length)) return glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
        axes[c] /= length;
    }
    return normalizedQuat(glm::quat_cast(axes));
}

// Rotation whose local -Z points along `dir` (cameras and lights look down -Z).
glm::quat lookRotation(const glm::vec3& dir) {
    glm::vec3 up = std::abs(dir.y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
    return glm::quatLookAtRH(glm::normalize(dir), up);
}

}  // namespace

namespace {

struct Fnv1a {
    uint64_t hash = 14695981039346656037ull;
    void bytes(const void* data, size_t size) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < size; ++i) hash = (hash ^ p[i]) * 1099511628211ull;
    }
    template <typename T>
    void value(const T& v) {
        bytes(&v, sizeof(v));
    }
};

}  // namespace

uint64_t sceneContentHash(const Scene& scene) {
    Fnv1a h;
    h.bytes(scene.vertices.data(), scene.vertices.size() * sizeof(Vertex));
    h.bytes(scene.indices.data(), scene.indices.size() * sizeof(uint32_t));
    for (const Primitive& p : scene.primitives) {
        h.value(p.firstIndex);
        h.value(p.indexCount);
        h.value(p.vertexOffset);
        h.value(p.material);
        h.value(p.hasColors);
    }
    for (const Material& m : scene.materials) {
        h.value(m.baseColorFactor);
        h.value(m.emissiveFactor);
        h.value(m.alphaCutoff);
        h.value(m.alphaMode);
        for (int t : {m.baseColorTexture, m.emissiveTexture}) h.value(t);
    }
    for (const Texture& t : scene.textures) {
        h.value(t.width);
        h.value(t.height);
        h.value(t.kind);
        if (!t.mips.empty()) h.bytes(t.mips[0].data(), t.mips[0].size());
    }
    for (const Instance& instance : scene.instances(0.0f)) {
        h.value(instance.mesh);
        h.value(instance.world);
        h.value(instance.moving);
    }
    return h.hash;
}

glm::mat3 worldAxes(const glm::mat4& world, const glm::quat& worldRotation) {
    glm::mat3 axes(world);
    for (int c = 0; c < 3; ++c) {
        // The squared length must stay a normal float for normalize(): ~1e-19 is the smallest usable length.
        const float squared = glm::dot(axes[c], axes[c]);
        if (!(squared > 1e-36f) || !std::isfinite(squared)) return glm::mat3_cast(worldRotation);
        axes[c] = glm::normalize(axes[c]);
    }
    // Two axes scaled into one (a singular matrix) leave no frame either.
    if (!(std::abs(glm::determinant(axes)) > 1e-6f)) return glm::mat3_cast(worldRotation);
    return axes;
}

std::vector<glm::mat4> Scene::evaluate(float timeSeconds, std::vector<glm::quat>* worldRotations) const {
    // Only the TRS of each node changes; keep just those (this runs every frame) instead of copying nodes.
    struct Pose {
        glm::vec3 t;
        glm::quat r;
        glm::vec3 s;
    };
    std::vector<Pose> pose(nodes.size());
    for (size_t n = 0; n < nodes.size(); ++n)
        pose[n] = {nodes[n].translation, nodes[n].rotation, nodes[n].scale};
    for (const Animation& anim : animations) {
        // Loop: every animation wraps over its own duration (negative times wrap too).
        float t = anim.duration > 0.0f ? std::fmod(timeSeconds, anim.duration) : 0.0f;
        if (t < 0.0f) t += anim.duration;
        for (const AnimationChannel& ch : anim.channels) {
            if (ch.node < 0 || static_cast<size_t>(ch.node) >= pose.size() || ch.times.empty()) continue;
            size_t needed = ch.times.size() * (ch.interpolation == Interpolation::CubicSpline ? 3 : 1);
            if (ch.values.size() < needed) continue;
            Pose& p = pose[static_cast<size_t>(ch.node)];
            glm::vec4 v = sampleChannel(ch, t);
            switch (ch.path) {
                case AnimationPath::Translation:
                    p.t = glm::vec3(v);
                    break;
                case AnimationPath::Rotation:
                    p.r = normalizedQuat(toQuat(v));
                    break;
                case AnimationPath::Scale:
                    p.s = glm::vec3(v);
                    break;
            }
        }
    }
    std::vector<glm::mat4> world(nodes.size(), glm::mat4(1.0f));
    if (worldRotations) worldRotations->assign(nodes.size(), glm::quat(1.0f, 0.0f, 0.0f, 0.0f));
    for (int n : topologicalOrder(nodes, parentlessNodes(nodes))) {
        const Node& node = nodes[static_cast<size_t>(n)];
        const Pose& p = pose[static_cast<size_t>(n)];
        // A node with a matrix cannot be animated (glTF), so its matrix is its pose.
        glm::mat4 local = node.matrix ? *node.matrix
                                      : glm::translate(glm::mat4(1.0f), p.t) * glm::mat4_cast(p.r) *
                                            glm::scale(glm::mat4(1.0f), p.s);
        world[static_cast<size_t>(n)] =
            node.parent >= 0 ? world[static_cast<size_t>(node.parent)] * local : local;
        if (worldRotations) {
            const glm::quat r = node.matrix ? matrixRotation(*node.matrix) : p.r;
            (*worldRotations)[static_cast<size_t>(n)] = normalizedQuat(
                node.parent >= 0 ? (*worldRotations)[static_cast<size_t>(node.parent)] * r : r);
        }
    }
    return world;
}

std::vector<bool> Scene::animatedNodes() const {
    std::vector<bool> animated(nodes.size(), false);
    for (const Animation& anim : animations)
        for (const AnimationChannel& ch : anim.channels)
            if (ch.node >= 0 && static_cast<size_t>(ch.node) < nodes.size())
                animated[static_cast<size_t>(ch.node)] = true;
    for (int n : topologicalOrder(nodes, parentlessNodes(nodes))) {
        int p = nodes[static_cast<size_t>(n)].parent;
        if (p >= 0 && animated[static_cast<size_t>(p)]) animated[static_cast<size_t>(n)] = true;
    }
    return animated;
}

std::vector<Instance> Scene::instances(float timeSeconds) const {
    std::vector<glm::mat4> world = evaluate(timeSeconds);
    std::vector<bool> animated = animatedNodes();
    const bool deforms = !skins.empty() || !morphDeltas.empty();
    std::vector<std::vector<float>> weights;
    std::vector<bool> weightAnimated;
    if (deforms) {
        weights = morphWeights(*this, timeSeconds);
        weightAnimated = weightAnimatedNodes(*this);
    }
    std::vector<Instance> out;
    for (int n : topologicalOrder(nodes, roots)) {
        const Node& node = nodes[static_cast<size_t>(n)];
        if (node.mesh < 0 || static_cast<size_t>(node.mesh) >= meshes.size()) continue;
        Instance instance{n, node.mesh, world[static_cast<size_t>(n)], animated[static_cast<size_t>(n)]};
        if (deforms) {
            // A skinned mesh is placed by its joints alone (glTF ignores its node's transform); it moves when a
            // joint does. Morphed meshes move when their weights are animated.
            instance.skin = node.skin >= 0 && static_cast<size_t>(node.skin) < skins.size() ? node.skin : -1;
            instance.morphWeights = weights[static_cast<size_t>(n)];
            instance.deformed = instance.skin >= 0 || !instance.morphWeights.empty();
            if (instance.skin >= 0) {
                instance.world = glm::mat4(1.0f);
                instance.moving = false;
                for (int joint : skins[static_cast<size_t>(instance.skin)].joints)
                    if (joint >= 0 && static_cast<size_t>(joint) < animated.size())
                        instance.moving = instance.moving || animated[static_cast<size_t>(joint)];
            }
            instance.moving = instance.moving || weightAnimated[static_cast<size_t>(n)];
        }
        if (instance.deformed) {
            instance.bounds = deformedBounds(*this, instance, jointMatrices(*this, instance.skin, world));
        } else {
            for (uint32_t p : meshes[static_cast<size_t>(node.mesh)].primitives)
                if (p < primitives.size())
                    instance.bounds.extend(primitives[p].bounds.transformed(instance.world));
        }
        out.push_back(std::move(instance));
    }
    return out;
}

Aabb Scene::bounds() const {
    Aabb box;
    for (const Instance& inst : instances(0.0f)) box.extend(inst.bounds);
    return box;
}

void Scene::scaleRootNodes(int exponent) {
    const auto scaled = [exponent](float v) { return std::ldexp(v, exponent); };
    const auto scaled3 = [&](glm::vec3 v) { return glm::vec3(scaled(v.x), scaled(v.y), scaled(v.z)); };
    const auto leavesFloat = [](float v) { return v != 0.0f && !std::isnormal(v); };
    std::vector<bool> isRoot(nodes.size(), false);
    for (int r : roots)
        if (r >= 0 && size_t(r) < nodes.size()) isRoot[size_t(r)] = true;
    bool out = false;
    for (size_t n = 0; n < nodes.size(); ++n) {
        if (!isRoot[n]) continue;
        Node& node = nodes[n];
        if (node.matrix) {
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 3; ++r)
                    out |= leavesFloat((*node.matrix)[c][r] = scaled((*node.matrix)[c][r]));
        }
        node.translation = scaled3(node.translation);
        node.scale = scaled3(node.scale);
        for (int k = 0; k < 3; ++k) out |= leavesFloat(node.scale[k]);
    }
    for (Animation& anim : animations)
        for (AnimationChannel& ch : anim.channels)
            if (ch.node >= 0 && size_t(ch.node) < nodes.size() && isRoot[size_t(ch.node)] &&
                (ch.path == AnimationPath::Translation || ch.path == AnimationPath::Scale))
                for (glm::vec4& v : ch.values) {
                    v = glm::vec4(scaled3(glm::vec3(v)), v.w);
                    if (ch.path == AnimationPath::Scale)
                        for (int k = 0; k < 3; ++k) out |= leavesFloat(v[k]);
                }
    if (out)
        throw Error(
            "the scene's size lives both in its vertices and in its node scales at float's limits: "
            "neither can be scaled by 2^" +
            std::to_string(exponent) + " without leaving float's range");
}

void Scene::normalizeScale() {
    const Aabb box = bounds();
    if (box.empty()) return;
    // The largest side in double: a span from -FLT_MAX to FLT_MAX is finite there, not in float.
    const glm::dvec3 size = glm::dvec3(box.max) - glm::dvec3(box.min);
    const double extent = std::max(size.x, std::max(size.y, size.z));
    constexpr double kMinExtent = 1e-2, kMaxExtent = 1e6;
    if (!(extent > 0.0) || (extent >= kMinExtent && extent <= kMaxExtent)) return;
    if (!std::isfinite(extent)) throw Error("the scene's extent is not finite");
    // A power of two: every scaled value keeps its bits (subnormal inputs gain them back), so the image is
    // the one the scene would give if float could hold it. The scale goes into the vertices and the
    // translations (of every node, animated ones included), never into a node's linear part: a matrix of
    // 2^-127 would be subnormal, flushed to zero on the GPU, and draw nothing. s·(T1 L1 (T2 L2 v)) =
    // T(s t1) L1 (T(s t2) L2 (s v)) for uniform s, so this is exact for any hierarchy.
    const int exponent = -std::ilogb(extent);
    const auto scaled = [exponent](float v) { return std::ldexp(v, exponent); };
    const auto scaled3 = [&](glm::vec3 v) { return glm::vec3(scaled(v.x), scaled(v.y), scaled(v.z)); };
    // When the magnitude lives in the nodes' scales rather than in the vertices (a unit triangle under a node
    // scaled by 3e38), scaling the vertices would make them subnormal: flushed to zero on the GPU, drawing
    // nothing. Then the scale goes into the root nodes instead: s·(T R S x) = T(s·t) R (s·S) x, exact for any
    // hierarchy below them.
    const auto subnormalOrInfinite = [](float v) { return v != 0.0f && !(std::isnormal(v)); };
    bool verticesLeaveFloat = false;
    for (const Vertex& v : vertices)
        for (int k = 0; k < 3; ++k) verticesLeaveFloat |= subnormalOrInfinite(scaled(v.position[k]));
    if (!verticesLeaveFloat) {
        for (Vertex& v : vertices) v.position = scaled3(v.position);
        // Skins and morph targets: world' = S world S^-1 for every node, so inverse bind matrices (inverses of
        // joint worlds) become S IBM S^-1 (their translation scaled), and position deltas scale like positions.
        for (Skin& skin : skins)
            for (glm::mat4& m : skin.inverseBindMatrices) m[3] = glm::vec4(scaled3(glm::vec3(m[3])), m[3].w);
        for (MorphDelta& d : morphDeltas)
            d.position = glm::vec4(scaled3(glm::vec3(d.position)), d.position.w);
        for (Primitive& prim : primitives)
            if (!prim.bounds.empty()) prim.bounds = Aabb{scaled3(prim.bounds.min), scaled3(prim.bounds.max)};
        for (Node& node : nodes) {
            if (node.matrix)
                for (int r = 0; r < 3; ++r) (*node.matrix)[3][r] = scaled((*node.matrix)[3][r]);
            node.translation = scaled3(node.translation);
        }
        for (Animation& anim : animations)
            for (AnimationChannel& ch : anim.channels)
                if (ch.path == AnimationPath::Translation)
                    for (glm::vec4& v : ch.values) v = glm::vec4(scaled3(glm::vec3(v)), v.w);
    } else {
        scaleRootNodes(exponent);
    }
    for (Camera& cam : cameras) {
        cam.znear = scaled(cam.znear);
        cam.zfar = scaled(cam.zfar);
    }
    for (size_t l = 0; l < lights.size(); ++l) {
        Light& light = lights[l];
        light.range = scaled(light.range);
        // A point or spot light's irradiance falls with the squared distance, which scaled by s².
        if (light.type != LightType::Directional) light.intensity = std::ldexp(light.intensity, 2 * exponent);
        if (!std::isfinite(light.intensity) || !finite(light.color * light.intensity) ||
            std::max({light.color.x, light.color.y, light.color.z}) * light.intensity > kMaxLightPower)
            throw Error("light '" + light.name + "': its intensity at this scene's scale (" +
                        numberText(extent) + " across) overflows float");
    }
    const Aabb after = bounds();
    const float newExtent =
        std::max({after.max.x - after.min.x, after.max.y - after.min.y, after.max.z - after.min.z});
    if (!(newExtent >= 0.25f && newExtent <= 4.0f))
        throw Error("the scene (" + numberText(extent) + " across) cannot be brought into float's range: " +
                    numberText(newExtent) + " across after scaling by 2^" + std::to_string(exponent));
    notes.push_back("scene is " + numberText(extent) + " units across: scaled by 2^" +
                    std::to_string(exponent) +
                    " to keep float math in range (lights and cameras scaled with it)");
}

void Scene::addDefaultsIfMissing() {
    bool hasCamera = false, hasLight = false;
    for (int n : topologicalOrder(nodes, roots)) {
        const Node& node = nodes[static_cast<size_t>(n)];
        hasCamera |= node.camera >= 0 && static_cast<size_t>(node.camera) < cameras.size();
        hasLight |= node.light >= 0 && static_cast<size_t>(node.light) < lights.size();
    }
    Aabb box = bounds();
    if (box.empty()) box = Aabb{glm::vec3(-1.0f), glm::vec3(1.0f)};
    glm::vec3 centre = 0.5f * (box.min + box.max);
    float radius = std::max(0.5f * glm::length(box.max - box.min), 1e-3f);

    if (!hasCamera) {
        Camera cam;
        cam.name = "default camera";
        cam.yfov = glm::radians(45.0f);
        // Far enough that the bounding sphere fits the vertical field of view, with a margin.
        float distance = 1.1f * radius / std::sin(0.5f * cam.yfov);
        cam.znear = std::max(1e-3f, 0.01f * radius);
        cam.zfar = 4.0f * (distance + radius);
        glm::vec3 fromCentre = glm::normalize(glm::vec3(0.0f, 0.35f, 1.0f));  // front, a little above
        Node node;
        node.name = "default camera";
        node.translation = centre + fromCentre * distance;
        node.rotation = lookRotation(-fromCentre);
        node.camera = static_cast<int>(cameras.size());
        cameras.push_back(cam);
        roots.push_back(static_cast<int>(nodes.size()));
        nodes.push_back(node);
        notes.push_back(kDefaultCameraNote);
    }
    if (!hasLight) {
        Light light;
        light.name = "default light";
        light.type = LightType::Directional;
        light.intensity = 3.0f;  // lux; a dim overcast-sky level that exposure 1 shows well
        glm::vec3 dir = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.6f));  // from above, front, slightly right
        Node node;
        node.name = "default light";
        node.translation = centre - dir * (2.0f * radius);  // position is irrelevant for a directional light
        node.rotation = lookRotation(dir);
        node.light = static_cast<int>(lights.size());
        lights.push_back(light);
        roots.push_back(static_cast<int>(nodes.size()));
        nodes.push_back(node);
        notes.push_back("scene has no light: added a default directional light");
    }
}

namespace {

// Scene::validate, one entity kind at a time (in the order the checks have always run: the first problem
// found is the one reported).
[[noreturn]] void fail(const std::string& what) {
    throw Error(what);
}

std::string quoted(const std::string& s, size_t i) {
    return "'" + (s.empty() ? "#" + std::to_string(i) : s) + "'";
}

void validateTextures(const Scene& scene) {
    for (size_t t = 0; t < scene.textures.size(); ++t) {
        const Texture& tex = scene.textures[t];
        size_t expected = size_t(tex.width) * tex.height * 4;
        if (tex.width == 0 || tex.height == 0 || tex.mips.empty() || tex.mips[0].size() != expected)
            fail("texture " + quoted(tex.name, t) + ": image data does not match its size " +
                 std::to_string(tex.width) + "x" + std::to_string(tex.height));
    }
}

void validateMaterials(const Scene& scene) {
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        const Material& mat = scene.materials[m];
        for (int tex : {mat.baseColorTexture, mat.metallicRoughnessTexture, mat.normalTexture,
                        mat.emissiveTexture, mat.occlusionTexture})
            if (tex < -1 || tex >= static_cast<int>(scene.textures.size()))
                fail("material " + quoted(mat.name, m) + ": texture index " + std::to_string(tex) +
                     " is out of range");
        if (!finite(mat.baseColorFactor) || !finite(mat.emissiveFactor) ||
            !std::isfinite(mat.metallicFactor) || !std::isfinite(mat.roughnessFactor))
            fail("material " + quoted(mat.name, m) + ": a factor is not finite");
    }
}

// One primitive of a mesh: its ranges in the index and vertex buffers, its indices and its vertices.
void validatePrimitive(const Scene& scene, const Primitive& prim, const std::string& where) {
    if (prim.material >= scene.materials.size())
        fail(where + "material " + std::to_string(prim.material) + " is out of range (" +
             std::to_string(scene.materials.size()) + " materials)");
    if (size_t(prim.firstIndex) + prim.indexCount > scene.indices.size())
        fail(where + "index range is past the end of the index buffer");
    if (prim.vertexOffset < 0 || size_t(prim.vertexOffset) + prim.vertexCount > scene.vertices.size())
        fail(where + "vertex range is past the end of the vertex buffer");
    if (prim.indexCount % 3 != 0) fail(where + "index count is not a multiple of 3");
    for (uint32_t i = 0; i < prim.indexCount; ++i) {
        uint32_t index = scene.indices[prim.firstIndex + i];
        if (index >= prim.vertexCount)
            fail(where + "index " + std::to_string(i) + " (= " + std::to_string(index) +
                 ") is out of range (" + std::to_string(prim.vertexCount) + " vertices)");
    }
    for (uint32_t v = 0; v < prim.vertexCount; ++v) {
        const Vertex& vert = scene.vertices[size_t(prim.vertexOffset) + v];
        const char* bad = !finite(vert.position)  ? "position"
                          : !finite(vert.normal)  ? "normal"
                          : !finite(vert.uv)      ? "texture coordinate"
                          : !finite(vert.tangent) ? "tangent"
                          : !finite(vert.color)   ? "colour"
                                                  : nullptr;
        if (bad) fail(where + "vertex " + std::to_string(v) + " has a non-finite " + bad);
    }
}

void validateMeshes(const Scene& scene) {
    for (size_t me = 0; me < scene.meshes.size(); ++me) {
        const Mesh& mesh = scene.meshes[me];
        for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
            std::string where = "mesh " + quoted(mesh.name, me) + " primitive " + std::to_string(pi) + ": ";
            if (mesh.primitives[pi] >= scene.primitives.size())
                fail(where + "primitive index is out of range");
            validatePrimitive(scene, scene.primitives[mesh.primitives[pi]], where);
        }
    }
}

void validateNodes(const Scene& scene) {
    for (size_t n = 0; n < scene.nodes.size(); ++n) {
        const Node& node = scene.nodes[n];
        std::string where = "node " + quoted(node.name, n) + ": ";
        if (node.mesh >= static_cast<int>(scene.meshes.size())) fail(where + "mesh index is out of range");
        if (node.camera >= static_cast<int>(scene.cameras.size()))
            fail(where + "camera index is out of range");
        if (node.light >= static_cast<int>(scene.lights.size())) fail(where + "light index is out of range");
        for (int c : node.children)
            if (c < 0 || c >= static_cast<int>(scene.nodes.size()))
                fail(where + "child index is out of range");
        bool finiteTransform =
            finite(node.translation) && finite(node.scale) &&
            finite(glm::vec4(node.rotation.x, node.rotation.y, node.rotation.z, node.rotation.w));
        if (node.matrix)
            for (int c = 0; c < 4; ++c) finiteTransform = finiteTransform && finite((*node.matrix)[c]);
        if (!finiteTransform) fail(where + "transform is not finite");
    }
}

// Lights and cameras like material factors: finite, and in the range their formulas are defined for.
constexpr float kHalfPi = 1.5707964f, kPi = 3.1415927f;

void validateLights(const Scene& scene) {
    for (size_t l = 0; l < scene.lights.size(); ++l) {
        const Light& light = scene.lights[l];
        const std::string where = "light " + quoted(light.name, l) + ": ";
        if (!finite(light.color) || light.color.x < 0.0f || light.color.y < 0.0f || light.color.z < 0.0f)
            fail(where + "color is not finite and non-negative");
        if (!std::isfinite(light.intensity) || light.intensity < 0.0f)
            fail(where + "intensity " + numberText(light.intensity) + " is not finite and non-negative");
        if (!finite(light.color * light.intensity)) fail(where + "color x intensity overflows float");
        // The shaders divide by the squared distance (at least 1e-8): past this, light would overflow.
        const float power = std::max({light.color.x, light.color.y, light.color.z}) * light.intensity;
        if (power > kMaxLightPower)
            fail(where + "color x intensity " + numberText(power) + " is beyond the " +
                 numberText(kMaxLightPower) + " vct renders (its light would overflow float)");
        if (!std::isfinite(light.range) || light.range < 0.0f)
            fail(where + "range " + numberText(light.range) + " is not finite and non-negative");
        if (light.type == LightType::Spot &&
            !(light.innerConeAngle >= 0.0f && light.innerConeAngle < light.outerConeAngle &&
              light.outerConeAngle <= kHalfPi))
            fail(where + "spot cone angles " + numberText(light.innerConeAngle) + ", " +
                 numberText(light.outerConeAngle) + " are not 0 <= inner < outer <= pi/2");
    }
}

void validateCameras(const Scene& scene) {
    for (size_t c = 0; c < scene.cameras.size(); ++c) {
        const Camera& cam = scene.cameras[c];
        const std::string where = "camera " + quoted(cam.name, c) + ": ";
        if (!(cam.yfov > 0.0f && cam.yfov < kPi))
            fail(where + "yfov " + numberText(cam.yfov) + " is not in (0, pi)");
        if (!(cam.znear > 0.0f) || !std::isfinite(cam.znear))
            fail(where + "znear " + numberText(cam.znear) + " is not finite and positive");
        if (!std::isfinite(cam.zfar)) fail(where + "zfar is not finite");
    }
}

// Each node may be finite while their product is not (a scale of 1e20 over a translation of 1e20): the
// world transforms at t = 0 and at every key time (up to a few thousand) must be finite too.
void validateWorldTransforms(const Scene& scene) {
    std::vector<float> times{0.0f};
    for (const Animation& anim : scene.animations)
        for (const AnimationChannel& ch : anim.channels)
            times.insert(times.end(), ch.times.begin(), ch.times.end());
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
    // Between keys too: two finite keys can interpolate past float's range midway.
    for (size_t i = 0, keys = times.size(); i + 1 < keys && keys < 4096; ++i)
        times.push_back(0.5f * times[i] + 0.5f * times[i + 1]);
    std::sort(times.begin(), times.end());
    const size_t step = std::max<size_t>(1, times.size() / 4096);
    for (size_t t = 0; t < times.size(); t += step) {
        const std::vector<glm::mat4> world = scene.evaluate(times[t]);
        for (size_t n = 0; n < world.size(); ++n)
            for (int col = 0; col < 4; ++col)
                if (!finite(world[n][col]))
                    fail("node " + quoted(scene.nodes[n].name, n) +
                         ": world transform at t = " + std::to_string(times[t]) +
                         " is not finite (the product of its ancestors' transforms overflows float)");
    }
}

// Something to draw, finite bounds, and every camera near enough to see it.
void validateExtent(const Scene& scene) {
    if (scene.instances(0.0f).empty())
        fail("scene " + quoted(scene.name, 0) + " has no mesh instances: nothing to draw");
    const Aabb box = scene.bounds();
    if (!finite(box.min) || !finite(box.max))
        fail("scene " + quoted(scene.name, 0) +
             ": the transformed vertices are not finite (bounds overflow float)");
    // A camera a million scene sizes away sees at most a pixel of it, and its view products overflow float
    // long before a float position does.
    const glm::vec3 size = box.max - box.min, centre = 0.5f * box.min + 0.5f * box.max;
    const double reach = 1e6 * std::max(double(std::max(size.x, std::max(size.y, size.z))), 1e-30);
    const std::vector<glm::mat4> world = scene.evaluate(0.0f);
    for (size_t n = 0; n < scene.nodes.size(); ++n) {
        if (scene.nodes[n].camera < 0) continue;
        const glm::dvec3 offset = glm::dvec3(glm::vec3(world[n][3])) - glm::dvec3(centre);
        if (glm::length(offset) > reach)
            fail("node " + quoted(scene.nodes[n].name, n) + ": its camera is " +
                 numberText(glm::length(offset)) +
                 " units from the scene, more than 1e6 times the scene's size: nothing would be in view");
    }
}

}  // namespace

void Scene::validate() const {
    validateTextures(*this);
    validateMaterials(*this);
    validateMeshes(*this);
    validateNodes(*this);
    validateDeformation(*this);
    validateLights(*this);
    validateCameras(*this);
    validateWorldTransforms(*this);
    validateExtent(*this);
}

namespace {

// sRGB transfer functions (IEC 61966-2-1), used so Color mips average light, not encoded values.
float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}
float linearToSrgb(float c) {
    c = std::clamp(c, 0.0f, 1.0f);
    return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

}  // namespace

void buildMipChain(Texture& texture) {
    if (texture.mips.empty() || texture.width == 0 || texture.height == 0) return;
    texture.mips.resize(1);
    bool srgb = texture.kind == TextureKind::Color;

    // Work in float from level 0 to the last level so rounding does not accumulate level after level.
    std::array<float, 256> decode{};
    for (int i = 0; i < 256; ++i)
        decode[static_cast<size_t>(i)] = srgb ? srgbToLinear(i / 255.0f) : i / 255.0f;
    uint32_t w = texture.width, h = texture.height;
    std::vector<float> level(size_t(w) * h * 4);
    const std::vector<uint8_t>& base = texture.mips[0];
    for (size_t i = 0; i < level.size(); ++i)
        level[i] = (i % 4 == 3) ? base[i] / 255.0f : decode[base[i]];  // alpha is always linear

    while (w > 1 || h > 1) {
        uint32_t nw = std::max(1u, w / 2), nh = std::max(1u, h / 2);
        std::vector<float> next(size_t(nw) * nh * 4, 0.0f);
        // Box filter: texel x of the new level covers source texels 2x and 2x+1; for an odd source size
        // the last one also takes the leftover texel, so every source texel contributes.
        auto span = [](uint32_t x, uint32_t src, uint32_t dst, uint32_t& first, uint32_t& count) {
            first = std::min(2 * x, src - 1);
            count = src == 1 ? 1 : (x == dst - 1 && (src & 1) ? 3 : 2);
        };
        for (uint32_t y = 0; y < nh; ++y) {
            uint32_t y0, ny;
            span(y, h, nh, y0, ny);
            for (uint32_t x = 0; x < nw; ++x) {
                uint32_t x0, nx;
                span(x, w, nw, x0, nx);
                float* out = &next[(size_t(y) * nw + x) * 4];
                for (uint32_t sy = y0; sy < y0 + ny; ++sy)
                    for (uint32_t sx = x0; sx < x0 + nx; ++sx)
                        for (int c = 0; c < 4; ++c) out[c] += level[(size_t(sy) * w + sx) * 4 + size_t(c)];
                for (int c = 0; c < 4; ++c) out[c] /= float(nx * ny);
            }
        }
        // Normal maps: averaging the encoded values equals averaging the decoded normals (the encoding is
        // affine), and we deliberately do not renormalise: |N̄| < 1 is what Toksvig's roughness needs.
        std::vector<uint8_t> bytes(next.size());
        for (size_t i = 0; i < next.size(); ++i) {
            float v = (srgb && i % 4 != 3) ? linearToSrgb(next[i]) : std::clamp(next[i], 0.0f, 1.0f);
            bytes[i] = static_cast<uint8_t>(std::lround(v * 255.0f));
        }
        texture.mips.push_back(std::move(bytes));
        level = std::move(next);
        w = nw;
        h = nh;
    }
}

}  // namespace vct
