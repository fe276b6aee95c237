// Sparse voxel storage (docs/design.md §5.10), shared by the voxel shaders and the CPU (render/voxel_bricks.h):
// the N³ grid is cut into bricks of VOXEL_BRICK³ voxels, and only the bricks where the scene can have surfaces
// get storage. A brick map of (N / VOXEL_BRICK)³ entries gives each brick its index k in the pools
// (VCT_BRICK_NONE: no storage, every voxel of it empty). Brick k's storage:
//  - accumulators: VOXEL_BRICK³ voxels × VCT_VOXEL_ACCUM_STRIDE uints from (k·VOXEL_BRICK³ + local)·stride;
//  - material atlases (albedo, normal, emission, bounce: 3D images): a block of VOXEL_BRICK³ texels;
//  - radiance atlas (mip 0 of the radiance, six direction slabs side by side along x): per slab a block of
//    VOXEL_BRICK_APRON³ texels, the brick's voxels and, on its +x, +y and +z sides, the first voxels of the bricks
//    beyond (the apron). A trilinear sample whose lower corner voxel is in the brick reads only that block, so
//    the filtering hardware does it in one texture read.
// Blocks fill the atlases in rows and columns of `side` blocks (brickAtlasSide), then layers.
// Rules for this shared header: lib/cpp_glsl.h.
#ifndef VCT_VOXEL_BRICKS_GLSL
#define VCT_VOXEL_BRICKS_GLSL

const int VOXEL_BRICK = VCT_VOXEL_BRICK;
const int VOXEL_BRICK_APRON = VCT_VOXEL_BRICK + 1;

VCT_INLINE ivec3 voxelBrickOf(ivec3 voxel) { return voxel / VOXEL_BRICK; }
VCT_INLINE uint brickLinearIndex(ivec3 brick, int bricksPerAxis) {
    return uint(brick.x + bricksPerAxis * (brick.y + bricksPerAxis * brick.z));
}
// Brick k's block in an atlas of `side` × `side` blocks per layer.
VCT_INLINE ivec3 brickAtlasBlock(uint k, uint side) {
    return ivec3(int(k % side), int((k / side) % side), int(k / (side * side)));
}
// Voxel `local` (0..VOXEL_BRICK − 1 per axis) of brick k in the material atlases.
VCT_INLINE ivec3 materialAtlasTexel(uint k, uint side, ivec3 local) {
    return brickAtlasBlock(k, side) * VOXEL_BRICK + local;
}
// Voxel `local` (0..VOXEL_BRICK per axis: VOXEL_BRICK is the apron) of brick k in slab `slab` of the radiance atlas.
VCT_INLINE ivec3 radianceAtlasTexel(uint k, uint side, ivec3 local, int slab) {
    return brickAtlasBlock(k, side) * VOXEL_BRICK_APRON + local +
           ivec3(slab * int(side) * VOXEL_BRICK_APRON, 0, 0);
}
// First accumulator uint of voxel `local` of brick k.
VCT_INLINE uint voxelAccumIndex(uint k, ivec3 local) {
    const uint inBrick = uint(local.x + VOXEL_BRICK * (local.y + VOXEL_BRICK * local.z));
    return (k * uint(VOXEL_BRICK * VOXEL_BRICK * VOXEL_BRICK) + inBrick) * uint(VCT_VOXEL_ACCUM_STRIDE);
}

#endif  // VCT_VOXEL_BRICKS_GLSL
