#version 460
#extension GL_GOOGLE_include_directive : require
// inject: direct light into the voxels. For each occupied voxel: Σ lights E·(1 − F)·albedo/π·cos to every side
// it faces and each light's specular lobe into the sides it leaves towards (lib/voxel_specular.glsl; the main light
// shadow-mapped at the voxel centre, the others unshadowed) + emission, written premultiplied by opacity into
// mip 0 of the radiance, the radiance atlas's six direction slabs (rgb = (diffuse radiance × facing + the lobes'
// shares) × opacity, a = opacity; lib/voxel.glsl, lib/voxel_bricks.glsl), in the voxel's brick and in the aprons
// of the bricks below it. One workgroup per brick (every allocated brick, or those of the frame's region), its
// invocations packed onto the brick's occupied voxels (lib/voxel_packing.glsl).
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/voxel.glsl"
#include "lib/voxel_bricks.glsl"
#include "lib/lights.glsl"
#include "lib/brdf.glsl"
#include "lib/toksvig.glsl"
#include "lib/cone.glsl"
#include "lib/voxel_specular.glsl"

// Invocations per brick (VCT_VOXEL_SPEC_LANES, a divisor of 64): 64 on a GPU, one per voxel; the subgroup size on
// a CPU device, one SIMD batch a brick (lib/voxel_packing.glsl: why).
layout(local_size_x_id = VCT_VOXEL_SPEC_LANES) in;

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
// Split-sum DFG table, uv = (n·l, perceptual roughness): the specular lobes' directional albedo F0·A + B.
layout(set = 0, binding = 9) uniform sampler2D dfgTable;

#include "lib/voxel_storage.glsl"
#include "lib/voxel_workgroup.glsl"
#include "lib/voxel_packing.glsl"
#include "lib/voxel_sheet.glsl"

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

