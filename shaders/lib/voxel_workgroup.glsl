// Which brick a workgroup of the resolve, inject or bounce covers (docs/design.md §5.10). GLSL only, compute
// shaders. Expects before inclusion: lib/voxel_storage.glsl.
#ifndef VCT_VOXEL_WORKGROUP_GLSL
#define VCT_VOXEL_WORKGROUP_GLSL

// The brick this workgroup covers (index k and coordinates): with `region`, the brick of the region box whose
// first voxel is `regionMin` at this workgroup's offset (false: it has no storage); else the k-th allocated brick,
// rows of VCT_BRICK_DISPATCH_ROW workgroups (false: past the last).
bool workgroupBrick(bool region, uvec3 regionMin, out uint k, out ivec3 brick) {
    if (region) {
        brick = ivec3(regionMin) / VOXEL_BRICK + ivec3(gl_WorkGroupID);
        if (any(greaterThanEqual(brick, ivec3(bricksPerAxis())))) return false;
        k = brickIndex(brick);
        return k != VCT_BRICK_NONE;
    }
    k = gl_WorkGroupID.y * VCT_BRICK_DISPATCH_ROW + gl_WorkGroupID.x;
    if (k >= frame.voxels.brickCount) return false;
    brick = allocatedBrick(k);
    return true;
}

#endif  // VCT_VOXEL_WORKGROUP_GLSL
