// Packs a voxel workgroup's invocations onto the occupied voxels of its brick (inject.comp, voxel_bounce.comp).
// GLSL only, compute shaders of one workgroup per brick, `lanes` invocations each (a divisor of the brick's 64
// voxels; VCT_VOXEL_SPEC_LANES).
//
// A thread per voxel leaves most lanes of a SIMD batch idle: a wall across a brick fills a quarter of its
// voxels, the floor half of the batches it crosses. lavapipe runs a batch's code as long as any lane of it is
// active (benchmarks/README.md, round 8), and a GPU's warp alike; listing the occupied voxels first and letting
// invocation i take the i-th of them fills whole batches and leaves the rest with nothing to run. The list keeps
// the voxels' own order (each one's place is the number of occupied voxels before it), so neighbouring lanes take
// neighbouring voxels, whose cones run alike: the bounce gather measured 5 % faster than with the arbitrary order
// of an atomic counter. Each voxel's result depends on that voxel alone, so the images are the same either way.
//
// On a CPU device a workgroup of 64 invocations is 8 SIMD batches (lavapipe: 8 lanes at 256 bits), and lavapipe
// runs every batch through the code, masked, even one none of whose lanes has a voxel: the gather's cone loops ran
// at least once per cone for each of them. inject and bounce therefore run one batch a brick there (`lanes` the
// device's subgroup size), each invocation marking 64 / lanes voxels and then taking every lanes-th listed one; on
// a GPU, whose warps without an active lane do not run, one invocation per voxel.
#ifndef VCT_VOXEL_PACKING_GLSL
#define VCT_VOXEL_PACKING_GLSL

#if VCT_VOXEL_TILE != 4
#error "occupiedMask holds 64 voxels: one bit per voxel of a 4×4×4 brick"
#endif

shared uint occupiedMask[2];  // bit i: voxel i of the brick (x fastest, then y, z) is occupied
shared uint packedVoxels[VCT_VOXEL_TILE * VCT_VOXEL_TILE * VCT_VOXEL_TILE];

// Voxel i of a brick (x fastest, then y, z): its place in the brick.
ivec3 brickVoxel(uint i) {
    return ivec3(i % VCT_VOXEL_TILE, (i / VCT_VOXEL_TILE) % VCT_VOXEL_TILE,
                 i / (VCT_VOXEL_TILE * VCT_VOXEL_TILE));
}

// The list in three steps, for a workgroup of `lanes` invocations (a divisor of 64), every invocation calling each
// in uniform control flow (barriers): clear the mask; mark the occupied voxels (an invocation may mark several);
// list them: packedVoxels[0 .. count) holds the occupied voxels in their own order, count returned.
void clearOccupancy() {
    for (uint i = gl_LocalInvocationIndex; i < 2u; i += gl_WorkGroupSize.x) occupiedMask[i] = 0u;
    barrier();
}
void markOccupied(uint voxel) { atomicOr(occupiedMask[voxel >> 5u], 1u << (voxel & 31u)); }
uint listOccupiedVoxels(uint lanes) {
    barrier();
    const uint low = occupiedMask[0], high = occupiedMask[1];
    for (uint voxel = gl_LocalInvocationIndex; voxel < 64u; voxel += lanes) {
        const bool occupied = ((voxel < 32u ? low >> voxel : high >> (voxel - 32u)) & 1u) != 0u;
        // Its place: the number of occupied voxels before it.
        if (occupied)
            packedVoxels[voxel < 32u ? uint(bitCount(low & ((1u << voxel) - 1u)))
                                     : uint(bitCount(low) + bitCount(high & ((1u << (voxel - 32u)) - 1u)))] =
                voxel;
    }
    barrier();
    return uint(bitCount(low) + bitCount(high));
}

#endif  // VCT_VOXEL_PACKING_GLSL
