// GPU data layouts, binding numbers and workgroup sizes, written once for C++ and GLSL.
// Every struct is std140/std430-compatible: the storage and push-constant structs by construction (only vec4,
// mat4 and uvec4 members); the frame uniforms' named fields by their order (a vec3 followed by a 4-byte
// scalar, vec2 pairs, nested structs of 16-byte multiples at 16-byte offsets), checked by the static_asserts
// at the end.
#ifndef VCT_SHARED_H
#define VCT_SHARED_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
namespace vct::gpu {
using glm::ivec2;
using glm::ivec4;
using glm::mat4;
using glm::uint;
using glm::uvec4;
using glm::vec2;
using glm::vec3;
using glm::vec4;
#endif

// Compute passes over the image run in 8x8 tiles.
#define VCT_TILE_SIZE 8
#define VCT_SHADOW_MAP_SIZE 2048

// ---- per-frame constants (uniform buffer, binding VCT_BINDING_FRAME in every pass; std140) ----

// Bits of FrameUniforms::flags: the frame's switches.
#define VCT_FLAG_GI 1u              // cone-traced indirect light (off: direct adds the environment's light)
#define VCT_FLAG_TOKSVIG 2u         // Toksvig roughness from normal-map mips (docs/design.md §4.1)
#define VCT_FLAG_SPECULAR_AA 4u     // geometric specular anti-aliasing from normal derivatives (§4.2)
#define VCT_FLAG_HISTORY 16u        // last frame's indirect light is a valid history (temporal on, no cut)
#define VCT_FLAG_CONE_ROTATION 64u  // turn the diffuse cones per pixel and frame (lib/cone_trace.glsl)
#define VCT_FLAG_VOXEL_GLOSSY 128u  // voxels reflect the lights' specular lobes (inject.comp; §5.11)
#define VCT_FLAG_CONE_JITTER \
    256u  // jitter every cone within its tile, narrow footprints (lib/cone_trace.glsl)

// The trace scale s reaches the shaders one way: this specialization constant, in trace (s = 1 writes the
// full-res targets, no guides) and upsample (the cell loops are unrolled for s) alike. The low-res images'
// extent, ceil(size / s), is what their bounds checks read (imageSize, textureSize).
#define VCT_SPEC_TRACE_SCALE 0
// The cone-tracing passes, trace, resample and bounce (lib/cone_trace.glsl): invocations per pixel or voxel, the
// workgroup's z size: 1 (its cones one after the other) or VCT_CONE_LANES_PER_PIXEL (one cone each:
// RenderSettings::TraceLayout).
#define VCT_SPEC_CONE_LANES 1
#define VCT_CONE_LANES_PER_PIXEL 8
// The G-buffer and blend pipelines (gbuffer.vert, gbuffer.frag, blend.frag): whether any primitive of the scene
// has COLOR_0. Without, the colour varying is not passed at all (one interpolant less per fragment on a GPU;
// on lavapipe it measured within noise).
#define VCT_SPEC_VERTEX_COLORS 0
// Every shader that reads the radiance's mip 0 (lib/voxel_storage.glsl): whether it is sparse, in the brick atlas
// (RenderSettings::sparseMip0From). A constant, not a uniform: lavapipe runs both sides of a branch its lanes
// could take, so the path not taken would still cost its texture reads (trace 3.3× measured with a uniform).
#define VCT_SPEC_SPARSE_MIP0 4
// The G-buffer and blend pipelines (lib/surface.glsl): bit (1 << VCT_TEXTURE_SLOT_*) set for each texture slot the
// pipeline may sample. On a CPU device there is one pipeline per set of slots the scene's materials have, each
// draw using its material's (render/scene_draw.h): lavapipe would filter a missing texture's 1x1 default like a
// real one, a branch on the material's flags would not skip it. On a GPU one pipeline has every slot and that
// branch (uniform over a draw) skips the missing ones.
#define VCT_SPEC_TEXTURED_SLOTS 5
// The same pipelines: sample material textures at level 0 only (RenderSettings::textureLod0, supersampled
// references). A constant: a flag would make lavapipe filter every material texture twice, at level 0 and
// mip-mapped.
#define VCT_SPEC_TEXTURE_LOD0 6
// The cone-tracing passes (lib/cone_trace.glsl): whether cones end where they pass from one closed region of the
// static grid into another (render/voxel_regions.h). Only scenes whose closure box holds two regions light can come
// from pay for the label read at every step.
#define VCT_SPEC_VOXEL_REGIONS 7
// direct.comp: whether GI is on (RenderSettings::gi). Off, direct adds the environment's light; a uniform flag
// would make lavapipe pay for those environment reads on every pixel with GI on too (direct 55 → 45 ms measured,
// cornell 640×360).
#define VCT_DIRECT_SPEC_GI 0
// direct.comp and composite.comp: whether the scene's materials emit (GpuScene::hasEmission) and have an
// occlusion texture (GpuScene::hasOcclusion). Without them the G-buffer's emissiveOcclusion target holds
// (0, 0, 0, 1) on every pixel, and the passes use that instead of reading it: lavapipe pays for a read whether
// or not it matters (about 1.5 ms a read at 640×360).
#define VCT_DIRECT_SPEC_EMISSION 1
#define VCT_DIRECT_SPEC_OCCLUSION 2
// bool: recompute the pixels of the list direct_select.comp made (an indirect dispatch), not every pixel
#define VCT_DIRECT_SPEC_LIST 3
// composite.comp: whether GI is on (the indirect light's reads) and whether the scene has blended surfaces (the
// blend pass's layer, put over the frame). Constants for the same reason: as flags, lavapipe read the layer
// on every pixel of every scene.
#define VCT_COMPOSITE_SPEC_GI 0
#define VCT_COMPOSITE_SPEC_BLEND 1
#define VCT_COMPOSITE_SPEC_OCCLUSION 2
// composite.comp: whether it also writes the linear HDR image (FrameTargets::hdr). Only what is read back wants
// it (final.exr, error metrics: Renderer::readFinalHdr runs composite again with it); the frame writes the
// tone-mapped image alone (the RGBA32F store was about a quarter of composite on lavapipe, 640×360).
#define VCT_COMPOSITE_SPEC_HDR 3

// The lights and the shadow map (direct, inject), the environment's rotation (lib/environment_sample.glsl).
struct LightingUniforms {
    vec3 ambient;               // the environment's mean radiance (the voxel view's background)
    uint lightCount;            // entries of the light buffer
    int shadowLight;            // index of the light with the shadow map, -1 when none is shadowed
    float shadowNormalOffset;   // world units per shadow-map texel (direct's normal offset)
    float shadowTexelSize;      // 1 / shadow-map size (uv units per texel)
    float environmentRotation;  // radians about +y (lib/environment.glsl)
};

// The voxel grid of cone tracing (lib/voxel.glsl's originSize is vec4(origin, voxelSize)).
struct VoxelUniforms {
    vec3 origin;      // world position of the grid's min corner
    float voxelSize;  // edge length of one voxel, world units; 0 while there is no grid
    uint resolution;  // N (N³ voxels)
    uint mipCount;
    uint brickAtlasSide;  // bricks per atlas row and column (lib/voxel_bricks.glsl)
    uint brickCount;      // bricks allocated (the atlases' and pools' blocks in use)
    vec4 atlasInvSize;    // xyz: 1 / the radiance atlas's size in texels (lib/cone_trace.glsl), w unused
    // xyz: where cones close (render/voxel_bricks.h's coneClosureBox: the faces of what was voxelized that geometry
    // covers, the grid's elsewhere; lib/cone_trace.glsl). w unused.
    vec4 closureMin;
    vec4 closureMax;
    // xyz: the bounds of what was voxelized (VoxelGrid::contentBounds): how far a closed face reaches. w unused.
    vec4 contentMin;
    vec4 contentMax;
};

// Spatio-temporal upsampling and adaptive re-tracing (docs/design.md §6): trace, upsample, resample.
struct UpsampleUniforms {
    ivec2 traceOffset;       // o_k: this frame's low-res sample offset in full-res pixels (jitterOffset)
    float beta;              // β, the SG lobe weight exponent
    float kappa;             // κ, the SG smoothing kernel sharpness (bounds every lobe's sharpness)
    float normalVariance;    // σ_n², the normal weight's width squared
    float diffuseSharpness;  // λ_d, the sg diffuse lobe sharpness
    float gamma;             // γ, the history's decay per frame
    float tau;               // τ: re-trace below this sum of weights; 0 without adaptive re-tracing
    float maxHistoryWeight;  // A_max, the cap on the accumulated weight
    uint frameIndex;         // frames rendered before this one: turns the diffuse cones (lib/cone_trace.glsl)
    float pad1, pad2;
};

struct FrameUniforms {
    mat4 view;
    mat4 proj;
    mat4 viewProj;
    mat4 invViewProj;
    mat4 prevViewProj;        // last frame's, for motion vectors
    mat4 prevInvViewProj;     // last frame's inverse (history positions from the previous depth)
    mat4 lightViewProj;       // main (shadowed) light
    vec3 cameraPosition;      // world position
    uint flags;               // VCT_FLAG_*
    vec3 prevCameraPosition;  // last frame's (history view vectors)
    float exposure;           // linear scale before tone mapping
    vec2 imageSize;           // width, height in pixels
    vec2 texelSize;           // 1 / width, 1 / height
    LightingUniforms lighting;
    VoxelUniforms voxels;
    UpsampleUniforms upsample;
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
#define VCT_ALPHA_BLEND 2  // drawn by the blend pass, not the G-buffer (docs/design.md §2.6)

// A material's texture slots (GpuScene::Slot takes its values from these). GpuMaterial.flags.y has bit
// (1 << slot) set where the material has a texture in that slot. A slot without one is not sampled: the shaders
// use its neutral value (lib/surface.glsl) where they would have filtered a 1x1 default texture, which on
// lavapipe cost as much as a real texture (benchmarks/README.md, round 8).
#define VCT_TEXTURE_SLOT_BASE_COLOR 0
#define VCT_TEXTURE_SLOT_METALLIC_ROUGHNESS 1
#define VCT_TEXTURE_SLOT_NORMAL 2
#define VCT_TEXTURE_SLOT_EMISSIVE 3
#define VCT_TEXTURE_SLOT_OCCLUSION 4
#define VCT_EVERY_TEXTURE_SLOT 31u  // bit (1 << slot) of each slot above (GpuScene::kSlots checks it)
// The x and y texel (8-bit unorm) of the flat normal that a material without a normal map reads: the GPU's 1x1
// default, lib/surface.glsl's neutral value and the path tracer's (reference/material_eval.cpp) alike. 128/255 is
// 0.0039 off the flat 0.5, a 0.3° tilt of every surface without a normal map, kept so that images and the
// committed references stay comparable.
#define VCT_FLAT_NORMAL_TEXEL 128

struct GpuMaterial {
    vec4 baseColorFactor;
    vec4 emissiveNormalScale;        // rgb emissive factor, w: normal scale
    vec4 metallicRoughnessCutoffAo;  // metallic, perceptual roughness, alpha cutoff, occlusion strength
    uvec4 flags;                     // x: alpha mode, y: the slots that have a texture (VCT_TEXTURE_SLOT_*)
};

struct GpuInstance {
    mat4 world;
    mat4 prevWorld;     // last frame's world matrix (motion vectors of moving objects)
    mat4 normalMatrix;  // inverse transpose of world (upper 3x3 used)
};

// The vertex (engine/core/vertex.h: position, normal, uv, tangent, color) as floats, for the shaders that read
// vertex buffers as storage buffers (std430 would pad its vec3s): voxelize, skin, the G-buffer's previous
// positions. The colour is floats 12..15.
#define VCT_FLOATS_PER_VERTEX 16
#define VCT_VERTEX_COLOR_OFFSET 12

// Push constants of the scene-drawing passes.
struct DrawPushConstants {
    uvec4 indices;  // x: instance, y: material, z: 1 when drawn from the skin pass's deformed vertices,
                    // w: 1 when the primitive has vertex colours (COLOR_0) to multiply into the base colour
};

// skin (skinned and morphed primitives → the deformed vertex buffer): one dispatch per instance × primitive,
// one invocation per vertex.
#define VCT_SKIN_GROUP_SIZE 64
struct SkinPushConstants {
    uvec4 vertices;  // x: first rest vertex, y: vertex count, z: first deformed vertex, w: first SkinVertex
                     // (VCT_SKIN_NONE: not skinned)
    uvec4 morph;     // x: first MorphDelta, y: target count, z: first morph weight, w: first joint matrix
    uvec4 flags;     // x: 1 also writes the previous-frame buffer (a cut: no motion), y: joint count
};
#define VCT_SKIN_NONE 0xFFFFFFFFu

// ---- binding numbers ----
// Each pass declares its resources, with their binding numbers, once in its resource table
// (engine/passes/NAME_pass.cpp, render/pass_resources.h); its shader declares the same numbers, and the
// pipeline's creation checks the two against each other (vk/binding_check.h). Only the frame's, the sparse
// voxel storage's (lib/voxel_storage.glsl declares those) and the environment's cone layers
// (lib/environment_sample.glsl) are common:
#define VCT_BINDING_FRAME 0         // FrameUniforms, in every pass that needs it
#define VCT_BINDING_BRICKS 20       // the brick table (map, then coordinates), in every pass reading voxels
#define VCT_BINDING_VOXEL_ATLAS 21  // mip 0 of the radiance (the radiance atlas), where cones are traced
#define VCT_BINDING_ENVIRONMENT_CONES 22  // the environment's cone layers, where the environment is read
#define VCT_BINDING_VOXEL_REGIONS 23      // the static grid's region labels, where cones are traced

// upsample's specialization constants (one pipeline per configuration), after VCT_SPEC_TRACE_SCALE (2 or 4)
#define VCT_UPSAMPLE_SPEC_WEIGHTS 1      // VCT_WEIGHTS_*
#define VCT_UPSAMPLE_SPEC_TEMPORAL 2     // bool: reproject the history
#define VCT_UPSAMPLE_SPEC_WEIGHT_SUM 3   // bool: write the sum-of-weights image (views, --aux)
#define VCT_UPSAMPLE_SPEC_PER_PIXEL 4    // bool: one invocation per pixel (GPUs), not per low-res cell
#define VCT_UPSAMPLE_SPEC_RATIO_POWER 5  // int: sgRatioPower(β) (lib/upsample_weights.glsl)
#define VCT_UPSAMPLE_SPEC_WHOLE_CELLS 6  // bool: the image size is a multiple of the trace scale

// resample (full-res cone tracing of the listed pixels)
#define VCT_RESAMPLE_GROUP_SIZE 64

// The compacted list of pixels to re-trace: header, then one packed pixel per entry (lib/pixel_list.glsl). The
// header's dispatch is the resample pass's indirect dispatch, counted up as entries are appended.
struct ResampleListHeader {
    uvec4 counts;    // x: entries, yzw: unused
    uvec4 dispatch;  // xyz: VkDispatchIndirectCommand (groups of VCT_RESAMPLE_GROUP_SIZE), w: unused
};

// voxelize (triangles → fixed-point accumulators) and its resolve (accumulators → albedo/normal/emission)
#define VCT_VOXEL_GROUP_SIZE 64  // voxelize: triangles per workgroup
#define VCT_VOXEL_TILE 4         // resolve / inject / mips: 4×4×4 voxels per workgroup
// Sparse storage (docs/design.md §5.10): the grid is stored in bricks of VCT_VOXEL_BRICK³ voxels, allocated where
// the scene can have surfaces. One brick is one workgroup of the resolve, inject and bounce.
#define VCT_VOXEL_BRICK VCT_VOXEL_TILE
#define VCT_BRICK_NONE 0xFFFFFFFFu  // the brick map's entry for a brick with no storage
// Whole-grid dispatches run one workgroup per allocated brick, in rows of this many (maxComputeWorkGroupCount).
#define VCT_BRICK_DISPATCH_ROW 32768
// uints per voxel: albedo rgb, normal xyz, emission rgb, count, then the transparency sum: Σ (1 − alpha) of
// the samples of alphaMode BLEND surfaces (0 for opaque ones), from which the resolve takes the opacity; then the
// metallic and perceptual roughness sums (× 1023 like albedo), from which inject shapes the voxel's specular lobe.
#define VCT_VOXEL_ACCUM_STRIDE 13
#define VCT_VOXEL_ACCUM_COUNT 9
#define VCT_VOXEL_ACCUM_TRANSPARENCY 10
#define VCT_VOXEL_ACCUM_METALLIC 11
#define VCT_VOXEL_ACCUM_ROUGHNESS 12

// voxel view (`vct render --view voxels`: the grid ray-marched at one mip, on demand after the frame)
struct VoxelViewPushConstants {
    uvec4 params;  // x: mip level marched
};
#ifdef __cplusplus
static_assert(sizeof(VoxelViewPushConstants) == 16);
#endif

// Push constants of voxelize (one dispatch per instance × primitive) and resolve.
struct VoxelizePushConstants {
    uvec4 draw;  // x: instance, y: material, z: first index, w: triangle count
    // x: vertex offset (int32 bits); voxelize: y = 1 when the primitive has vertex colours (COLOR_0);
    // resolve: y = 1 when the dynamic accumulator is bound, z = 1 to zero it once read (the next frame's
    // moving instances start from zero where they were)
    uvec4 params;
    uvec4 region;  // resolve: as InjectPushConstants::region
};

// Push constants of inject: params.x = 1 adds the gathered bounce (albedo × the voxel_bounce image) to the
// direct light; 0 (the first inject of a frame) injects direct light and emission only.
struct InjectPushConstants {
    uvec4 params;  // x = 1: add the gathered bounce
    // xyz: the first voxel of the region the dispatch covers, w = 1 when it covers a region (then empty voxels are
    // stored too: the atlas was not cleared); w = 0: one workgroup per allocated brick (lib/voxel_storage.glsl)
    uvec4 region;
};

// inject's and bounce's specialization constant (then VCT_SPEC_SPARSE_MIP0): their invocations per brick, a divisor
// of 64 (64 on a GPU; the subgroup size on a CPU device: voxelPassLanes, engine/render/voxel_grid.h).
#define VCT_VOXEL_SPEC_LANES 0

// Push constants of bounce: region.xyz the first voxel of the region the dispatch covers and w = 1 (`--bounces
// all`: one slab of the grid a frame); w = 0: one workgroup per allocated brick.
struct VoxelBouncePushConstants {
    uvec4 region;
};

// Push constants of direct_select (docs/design.md §5.8), when only instances moved since the last frame, which
// direct then computed whole with the same camera, lights and settings: it lists the pixels in changedPixels and
// those whose shadow lookup reads a texel of changedShadowTexels (each a rectangle [xy, zw) of pixels or shadow-map
// texels) for direct to recompute; the others keep their last value. params.yz: the first pixel its dispatch
// covers (only the pixels that can change are dispatched); x, w: unused.
struct DirectPushConstants {
    ivec4 changedPixels;
    ivec4 changedShadowTexels;
    uvec4 params;
};
#ifdef __cplusplus
static_assert(sizeof(DirectPushConstants) == 48);
#endif

// Push constants of mips: the region of the level written, its first texel (xyz, per slab) and width in x; params.x
// = 1 for level 1 (read from the radiance atlas).
struct VoxelMipsPushConstants {
    uvec4 region;
    uvec4 params;
};

#ifdef __cplusplus
// std140 as glslang lays out the frame uniforms: every offset below is the GLSL one.
static_assert(sizeof(LightingUniforms) == 32 && offsetof(LightingUniforms, lightCount) == 12 &&
              offsetof(LightingUniforms, shadowLight) == 16 &&
              offsetof(LightingUniforms, shadowTexelSize) == 24);
static_assert(sizeof(VoxelUniforms) == 112 && offsetof(VoxelUniforms, voxelSize) == 12 &&
              offsetof(VoxelUniforms, resolution) == 16 && offsetof(VoxelUniforms, mipCount) == 20 &&
              offsetof(VoxelUniforms, closureMin) == 48 && offsetof(VoxelUniforms, closureMax) == 64 &&
              offsetof(VoxelUniforms, contentMax) == 96);
static_assert(sizeof(UpsampleUniforms) == 48 && offsetof(UpsampleUniforms, beta) == 8 &&
              offsetof(UpsampleUniforms, normalVariance) == 16 && offsetof(UpsampleUniforms, tau) == 28 &&
              offsetof(UpsampleUniforms, maxHistoryWeight) == 32 &&
              offsetof(UpsampleUniforms, frameIndex) == 36);
static_assert(offsetof(FrameUniforms, cameraPosition) == 7 * 64 &&
              offsetof(FrameUniforms, flags) == 7 * 64 + 12 &&
              offsetof(FrameUniforms, prevCameraPosition) == 7 * 64 + 16 &&
              offsetof(FrameUniforms, exposure) == 7 * 64 + 28 &&
              offsetof(FrameUniforms, imageSize) == 7 * 64 + 32 &&
              offsetof(FrameUniforms, texelSize) == 7 * 64 + 40);
static_assert(offsetof(FrameUniforms, lighting) == 7 * 64 + 48 &&
              offsetof(FrameUniforms, voxels) == 7 * 64 + 80 &&
              offsetof(FrameUniforms, upsample) == 7 * 64 + 192);
static_assert(sizeof(FrameUniforms) == 7 * 64 + 240);
static_assert(sizeof(ResampleListHeader) == 32);
static_assert(sizeof(GpuLight) == 64);
static_assert(sizeof(GpuMaterial) == 64);
static_assert(sizeof(GpuInstance) == 192);
static_assert(sizeof(DrawPushConstants) == 16);
static_assert(sizeof(VoxelizePushConstants) == 48);
static_assert(sizeof(SkinPushConstants) == 48);
static_assert(sizeof(InjectPushConstants) == 32);
static_assert(sizeof(VoxelMipsPushConstants) == 32);
}  // namespace vct::gpu
#endif

#endif  // VCT_SHARED_H
