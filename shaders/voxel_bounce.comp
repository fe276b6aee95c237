#version 460
#extension GL_GOOGLE_include_directive : require
// bounce: the light each occupied voxel receives through the grid (docs/design.md §5.7), for the next inject to
// send on as albedo × it. The 6 diffuse cones of a surface pixel (lib/cone_trace.glsl's traceDiffuse), from the
// voxel's centre about its averaged normal: the cosine-weighted mean incoming radiance, the Lambertian bounce's
// albedo/π · E. Voxels whose surfaces disagree on a side (|n̄| short: both faces of a thin wall) gather about
// n̄'s side only when it is clear, and over both sides when it is not, apart (gatheredLight: their mean and the
// share of one side, which inject.comp splits between a thin sheet's faces again). Cones that leave the grid
// see the environment (lib/cone_trace.glsl), so sky light bounces too. One workgroup per allocated brick
// (lib/voxel_storage.glsl), its invocations packed onto the brick's occupied voxels (lib/voxel_packing.glsl).
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/brdf.glsl"
#include "lib/color.glsl"
#include "lib/cone.glsl"
#include "lib/gbuffer_read.glsl"
#include "lib/voxel_bricks.glsl"

// Invocations per brick (VCT_VOXEL_SPEC_LANES, a divisor of 64): 64 on a GPU, one per voxel; the subgroup size
// on a CPU device, one SIMD batch a brick (lib/voxel_packing.glsl: why).
// z: invocations per voxel, 1 (its cones one after the other) or CONE_LANES_PER_PIXEL (one cone each, combined
// through shared memory: the cone layout, RenderSettings::TraceLayout, lib/cone_trace.glsl).
layout(local_size_x_id = VCT_VOXEL_SPEC_LANES, local_size_z_id = VCT_SPEC_CONE_LANES) in;

// Resources: bound by engine/passes/voxel_bounce_pass.cpp (its resource table gives these binding numbers and is
// checked against them when the pipeline is made).
layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1, rgba8) uniform readonly image3D albedoImage;
layout(set = 0, binding = 2, rgba16f) uniform readonly image3D normalImage;
layout(set = 0,
       binding = 3) uniform sampler3D voxels;  // radiance slabs, mips 1 and coarser (lib/cone_trace.glsl)
layout(set = 0, binding = 4, rgba16f) uniform writeonly image3D bounceImage;
// The environment: sky light reaches the voxels through cones that leave the grid (lib/environment_sample.glsl).
layout(set = 0, binding = 5) uniform sampler2D environmentMap;

layout(push_constant) uniform Push { VoxelBouncePushConstants push; };

#include "lib/cone_trace.glsl"
#include "lib/voxel_workgroup.glsl"
#include "lib/voxel_packing.glsl"
#include "lib/voxel_sheet.glsl"

// Where voxel `local` of brick k (at `brick`) gathers from: its centre, lifted one voxel along its axis (and against
// it where its surfaces face both ways, |n̄| below VOXEL_TWO_SIDED_NORMAL_LENGTH: twoSided). A thin sheet's axis is
// its plane's normal (sheetAxis), so that each side's gather is that face's, for inject.comp to send back out on
// that side alone; other two-sided voxels gather about n̄ (or +y when nothing is left of it).
struct GatherPoint {
    vec3 p;
    vec3 axis;
    bool twoSided;
};

GatherPoint gatherPoint(uint k, ivec3 brick, ivec3 local) {
    const ivec3 voxel = brick * VOXEL_BRICK + local;
    const ivec3 texel = materialAtlasTexel(k, frame.voxels.brickAtlasSide, local);
    const vec3 nbar = imageLoad(normalImage, texel).xyz;
    const float r = length(nbar);
    GatherPoint g;
    g.p = voxelCenterWorld(voxel, vec4(frame.voxels.origin, frame.voxels.voxelSize));
    // No direction at all (rare: opposite faces in one voxel cancelling exactly): +y's two sides.
    g.twoSided = r < VOXEL_TWO_SIDED_NORMAL_LENGTH;
    const vec3 sheet = g.twoSided ? sheetAxis(voxel) : vec3(0.0);
    g.axis = any(notEqual(sheet, vec3(0.0))) ? sheet : (r > 1e-3 ? nbar / r : vec3(0.0, 1.0, 0.0));
    return g;
}

// The cones leave from one voxel out along the normal, not from the centre: the surface lies anywhere within its
// voxel, and from the centre the side cones met the voxel's own neighbours along the surface (its own light, or a
// shadow where the truth sees the room). Measured on cornell against the all-bounce truth (320×180, 64 frames):
// 64³ 0.890 → 0.925 of the indirect light, sRGB PSNR 22.90 → 23.33 dB; 32³ and 128³ and DamagedHelmet gain 0.1–0.5
// dB (docs/design.md §5.7).
vec3 gatherOrigin(GatherPoint g, float side) { return g.p + side * frame.voxels.voxelSize * g.axis; }

