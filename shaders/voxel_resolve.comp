#version 460
#extension GL_GOOGLE_include_directive : require
// voxelize, second step: averages the static accumulator (voxelized once) plus the per-frame accumulator of
// moving instances into the albedo + opacity, normal and emission atlases (lib/voxel_bricks.glsl). One workgroup
// per brick, one thread per voxel: every allocated brick, or those of the frame's region (where moving instances
// were and are: render/voxel_update.h).
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/voxel.glsl"
#include "lib/voxel_bricks.glsl"

layout(local_size_x = VCT_VOXEL_TILE, local_size_y = VCT_VOXEL_TILE, local_size_z = VCT_VOXEL_TILE) in;

// Resources: bound by engine/passes/voxelize_pass.cpp (its resource table gives these binding numbers and is checked
// against them when the pipeline is made).
layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) readonly buffer Static { uint staticAccum[]; };
layout(set = 0, binding = 2) buffer Dynamic { uint dynamicAccum[]; };
layout(set = 0, binding = 3, rgba8) uniform writeonly image3D albedoImage;  // albedo, opacity
// Averaged normal (not renormalised), mean perceptual roughness.
layout(set = 0, binding = 4, rgba16f) uniform writeonly image3D normalImage;
layout(set = 0, binding = 5,
       rgba16f) uniform writeonly image3D emissionImage;  // emitted radiance, mean metallic
#include "lib/voxel_storage.glsl"
#include "lib/voxel_workgroup.glsl"

layout(push_constant) uniform Push { VoxelizePushConstants push; };

void main() {
    uint k;
    ivec3 brick;
    if (!workgroupBrick(push.region.w != 0u, push.region.xyz, k, brick)) return;
    const ivec3 local = ivec3(gl_LocalInvocationID);
    const ivec3 texel = materialAtlasTexel(k, frame.voxels.brickAtlasSide, local);
    const uint base = voxelAccumIndex(k, local);
    const bool dynamic = push.params.y != 0;
    // The count first: most voxels are empty and need nothing else read.
    const uint count = staticAccum[base + VCT_VOXEL_ACCUM_COUNT] +
                       (dynamic ? dynamicAccum[base + VCT_VOXEL_ACCUM_COUNT] : 0u);
    if (count == 0u) {
        imageStore(albedoImage, texel, vec4(0.0));
        imageStore(normalImage, texel, vec4(0.0));
        imageStore(emissionImage, texel, vec4(0.0));
        return;
    }
    // Sums of both accumulators (uint addition wraps like the atomics, so signed normals add correctly).
    uint sums[VCT_VOXEL_ACCUM_STRIDE];
    for (int i = 0; i < VCT_VOXEL_ACCUM_STRIDE; ++i)
        sums[i] = staticAccum[base + i] + (dynamic ? dynamicAccum[base + i] : 0u);
    // Zeroed once read: the next frame's moving instances accumulate from zero (voxelize_pass.cpp).
    if (push.params.z != 0u)
        for (int i = 0; i < VCT_VOXEL_ACCUM_STRIDE; ++i) dynamicAccum[base + i] = 0u;
    const vec3 albedo = vec3(voxelDecodeUnit(sums[0], count), voxelDecodeUnit(sums[1], count),
                             voxelDecodeUnit(sums[2], count));
    const vec3 normal = vec3(voxelDecodeSigned(sums[3], count), voxelDecodeSigned(sums[4], count),
                             voxelDecodeSigned(sums[5], count));
    const vec3 emission = vec3(voxelDecodeEmission(sums[6], count), voxelDecodeEmission(sums[7], count),
                               voxelDecodeEmission(sums[8], count));
    // Any opaque surface in the voxel makes it opaque (binary coverage, as in Crassin et al.); blended surfaces
    // (docs/design.md §5.1) cover it by their mean alpha over the voxel's samples, opaque ones counting 1: one
    // blended surface alone gives its alpha, one beside an opaque surface less than the opaque 1 it should be.
    const uint transparency = sums[VCT_VOXEL_ACCUM_TRANSPARENCY];
    const float opacity = transparency == 0u ? 1.0 : 1.0 - voxelDecodeUnit(transparency, count);
    imageStore(albedoImage, texel, vec4(albedo, opacity));
    const float metallic = voxelDecodeUnit(sums[VCT_VOXEL_ACCUM_METALLIC], count);
    const float roughness = voxelDecodeUnit(sums[VCT_VOXEL_ACCUM_ROUGHNESS], count);
    imageStore(normalImage, texel, vec4(normal, roughness));
    imageStore(emissionImage, texel, vec4(emission, metallic));
}
