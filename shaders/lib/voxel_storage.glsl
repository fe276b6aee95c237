// Sparse voxel storage in the shaders (docs/design.md §5.10, lib/voxel_bricks.glsl): the brick table. GLSL only. Expects before inclusion: `frame`
// (FrameUniforms), lib/voxel_bricks.glsl.
#ifndef VCT_VOXEL_STORAGE_GLSL
#define VCT_VOXEL_STORAGE_GLSL

// The brick table (render/voxel_bricks.h): the brick map, (N / VOXEL_BRICK)³ entries in brickLinearIndex order,
// each the brick's index k or VCT_BRICK_NONE; then brickCount packed brick coordinates (x | y << 10 | z << 20), the
// allocated bricks in index order.
layout(set = 0, binding = VCT_BINDING_BRICKS, std430) readonly buffer BrickTable { uint brickTable[]; };

// Mip 0 of the radiance in the brick atlas (true) or dense, level 0 of the mips' texture (lib/shared.h).
layout(constant_id = VCT_SPEC_SPARSE_MIP0) const bool SPARSE_MIP0 = true;

int bricksPerAxis() { return int(frame.voxels.resolution) / VOXEL_BRICK; }

// Index k of `brick` (inside the grid), VCT_BRICK_NONE when it has no storage.
uint brickIndex(ivec3 brick) { return brickTable[brickLinearIndex(brick, bricksPerAxis())]; }

// The sides of the cones' closure box (render/voxel_bricks.h's coneClosureBox) that are a closed room's faces, 1 per
// axis, on its lower and upper sides: those inside the grid (the others are the grid's own faces, open). Read by the
// cones (lib/cone_trace.glsl) and by inject's shell faces (lib/voxel_sheet.glsl).
vec3 closedLowFaces() { return vec3(greaterThan(frame.voxels.closureMin.xyz, frame.voxels.origin)); }
vec3 closedHighFaces() {
    const vec3 gridMax = frame.voxels.origin + vec3(float(frame.voxels.resolution) * frame.voxels.voxelSize);
    return vec3(lessThan(frame.voxels.closureMax.xyz, gridMax));
}

ivec3 allocatedBrick(uint k) {
    const uint bits = brickTable[uint(bricksPerAxis() * bricksPerAxis() * bricksPerAxis()) + k];
    return ivec3(bits & 1023u, (bits >> 10) & 1023u, bits >> 20);
}

#endif  // VCT_VOXEL_STORAGE_GLSL
