#version 460
#extension GL_GOOGLE_include_directive : require
// inject: direct light into the voxels. For each occupied voxel: Σ lights E·albedo/π·cos (the main light
// shadow-mapped at the voxel centre, the others unshadowed) + emission, written premultiplied by opacity into
// mip 0 of the radiance, the radiance atlas's six direction slabs (rgb = radiance × facing × opacity, a = opacity;
// lib/voxel.glsl, lib/voxel_bricks.glsl), in the voxel's brick and in the aprons of the bricks below it. One
// workgroup per brick (every allocated brick, or those of the frame's region), one thread per voxel.
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/voxel.glsl"
#include "lib/voxel_bricks.glsl"
#include "lib/lights.glsl"

layout(local_size_x = VCT_VOXEL_TILE, local_size_y = VCT_VOXEL_TILE, local_size_z = VCT_VOXEL_TILE) in;

// Resources: bound by engine/passes/inject_pass.cpp (its resource table gives these binding numbers and is checked
// against them when the pipeline is made).
layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) readonly buffer Lights { GpuLight lights[]; };
layout(set = 0, binding = 2, rgba8) uniform readonly image3D albedoImage;
layout(set = 0, binding = 3, rgba16f) uniform readonly image3D normalImage;
layout(set = 0, binding = 4, rgba16f) uniform readonly image3D emissionImage;
layout(set = 0, binding = 5) uniform sampler2DShadow shadowMap;
// The radiance atlas (mip 0, 6 slabs), cleared before a whole-grid dispatch; then only occupied voxels are written.
layout(set = 0, binding = 6, rgba16f) uniform image3D radianceImage;
// The light the voxels gathered from the grid (voxel_bounce.comp): cosine-weighted mean incoming radiance.
layout(set = 0, binding = 7, rgba16f) uniform readonly image3D bounceImage;
// Mip 0 when it is dense (level 0 of the radiance mips, six slabs of N³ side by side along x), cleared alike.
layout(set = 0, binding = 8, rgba16f) uniform image3D denseRadianceImage;

#include "lib/voxel_storage.glsl"
#include "lib/voxel_workgroup.glsl"

layout(push_constant) uniform Push { InjectPushConstants push; };

// The main light's shadow map at p (same lightViewProj as the direct pass). One bilinear comparison tap:
// a voxel spans many shadow texels, so a wider PCF kernel would cost much and change little.
float shadowVisibility(vec3 p) {
    const vec4 clip = frame.lightViewProj * vec4(p, 1.0);
    if (clip.w <= 0.0) return 1.0;
    const vec3 ndc = clip.xyz / clip.w;
    const vec2 uv = ndc.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || ndc.z >= 1.0) return 1.0;
    return texture(shadowMap, vec3(uv, ndc.z));
}

// The voxel's six slab values: in the dense mip 0, or in its brick's atlas block and in the apron of each brick
// below it whose block reaches it (a voxel on the brick's −x face is the +x apron of the brick before it in x, and
// so on: up to 8 blocks).
void storeRadiance(uint k, ivec3 brick, ivec3 local, const vec4 slabs[VOXEL_SLAB_COUNT]) {
    if (!SPARSE_MIP0) {
        const ivec3 voxel = brick * VOXEL_BRICK + local;
        const int n = int(frame.voxels.resolution);
        for (int slab = 0; slab < VOXEL_SLAB_COUNT; ++slab)
            imageStore(denseRadianceImage, ivec3(voxel.x + slab * n, voxel.yz), slabs[slab]);
        return;
    }
    const uint side = frame.voxels.brickAtlasSide;
    for (int below = 0; below < 8; ++below) {
        const ivec3 step = ivec3(below & 1, (below >> 1) & 1, below >> 2);
        // Only along the axes where the voxel is on the brick's lower face.
        if (any(greaterThan(step, ivec3(equal(local, ivec3(0)))))) continue;
        uint target = k;
        if (below != 0) {
            const ivec3 other = brick - step;
            if (any(lessThan(other, ivec3(0)))) continue;
            target = brickIndex(other);
            if (target == VCT_BRICK_NONE) continue;
        }
        for (int slab = 0; slab < VOXEL_SLAB_COUNT; ++slab)
            imageStore(radianceImage, radianceAtlasTexel(target, side, local + step * VOXEL_BRICK, slab),
                       slabs[slab]);
    }
}

void main() {
    uint k;
    ivec3 brick;
    const bool region = push.region.w != 0u;
    if (!workgroupBrick(region, push.region.xyz, k, brick)) return;
    const ivec3 local = ivec3(gl_LocalInvocationID);
    const ivec3 voxel = brick * VOXEL_BRICK + local;
    const ivec3 texel = materialAtlasTexel(k, frame.voxels.brickAtlasSide, local);
    const vec4 albedoOpacity = imageLoad(albedoImage, texel);
    vec4 slabs[VOXEL_SLAB_COUNT];
    // Empty: left as the clear before the dispatch made it (inject_pass.cpp), or, in a region (the atlas was not
    // cleared), stored as zero here.
    if (albedoOpacity.a <= 0.0) {
        if (region) {
            for (int slab = 0; slab < VOXEL_SLAB_COUNT; ++slab) slabs[slab] = vec4(0.0);
            storeRadiance(k, brick, local, slabs);
        }
        return;
    }
    const vec3 nbar = imageLoad(normalImage, texel).xyz;
    const vec3 emission = imageLoad(emissionImage, texel).rgb;
    const float voxelSize = frame.voxels.voxelSize;
    const vec3 center = voxelCenterWorld(voxel, vec4(frame.voxels.origin, frame.voxels.voxelSize));

    vec3 radiance = emission;
    // Light that has bounced before (multiple bounces): a Lambertian voxel sends albedo × the cosine-weighted
    // mean radiance it receives, albedo/π · E.
    if (push.params.x != 0u) radiance += albedoOpacity.rgb * imageLoad(bounceImage, texel).rgb;
    const int lightCount = int(frame.lighting.lightCount);
    const int shadowLight = frame.lighting.shadowLight;
    for (int i = 0; i < lightCount; ++i) {
        const IncidentLight light = incidentLight(lights[i], center);
        const vec3 incident = light.radiance;
        const vec3 l = light.towardsLight;
        const float cosine = voxelCosine(nbar, l);
        if (cosine <= 0.0 || all(equal(incident, vec3(0.0)))) continue;
        float visibility = 1.0;
        if (i == shadowLight) {
            // The centre may lie up to half a diagonal behind the surface: step out along the light and
            // the normal (turned towards the light) so the surface does not shadow its own voxel.
            const float r = length(nbar);
            const vec3 towardsLightSide = r > 1e-3 ? nbar / r * sign(dot(nbar, l) + 1e-6) : vec3(0.0);
            visibility = shadowVisibility(center + voxelSize * (l + towardsLightSide));
        }
        radiance += incident * albedoOpacity.rgb * INV_PI * cosine * visibility;
    }
    // Each slab sees the light that leaves towards the cones reading it, i.e. against its direction.
    for (int slab = 0; slab < VOXEL_SLAB_COUNT; ++slab) {
        const float facing = voxelFacing(nbar, -voxelSlabDirection(slab));
        slabs[slab] = vec4(radiance * (facing * albedoOpacity.a), albedoOpacity.a);
    }
    storeRadiance(k, brick, local, slabs);
}
