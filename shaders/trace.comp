#version 460
#extension GL_GOOGLE_include_directive : require
// trace: one thread per LOW-res pixel (x, y), traced at full-res pixel (s·x, s·y) (jitter comes later) from the
// full-res G-buffer: 6 diffuse cones around n and 1 specular cone along reflect(−v, n) through the voxel grid.
// Outputs are demodulated (lib/cone.glsl): diffuse = cosine-weighted mean incoming radiance (albedo divided
// out), specular = incoming radiance along the cone (specular colour / DFG divided out).
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/brdf.glsl"
#include "lib/cone.glsl"
#include "lib/gbuffer_read.glsl"

layout(local_size_x = VCT_TILE_SIZE, local_size_y = VCT_TILE_SIZE) in;

layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = VCT_TRACE_BINDING_DEPTH) uniform sampler2D depthTexture;
layout(set = 0, binding = VCT_TRACE_BINDING_NORMAL_ROUGHNESS) uniform sampler2D normalRoughnessTexture;
layout(set = 0, binding = VCT_TRACE_BINDING_VOXELS) uniform sampler3D voxels;
layout(set = 0, binding = VCT_TRACE_BINDING_DIFFUSE, rgba16f) uniform writeonly image2D diffuseImage;
layout(set = 0, binding = VCT_TRACE_BINDING_SPECULAR, rgba16f) uniform writeonly image2D specularImage;

// Marches one cone from `origin` along unit `dir`; returns premultiplied radiance (rgb) and opacity (a).
// Light that leaves the grid unoccluded sees the environment, the constant ambient radiance (the background
// shows the same value, so the two agree).
vec4 traceCone(vec3 origin, vec3 dir, float tanHalfAngle) {
    const vec3 gridOrigin = frame.voxelOrigin.xyz;
    const float v0 = frame.voxelOrigin.w;
    const float gridSize = frame.voxelParams.x * v0;
    const float maxMip = max(frame.voxelParams.y - 1.0, 0.0);
    vec4 acc = vec4(0.0);
    // Start one voxel out: the cone's first footprint then lies beside the surface, not on it.
    float t = v0;
    // Bounded even for a mirror cone (footprint v0): the grid diagonal is √3·N voxels, steps ≥ v0/2.
    const int maxSteps = int(4.0 * frame.voxelParams.x) + 8;
    for (int i = 0; i < maxSteps && acc.a < CONE_MAX_OPACITY; ++i) {
        const float d = coneDiameter(tanHalfAngle, t, v0);
        const vec3 uvw = (origin + dir * t - gridOrigin) / gridSize;
        // The axis leaves the grid: the grid is padded around the scene bounds, so nothing lies beyond. (No
        // margin that grows with d: wide cones would then never leave, and t would overflow.)
        if (any(lessThan(uvw, vec3(0.0))) || any(greaterThan(uvw, vec3(1.0)))) break;
        const float mip = min(coneMip(d, v0), maxMip);
        const vec4 s = textureLod(voxels, uvw, mip);
        const float dt = coneStep(d);
        // The sample averaged its opacity over voxels of side v0·2^mip (the footprint, up to the top mip).
        acc = coneComposite(acc, s, dt, v0 * exp2(mip));
        t += dt;
    }
    acc.rgb += (1.0 - saturate(acc.a)) * frame.ambient.rgb;
    return acc;
}

void main() {
    const ivec2 lowPixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(lowPixel, imageSize(diffuseImage)))) return;
    const int scale = max(int(frame.voxelParams.w), 1);
    const ivec2 size = ivec2(frame.imageSize.xy);
    const ivec2 pixel = min(lowPixel * scale, size - 1);

    const float depth = texelFetch(depthTexture, pixel, 0).r;
    if (isBackground(depth) || frame.voxelOrigin.w <= 0.0) {
        // Background (nothing to light) or no grid yet: no indirect light.
        imageStore(diffuseImage, lowPixel, vec4(0.0));
        imageStore(specularImage, lowPixel, vec4(0.0));
        return;
    }
    const vec2 uv = (vec2(pixel) + 0.5) * frame.imageSize.zw;
    const vec4 normalRoughness = texelFetch(normalRoughnessTexture, pixel, 0);
    const vec3 p = worldFromDepth(frame.invViewProj, uv, depth);
    const float nLength = length(normalRoughness.xyz);
    const vec3 n = nLength > 1e-6 ? normalRoughness.xyz / nLength : vec3(0.0, 1.0, 0.0);
    const vec3 v = normalize(frame.cameraPosition.xyz - p);
    const float v0 = frame.voxelOrigin.w;
    const vec3 origin = p + n * (v0 * CONE_START_OFFSET);

    vec3 diffuse = vec3(0.0);
    for (int i = 0; i < DIFFUSE_CONE_COUNT; ++i)
        diffuse += diffuseConeWeight(i) * traceCone(origin, diffuseConeDirection(n, i), DIFFUSE_CONE_TAN_HALF).rgb;

    // Back-facing shading normals (normal maps, grazing views): reflect about n with n·v clamped to ≥ 0 so the
    // cone never points into the surface.
    const float NoV = max(dot(n, v), 0.0);
    vec3 r = 2.0 * NoV * n - v;
    r = dot(r, r) > 1e-12 ? normalize(r) : n;
    const float alpha = alphaFromPerceptual(normalRoughness.w);
    const vec3 specular = traceCone(origin, r, specularConeTanHalf(alpha)).rgb;

    imageStore(diffuseImage, lowPixel, vec4(diffuse, 1.0));
    imageStore(specularImage, lowPixel, vec4(specular, 1.0));
}
