// GPU data layouts, binding numbers and workgroup sizes, written once for C++ and GLSL.
// Every struct is std140/std430-compatible by construction: only vec4, mat4 and uvec4 members.
#ifndef VCT_SHARED_H
#define VCT_SHARED_H

#ifdef __cplusplus
#include <glm/glm.hpp>
#include <cstdint>
namespace vct::gpu {
using glm::mat4;
using glm::uvec4;
using glm::vec4;
#endif

// Compute passes over the image run in 8x8 tiles.
#define VCT_TILE_SIZE 8
#define VCT_SHADOW_MAP_SIZE 2048

// Per-frame constants (uniform buffer, binding VCT_BINDING_FRAME in every pass).
struct FrameUniforms {
    mat4 view;
    mat4 proj;
    mat4 viewProj;
    mat4 invViewProj;
    mat4 prevViewProj;     // last frame's, for motion vectors
    mat4 lightViewProj;    // main (shadowed) light
    vec4 cameraPosition;   // xyz world position, w: 1
    vec4 imageSize;        // width, height, 1/width, 1/height
    vec4 ambient;          // rgb: constant ambient radiance (stand-in for GI), w: exposure
    vec4 shadowParams;     // x: normal offset (world units per shadow texel), y: 1/shadow map size,
                           // z: number of lights, w: main light index or -1 when none is shadowed
    vec4 voxelOrigin;      // xyz: world position of the voxel grid's min corner, w: voxel size (world units)
    vec4 voxelParams;      // x: resolution N (N³ voxels), y: mip count, z: 1 when GI is on, w: trace scale
    vec4 materialParams;   // x: 1 when Toksvig roughness is on, y: 1 when geometric specular AA is on
};

#define VCT_LIGHT_DIRECTIONAL 0
#define VCT_LIGHT_POINT 1
#define VCT_LIGHT_SPOT 2

struct GpuLight {
    vec4 positionRange;    // xyz world position, w: range (0 = infinite)
    vec4 directionType;    // xyz direction the light travels (world, unit), w: type
    vec4 colorIntensity;   // rgb linear colour × intensity, w: unused
    vec4 spotScaleOffset;  // x, y: KHR_lights_punctual angular attenuation scale and offset
};

#define VCT_ALPHA_OPAQUE 0
#define VCT_ALPHA_MASK 1

struct GpuMaterial {
    vec4 baseColorFactor;
    vec4 emissiveNormalScale;        // rgb emissive factor, w: normal scale
    vec4 metallicRoughnessCutoffAo;  // metallic, perceptual roughness, alpha cutoff, occlusion strength
    uvec4 flags;                     // x: alpha mode
};

struct GpuInstance {
    mat4 world;
    mat4 prevWorld;     // last frame's world matrix (motion vectors of moving objects)
    mat4 normalMatrix;  // inverse transpose of world (upper 3x3 used)
};

// Push constants of the scene-drawing passes.
struct DrawPushConstants {
    uvec4 indices;  // x: instance, y: material
};

// ---- binding numbers, one block per pass ----
#define VCT_BINDING_FRAME 0  // FrameUniforms, in every pass that needs it

// shadow + gbuffer (scene drawing)
#define VCT_DRAW_BINDING_INSTANCES 1
#define VCT_DRAW_BINDING_MATERIALS 2
#define VCT_DRAW_BINDING_BASE_COLOR 3
#define VCT_DRAW_BINDING_METALLIC_ROUGHNESS 4
#define VCT_DRAW_BINDING_NORMAL 5
#define VCT_DRAW_BINDING_EMISSIVE 6
#define VCT_DRAW_BINDING_OCCLUSION 7

// direct
#define VCT_DIRECT_BINDING_LIGHTS 1
#define VCT_DIRECT_BINDING_DEPTH 2
#define VCT_DIRECT_BINDING_NORMAL_ROUGHNESS 3
#define VCT_DIRECT_BINDING_BASE_COLOR_METALLIC 4
#define VCT_DIRECT_BINDING_EMISSIVE_OCCLUSION 5
#define VCT_DIRECT_BINDING_SHADOW_MAP 6
#define VCT_DIRECT_BINDING_OUTPUT 7

// composite
#define VCT_COMPOSITE_BINDING_DIRECT 1
#define VCT_COMPOSITE_BINDING_HDR 2
#define VCT_COMPOSITE_BINDING_LDR 3

#ifdef __cplusplus
static_assert(sizeof(FrameUniforms) == 6 * 64 + 7 * 16);
static_assert(sizeof(GpuLight) == 64);
static_assert(sizeof(GpuMaterial) == 64);
static_assert(sizeof(GpuInstance) == 192);
static_assert(sizeof(DrawPushConstants) == 16);
}  // namespace vct::gpu
#endif

#endif  // VCT_SHARED_H