// What a voxel stores of its gathers: one side's light (rgb; a: 1, all of it from its axis's side), or the mean of
// both sides' (a: the share of it that came from the +axis side, by luminance; ½ when neither side sees light),
// which inject.comp splits again between a sheet's two faces.
vec4 gatheredLight(vec3 front, vec3 back, bool twoSided) {
    if (!twoSided) return vec4(front, 1.0);
    const float f = luminance(front), b = luminance(back);
    return vec4(0.5 * (front + back), f + b > 0.0 ? f / (f + b) : 0.5);
}

// The light voxel `local` of brick k (at `brick`) receives through the grid, its cones one after the other.
vec4 gather(uint k, ivec3 brick, ivec3 local) {
    const GatherPoint g = gatherPoint(k, brick, local);
    const vec3 front = traceDiffuse(voxels, gatherOrigin(g, 1.0), g.axis);
    const vec3 back = g.twoSided ? traceDiffuse(voxels, gatherOrigin(g, -1.0), -g.axis) : vec3(0.0);
    return gatheredLight(front, back, g.twoSided);
}

// The cone layout's radiances, per side, cone and listed voxel of the workgroup's current batch.
const bool CONE_LANES = gl_WorkGroupSize.z > 1;
shared vec3 gatherRadiance[2][CONE_LANES_PER_PIXEL][VCT_VOXEL_TILE * VCT_VOXEL_TILE * VCT_VOXEL_TILE];

void main() {
    uint k;
    ivec3 brick;
    // Uniform over the workgroup (one brick each): all of it or none reaches the packing's barriers.
    if (!workgroupBrick(push.region.w != 0u, push.region.xyz, k, brick)) return;
    const uint lanes = gl_WorkGroupSize.x;  // voxels gathered at a time
    // Every voxel of the brick: empty ones store no light, occupied ones are listed (by all the invocations).
    const uint invocations = gl_WorkGroupSize.x * gl_WorkGroupSize.z;
    clearOccupancy();
    for (uint voxel = gl_LocalInvocationIndex; voxel < 64u; voxel += invocations) {
        const ivec3 local = brickVoxel(voxel);
        if (brickVoxelOccupied(k, local))
            markOccupied(voxel);
        else
            imageStore(bounceImage, materialAtlasTexel(k, frame.voxels.brickAtlasSide, local), vec4(0.0));
    }
    const uint count = listOccupiedVoxels(invocations);
    if (!CONE_LANES) {
        // The listed voxels, neighbours in neighbouring lanes.
        for (uint i = gl_LocalInvocationIndex; i < count; i += lanes) {
            const ivec3 local = brickVoxel(packedVoxels[i]);
            imageStore(bounceImage, materialAtlasTexel(k, frame.voxels.brickAtlasSide, local),
                       gather(k, brick, local));
        }
        return;
    }
    // The cone layout: `lanes` listed voxels at a time, cone z of each in invocation (x, z); the batches' count is
    // uniform, so every invocation reaches the barriers.
    const uint lane = gl_LocalInvocationID.x;
    const int cone = int(gl_LocalInvocationID.z);
    for (uint first = 0u; first < count; first += lanes) {
        const bool listed = first + lane < count;
        const ivec3 local = brickVoxel(packedVoxels[listed ? first + lane : 0u]);
        const GatherPoint g = gatherPoint(k, brick, local);
        if (listed && cone < DIFFUSE_CONE_COUNT) {
            gatherRadiance[0][cone][lane] = traceDiffuseCone(voxels, gatherOrigin(g, 1.0), g.axis, cone);
            if (g.twoSided)
                gatherRadiance[1][cone][lane] =
                    traceDiffuseCone(voxels, gatherOrigin(g, -1.0), -g.axis, cone);
        }
        barrier();
        if (listed && cone == 0) {
            vec3 radiance[DIFFUSE_CONE_COUNT];
            for (int i = 0; i < DIFFUSE_CONE_COUNT; ++i) radiance[i] = gatherRadiance[0][i][lane];
            const vec3 front = diffuseFromCones(radiance);
            vec3 back = vec3(0.0);
            if (g.twoSided) {
                for (int i = 0; i < DIFFUSE_CONE_COUNT; ++i) radiance[i] = gatherRadiance[1][i][lane];
                back = diffuseFromCones(radiance);
            }
            imageStore(bounceImage, materialAtlasTexel(k, frame.voxels.brickAtlasSide, local),
                       gatheredLight(front, back, g.twoSided));
        }
        barrier();  // before the next batch overwrites the radiances
    }
}
