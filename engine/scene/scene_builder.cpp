#include "scene/scene_builder.h"

#include <cmath>
#include <glm/gtc/constants.hpp>

#include "scene/tangents.h"

namespace vct {

void addQuad(Geometry& g, glm::vec3 o, glm::vec3 u, glm::vec3 v, glm::vec2 uvScale) {
    auto base = static_cast<uint32_t>(g.vertices.size());
    glm::vec3 n = glm::normalize(glm::cross(u, v));
    const glm::vec2 corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (const glm::vec2& c : corners) {
        Vertex vert;
        vert.position = o + c.x * u + c.y * v;
        vert.normal = n;
        vert.uv = glm::vec2(c.x, 1.0f - c.y) * uvScale;
        g.vertices.push_back(vert);
    }
    g.indices.insert(g.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

void addBox(Geometry& g, glm::vec3 c, glm::vec3 h) {
    glm::vec3 X(2 * h.x, 0, 0), Y(0, 2 * h.y, 0), Z(0, 0, 2 * h.z);
    addQuad(g, c + glm::vec3(h.x, -h.y, h.z), -Z, Y);   // +X
    addQuad(g, c + glm::vec3(-h.x, -h.y, -h.z), Z, Y);  // -X
    addQuad(g, c + glm::vec3(-h.x, -h.y, h.z), X, Y);   // +Z
    addQuad(g, c + glm::vec3(h.x, -h.y, -h.z), -X, Y);  // -Z
    addQuad(g, c + glm::vec3(-h.x, h.y, h.z), X, -Z);   // +Y
    addQuad(g, c + glm::vec3(-h.x, -h.y, -h.z), X, Z);  // -Y
}

Geometry box(glm::vec3 h) {
    Geometry g;
    addBox(g, glm::vec3(0.0f), h);
    return g;
}

Geometry sphere(float radius, uint32_t segments, uint32_t rings) {
    Geometry g;
    for (uint32_t i = 0; i <= rings; ++i) {
        float theta = glm::pi<float>() * float(i) / float(rings);
        for (uint32_t j = 0; j <= segments; ++j) {
            float phi = glm::two_pi<float>() * float(j) / float(segments);
            Vertex v;
            v.normal =
                glm::vec3(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
            v.position = radius * v.normal;
            v.uv = glm::vec2(float(j) / float(segments), float(i) / float(rings));
            g.vertices.push_back(v);
        }
    }
    for (uint32_t i = 0; i < rings; ++i) {
        for (uint32_t j = 0; j < segments; ++j) {
            uint32_t a = i * (segments + 1) + j, b = a + segments + 1;  // a: this ring, b: the ring below
            g.indices.insert(g.indices.end(), {a, b, b + 1, a, b + 1, a + 1});
        }
    }
    return g;
}

void addCylinder(Geometry& g, glm::vec3 base, float radius, float height, uint32_t segments) {
    const uint32_t first = uint32_t(g.vertices.size());
    for (uint32_t j = 0; j <= segments; ++j) {  // the side: a column of two vertices per angle
        const float phi = glm::two_pi<float>() * float(j) / float(segments);
        const glm::vec3 n(std::sin(phi), 0.0f, std::cos(phi));
        for (int k = 0; k < 2; ++k) {
            Vertex v;
            v.normal = n;
            v.position = base + radius * n + glm::vec3(0.0f, k ? height : 0.0f, 0.0f);
            v.uv = glm::vec2(float(j) / float(segments), k ? 0.0f : 1.0f);
            g.vertices.push_back(v);
        }
    }
    for (uint32_t j = 0; j < segments; ++j) {
        const uint32_t a = first + 2 * j;  // a: bottom, a + 1: top, a + 2 / a + 3: the next angle's
        g.indices.insert(g.indices.end(), {a, a + 2, a + 3, a, a + 3, a + 1});
    }
    for (int k = 0; k < 2; ++k) {  // caps: fans around their centres, facing -Y and +Y
        const uint32_t centre = uint32_t(g.vertices.size());
        const glm::vec3 n(0.0f, k ? 1.0f : -1.0f, 0.0f);
        Vertex c;
        c.normal = n;
        c.position = base + glm::vec3(0.0f, k ? height : 0.0f, 0.0f);
        c.uv = glm::vec2(0.5f);
        g.vertices.push_back(c);
        for (uint32_t j = 0; j <= segments; ++j) {
            const float phi = glm::two_pi<float>() * float(j) / float(segments);
            Vertex v = c;
            v.position += radius * glm::vec3(std::sin(phi), 0.0f, std::cos(phi));
            v.uv = 0.5f + 0.5f * glm::vec2(std::sin(phi), std::cos(phi));
            g.vertices.push_back(v);
        }
        for (uint32_t j = 0; j < segments; ++j) {
            // Counter-clockwise seen from outside: the bottom cap is seen from below.
            if (k)
                g.indices.insert(g.indices.end(), {centre, centre + 1 + j, centre + 2 + j});
            else
                g.indices.insert(g.indices.end(), {centre, centre + 2 + j, centre + 1 + j});
        }
    }
}

void addArch(Geometry& g, glm::vec3 centre, float innerRadius, float outerRadius, float depth,
             uint32_t segments) {
    const float zf = centre.z + 0.5f * depth, zb = centre.z - 0.5f * depth;
    auto at = [&](float radius, float angle, float z) {
        return glm::vec3(centre.x + radius * std::cos(angle), centre.y + radius * std::sin(angle), z);
    };
    for (uint32_t j = 0; j < segments; ++j) {
        const float a0 = glm::pi<float>() * float(j) / float(segments);
        const float a1 = glm::pi<float>() * float(j + 1) / float(segments);
        // Intrados faces the arch's centre, extrados away from it (each a flat facet per segment).
        const glm::vec3 i0 = at(innerRadius, a0, zb), i1 = at(innerRadius, a1, zb);
        addQuad(g, i0, i1 - i0, glm::vec3(0.0f, 0.0f, depth));
        const glm::vec3 o0 = at(outerRadius, a0, zf), o1 = at(outerRadius, a1, zf);
        addQuad(g, o0, o1 - o0, glm::vec3(0.0f, 0.0f, -depth));
        // The two faces (z = zf towards +Z, z = zb towards -Z) as one quad per segment.
        const glm::vec3 f0 = at(innerRadius, a0, zf), f1 = at(outerRadius, a0, zf);
        const glm::vec3 f2 = at(outerRadius, a1, zf), f3 = at(innerRadius, a1, zf);
        const uint32_t base = uint32_t(g.vertices.size());
        for (const glm::vec3& p : {f0, f1, f2, f3}) {
            Vertex v;
            v.position = p;
            v.normal = glm::vec3(0.0f, 0.0f, 1.0f);
            v.uv = glm::vec2(p.x, -p.y);
            g.vertices.push_back(v);
        }
        g.indices.insert(g.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
        const uint32_t back = uint32_t(g.vertices.size());
        for (const glm::vec3& p : {f0, f1, f2, f3}) {
            Vertex v;
            v.position = glm::vec3(p.x, p.y, zb);
            v.normal = glm::vec3(0.0f, 0.0f, -1.0f);
            v.uv = glm::vec2(-p.x, -p.y);
            g.vertices.push_back(v);
        }
        g.indices.insert(g.indices.end(), {back, back + 2, back + 1, back, back + 3, back + 2});
    }
}

Material makeMaterial(const std::string& name, glm::vec3 baseColor, float metallic, float roughness) {
    Material m;
    m.name = name;
    m.baseColorFactor = glm::vec4(baseColor, 1.0f);
    m.metallicFactor = metallic;
    m.roughnessFactor = roughness;
    return m;
}

uint32_t SceneBuilder::material(const Material& m) {
    scene.materials.push_back(m);
    return uint32_t(scene.materials.size() - 1);
}

int SceneBuilder::texture(Texture t) {
    scene.textures.push_back(std::move(t));
    return int(scene.textures.size() - 1);
}

int SceneBuilder::mesh(const std::string& name, std::vector<std::pair<Geometry, uint32_t>> parts) {
    Mesh m;
    m.name = name;
    for (auto& [g, mat] : parts) {
        generateTangents(g.vertices, g.indices);
        Primitive p;
        p.firstIndex = uint32_t(scene.indices.size());
        p.indexCount = uint32_t(g.indices.size());
        p.vertexOffset = int32_t(scene.vertices.size());
        p.vertexCount = uint32_t(g.vertices.size());
        p.material = mat;
        for (const Vertex& v : g.vertices) p.bounds.extend(v.position);
        scene.vertices.insert(scene.vertices.end(), g.vertices.begin(), g.vertices.end());
        scene.indices.insert(scene.indices.end(), g.indices.begin(), g.indices.end());
        m.primitives.push_back(uint32_t(scene.primitives.size()));
        scene.primitives.push_back(p);
    }
    scene.meshes.push_back(std::move(m));
    return int(scene.meshes.size() - 1);
}

int SceneBuilder::node(Node n) {
    scene.nodes.push_back(std::move(n));
    scene.roots.push_back(int(scene.nodes.size() - 1));
    return int(scene.nodes.size() - 1);
}

int SceneBuilder::cameraNode(const std::string& name, glm::vec3 position, glm::vec3 target, float yfovDegrees,
                             float zfar) {
    Camera cam;
    cam.name = name;
    cam.yfov = glm::radians(yfovDegrees);
    cam.znear = 0.05f;
    cam.zfar = zfar;
    scene.cameras.push_back(cam);
    Node n;
    n.name = name;
    n.translation = position;
    n.rotation =
        glm::quatLookAtRH(glm::normalize(target - position), glm::vec3(0, 1, 0));  // -Z looks at target
    n.camera = int(scene.cameras.size() - 1);
    return node(n);
}

int SceneBuilder::lightNode(const Light& light, glm::vec3 position, glm::quat rotation) {
    scene.lights.push_back(light);
    Node n;
    n.name = light.name;
    n.translation = position;
    n.rotation = rotation;
    n.light = int(scene.lights.size() - 1);
    return node(n);
}

}  // namespace vct
