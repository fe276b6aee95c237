// Scenes made in code: geometry primitives (quads, boxes, spheres, cylinders, arches) and a builder that
// appends meshes, materials, nodes, cameras and lights to a Scene. Used by the built-in scenes.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "scene/scene.h"

namespace vct {

// Geometry for one primitive before it is appended to the scene.
struct Geometry {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
};

// Quad with corners o, o+u, o+u+v, o+v, facing cross(u, v) (counter-clockwise seen from that side, the
// glTF front face). UVs run u: 0..uvScale.x along `u` and v: uvScale.y..0 along `v`, so an image appears
// upright when `v` points up (glTF's v grows downwards in the image).
void addQuad(Geometry& g, glm::vec3 o, glm::vec3 u, glm::vec3 v, glm::vec2 uvScale = glm::vec2(1.0f));
// Axis-aligned box with outward faces (half extents h), centred at `centre`.
void addBox(Geometry& g, glm::vec3 centre, glm::vec3 h);
// Axis-aligned box centred at the origin with outward faces (half extents h).
Geometry box(glm::vec3 h);
// UV sphere centred at the origin: u follows longitude, v latitude (v = 0 at the north pole, +Y).
Geometry sphere(float radius, uint32_t segments, uint32_t rings);
// Closed cylinder along +Y from y = 0 to `height`, centred on x = z = 0, smooth sides, flat caps.
void addCylinder(Geometry& g, glm::vec3 base, float radius, float height, uint32_t segments);
// A semicircular arch in the plane z = centre.z (thickness `depth` along z), springing from y = centre.y at
// x = centre.x ± innerRadius..outerRadius: its underside (intrados), top (extrados) and two faces.
void addArch(Geometry& g, glm::vec3 centre, float innerRadius, float outerRadius, float depth,
             uint32_t segments);

Material makeMaterial(const std::string& name, glm::vec3 baseColor, float metallic, float roughness);

// Appends meshes, materials and nodes to a Scene, generating tangents for every primitive.
class SceneBuilder {
  public:
    explicit SceneBuilder(const std::string& name) { scene.name = name; }

    uint32_t material(const Material& m);
    int texture(Texture t);
    // A mesh of one or more (geometry, material) primitives.
    int mesh(const std::string& name, std::vector<std::pair<Geometry, uint32_t>> parts);
    // A root node.
    int node(Node n);
    int cameraNode(const std::string& name, glm::vec3 position, glm::vec3 target, float yfovDegrees,
                   float zfar);
    int lightNode(const Light& light, glm::vec3 position, glm::quat rotation);

    Scene scene;
};

}  // namespace vct
