#version 460
#extension GL_GOOGLE_include_directive : require
// mips: one level of the radiance + opacity chain from the level above (2×2×2 premultiplied average, so
// empty voxels lower both colour and opacity and the colour stays un-fringed). One thread per voxel.
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/voxel.glsl"

layout(local_size_x = VCT_VOXEL_TILE, local_size_y = VCT_VOXEL_TILE, local_size_z = VCT_VOXEL_TILE) in;

// Resources: bound by engine/passes/voxel_mips_pass.cpp (its resource table gives these binding numbers and is checked
// against them when the pipeline is made).
layout(set = 0, binding = 1, rgba16f) uniform readonly image3D source;
layout(set = 0, binding = 2, rgba16f) uniform writeonly image3D dest;

void main() {
    const ivec3 voxel = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(voxel, imageSize(dest)))) return;
    const ivec3 s = voxel * 2;
    imageStore(dest, voxel,
               voxelAverage8(imageLoad(source, s), imageLoad(source, s + ivec3(1, 0, 0)),
                             imageLoad(source, s + ivec3(0, 1, 0)), imageLoad(source, s + ivec3(1, 1, 0)),
                             imageLoad(source, s + ivec3(0, 0, 1)), imageLoad(source, s + ivec3(1, 0, 1)),
                             imageLoad(source, s + ivec3(0, 1, 1)), imageLoad(source, s + ivec3(1, 1, 1))));
}
