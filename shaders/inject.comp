#version 460
#extension GL_GOOGLE_include_directive : require
// inject: direct light into the voxels. For each occupied voxel: Σ lights E·albedo/π·cos (the main light
// shadow-mapped at the voxel centre, the others unshadowed) + emission, written premultiplied by opacity into
// mip 0 of the radiance texture's six direction slabs (rgb = radiance × facing × opacity, a = opacity;
// lib/voxel.glsl). One thread per voxel.
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/voxel.glsl"
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
// Mip 0 of the radiance texture (6 slabs), cleared before the dispatch; only occupied voxels are written.
layout(set = 0, binding = 6, rgba16f) uniform image3D radianceImage;
// The light the voxels gathered from the grid (voxel_bounce.comp): cosine-weighted mean incoming radiance.
layout(set = 0, binding = 7, rgba16f) uniform readonly image3D bounceImage;

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

// Voxel `voxel` of slab `slab` in the 6N-wide radiance texture (lib/voxel.glsl, directional radiance).
ivec3 slabTexel(ivec3 voxel, int slab, int n) { return ivec3(voxel.x + slab * n, voxel.yz); }

void main() {
    const ivec3 voxel = ivec3(push.region.xyz + gl_GlobalInvocationID);
    const int n = int(frame.voxels.resolution);
    if (any(greaterThanEqual(voxel, ivec3(n)))) return;
    const vec4 albedoOpacity = imageLoad(albedoImage, voxel);
    // Empty: left as the clear before the dispatch made it (inject_pass.cpp), or, in a region of a level that
    // was not cleared, stored as zero here.
    if (albedoOpacity.a <= 0.0) {
        if (push.params.y != 0u)
            for (int slab = 0; slab < VOXEL_SLAB_COUNT; ++slab)
                imageStore(radianceImage, slabTexel(voxel, slab, n), vec4(0.0));
        return;
    }
    const vec3 nbar = imageLoad(normalImage, voxel).xyz;
    const vec3 emission = imageLoad(emissionImage, voxel).rgb;
    const float voxelSize = frame.voxels.voxelSize;
    const vec3 center = voxelCenterWorld(voxel, vec4(frame.voxels.origin, frame.voxels.voxelSize));

    vec3 radiance = emission;
    // Light that has bounced before (multiple bounces): a Lambertian voxel sends albedo × the cosine-weighted
    // mean radiance it receives, albedo/π · E.
    if (push.params.x != 0u) radiance += albedoOpacity.rgb * imageLoad(bounceImage, voxel).rgb;
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
        imageStore(radianceImage, slabTexel(voxel, slab, n),
                   vec4(radiance * (facing * albedoOpacity.a), albedoOpacity.a));
    }
}
