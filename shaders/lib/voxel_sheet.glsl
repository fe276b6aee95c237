// Thin sheets in the voxels (docs/design.md §5.6): a voxel whose surfaces' normals cancel may hold both faces of a
// wall or roof of no thickness, and its averaged normal then no longer says which side each face's light leaves by.
// Shared by inject.comp (where each face's direct and bounced light goes) and voxel_bounce.comp (which side each
// gather looks to). GLSL only. Expects before inclusion: `frame` (FrameUniforms), the `albedoImage` (alpha: opacity)
// and `normalImage` of the resolved voxels, lib/voxel.glsl, lib/voxel_bricks.glsl, lib/voxel_storage.glsl.
#ifndef VCT_VOXEL_SHEET_GLSL
#define VCT_VOXEL_SHEET_GLSL

// A sheet's two faces share one colour in the bounced light: voxel_bounce.comp keeps the mean of their gathers
// (rgb) and the share of one side (a, by luminance), four channels; a blue sky above a warm room tints both faces.

// Below this |n̄| a voxel's surfaces face both ways about equally: it is looked at as a sheet (sheetAxis), and the
// voxels' gathers look to both sides of it (voxel_bounce.comp).
const float VOXEL_TWO_SIDED_NORMAL_LENGTH = 0.5;

// Whether voxel `local` of brick k holds a surface (its resolved opacity).
bool brickVoxelOccupied(uint k, ivec3 local) {
    return imageLoad(albedoImage, materialAtlasTexel(k, frame.voxels.brickAtlasSide, local)).a > 0.0;
}

// Where `voxel` (grid coordinates, in any brick) lies in the material atlas, if it has storage: false outside the
// grid and in unallocated bricks.
bool voxelMaterialTexel(ivec3 voxel, out ivec3 texel) {
    texel = ivec3(0);
    const int n = int(frame.voxels.resolution);
    if (any(lessThan(voxel, ivec3(0))) || any(greaterThanEqual(voxel, ivec3(n)))) return false;
    const uint k = brickIndex(voxelBrickOf(voxel));
    if (k == VCT_BRICK_NONE) return false;
    texel = materialAtlasTexel(k, frame.voxels.brickAtlasSide, voxel % VOXEL_BRICK);
    return true;
}

// Whether `voxel` holds a surface; outside the grid or its storage it holds none.
bool voxelOccupied(ivec3 voxel) {
    ivec3 texel;
    return voxelMaterialTexel(voxel, texel) && imageLoad(albedoImage, texel).a > 0.0;
}

// A voxel whose surfaces' normals cancel (|n̄| below VOXEL_TWO_SIDED_NORMAL_LENGTH) may hold both faces of a thin
// sheet (a wall or roof of no thickness): its averaged normal no longer says which side each face's light leaves by,
// and voxelCosine / voxelFacing send the lit face's light to both sides, into the room behind the sheet
// (docs/design.md §5.6). The sheet's plane is read from its neighbours instead: the one axis along which the occupied run through
// the voxel is at most two voxels long (a sheet on a voxel face fills the layers on both sides) while along another
// axis both neighbours are occupied. Returns that axis as a unit vector, or 0 where the neighbours say no one plane
// (a corner, a lone voxel, an oblique sheet): the averaged normal then stays in charge.
vec3 sheetAxis(ivec3 voxel) {
    bvec3 thin = bvec3(false), continues = bvec3(false);
    for (int axis = 0; axis < 3; ++axis) {
        ivec3 step = ivec3(0);
        step[axis] = 1;
        const bool below = voxelOccupied(voxel - step), above = voxelOccupied(voxel + step);
        continues[axis] = below && above;
        // The run's length: this voxel, and one more on at most one side, with empty space past it.
        thin[axis] = (!below && !above) || (below && !above && !voxelOccupied(voxel - 2 * step)) ||
                     (!below && above && !voxelOccupied(voxel + 2 * step));
    }
    const int thins = int(thin.x) + int(thin.y) + int(thin.z);
    if (thins != 1 || !any(continues)) return vec3(0.0);
    return vec3(thin);
}

