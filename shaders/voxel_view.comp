#version 460
#extension GL_GOOGLE_include_directive : require
// voxel view (`vct render --view voxels --voxel-mip M`): one thread per pixel marches the camera ray through the
// voxel grid's radiance texture at mip M with a 3D DDA over that level's texels (Amanatides & Woo), reading
// each texel it crosses unfiltered (texelFetch, so the voxels show as cubes) and compositing its premultiplied
// radiance + opacity front to back, the opacity corrected for the length of ray inside the texel. It stops at
// opacity ≥ VOXEL_VIEW_MAX_OPACITY or where the ray leaves the grid; what is left sees the environment's mean
// radiance (the trace's cones read the environment map in their own direction instead).
//
// Unlit voxels (in shadow, never injected) have no radiance and would be invisible against a dark background,
// so each texel also shows VOXEL_VIEW_GREY × opacity of grey radiance, shaded by the axis of the texel face the
// ray entered through (x 0.7, y 1.0, z 0.45: the three face orientations of the cubes tell apart). This is a
// display aid only; it is not part of the grid.
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/gbuffer_read.glsl"
#include "lib/voxel.glsl"
#include "lib/voxel_bricks.glsl"

layout(local_size_x = VCT_TILE_SIZE, local_size_y = VCT_TILE_SIZE) in;

// Resources: bound by engine/passes/voxel_view_pass.cpp (its resource table gives these binding numbers and is checked
// against them when the pipeline is made).
layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler3D voxels;  // radiance (premultiplied rgb) + opacity, mips 1..
// Mip 0: the radiance atlas (lib/voxel_bricks.glsl).
layout(set = 0, binding = VCT_BINDING_VOXEL_ATLAS) uniform sampler3D voxelAtlas;
layout(set = 0, binding = 2,
       rgba16f) uniform writeonly image2D outputImage;  // radiance seen through the grid, full res
layout(push_constant) uniform Push { VoxelViewPushConstants push; };
#include "lib/voxel_storage.glsl"

// Texel `cell` of slab `slab` at level `mip`: from the radiance mips' texture, or for a sparse mip 0 from its
// brick's atlas block (empty without one).
vec4 fetchTexel(ivec3 cell, int slab, int cells, int mip) {
    const int mipBase =
        SPARSE_MIP0 ? 1 : 0;  // the mips' texture's level 0 is mip 1 when mip 0 is in the atlas
    if (mip >= mipBase) return texelFetch(voxels, ivec3(cell.x + slab * cells, cell.yz), mip - mipBase);
    const ivec3 brick = voxelBrickOf(cell);
    const uint k = brickIndex(brick);
    if (k == VCT_BRICK_NONE) return vec4(0.0);
    return texelFetch(
        voxelAtlas, radianceAtlasTexel(k, frame.voxels.brickAtlasSide, cell - brick * VOXEL_BRICK, slab), 0);
}

const float VOXEL_VIEW_MAX_OPACITY = 0.99;
const float VOXEL_VIEW_GREY = 0.15;
const vec3 VOXEL_VIEW_FACE_SHADE = vec3(0.7, 1.0, 0.45);

// The ray against the grid's box [0, cells)³ in texel units of the level (slab test): tNear per axis, where it
// enters and leaves. An axis the ray (nearly) runs parallel to never steps and only limits the ray if the eye is
// outside the grid's slab on it.
struct GridSpan {
    vec3 tNear;
    float tEnter;
    float tExit;
};

GridSpan gridSpan(const vec3 o, const vec3 invDir, const bvec3 moves, const int cells) {
    vec3 tNear = vec3(-1e30), tFar = vec3(1e30);
    for (int k = 0; k < 3; ++k) {
        if (moves[k]) {
            const float ta = -o[k] * invDir[k], tb = (float(cells) - o[k]) * invDir[k];
            tNear[k] = min(ta, tb);
            tFar[k] = max(ta, tb);
        } else if (o[k] < 0.0 || o[k] >= float(cells)) {
            tFar[k] = -1e30;  // parallel outside: no hit
        }
    }
    return GridSpan(tNear, max(max(tNear.x, tNear.y), tNear.z), min(min(tFar.x, tFar.y), tFar.z));
}

// The march starts where the ray leaves the level-0 voxel the eye is in: a camera close to a surface sits in
// that surface's voxel (cornell's at N = 32, 0.1 m from the front wall in 0.13 m voxels), which would
// otherwise veil the whole view. In level-0 units: the first boundary ahead on each axis (the eye exactly on
// a boundary is in the voxel the ray goes into). Returned in texel units of the level; 0 outside the grid.
float eyeVoxelExit(const vec3 o, const vec3 dir, const vec3 invDir, const bvec3 moves, const int cells) {
    const float texelsPerCell = float(int(frame.voxels.resolution) / cells);
    const vec3 o0 = o * texelsPerCell;
    float tSkip = 0.0;
    if (all(greaterThanEqual(o0, vec3(0.0))) && all(lessThan(o0, vec3(float(frame.voxels.resolution))))) {
        float exit0 = 1e30;
        for (int k = 0; k < 3; ++k) {
            const float boundary = dir[k] > 0.0 ? floor(o0[k]) + 1.0 : ceil(o0[k]) - 1.0;
            if (moves[k]) exit0 = min(exit0, (boundary - o0[k]) * invDir[k]);
        }
        tSkip = exit0 / texelsPerCell;
    }
    return tSkip;
}

