// Reading the environment map on the GPU (lib/environment.glsl: layout and mip; docs/design.md §5.9).
// GLSL only. Expects before inclusion: `frame` (FrameUniforms), `environmentMap` (sampler2D: the map with its
// prefiltered mips, linear filtering, u repeated, v clamped), lib/constants, lib/cone. Declares
// `environmentCones`, the cones' layers (render/environment_cones.h: one slice a layer, the same filtering, w
// clamped), at binding VCT_BINDING_ENVIRONMENT_CONES.
#ifndef VCT_ENVIRONMENT_SAMPLE_GLSL
#define VCT_ENVIRONMENT_SAMPLE_GLSL

#include "lib/environment.glsl"

layout(set = 0, binding = VCT_BINDING_ENVIRONMENT_CONES) uniform sampler3D environmentCones;

// Radiance arriving from unit direction `dir`, averaged over a cone of half-angle atan(tanHalfAngle): the mean
// over the cap of that half-angle, between the two layers whose caps hold it (render/environment_cones.h; the
// map's own mips are boxes in azimuth and polar angle, a sector near the poles). render/environment_cones.cpp's
// sampleEnvironmentCone is the CPU twin.
vec3 environmentCone(vec3 dir, float tanHalfAngle) {
    const ivec3 size = textureSize(environmentCones, 0);
    const float layer = min(environmentMip(tanHalfAngle, float(size.x)), float(size.z - 1));
    const vec2 uv = equirectUv(dir, frame.lighting.environmentRotation);
    return textureLod(environmentCones, vec3(uv, (layer + 0.5) / float(size.z)), 0.0).rgb;
}

// Radiance seen along `dir` at full resolution (the background).
vec3 environmentRadiance(vec3 dir) {
    return textureLod(environmentMap, equirectUv(dir, frame.lighting.environmentRotation), 0.0).rgb;
}

// The cosine-weighted mean radiance over the hemisphere about unit n (irradiance / π): the six diffuse cones'
// weights (lib/cone.glsl), each reading the map at its aperture, the estimate the cone tracer makes of an open
// sky, so that GI off and GI on agree where nothing occludes.
vec3 environmentDiffuse(vec3 n) {
    vec3 sum = vec3(0.0);
    for (int i = 0; i < DIFFUSE_CONE_COUNT; ++i)
        sum += diffuseConeWeight(i) * environmentCone(diffuseConeDirection(n, i), DIFFUSE_CONE_TAN_HALF);
    return sum;
}

// The environment's light reflected by a surface with GI off (no occlusion but the material's): the
// cosine-weighted mean radiance (what the six diffuse cones read of an open sky) × the diffuse albedo, plus the
// mean over the specular lobe's equivalent cap (sgEquivalentCapTanHalf) × F0. A uniform environment L gives
// L·(albedo + F0). Expects lib/brdf.
vec3 environmentReflected(vec3 n, vec3 v, vec3 baseColor, float metallic, float perceptualRoughness) {
    const vec3 albedo = diffuseAlbedo(baseColor, metallic);
    const vec3 f0 = f0FromMetallic(baseColor, metallic);
    const float alpha = alphaFromPerceptual(perceptualRoughness);
    const vec3 specular =
        environmentCone(specularConeDirection(n, v),
                        sgEquivalentCapTanHalf(specularLobeInverseSharpness(alpha, dot(n, v)), 2.0));
    return environmentDiffuse(n) * albedo + specular * f0;
}

#endif  // VCT_ENVIRONMENT_SAMPLE_GLSL
