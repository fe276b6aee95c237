#include "reference/ray_scene.h"

#include <cmath>
#include <cstring>
#include <limits>

#include "core/error.h"
#include "scene/deform.h"

namespace vct::reference {

namespace {

// The context every ray carries, so that filter functions know the scene and what kind of ray it is.
struct RayContext {
    RTCIntersectContext embree;  // first member: Embree passes a pointer to it back to the filters
    const RayScene* scene = nullptr;
    bool cameraRay = false;
};

void filterHit(const RTCFilterFunctionNArguments* args) {
    const auto* context = reinterpret_cast<const RayContext*>(args->context);
    const auto geometry = uint32_t(reinterpret_cast<uintptr_t>(args->geometryUserPtr));
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        const glm::vec3 direction(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                                  RTCRayN_dir_z(args->ray, args->N, i));
        const glm::vec3 origin(RTCRayN_org_x(args->ray, args->N, i), RTCRayN_org_y(args->ray, args->N, i),
                               RTCRayN_org_z(args->ray, args->N, i));
        if (context->scene->rejects(geometry, RTCHitN_primID(args->hit, args->N, i),
                                    RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i),
                                    direction, context->cameraRay, origin))
            args->valid[i] = 0;
    }
}

void reportEmbreeError(void*, RTCError code, const char* message) {
    // Errors are checked where they matter (device and scene creation); this only keeps Embree quiet
    // otherwise.
    (void)code;
    (void)message;
}

// The triangle's unnormalised normal by its winding: the counter-clockwise (front) side faces along it, as
// the raster decides facing from the world-space vertices.
glm::vec3 windingNormal(const RayGeometry& g, uint32_t triangle) {
    const uint32_t* tri = &g.indices[size_t(triangle) * 3];
    return glm::cross(g.positions[tri[1]] - g.positions[tri[0]], g.positions[tri[2]] - g.positions[tri[0]]);
}

// A 32-bit integer hash with full avalanche (the "lowbias32" finaliser of C. Wellons' hash prospector).
uint32_t hashMix(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7FEB352Du;
    x ^= x >> 15;
    x *= 0x846CA68Bu;
    x ^= x >> 16;
    return x;
}

std::string nodeName(const Scene& scene, int node) {
    const Node& n = scene.nodes[size_t(node)];
    if (!n.name.empty()) return n.name;
    if (n.mesh >= 0 && !scene.meshes[size_t(n.mesh)].name.empty()) return scene.meshes[size_t(n.mesh)].name;
    return "node " + std::to_string(node);
}

}  // namespace