// The DDA over the level's texels from the grid's entry to its exit (none of the ray before tSkip counts),
// compositing each texel's radiance + opacity front to back; premultiplied rgb and opacity of what was crossed.
vec4 marchTexels(const vec3 o, const vec3 dir, const vec3 invDir, const bvec3 moves, const GridSpan span,
                 const float tSkip, const int cells, const int mip) {
    vec4 acc = vec4(0.0);
    const float tExit = span.tExit;
    float t = max(span.tEnter, 0.0);
    // The face the ray entered the grid through (outside the grid); from inside, the view faces no face.
    int axis = -1;
    if (span.tEnter > 0.0) axis = span.tNear.x == span.tEnter ? 0 : (span.tNear.y == span.tEnter ? 1 : 2);
    // The first texel: the one the entry point (nudged inside) lies in.
    const vec3 start = o + dir * t;
    ivec3 cell = clamp(ivec3(floor(start + dir * 1e-4)), ivec3(0), ivec3(cells - 1));
    const ivec3 stepDir = ivec3(sign(dir)) * ivec3(moves);
    const vec3 tDelta = abs(invDir);
    // t at which the ray crosses the next texel boundary on each axis (never on one it does not move along).
    vec3 tMax = (vec3(cell) + vec3(greaterThan(dir, vec3(0.0))) - o) * invDir;
    tMax = mix(vec3(1e30), tMax, moves);

    // At most 3·cells crossings; bounded even if rounding keeps a crossing from advancing.
    for (int i = 0; i < 3 * cells + 3 && acc.a < VOXEL_VIEW_MAX_OPACITY; ++i) {
        const float tNext = min(min(tMax.x, tMax.y), tMax.z);
        // Texel lengths of ray inside this texel (none of it before tSkip).
        const float len = min(tNext, tExit) - max(t, tSkip);
        if (len > 0.0) {
            // The three direction slabs facing the ray (lib/voxel.glsl), weighted as the cones weigh them.
            vec4 s = vec4(0.0);
            const vec3 w = voxelSlabWeights(dir);
            for (int k = 0; k < 3; ++k) s += w[k] * fetchTexel(cell, voxelSlabFor(dir, k), cells, mip);
            const float a = saturate(s.a);
            // Opacity a is for one texel length; over `len`: 1 − (1 − a)^len, colour scaled alike.
            const float aLen = 1.0 - pow(1.0 - min(a, 0.999999), len);
            const float scale = a > 1e-5 ? aLen / a : len;
            const float shade = axis < 0 ? 1.0 : VOXEL_VIEW_FACE_SHADE[axis];
            const vec3 rgb = max(s.rgb, vec3(0.0)) + VOXEL_VIEW_GREY * shade * a;
            acc.rgb += (1.0 - acc.a) * rgb * scale;
            acc.a += (1.0 - acc.a) * aLen;
        }
        if (tNext >= tExit) break;
        axis = tMax.x == tNext ? 0 : (tMax.y == tNext ? 1 : 2);
        cell[axis] += stepDir[axis];
        tMax[axis] += tDelta[axis];
        t = tNext;
        if (cell[axis] < 0 || cell[axis] >= cells) break;
    }
    return acc;
}

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    const ivec2 size = imageSize(outputImage);
    if (any(greaterThanEqual(pixel, size))) return;
    const vec3 ambient = frame.lighting.ambient;
    const float v0 = frame.voxels.voxelSize;
    if (v0 <= 0.0) {  // no grid
        imageStore(outputImage, pixel, vec4(ambient, 1.0));
        return;
    }

    // The camera ray through the pixel centre.
    const vec2 uv = (vec2(pixel) + 0.5) / vec2(size);
    const vec3 eye = frame.cameraPosition;
    const vec3 dir = normalize(worldFromDepth(frame.invViewProj, uv, 1.0) - eye);

    // In units of one texel of level `mip`: the grid is [0, cells)³.
    const int mip = int(push.params.x);
    const int cells = max(int(frame.voxels.resolution) >> mip, 1);
    const float cellSize = v0 * float(int(frame.voxels.resolution) / cells);
    const vec3 o = (eye - frame.voxels.origin) / cellSize;

    const bvec3 moves = greaterThanEqual(abs(dir), vec3(1e-12));
    const vec3 invDir = 1.0 / mix(vec3(1.0), dir, moves);
    const GridSpan span = gridSpan(o, invDir, moves, cells);
    const float tSkip = eyeVoxelExit(o, dir, invDir, moves, cells);
    vec4 acc = vec4(0.0);
    if (span.tExit > max(span.tEnter, tSkip))
        acc = marchTexels(o, dir, invDir, moves, span, tSkip, cells, mip);
    imageStore(outputImage, pixel, vec4(acc.rgb + (1.0 - saturate(acc.a)) * ambient, 1.0));
}
