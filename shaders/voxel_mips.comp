#version 460
#extension GL_GOOGLE_include_directive : require
// mips: one level of the radiance + opacity chain from the level above, per direction slab (lib/voxel.glsl):
// the two children along the slab's direction composited front to back, the four pairs averaged
// (premultiplied, so empty voxels lower both colour and opacity and the colour stays un-fringed). One thread
// per texel of the frame's region of the 6n × n × n level (the whole level, or render/voxel_update.h's).
// Level 1 reads mip 0 from the radiance atlas (lib/voxel_bricks.glsl); the levels from 1 on are the coarse
// texture's (its level m − 1 holds mip m).
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/voxel.glsl"
#include "lib/voxel_bricks.glsl"

layout(local_size_x = VCT_VOXEL_TILE, local_size_y = VCT_VOXEL_TILE, local_size_z = VCT_VOXEL_TILE) in;

// Resources: bound by engine/passes/voxel_mips_pass.cpp (its resource table gives these binding numbers and is checked
// against them when the pipeline is made).
layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1,
       rgba16f) uniform readonly image3D source;  // the level above (unused for level 1)
layout(set = 0, binding = 2, rgba16f) uniform writeonly image3D dest;
layout(set = 0, binding = 3, rgba16f) uniform readonly image3D radianceAtlas;  // mip 0
#include "lib/voxel_storage.glsl"

layout(push_constant) uniform Push { VoxelMipsPushConstants push; };

void main() {
    const ivec3 size = imageSize(dest);  // (6·n, n, n): six slabs of n³ side by side
    const int n = size.y;
    // The dispatch covers the region (push.region: first texel, width in x) in each slab: the threads along x
    // run through the six slabs' rows of the region one after the other.
    const int width = int(push.region.w);
    const int slab = int(gl_GlobalInvocationID.x) / width;
    const ivec3 inSlab =
        ivec3(push.region.xyz) + ivec3(int(gl_GlobalInvocationID.x) - slab * width, gl_GlobalInvocationID.yz);
    if (slab >= VOXEL_SLAB_COUNT || any(greaterThanEqual(inSlab, ivec3(n)))) return;
    const ivec3 texel = ivec3(inSlab.x + slab * n, inSlab.yz);
    const int axis = slab / 2;
    // The children: 2×2×2 voxels of the same slab one level up (n·2 texels per slab there), for level 1 in the
    // atlas block of the brick holding them (even, so all eight are in one brick), zero where it has no storage.
    const bool fromAtlas = SPARSE_MIP0 && push.params.x != 0u;  // a constant false when mip 0 is dense
    ivec3 s = ivec3(slab * 2 * n + 2 * (texel.x - slab * n), 2 * texel.yz);
    if (fromAtlas) {
        const ivec3 voxel = 2 * inSlab;
        const uint k = brickIndex(voxelBrickOf(voxel));
        if (k == VCT_BRICK_NONE) {
            imageStore(dest, texel, vec4(0.0));
            return;
        }
        s = radianceAtlasTexel(k, frame.voxels.brickAtlasSide, voxel % VOXEL_BRICK, slab);
    }
    // Along the slab's axis, the child the cone meets first is in front: the lower one for +axis.
    ivec3 along = ivec3(0), across1 = ivec3(0), across2 = ivec3(0);
    along[axis] = 1;
    across1[(axis + 1) % 3] = 1;
    across2[(axis + 2) % 3] = 1;
    const bool positive = (slab % 2) == 0;
    vec4 pairs[4];
    for (int i = 0; i < 4; ++i) {
        const ivec3 c = s + (i & 1) * across1 + (i >> 1) * across2;
        const vec4 lower = fromAtlas ? imageLoad(radianceAtlas, c) : imageLoad(source, c);
        const vec4 upper = fromAtlas ? imageLoad(radianceAtlas, c + along) : imageLoad(source, c + along);
        pairs[i] = positive ? voxelOver(lower, upper) : voxelOver(upper, lower);
    }
    imageStore(dest, texel, voxelAverage4(pairs[0], pairs[1], pairs[2], pairs[3]));
}