RayScene::RayScene(const Scene& scene, float timeSeconds, const MaterialEvaluator& materials)
    : scene_(scene), materials_(materials) {
    Aabb bounds;
    const std::vector<glm::mat4> world = scene.evaluate(timeSeconds);
    for (const Instance& instance : scene.instances(timeSeconds)) {
        const Mesh& mesh = scene.meshes[size_t(instance.mesh)];
        const std::vector<glm::mat4> joints = jointMatrices(scene, instance.skin, world);
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(instance.world)));
        for (uint32_t primitiveIndex : mesh.primitives) {
            const Primitive& primitive = scene.primitives[primitiveIndex];
            if (primitive.indexCount < 3) continue;
            triangleCount_ += primitive.indexCount / 3;
            if (triangleCount_ > kMaxReferenceTriangles)
                throw Error("scene '" + scene.name + "': more than " +
                            std::to_string(kMaxReferenceTriangles) +
                            " triangles over all instances, too many for the path-traced reference");
            RayGeometry g;
            const Material& material = scene.materials[primitive.material];
            g.name =
                nodeName(scene, instance.node) + "/" +
                (material.name.empty() ? "material " + std::to_string(primitive.material) : material.name);
            g.node = instance.node;
            g.primitive = primitiveIndex;
            g.material = primitive.material;
            g.cullBackFacesForCamera = !material.doubleSided;
            g.alphaMask = material.alphaMode == AlphaMode::Mask;
            g.hasColors = primitive.hasColors;
            g.alphaBlend = material.alphaMode == AlphaMode::Blend;
            g.world = instance.world;
            g.normalMatrix = std::isfinite(normalMatrix[0][0]) ? normalMatrix : glm::mat3(1.0f);
            g.vertexOffset = primitive.vertexOffset;
            g.positions.reserve(primitive.vertexCount);
            if (instance.deformed)
                g.deformedVertices = deformPrimitive(scene, instance, primitiveIndex, joints);
            const Vertex* source = vertexData(g);
            for (uint32_t i = 0; i < primitive.vertexCount; ++i) {
                const glm::vec3 p = glm::vec3(instance.world * glm::vec4(source[i].position, 1.0f));
                g.positions.push_back(p);
                bounds.extend(p);
            }
            const uint32_t triangles = primitive.indexCount / 3;
            g.indices.assign(scene.indices.begin() + primitive.firstIndex,
                             scene.indices.begin() + primitive.firstIndex + triangles * 3);
            geometries_.push_back(std::move(g));
        }
    }
    extent_ = bounds.empty() ? 1.0f : std::max(glm::length(bounds.max - bounds.min), 1e-6f);

    device_ = rtcNewDevice(nullptr);
    if (!device_)
        throw Error("Embree: cannot create a device (error " +
                    std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
    rtcSetDeviceErrorFunction(device_, reportEmbreeError, nullptr);
    rtcScene_ = rtcNewScene(device_);
    rtcSetSceneBuildQuality(rtcScene_, RTC_BUILD_QUALITY_HIGH);
    for (size_t index = 0; index < geometries_.size(); ++index) {
        const RayGeometry& g = geometries_[index];
        RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), g.positions.size()));
        auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                                       RTC_FORMAT_UINT3, 3 * sizeof(uint32_t),
                                                                       g.indices.size() / 3));
        if (!vertices || !indices) {
            rtcReleaseGeometry(geometry);
            throw Error("Embree: out of memory building the scene of '" + scene.name + "'");
        }
        for (size_t i = 0; i < g.positions.size(); ++i) {
            vertices[3 * i + 0] = g.positions[i].x;
            vertices[3 * i + 1] = g.positions[i].y;
            vertices[3 * i + 2] = g.positions[i].z;
        }
        std::copy(g.indices.begin(), g.indices.end(), indices);
        rtcSetGeometryUserData(geometry, reinterpret_cast<void*>(uintptr_t(index)));
        if (g.cullBackFacesForCamera || g.alphaMask || g.alphaBlend)
            rtcSetGeometryIntersectFilterFunction(geometry, filterHit);
        if (g.alphaMask || g.alphaBlend) rtcSetGeometryOccludedFilterFunction(geometry, filterHit);
        rtcCommitGeometry(geometry);
        rtcAttachGeometryByID(rtcScene_, geometry, unsigned(index));
        rtcReleaseGeometry(geometry);
    }
    rtcCommitScene(rtcScene_);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE)
        throw Error("Embree: building the BVH of '" + scene.name + "' failed");
}

RayScene::~RayScene() {
    if (rtcScene_) rtcReleaseScene(rtcScene_);
    if (device_) rtcReleaseDevice(device_);
}

RayHit RayScene::intersect(glm::vec3 origin, glm::vec3 direction, float tnear, float tfar,
                           bool cameraRay) const {
    RayContext context;
    rtcInitIntersectContext(&context.embree);
    context.scene = this;
    context.cameraRay = cameraRay;
    RTCRayHit rayHit{};
    rayHit.ray.org_x = origin.x;
    rayHit.ray.org_y = origin.y;
    rayHit.ray.org_z = origin.z;
    rayHit.ray.dir_x = direction.x;
    rayHit.ray.dir_y = direction.y;
    rayHit.ray.dir_z = direction.z;
    rayHit.ray.tnear = tnear;
    rayHit.ray.tfar = tfar;
    rayHit.ray.mask = 0xFFFFFFFFu;
    rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(rtcScene_, &context.embree, &rayHit);
    RayHit hit;
    if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
    hit.hit = true;
    hit.geometry = rayHit.hit.geomID;
    hit.triangle = rayHit.hit.primID;
    hit.u = rayHit.hit.u;
    hit.v = rayHit.hit.v;
    hit.t = rayHit.ray.tfar;
    return hit;
}

bool RayScene::occluded(glm::vec3 origin, glm::vec3 direction, float tnear, float tfar) const {
    if (!(tfar > tnear)) return false;
    RayContext context;
    rtcInitIntersectContext(&context.embree);
    context.scene = this;
    RTCRay ray{};
    ray.org_x = origin.x;
    ray.org_y = origin.y;
    ray.org_z = origin.z;
    ray.dir_x = direction.x;
    ray.dir_y = direction.y;
    ray.dir_z = direction.z;
    ray.tnear = tnear;
    ray.tfar = tfar;
    ray.mask = 0xFFFFFFFFu;
    rtcOccluded1(rtcScene_, &context.embree, &ray);
    return ray.tfar == -std::numeric_limits<float>::infinity();
}

