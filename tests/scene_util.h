// Small scenes built in code for the tests (closed rooms, quads, lights): what the path tracer's analytic
// cases and the voxel GI's furnace and leak cases are made of.
#pragma once

#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <string>
#include <utility>

#include "scene/scene.h"
#include "scene/scene_builder.h"
#include "scene/tangents.h"

namespace vct::test::scenes {

// Appends a quad centred at c spanning ±u, ±v whose front (counter-clockwise) side faces cross(u, v).
inline void addQuad(vct::Scene& scene, glm::vec3 c, glm::vec3 u, glm::vec3 v, uint32_t material) {
    const glm::vec3 n = glm::normalize(glm::cross(u, v));
    const uint32_t base = uint32_t(scene.vertices.size());
    const glm::vec3 corners[4] = {c - u - v, c + u - v, c + u + v, c - u + v};
    const glm::vec2 uvs[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    vct::Primitive primitive;
    primitive.firstIndex = uint32_t(scene.indices.size());
    primitive.indexCount = 6;
    primitive.vertexOffset = int32_t(base);
    primitive.vertexCount = 4;
    primitive.material = material;
    for (int i = 0; i < 4; ++i) {
        scene.vertices.push_back({corners[i], n, uvs[i], glm::vec4(glm::normalize(u), 1.0f)});
        primitive.bounds.extend(corners[i]);
    }
    for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) scene.indices.push_back(i);
    scene.primitives.push_back(primitive);
    scene.meshes[0].primitives.push_back(uint32_t(scene.primitives.size() - 1));
}

// Appends an open column (no caps) of `sides` quads about the y axis: radius `radius` to the middle of its faces,
// from y = −halfHeight to +halfHeight, its front faces outwards.
inline void addColumn(vct::Scene& scene, float radius, float halfHeight, int sides, uint32_t material) {
    const float pi = 3.14159265358979f;
    const float halfWidth = radius * std::tan(pi / float(sides));
    for (int i = 0; i < sides; ++i) {
        const float a = 2.0f * pi * (float(i) + 0.5f) / float(sides);
        const glm::vec3 out(std::cos(a), 0.0f, std::sin(a));
        const glm::vec3 along(out.z, 0.0f, -out.x);  // cross(along, up) = out
        addQuad(scene, out * radius, along * halfWidth, glm::vec3(0.0f, halfHeight, 0.0f), material);
    }
}

// Appends the engine's UV sphere (scene/scene_builder.h's sphere: `segments` around, `rings` from pole to pole, with
// generated tangents) about `centre`, its front faces outwards.
inline void addSphere(vct::Scene& scene, glm::vec3 centre, float radius, uint32_t segments, uint32_t rings,
                      uint32_t material) {
    vct::Geometry g = vct::sphere(radius, segments, rings);
    for (vct::Vertex& v : g.vertices) v.position += centre;
    vct::generateTangents(g.vertices, g.indices);
    vct::Primitive primitive;
    primitive.firstIndex = uint32_t(scene.indices.size());
    primitive.indexCount = uint32_t(g.indices.size());
    primitive.vertexOffset = int32_t(scene.vertices.size());
    primitive.vertexCount = uint32_t(g.vertices.size());
    primitive.material = material;
    for (const vct::Vertex& v : g.vertices) primitive.bounds.extend(v.position);
    scene.vertices.insert(scene.vertices.end(), g.vertices.begin(), g.vertices.end());
    scene.indices.insert(scene.indices.end(), g.indices.begin(), g.indices.end());
    scene.primitives.push_back(primitive);
    scene.meshes[0].primitives.push_back(uint32_t(scene.primitives.size() - 1));
}

inline vct::Scene emptyScene(const std::string& name, const vct::Material& material) {
    vct::Scene scene;
    scene.name = name;
    scene.materials.push_back(material);
    scene.meshes.push_back({name, {}});
    vct::Node node;
    node.name = name;
    node.mesh = 0;
    scene.nodes.push_back(node);
    scene.roots = {0};
    return scene;
}

inline vct::Material diffuseMaterial(float albedo, float emission) {
    vct::Material m;
    m.name = "grey";
    m.baseColorFactor = glm::vec4(glm::vec3(albedo), 1.0f);
    m.metallicFactor = 0.0f;
    m.roughnessFactor = 1.0f;
    m.emissiveFactor = glm::vec3(emission);
    return m;
}

// Adds a light of `type` and `intensity` on a new root node and returns that node (to place or turn it).
inline vct::Node& addLight(vct::Scene& scene, const std::string& name, vct::LightType type, float intensity) {
    vct::Light light;
    light.name = name;
    light.type = type;
    light.intensity = intensity;
    scene.lights.push_back(light);
    vct::Node node;
    node.name = name;
    node.light = int(scene.lights.size() - 1);
    scene.nodes.push_back(node);
    scene.roots.push_back(int(scene.nodes.size() - 1));
    return scene.nodes.back();
}

// A floor 200 m wide lit by a directional light from unit-ish `towardsSun` (the light's direction reversed) of
// `lux`: the scene whose default environment is the procedural sky of that sun (render/environment.h).
inline vct::Scene sceneWithSun(glm::vec3 towardsSun, float lux) {
    vct::Scene scene = emptyScene("floor", diffuseMaterial(0.8f, 0.0f));
    addQuad(scene, glm::vec3(0.0f), glm::vec3(0, 0, 100), glm::vec3(100, 0, 0), 0);
    vct::Node& sun = addLight(scene, "sun", vct::LightType::Directional, lux);
    // The light shines along its local −Z: turn −Z onto −towardsSun.
    sun.rotation = glm::quatLookAtRH(-glm::normalize(towardsSun), glm::vec3(0, 1, 0));
    return scene;
}

// Appends the six inward faces of the box [lo, hi] with `material`, all but face `leftOut` (axis · 2 + 1 for the
// high side, axis · 2 for the low one; −1: none).
inline void addClosedBox(vct::Scene& scene, glm::vec3 lo, glm::vec3 hi, uint32_t material, int leftOut = -1) {
    const glm::vec3 c = 0.5f * (lo + hi), h = 0.5f * (hi - lo);
    for (int axis = 0; axis < 3; ++axis)
        for (float side : {-1.0f, 1.0f}) {
            if (axis * 2 + (side > 0.0f ? 1 : 0) == leftOut) continue;
            glm::vec3 e(0.0f);
            e[axis] = side;
            const glm::vec3 inward = -e;
            const int a = (axis + 1) % 3, b = (axis + 2) % 3;
            glm::vec3 u(0.0f), v(0.0f);
            u[a] = h[a];
            v[b] = h[b];
            // Order u, v so that cross(u, v) faces inwards.
            if (glm::dot(glm::cross(u, v), inward) < 0.0f) std::swap(u, v);
            addQuad(scene, c + e * h, u, v, material);
        }
}

// A closed cube [−1, 1]³ seen from inside: every face's front side faces inwards.
inline vct::Scene furnaceRoom(float albedo, float emission) {
    vct::Scene scene = emptyScene("furnace", diffuseMaterial(albedo, emission));
    addClosedBox(scene, glm::vec3(-1.0f), glm::vec3(1.0f), 0);
    return scene;
}

// Two closed rooms of albedo ρ side by side, sharing a wall of zero thickness at x = 0 (one quad facing each
// room): the left room [−2, 0] × [−1, 1]² has an emissive ceiling (radiance 1), the right one [0, 2] × [−1, 1]²
// no light at all. Any light in the right room has leaked through that wall: the exact answer is 0.
inline vct::Scene twoRooms(float albedo) {
    vct::Scene scene = emptyScene("two rooms", diffuseMaterial(albedo, 0.0f));
    scene.materials.push_back(diffuseMaterial(albedo, 1.0f));
    scene.materials.back().name = "emitter";
    addClosedBox(scene, {0.0f, -1.0f, -1.0f}, {2.0f, 1.0f, 1.0f}, 0);
    addClosedBox(scene, {-2.0f, -1.0f, -1.0f}, {0.0f, 1.0f, 1.0f}, 0);
    for (vct::Primitive& primitive : scene.primitives)
        if (primitive.bounds.min.y > 0.99f && primitive.bounds.max.x < 0.01f) primitive.material = 1;
    return scene;
}

// An open room (floor, left wall and back wall; no ceiling, no front) under a sun from the front, with a camera
// on the open side looking at the back wall (material 1, base colour `base`). With `vertexColors` the back
// wall's four vertices carry COLOR_0 = `color`; without, it has no vertex colours and the base colour
// `color × base` instead. The two should look the same wherever the base colour is evaluated (the G-buffer,
// the voxels, the path-traced reference): tests/vertex_color_test.cpp.
inline vct::Scene vertexColorRoom(bool vertexColors, glm::vec4 color, glm::vec3 base) {
    vct::Scene scene = emptyScene("vertex colours", diffuseMaterial(0.8f, 0.0f));
    vct::Material wall = diffuseMaterial(0.0f, 0.0f);
    wall.name = "wall";
    wall.baseColorFactor = vertexColors ? glm::vec4(base, 1.0f) : glm::vec4(base, 1.0f) * color;
    scene.materials.push_back(wall);
    addQuad(scene, glm::vec3(0.0f), glm::vec3(0, 0, 2), glm::vec3(2, 0, 0), 0);                  // floor, +y
    addQuad(scene, glm::vec3(-2.0f, 1.5f, 0.0f), glm::vec3(0, 1.5f, 0), glm::vec3(0, 0, 2), 0);  // left, +x
    addQuad(scene, glm::vec3(0.0f, 1.5f, -2.0f), glm::vec3(2, 0, 0), glm::vec3(0, 1.5f, 0), 1);  // back, +z
    if (vertexColors) {
        vct::Primitive& back = scene.primitives.back();
        back.hasColors = true;
        for (uint32_t v = 0; v < back.vertexCount; ++v)
            scene.vertices[size_t(back.vertexOffset) + v].color = color;
    }
    vct::Node& sun = addLight(scene, "sun", vct::LightType::Directional, 3.0f);
    sun.rotation = glm::angleAxis(glm::radians(-40.0f), glm::vec3(1, 0, 0));  // −Z turned down, towards −z
    scene.cameras.push_back(vct::Camera{"front", 1.0f, 0.05f, 50.0f, 0.0f});
    vct::Node camera;
    camera.name = "front";
    camera.camera = 0;
    camera.translation = glm::vec3(0.3f, 1.6f, 3.2f);
    camera.rotation = glm::quatLookAtRH(glm::normalize(glm::vec3(0.0f, 1.2f, -2.0f) - camera.translation),
                                        glm::vec3(0, 1, 0));
    scene.nodes.push_back(camera);
    scene.roots.push_back(int(scene.nodes.size() - 1));
    return scene;
}

}  // namespace vct::test::scenes
