// The CPU-side scene: what a glTF file (or a built-in scene made in code) holds, in one flat form that the
// renderer uploads once. Per frame the node transforms change (rigid TRS animation), and skinned or morphed
// meshes deform (their joint matrices and morph weights change; scene/deform.h, passes/skin_pass.h).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/vertex.h"

namespace vct {

struct Aabb {
    glm::vec3 min{std::numeric_limits<float>::max()};
    glm::vec3 max{-std::numeric_limits<float>::max()};
    bool empty() const { return min.x > max.x; }
    void extend(const glm::vec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    void extend(const Aabb& b) {
        if (!b.empty()) {
            extend(b.min);
            extend(b.max);
        }
    }
    Aabb transformed(const glm::mat4& m) const;  // bounds of the 8 transformed corners
};

// How a texture's texels are to be interpreted; decides the GPU format and how mips are averaged.
enum class TextureKind { Color /*sRGB*/, Linear, Normal };

enum class TextureWrap { Repeat, ClampToEdge, MirroredRepeat };

// RGBA8 texture with its whole mip chain made at load (level 0 first). Normal-map mips average the
// decoded normals without renormalising, so a mip's |N̄| < 1 records how much the normals disagreed.
struct Texture {
    std::string name;
    TextureKind kind = TextureKind::Color;
    TextureWrap wrapS = TextureWrap::Repeat;
    TextureWrap wrapT = TextureWrap::Repeat;
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<std::vector<uint8_t>> mips;  // mips[l] has max(1, w>>l) * max(1, h>>l) * 4 bytes
    // The image file as the glTF held it (PNG or JPEG bytes, shared by the textures one image makes) and its
    // MIME type: what `vct export-scene` writes back unchanged. Null for textures made in code; whoever
    // changes mips[0] of a loaded texture resets it.
    std::shared_ptr<const std::vector<uint8_t>> encodedImage;
    std::string encodedMimeType;
};

// Builds mips[1..] from mips[0] (2x2 box filter; in linear space for Color textures).
void buildMipChain(Texture& texture);

enum class AlphaMode { Opaque, Mask, Blend };

// glTF metallic-roughness material. Texture indices are into Scene::textures, -1 when absent.
struct Material {
    std::string name;
    glm::vec4 baseColorFactor{1.0f};
    float metallicFactor = 1.0f;
    float roughnessFactor = 1.0f;  // perceptual roughness; α = roughness²
    glm::vec3 emissiveFactor{0.0f};
    float normalScale = 1.0f;
    float occlusionStrength = 1.0f;
    float alphaCutoff = 0.5f;
    AlphaMode alphaMode = AlphaMode::Opaque;
    bool doubleSided = false;
    int baseColorTexture = -1;
    int metallicRoughnessTexture = -1;  // G = roughness, B = metallic (glTF)
    int normalTexture = -1;
    int emissiveTexture = -1;
    int occlusionTexture = -1;  // R = occlusion
};

// A drawable range of Scene::indices / Scene::vertices. Indices are relative to vertexOffset.
struct Primitive {
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    int32_t vertexOffset = 0;
    uint32_t vertexCount = 0;
    uint32_t material = 0;  // index into Scene::materials (a default material is always present)
    Aabb bounds;            // object space (the rest shape: scene/deform.h bounds the deformed one)
    // Skinning and morphing (kept outside the Vertex, in Scene::skinVertices and Scene::morphDeltas): the first
    // of vertexCount SkinVertex, -1 when the primitive has no JOINTS_0/WEIGHTS_0; its morph targets'
    // deltas, target-major (target t, vertex v at morphDeltaOffset + t * vertexCount + v).
    int32_t skinVertexOffset = -1;
    uint32_t maxJoint = 0;  // the largest joint index its skin vertices name (checked against each skin)
    uint32_t morphTargetCount = 0;
    uint32_t morphDeltaOffset = 0;
    // Vertex::color holds the file's COLOR_0, which multiplies the base colour; false: it is white and unused.
    bool hasColors = false;
};

// The joint influences of one skinned vertex: up to 8 (glTF JOINTS_0/WEIGHTS_0 and JOINTS_1/WEIGHTS_1),
// indices into the skin's joint list, weights summing to 1 (all 0: the vertex stays in the bind pose). The
// layout of shaders/skin.comp's SkinVertex (std430).
struct SkinVertex {
    glm::uvec4 joints0{0u};
    glm::uvec4 joints1{0u};
    glm::vec4 weights0{0.0f};
    glm::vec4 weights1{0.0f};
};
static_assert(sizeof(SkinVertex) == 64);

// One vertex's offsets in one morph target (xyz; w is 0): the layout of shaders/skin.comp's MorphDelta.
struct MorphDelta {
    glm::vec4 position{0.0f};
    glm::vec4 normal{0.0f};
    glm::vec4 tangent{0.0f};
};
static_assert(sizeof(MorphDelta) == 48);

// glTF skin: the joint nodes and their inverse bind matrices (identity when the file gives none).
struct Skin {
    std::string name;
    std::vector<int> joints;
    std::vector<glm::mat4> inverseBindMatrices;  // one per joint
    int skeleton = -1;                           // informative only (glTF: joints carry the pose)
};

struct Mesh {
    std::string name;
    std::vector<uint32_t> primitives;  // indices into Scene::primitives
    std::vector<float> weights;        // default morph target weights (one per target; empty: all 0)
};

enum class LightType { Directional, Point, Spot };

// KHR_lights_punctual. Lights shine along the node's local -Z. Intensity in the glTF units
// (lux for directional, candela for point/spot).
struct Light {
    std::string name;
    LightType type = LightType::Directional;
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    float range = 0.0f;  // 0 = infinite
    float innerConeAngle = 0.0f;
    float outerConeAngle = 0.7853982f;
};

// Perspective camera; looks along the node's local -Z. aspectRatio 0 = use the image's.
struct Camera {
    std::string name;
    float yfov = 0.8f;
    float znear = 0.05f;
    float zfar = 100.0f;  // 0 = infinite in glTF; the loader replaces it with a finite value
    float aspectRatio = 0.0f;
};

struct Node {
    std::string name;
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z
    glm::vec3 scale{1.0f};
    std::optional<glm::mat4> matrix;  // when set, replaces TRS (and cannot be animated)
    int parent = -1;
    std::vector<int> children;
    int mesh = -1;
    int camera = -1;
    int light = -1;
    int skin = -1;               // index into Scene::skins: the node's mesh is skinned by it
    std::vector<float> weights;  // morph weights overriding the mesh's (empty: the mesh's)
    glm::mat4 localMatrix() const;
};

enum class AnimationPath { Translation, Rotation, Scale };
enum class Interpolation { Linear, Step, CubicSpline };

struct AnimationChannel {
    int node = -1;
    AnimationPath path = AnimationPath::Translation;
    Interpolation interpolation = Interpolation::Linear;
    std::vector<float> times;
    // vec3 (T, S) or vec4 quaternion x,y,z,w (R) per key; for CubicSpline 3 values per key
    // (in-tangent, value, out-tangent), as in glTF.
    std::vector<glm::vec4> values;
};

// A channel with path "weights": all the node's morph target weights per key (`count` of them; for CubicSpline
// in-tangents, values, out-tangents of `count` each, as in glTF).
struct WeightsChannel {
    int node = -1;
    Interpolation interpolation = Interpolation::Linear;
    uint32_t count = 0;
    std::vector<float> times;
    std::vector<float> values;
};

struct Animation {
    std::string name;
    std::vector<AnimationChannel> channels;
    float duration = 0.0f;  // max key time; playback loops
    std::vector<WeightsChannel> weightChannels;
};

// One mesh placed in the world for one frame.
struct Instance {
    int node = -1;
    int mesh = -1;
    glm::mat4 world{1.0f};  // identity for a skinned instance: its joints place it (glTF)
    bool moving = false;    // transform animated (the node or an ancestor has a channel), or its deformation
    int skin = -1;          // Scene::skins index when the mesh is skinned
    bool deformed = false;  // skinned or morphed: drawn from the deformed vertex buffer
    std::vector<float> morphWeights;  // one per morph target of its mesh (empty without targets)
    Aabb bounds;                      // world space, deformed (conservative for deformed instances)
};

// The note addDefaultsIfMissing() leaves when the scene has no camera of its own. A command given a camera
// path does not print it: the path is the camera then (app/cli/session.h, printSceneNotes).
inline constexpr const char* kDefaultCameraNote =
    "scene has no camera: added a default camera looking at the scene bounds";

struct Scene {
    std::string name;
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    std::vector<Primitive> primitives;
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Light> lights;
    std::vector<Camera> cameras;
    std::vector<Node> nodes;
    std::vector<int> roots;
    std::vector<Animation> animations;
    std::vector<Skin> skins;
    std::vector<SkinVertex> skinVertices;  // Primitive::skinVertexOffset
    std::vector<MorphDelta> morphDeltas;   // Primitive::morphDeltaOffset
    std::vector<std::string>
        notes;  // things the loader changed or added, printed once ("no light: added ...")