// Which slabs a sheet's face of unit normal n sends its light into: those on its side (n·e > ½: the one slab facing
// away from the sheet), not the sideways ones. A one-sided surface's sideways slabs carry its light to the cones
// that see it obliquely (voxelFacing); a sheet's are read from both sides, and carried the lit face's light into
// the room behind it: a roof of no thickness under the sun sent 0.12–0.14 of its radiance into the room below with
// them (0.003 without), and the hall, whose roof and walls are such sheets, got 2.06× its true indirect light at
// 64³ with them (1.29× without; docs/design.md §5.6).
float sheetFacing(vec3 n, int slab) { return dot(n, -voxelSlabDirection(slab)) > 0.5 ? 1.0 : 0.0; }

// A sheet's sideways slabs: the light of its dimmer face, per channel (`slabs`: what each face sent into the slab on
// its side, sheetFacing; the sideways ones are added to). A cone meeting the sheet obliquely from either side reads
// them, so they may hold no more than the face on that side sends, and the dimmer face is the most both sides allow:
// no leak from a lit face into the room behind, and an oblique cone in the dim room still sees its own face's light.
// With nothing sideways a cone 60° off the sheet's normal saw a quarter of it (its slab's weight, cos²): the hall's
// partitions got 0.65× of their true second bounce at 64³, 0.89× with the dimmer face (docs/design.md §5.6).
void sheetSideways(vec3 sheet, inout vec3 slabs[VOXEL_SLAB_COUNT]) {
    const int axis = sheet.x > 0.5 ? 0 : (sheet.y > 0.5 ? 1 : 2);
    const vec3 dimmer = min(slabs[2 * axis], slabs[2 * axis + 1]);
    for (int slab = 0; slab < VOXEL_SLAB_COUNT; ++slab)
        if (slab / 2 != axis) slabs[slab] += dimmer;
}

// ---- a closed room's shell: the outer faces of a wall up to two voxels thick, and the shell's edges ----
// A wall or roof up to two voxels thick (the hall's 0.3 m shell at 64³ and 128³) whose faces fall in different voxel
// layers (neighbouring ones, or with one empty layer between) has one-sided voxels on each face (|n̄| ≈ 1, no
// sheet). A one-sided voxel sends its light sideways too (voxelFacing: a floor seen obliquely from above is lit),
// but every mip texel that holds both layers, and the trilinear reads between them, average the two faces' sideways
// slabs, which cones read from either side. The six slabs cannot tell a viewer above a lit roof from one below it.
// The sunlit top of the hall's roof lit the hall below that way (docs/design.md §5.6: 2.06× the hall's true sun
// light at 64³).
// Such a face on the outside of a closed room (within a voxel of a closed face of the cones' closure box, facing out
// of it) sends its light only into the slab on its own side, like a sheet's faces: nothing inside the room can see
// it, and nothing lies beyond the content to see it sideways. The inner faces keep their sideways light: sent along
// the one slab alone, the hall's floor and walls, seen obliquely, gave the hall 0.58× of its true second bounce at
// 128³ (0.86× with the sideways light). Between two rooms such a wall leaks as it did before (§5.6: 0.019 of a
// spot-lit room's light, a third of what a wall of no thickness lets through).
// The shell's edges and the voxels in it whose faces disagree likewise send their light into the one slab out of the
// room: a voxel within a voxel of a closed face, with nothing beyond it, whose averaged normal leans out through it,
// off the axes (the roof's edge along a wall's top, the rim of a skylight) or short (a roof's top, underside and the
// side of an opening in one voxel). Their light went to every side and lit the hall below its roof: with the sun
// alone and the marble absorbing, the floor got 2.96× its true light and the hall 1.43×; 1.03× and 0.97× with the
// edges one-slab (docs/design.md §5.6). What such a voxel holds that faces the room (a rim's underside) loses its
// light to the room: six slabs cannot send one face's light in and another's out.

