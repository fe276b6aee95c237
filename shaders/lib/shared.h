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
using glm::ivec4;
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
    vec4 materialParams;   // x: 1 when Toksvig roughness is on, y: 1 when geometric specular AA is on,
                           // z: 1 to sample material textures at level 0 only (supersampled references)
    // ---- spatio-temporal upsampling (docs/design.md §6) ----
    mat4 prevInvViewProj;  // last frame's inverse view-projection (history positions from the previous depth)
    vec4 prevCameraPosition;  // xyz last frame's camera position (history view vectors)
    vec4 upsampleParams;   // x: β, y: κ, z: σ_n², w: γ (history decay)
    vec4 upsampleMode;     // x: λ_d, the sg diffuse lobe sharpness, y: 1 when the history is valid (temporal on, no cut),
                           // z: τ (re-trace below this sum of weights; 0 = no adaptive), w: A_max
    ivec4 traceJitter;     // xy: this frame's low-res sample offset o_k in full-res pixels, z: frame index
};

#define VCT_WEIGHTS_BILINEAR 0
#define VCT_WEIGHTS_NORMAL 1
#define VCT_WEIGHTS_SG 2

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

// ---- binding numbers ----
// Each pass declares its resources, with their binding numbers, once in its resource table
// (engine/passes/NAME_pass.cpp, render/pass_resources.h); its shader declares the same numbers, and the
// pipeline's creation checks the two against each other (vk/binding_check.h). Only the frame's is common:
#define VCT_BINDING_FRAME 0  // FrameUniforms, in every pass that needs it

// trace's specialization constant: trace scale 1 (writes the full-res targets)
#define VCT_TRACE_SPEC_FULL_RESOLUTION 0

// upsample's specialization constants (one pipeline per configuration)
#define VCT_UPSAMPLE_SPEC_SCALE 0     // trace scale s (2 or 4)
#define VCT_UPSAMPLE_SPEC_WEIGHTS 1   // VCT_WEIGHTS_*
#define VCT_UPSAMPLE_SPEC_TEMPORAL 2  // bool: reproject the history
#define VCT_UPSAMPLE_SPEC_WEIGHT_SUM 3  // bool: write the sum-of-weights image (views, --aux)

// resample (full-res cone tracing of the listed pixels)
#define VCT_RESAMPLE_GROUP_SIZE 64

// The compacted list of pixels to re-trace: header, then one packed pixel (x | y << 16) per entry. The
// header's dispatch is the resample pass's indirect dispatch, counted up as entries are appended.
struct ResampleListHeader {
    uvec4 counts;    // x: entries, yzw: unused
    uvec4 dispatch;  // xyz: VkDispatchIndirectCommand (groups of VCT_RESAMPLE_GROUP_SIZE), w: unused
};

// voxelize (triangles → fixed-point accumulators) and its resolve (accumulators → albedo/normal/emission)
#define VCT_VOXEL_GROUP_SIZE 64        // voxelize: triangles per workgroup
#define VCT_VOXEL_TILE 4               // resolve / inject / mips: 4×4×4 voxels per workgroup
#define VCT_VOXEL_ACCUM_STRIDE 10      // uints per voxel: albedo rgb, normal xyz, emission rgb, count

// voxel view (`vct render --view voxels`: the grid ray-marched at one mip, on demand after the frame)
struct VoxelViewPushConstants {
    uvec4 params;  // x: mip level marched
};
#ifdef __cplusplus
static_assert(sizeof(VoxelViewPushConstants) == 16);
#endif

// Push constants of voxelize (one dispatch per instance × primitive) and resolve.
struct VoxelizePushConstants {
    uvec4 draw;    // x: instance, y: material, z: first index, w: triangle count
    uvec4 params;  // x: vertex offset (int32 bits); resolve: y = 1 when the dynamic accumulator is bound
};

#ifdef __cplusplus
static_assert(sizeof(FrameUniforms) == 7 * 64 + 11 * 16);
static_assert(sizeof(ResampleListHeader) == 32);
static_assert(sizeof(GpuLight) == 64);
static_assert(sizeof(GpuMaterial) == 64);
static_assert(sizeof(GpuInstance) == 192);
static_assert(sizeof(DrawPushConstants) == 16);
static_assert(sizeof(VoxelizePushConstants) == 32);
}  // namespace vct::gpu
#endif

#endif  // VCT_SHARED_H
