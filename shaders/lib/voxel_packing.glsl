// Packs a voxel workgroup's invocations onto the occupied voxels of its brick (inject.comp, voxel_bounce.comp).
// GLSL only, compute shaders with VCT_VOXEL_TILE³ invocations per workgroup.
//
// A thread per voxel leaves most lanes of a SIMD batch idle: a wall across a brick fills a quarter of its
// voxels, the floor half of the batches it crosses. lavapipe runs a batch's code as long as any lane of it is
// active (benchmarks/README.md, round 8), and a GPU's warp alike; listing the occupied voxels first and letting
// invocation i take the i-th of them fills whole batches and leaves the rest with nothing to run. The list's
// order (atomicAdd) varies from run to run; the results do not, as each voxel's depends on that voxel alone.
#ifndef VCT_VOXEL_PACKING_GLSL
#define VCT_VOXEL_PACKING_GLSL

shared uint packedCount;
shared uint packedVoxels[VCT_VOXEL_TILE * VCT_VOXEL_TILE * VCT_VOXEL_TILE];

// Called by every invocation of the workgroup, in uniform control flow (barriers), each saying whether its own
// voxel (gl_LocalInvocationID) is occupied. True for as many invocations as there are occupied voxels, with
// `local` the voxel the invocation takes.
bool packOccupiedVoxels(bool occupied, out ivec3 local) {
    if (gl_LocalInvocationIndex == 0u) packedCount = 0u;
    barrier();
    if (occupied) packedVoxels[atomicAdd(packedCount, 1u)] = gl_LocalInvocationIndex;
    barrier();
    local = ivec3(0);
    if (gl_LocalInvocationIndex >= packedCount) return false;
    const uint i = packedVoxels[gl_LocalInvocationIndex];
    local = ivec3(i % VCT_VOXEL_TILE, (i / VCT_VOXEL_TILE) % VCT_VOXEL_TILE,
                  i / (VCT_VOXEL_TILE * VCT_VOXEL_TILE));
    return true;
}

#endif  // VCT_VOXEL_PACKING_GLSL