const Vertex* RayScene::vertexData(const RayGeometry& g) const {
    return g.deformedVertices.empty() ? &scene_.vertices[size_t(g.vertexOffset)] : g.deformedVertices.data();
}

glm::vec2 RayScene::uvAt(uint32_t geometry, uint32_t triangle, float u, float v) const {
    const RayGeometry& g = geometries_[geometry];
    const Vertex* base = vertexData(g);
    const uint32_t* tri = &g.indices[size_t(triangle) * 3];
    return (1.0f - u - v) * base[tri[0]].uv + u * base[tri[1]].uv + v * base[tri[2]].uv;
}

glm::vec4 RayScene::colorAt(uint32_t geometry, uint32_t triangle, float u, float v) const {
    const RayGeometry& g = geometries_[geometry];
    if (!g.hasColors) return glm::vec4(1.0f);
    const Vertex* base = vertexData(g);
    const uint32_t* tri = &g.indices[size_t(triangle) * 3];
    return (1.0f - u - v) * base[tri[0]].color + u * base[tri[1]].color + v * base[tri[2]].color;
}

bool RayScene::rejects(uint32_t geometry, uint32_t triangle, float u, float v, glm::vec3 direction,
                       bool cameraRay, glm::vec3 origin) const {
    const RayGeometry& g = geometries_[geometry];
    if (cameraRay && g.cullBackFacesForCamera) {
        if (glm::dot(windingNormal(g, triangle), direction) >= 0.0f)
            return true;  // the back (clockwise) side
    }
    if (g.alphaBlend) {
        const float alpha =
            materials_.alpha(g.material, uvAt(geometry, triangle, u, v), colorAt(geometry, triangle, u, v).a);
        if (alpha >= 1.0f) return false;
        const float values[] = {origin.x, origin.y, origin.z, direction.x, direction.y, direction.z, u, v};
        uint32_t h = hashMix(geometry * 0x9E3779B9u + triangle);
        for (float value : values) {
            uint32_t bits;
            std::memcpy(&bits, &value, sizeof(bits));
            h = hashMix(h ^ bits);
        }
        return float(h >> 8) * (1.0f / 16777216.0f) >= alpha;  // uniform in [0, 1) from 24 bits
    }
    return g.alphaMask && materials_.discards(g.material, uvAt(geometry, triangle, u, v),
                                              colorAt(geometry, triangle, u, v).a);
}

SurfaceGeometry RayScene::geometryAt(const RayHit& hit, glm::vec3 rayDirection) const {
    const RayGeometry& g = geometries_[hit.geometry];
    const Vertex* base = vertexData(g);
    const uint32_t* tri = &g.indices[size_t(hit.triangle) * 3];
    const float w = 1.0f - hit.u - hit.v;
    SurfaceGeometry s;
    s.position = w * g.positions[tri[0]] + hit.u * g.positions[tri[1]] + hit.v * g.positions[tri[2]];
    const glm::vec3 winding = windingNormal(g, hit.triangle);
    s.frontFacing = glm::dot(winding, rayDirection) < 0.0f;
    const float length = glm::length(winding);
    // A degenerate triangle has no plane: face the ray.
    s.faceNormal = length > 0.0f && std::isfinite(length) ? (s.frontFacing ? winding : -winding) / length
                                                          : -rayDirection;
    s.normal = g.normalMatrix *
               (w * base[tri[0]].normal + hit.u * base[tri[1]].normal + hit.v * base[tri[2]].normal);
    const glm::vec4 tangent =
        w * base[tri[0]].tangent + hit.u * base[tri[1]].tangent + hit.v * base[tri[2]].tangent;
    s.tangent = glm::vec4(glm::mat3(g.world) * glm::vec3(tangent), tangent.w);
    s.uv = w * base[tri[0]].uv + hit.u * base[tri[1]].uv + hit.v * base[tri[2]].uv;
    s.color = colorAt(hit.geometry, hit.triangle, hit.u, hit.v);
    return s;
}

SurfacePoint RayScene::surfaceAt(const RayHit& hit, glm::vec3 rayDirection) const {
    return materials_.evaluate(geometries_[hit.geometry].material, geometryAt(hit, rayDirection));
}

}  // namespace vct::reference
