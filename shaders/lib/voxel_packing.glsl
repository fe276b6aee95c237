// Packs a voxel workgroup's invocations onto the occupied voxels of its brick (inject.comp, voxel_bounce.comp).
// GLSL only, compute shaders with VCT_VOXEL_TILE³ = 64 invocations per workgroup.
//
// A thread per voxel leaves most lanes of a SIMD batch idle: a wall across a brick fills a quarter of its
// voxels, the floor half of the batches it crosses. lavapipe runs a batch's code as long as any lane of it is
// active (benchmarks/README.md, round 8), and a GPU's warp alike; listing the occupied voxels first and letting
// invocation i take the i-th of them fills whole batches and leaves the rest with nothing to run. The list keeps
// the voxels' own order (each one's place is the number of occupied voxels before it), so neighbouring lanes take
// neighbouring voxels, whose cones run alike: the bounce gather measured 5 % faster than with the arbitrary order
// of an atomic counter. Each voxel's result depends on that voxel alone, so the images are the same either way.
#ifndef VCT_VOXEL_PACKING_GLSL
#define VCT_VOXEL_PACKING_GLSL

#if VCT_VOXEL_TILE != 4
#error "occupiedMask holds 64 voxels: one bit per invocation of a 4×4×4 workgroup"
#endif

shared uint occupiedMask[2];  // bit i: voxel (invocation) i is occupied
shared uint packedVoxels[VCT_VOXEL_TILE * VCT_VOXEL_TILE * VCT_VOXEL_TILE];

// Called by every invocation of the workgroup, in uniform control flow (barriers), each saying whether its own
// voxel (gl_LocalInvocationID) is occupied. True for as many invocations as there are occupied voxels, with
// `local` the voxel the invocation takes.
bool packOccupiedVoxels(bool occupied, out ivec3 local) {
    const uint own = gl_LocalInvocationIndex;
    if (own < 2u) occupiedMask[own] = 0u;
    barrier();
    if (occupied) atomicOr(occupiedMask[own >> 5u], 1u << (own & 31u));
    barrier();
    const uint low = occupiedMask[0], high = occupiedMask[1];
    if (occupied) {
        const uint before = own < 32u ? uint(bitCount(low & ((1u << own) - 1u)))
                                      : uint(bitCount(low) + bitCount(high & ((1u << (own - 32u)) - 1u)));
        packedVoxels[before] = own;
    }
    barrier();
    local = ivec3(0);
    if (own >= uint(bitCount(low) + bitCount(high))) return false;
    const uint i = packedVoxels[own];
    local = ivec3(i % VCT_VOXEL_TILE, (i / VCT_VOXEL_TILE) % VCT_VOXEL_TILE,
                  i / (VCT_VOXEL_TILE * VCT_VOXEL_TILE));
    return true;
}

#endif  // VCT_VOXEL_PACKING_GLSL