// The light occupied voxel `local` of brick k (at `brick`) sends to each side, stored.
void injectVoxel(uint k, ivec3 brick, ivec3 local) {
    const uint side = frame.voxels.brickAtlasSide;
    const ivec3 voxel = brick * VOXEL_BRICK + local;
    const ivec3 texel = materialAtlasTexel(k, side, local);
    const vec4 albedoOpacity = imageLoad(albedoImage, texel);
    vec4 slabs[VOXEL_SLAB_COUNT];
    const vec4 normalRoughness = imageLoad(normalImage, texel);
    const vec4 emissionMetallic = imageLoad(emissionImage, texel);
    const vec3 nbar = normalRoughness.xyz;
    const vec3 baseColor = albedoOpacity.rgb;
    const float nbarLength = length(nbar);
    const float metallic = emissionMetallic.w;
    const vec3 f0 = f0FromMetallic(baseColor, metallic);
    const vec3 albedo = diffuseAlbedo(baseColor, metallic);
    const float voxelSize = frame.voxels.voxelSize;
    const vec3 center = voxelCenterWorld(voxel, vec4(frame.voxels.origin, frame.voxels.voxelSize));

    // Both faces of a thin sheet (lib/voxel_sheet.glsl): each light lights the face turned towards it, and that
    // face's light leaves on its side only (per slab, like the lobes), not through the sheet.
    const vec3 sheet = nbarLength < VOXEL_TWO_SIDED_NORMAL_LENGTH ? sheetAxis(voxel) : vec3(0.0);
    const bool isSheet = any(notEqual(sheet, vec3(0.0)));
    // The lobes' roughness, widened by the spread of the normals in the voxel (Toksvig): not a sheet's, whose two
    // faces are flat and cancel in n̄ only by facing away from each other.
    const float perceptualRoughness = voxelLobeRoughness(normalRoughness.w, isSheet ? 1.0 : nbarLength);
    // What leaves per slab: the specular lobes of the lights (lib/voxel_specular.glsl), and a sheet's faces' light.
    vec3 specular[VOXEL_SLAB_COUNT];
    for (int slab = 0; slab < VOXEL_SLAB_COUNT; ++slab) specular[slab] = vec3(0.0);
    // What leaves to every side alike: emission, the diffuse part of the direct light, and (multiple bounces)
    // the light that has bounced before, diffuse and specular alike (bouncedLightReflectance,
    // lib/voxel_specular.glsl): the bounce gathers' light is not resolved by direction, so it has no lobe to follow.
    const bool glossy = (frame.flags & VCT_FLAG_VOXEL_GLOSSY) != 0u;
    vec3 radiance = emissionMetallic.rgb;
    if (push.params.x != 0u) {
        // Lambertian voxels reflect the diffuse albedo alone: no table read.
        const vec2 dfg =
            glossy ? textureLod(dfgTable, vec2(BOUNCE_MEAN_COSINE, perceptualRoughness), 0.0).rg : vec2(0.0);
        const vec4 gathered = imageLoad(bounceImage, texel);
        const vec3 bounced = bouncedLightReflectance(baseColor, metallic, dfg, glossy) * gathered.rgb;
        if (isSheet) {
            // A sheet's gather looked to each side apart (voxel_bounce.comp): rgb their mean, a the share of it
            // that came from the sheet's +axis side. Each face sends what reached it into the slab on its side:
            // a sunlit roof's sky light no longer falls into the room below it.
            for (int slab = 0; slab < VOXEL_SLAB_COUNT; ++slab)
                specular[slab] += bounced * (2.0 * (sheetFacing(sheet, slab) * gathered.a +
                                                    sheetFacing(-sheet, slab) * (1.0 - gathered.a)));
        } else {
            radiance += bounced;
        }
    }
    // Which sides the voxel's surfaces send light to (lib/voxel.glsl): its diffuse light, and its lobes' isotropic
    // part (their axis part goes where the reflection points: specularSlabShare). The outer face of a closed room's
    // wall up to two voxels thick, and the shell's edges (lib/voxel_sheet.glsl): only the one side out of the room,
    // all of it, lobes included.
    const vec3 wallFace = isSheet ? vec3(0.0) : outerWallFaceNormal(voxel, nbar);
    const bool isWallFace = any(notEqual(wallFace, vec3(0.0)));
    float facing[VOXEL_SLAB_COUNT];
    for (int slab = 0; slab < VOXEL_SLAB_COUNT; ++slab)
        facing[slab] =
            isWallFace ? sheetFacing(wallFace, slab) : voxelFacing(nbar, -voxelSlabDirection(slab));
    const int lightCount = int(frame.lighting.lightCount);
    const int shadowLight = frame.lighting.shadowLight;
    for (int i = 0; i < lightCount; ++i) {
        const IncidentLight light = incidentLight(lights[i], center);
        const vec3 incident = light.radiance;
        const vec3 l = light.towardsLight;
        // The face the light falls on: a sheet's turned towards it (unit), else the averaged normal.
        const vec3 litNormal = isSheet ? sheet * (dot(sheet, l) >= 0.0 ? 1.0 : -1.0) : nbar;
        const float cosine = voxelCosine(litNormal, l);
        if (cosine <= 0.0 || all(equal(incident, vec3(0.0)))) continue;
        // The voxel's surface turned towards the light (both sides of a thin wall reflect the side lit).
        const vec3 towardsLightSide =
            isSheet ? litNormal
                    : (nbarLength > 1e-3 ? nbar / nbarLength * sign(dot(nbar, l) + 1e-6) : vec3(0.0));
        float visibility = 1.0;
        if (i == shadowLight) {
            // The centre may lie up to half a diagonal behind the surface: step out along the light and
            // the normal (turned towards the light) so the surface does not shadow its own voxel.
            visibility = shadowVisibility(center + voxelSize * (l + towardsLightSide));
        }
        const vec3 irradiance = incident * (cosine * visibility);
        // Off: Lambertian voxels of the diffuse albedo alone (the reference's --secondary diffuse).
        const vec3 diffuse =
            irradiance * albedo * INV_PI * (glossy ? 1.0 - F_Schlick(f0, cosine) : vec3(1.0));
        if (isSheet) {
            for (int slab = 0; slab < VOXEL_SLAB_COUNT; ++slab)
                specular[slab] += diffuse * sheetFacing(litNormal, slab);
        } else {
            radiance += diffuse;
        }
        if (!glossy) continue;
        // No lobe without a direction: the surfaces in the voxel cancel (|nbar| → 0); their light stays diffuse.
        if (!isSheet && nbarLength <= 1e-3) {
            const vec2 dfg = textureLod(dfgTable, vec2(cosine, perceptualRoughness), 0.0).rg;
            radiance += irradiance * (f0 * dfg.x + dfg.y) * INV_PI;
            continue;
        }
        // A light on the room's side of a shell's face (lib/voxel_sheet.glsl, outerWallFaceNormal) lights it through
        // voxelCosine's two-sided share, and its lobe would leave by the one slab out of the room, which its exitance
        // there (as small as 1e-6) would divide it by: the room's side sends no lobe.
        if (isWallFace && dot(towardsLightSide, wallFace) <= 0.0) continue;
        const float NoL = max(dot(towardsLightSide, l), MIN_N_DOT_V);
        const vec4 lobe = specularLobe(towardsLightSide, l, NoL, perceptualRoughness);
        float shares[VOXEL_SLAB_COUNT];
        float exitance = 0.0;  // of the shares as radiance
        for (int slab = 0; slab < VOXEL_SLAB_COUNT; ++slab) {
            // A sheet's lobe leaves whole by the slab on its lit side, a wall face's by the slab on its own side:
            // their sideways slabs are read from both sides, and the part of a grazing light's reflection that runs
            // along the wall would cross it there.
            shares[slab] = isSheet      ? sheetFacing(litNormal, slab)
                           : isWallFace ? facing[slab]
                                        : specularSlabShare(lobe, slab, facing[slab]);
            exitance += shares[slab] * slabExitance(towardsLightSide, slab);
        }
        // A guard: r lies in front of the surface (r·n = n·l > 0), so the axis part sends some light through it
        // unless the lobe is uniform (no axis part).
        if (exitance <= 1e-6) continue;
        const vec2 dfg = textureLod(dfgTable, vec2(NoL, perceptualRoughness), 0.0).rg;
        const vec3 reflected = irradiance * (f0 * dfg.x + dfg.y) / exitance;
        for (int slab = 0; slab < VOXEL_SLAB_COUNT; ++slab) specular[slab] += reflected * shares[slab];
    }
    // A sheet's sideways slabs carry the light of its dimmer face (lib/voxel_sheet.glsl's sheetSideways): a cone
    // seeing the sheet obliquely, from either side, sees at most what that side's face sends.
    if (isSheet) sheetSideways(sheet, specular);
    // Each slab sees the light that leaves towards the cones reading it, i.e. against its direction (the
    // specular shares have the facing in them already: specularSlabShare).
    for (int slab = 0; slab < VOXEL_SLAB_COUNT; ++slab)
        slabs[slab] = vec4((radiance * facing[slab] + specular[slab]) * albedoOpacity.a, albedoOpacity.a);
    storeRadiance(k, brick, local, slabs);
}