// A wall's face: the averaged normal within ~25° of an axis (cos ≥ 0.9), and so is the voxel's behind it.
const float WALL_FACE_AXIS_COSINE = 0.9;
// A shell's edge leans out by at least this much of its averaged normal (unnormalised: a tenth of its surfaces' net
// facing), with nothing beyond it: a voxel that merely touches a closed face (an object's underside on a floor
// without geometry under it) keeps its light in the room. With the sun alone the hall read 0.955× of the truth with
// any lean, 0.971× with 0.1, 1.074× with 0.2 (its floor 1.02×, 1.03×, 1.61×).
const float SHELL_EDGE_MIN_LEAN = 0.1;

// The averaged normal of `voxel` (0 outside the grid, in unallocated bricks and in empty voxels).
vec3 voxelNormalAt(ivec3 voxel) {
    ivec3 texel;
    if (!voxelMaterialTexel(voxel, texel) || !(imageLoad(albedoImage, texel).a > 0.0)) return vec3(0.0);
    return imageLoad(normalImage, texel).xyz;
}

// Whether the voxel centred at `centre` lies within a voxel of a closed face of the closure box on `axis`, on its
// upper side (`up`) or lower one (lib/voxel_storage.glsl's closedLowFaces / closedHighFaces).
bool atClosedFace(vec3 centre, int axis, bool up) {
    const float voxelSize = frame.voxels.voxelSize;
    return up ? closedHighFaces()[axis] > 0.5 && frame.voxels.closureMax[axis] - centre[axis] < voxelSize
              : closedLowFaces()[axis] > 0.5 && centre[axis] - frame.voxels.closureMin[axis] < voxelSize;
}

// The unit axis out of the closed room that `voxel`'s light leaves by alone, or 0 where it leaves by every side its
// surfaces face (voxelFacing). A wall's outer face (the averaged normal n̄ within WALL_FACE_AXIS_COSINE of an axis):
// out through a closed face it lies at, with the wall's inner face in the voxel right behind, or past one empty voxel
// (a wall up to two voxels thick may leave one between its faces, by where it lies in the grid), its normal within
// WALL_FACE_AXIS_COSINE of the opposite way. A shell's edge or a voxel of disagreeing faces (n̄ off the axes, or
// shorter than VOXEL_TWO_SIDED_NORMAL_LENGTH but not a sheet: the caller's): out through the closed face it lies at
// that n̄ leans out through the most.
vec3 outerWallFaceNormal(ivec3 voxel, vec3 nbar) {
    const float r = length(nbar);
    if (r < 1e-3) return vec3(0.0);
    const vec3 n = nbar / r;
    const vec3 a = abs(n);
    const vec3 centre = voxelCenterWorld(voxel, vec4(frame.voxels.origin, frame.voxels.voxelSize));
    const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    vec3 face = vec3(0.0);
    if (r < VOXEL_TWO_SIDED_NORMAL_LENGTH || a[axis] < WALL_FACE_AXIS_COSINE) {
        float most = SHELL_EDGE_MIN_LEAN;
        for (int k = 0; k < 3; ++k) {
            ivec3 outward = ivec3(0);
            outward[k] = nbar[k] > 0.0 ? 1 : -1;
            if (abs(nbar[k]) >= most && atClosedFace(centre, k, nbar[k] > 0.0) &&
                !voxelOccupied(voxel + outward)) {
                most = abs(nbar[k]);
                face = vec3(outward);
            }
        }
        return face;
    }
    face[axis] = n[axis] > 0.0 ? 1.0 : -1.0;
    if (!atClosedFace(centre, axis, n[axis] > 0.0)) return vec3(0.0);
    vec3 behind = voxelNormalAt(voxel - ivec3(face));
    if (all(equal(behind, vec3(0.0)))) behind = voxelNormalAt(voxel - 2 * ivec3(face));
    const float behindLength = length(behind);
    if (behindLength < VOXEL_TWO_SIDED_NORMAL_LENGTH) return vec3(0.0);
    return dot(behind, face) / behindLength <= -WALL_FACE_AXIS_COSINE ? face : vec3(0.0);
}

#endif  // VCT_VOXEL_SHEET_GLSL
