// The scene at one time as an Embree 3 BVH, for the path-traced reference: one triangle geometry per mesh
// instance and primitive (a "surface": what the per-surface error sums over), in world space. Camera rays
// skip the back faces of single-sided materials (the G-buffer culls them); every ray skips the texels an
// alpha-masked material discards, and passes through an alpha-blended surface with probability 1 − alpha
// (stochastic transparency: the expected radiance is alpha·surface + (1 − alpha)·behind, the "over" of the
// blend pass, docs/design.md §2.6).
#pragma once

#include <embree3/rtcore.h>

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "reference/material_eval.h"
#include "scene/scene.h"

namespace vct::reference {

// At most this many triangles over all instances (each instance is a copy: ~100 bytes per triangle with its
// BVH), so that a file instancing one big mesh many times ends in one line, not in gigabytes.
constexpr uint64_t kMaxReferenceTriangles = uint64_t(1) << 24;

struct RayHit {
    bool hit = false;
    uint32_t geometry = 0;  // index into RayScene::geometries() (the surface id)
    uint32_t triangle = 0;
    float u = 0.0f, v = 0.0f;  // Embree barycentrics: p = (1 − u − v)·p0 + u·p1 + v·p2
    float t = 0.0f;
};

struct RayGeometry {
    std::string name;  // "<node or mesh name>/<material name>"
    int node = -1;
    uint32_t primitive = 0;
    uint32_t material = 0;
    bool cullBackFacesForCamera = false;
    bool alphaMask = false;
    bool hasColors = false;   // Primitive::hasColors: COLOR_0 multiplies the base colour
    bool alphaBlend = false;  // hit with probability alpha (RayScene::rejects)
    glm::mat4 world{1.0f};
    glm::mat3 normalMatrix{1.0f};
    std::vector<glm::vec3> positions;  // world space, the primitive's vertex range
    std::vector<uint32_t> indices;     // relative to positions
    int32_t vertexOffset = 0;          // of the primitive's range in Scene::vertices
    // A skinned or morphed instance's vertices at the frame's time (scene/deform.h: the CPU twin of the skin
    // pass), in the instance's space; empty for the others, which read Scene::vertices.
    std::vector<Vertex> deformedVertices;
};

class RayScene {
  public:
    RayScene(const Scene& scene, float timeSeconds, const MaterialEvaluator& materials);
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;

    // Closest hit in (tnear, tfar). `cameraRay`: back faces of single-sided materials are not hit.
    RayHit intersect(glm::vec3 origin, glm::vec3 direction, float tnear, float tfar, bool cameraRay) const;
    // Whether anything blocks the segment (tnear, tfar).
    bool occluded(glm::vec3 origin, glm::vec3 direction, float tnear, float tfar) const;
    // The hit's interpolated geometry (world space) and its material's evaluation.
    SurfaceGeometry geometryAt(const RayHit& hit, glm::vec3 rayDirection) const;
    SurfacePoint surfaceAt(const RayHit& hit, glm::vec3 rayDirection) const;
    glm::vec2 uvAt(uint32_t geometry, uint32_t triangle, float u, float v) const;
    // The interpolated COLOR_0; exactly white for a primitive without one.
    glm::vec4 colorAt(uint32_t geometry, uint32_t triangle, float u, float v) const;
    // True where the hit is to be skipped (filter functions). A blended surface's hit is kept when a uniform
    // number hashed from the ray (origin, direction) and the hit (surface, triangle, u, v) is below its alpha:
    // reproducible (no shared random state between threads), independent between samples, whose rays differ.
    bool rejects(uint32_t geometry, uint32_t triangle, float u, float v, glm::vec3 direction, bool cameraRay,
                 glm::vec3 origin = glm::vec3(0.0f)) const;

    const std::vector<RayGeometry>& geometries() const { return geometries_; }
    uint64_t triangleCount() const { return triangleCount_; }
    // A length on the scale of the scene (its bounds' diagonal), for ray offsets.
    float extent() const { return extent_; }

  private:
    const Vertex* vertexData(const RayGeometry& g) const;

    const Scene& scene_;
    const MaterialEvaluator& materials_;
    std::vector<RayGeometry> geometries_;
    RTCDevice device_ = nullptr;
    RTCScene rtcScene_ = nullptr;
    uint64_t triangleCount_ = 0;
    float extent_ = 1.0f;
};

}  // namespace vct::reference