void main() {
    uint k;
    ivec3 brick;
    const bool region = push.region.w != 0u;
    // Uniform over the workgroup (one brick each): all of it or none reaches the packing's barriers.
    if (!workgroupBrick(region, push.region.xyz, k, brick)) return;
    const uint lanes = gl_WorkGroupSize.x;
    // Every voxel of the brick: occupied ones are listed; empty ones are left as the clear before the dispatch made
    // them (inject_pass.cpp), or, in a region (the atlas was not cleared), stored as zero here.
    clearOccupancy();
    for (uint voxel = gl_LocalInvocationIndex; voxel < 64u; voxel += lanes) {
        const ivec3 own = brickVoxel(voxel);
        if (brickVoxelOccupied(k, own)) {
            markOccupied(voxel);
        } else if (region) {
            vec4 zero[VOXEL_SLAB_COUNT];
            for (int slab = 0; slab < VOXEL_SLAB_COUNT; ++slab) zero[slab] = vec4(0.0);
            storeRadiance(k, brick, own, zero);
        }
    }
    const uint count = listOccupiedVoxels(lanes);
    // The listed voxels, neighbours in neighbouring lanes.
    for (uint i = gl_LocalInvocationIndex; i < count; i += lanes)
        injectVoxel(k, brick, brickVoxel(packedVoxels[i]));
}