    // Node poses at time t (seconds; animations loop). Returns world matrices, one per node; with
    // `worldRotations`, also each node's rotation composed from its ancestors' (scale left out), which still
    // orients a node whose matrix a zero scale has flattened.
    std::vector<glm::mat4> evaluate(float timeSeconds,
                                    std::vector<glm::quat>* worldRotations = nullptr) const;
    // Mesh instances with their world matrices at time t; `moving` marks animated ones.
    std::vector<Instance> instances(float timeSeconds) const;
    // World-space bounds of all instances at t = 0 (static pose).
    Aabb bounds() const;
    // Nodes whose world transform is driven by an animation (the node or any ancestor).
    std::vector<bool> animatedNodes() const;

    // Rescales a scene whose extent is far from 1 (below 1e-2 or above 1e6 units) by a power of two, in its
    // vertices and translations (or, when that would leave the vertices subnormal, in its root nodes), with
    // cameras' depth ranges and lights' ranges and (point, spot) intensities, so that the image is the same
    // but every product the renderer forms stays within float's range. Records a note.
    void normalizeScale();
    // normalizeScale's second way: 2^exponent into the root nodes' translations and linear parts (animated
    // ones included). Throws vct::Error when a scaled value would leave float's normal range.
    void scaleRootNodes(int exponent);
    // Adds a camera looking at the scene bounds and/or a directional light when the scene has none,
    // and records a note for each.
    void addDefaultsIfMissing();
    // Throws vct::Error naming the first problem: non-finite vertex data, out-of-range indices, ...
    void validate() const;
};

// A 64-bit fingerprint (FNV-1a) of what the static voxelization depends on: vertices, indices, materials,
// textures and the mesh instances at t = 0. Equal scenes give equal hashes in every run; a voxel cache
// records it so that the cache of another scene with the same bounds is refused.
uint64_t sceneContentHash(const Scene& scene);

// Orthonormal axes of a world matrix (columns: local X, Y, Z), as cameras and lights are oriented (they
// ignore scale). Where a zero or collapsed scale leaves no axes, those of `worldRotation` (Scene::evaluate).
glm::mat3 worldAxes(const glm::mat4& world, const glm::quat& worldRotation);

}  // namespace vct
