#version 460
#extension GL_GOOGLE_include_directive : require
// direct: one thread per pixel; sums every punctual light (the main one shadowed), emission and, with GI off, the
// environment's light; the background is the environment.
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/brdf.glsl"
#include "lib/gbuffer_read.glsl"
#include "lib/lights.glsl"
#include "lib/cone.glsl"
#include "lib/shadow_pcf.glsl"

layout(local_size_x = VCT_TILE_SIZE, local_size_y = VCT_TILE_SIZE) in;

// Resources: bound by engine/passes/direct_pass.cpp (its resource table gives these binding numbers and is checked
// against them when the pipeline is made).
layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) readonly buffer Lights { GpuLight lights[]; };
layout(set = 0, binding = 2) uniform sampler2D depthTexture;
layout(set = 0, binding = 3) uniform sampler2D normalRoughnessTexture;
layout(set = 0, binding = 4) uniform sampler2D baseColorMetallicTexture;
layout(set = 0, binding = 5) uniform sampler2D emissiveOcclusionTexture;
layout(set = 0, binding = 6) uniform sampler2DShadow shadowMap;
layout(set = 0, binding = 7, rgba16f) uniform writeonly image2D outputImage;
layout(set = 0, binding = 8) uniform sampler2D environmentMap;  // lib/environment_sample.glsl

#include "lib/environment_sample.glsl"

// 3x3 PCF on the main light's shadow map, as four bilinear compare taps (lib/shadow_pcf.glsl); the position is
// pushed along the normal by a texel or so, which removes acne on surfaces at grazing light angles without
// detaching shadows.
float shadowVisibility(vec3 worldPosition, vec3 normal) {
    const vec3 offsetPosition = worldPosition + normal * frame.lighting.shadowNormalOffset * 1.5;
    const vec4 clip = frame.lightViewProj * vec4(offsetPosition, 1.0);
    if (clip.w <= 0.0) return 1.0;
    const vec3 ndc = clip.xyz / clip.w;
    const vec2 uv = ndc.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || ndc.z >= 1.0) return 1.0;
    const float texelSize = frame.lighting.shadowTexelSize;
    const PcfTaps taps = pcfTaps(uv / texelSize - 0.5);
    const vec2 first = (taps.first + 0.5) * texelSize, last = (taps.last + 0.5) * texelSize;
    const float visible =
        taps.firstWeight.x * taps.firstWeight.y * texture(shadowMap, vec3(first, ndc.z)) +
        taps.lastWeight.x * taps.firstWeight.y * texture(shadowMap, vec3(last.x, first.y, ndc.z)) +
        taps.firstWeight.x * taps.lastWeight.y * texture(shadowMap, vec3(first.x, last.y, ndc.z)) +
        taps.lastWeight.x * taps.lastWeight.y * texture(shadowMap, vec3(last, ndc.z));
    return visible / 9.0;
}

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    const ivec2 size = ivec2(frame.imageSize);
    if (any(greaterThanEqual(pixel, size))) return;

    const vec2 uv = (vec2(pixel) + 0.5) * frame.texelSize;
    const float depth = texelFetch(depthTexture, pixel, 0).r;
    if (isBackground(depth)) {
        const vec3 farPoint = worldFromDepth(frame.invViewProj, uv, 1.0);
        imageStore(outputImage, pixel,
                   vec4(environmentRadiance(normalize(farPoint - frame.cameraPosition)), 1.0));
        return;
    }
    const vec4 normalRoughness = texelFetch(normalRoughnessTexture, pixel, 0);
    const vec4 baseColorMetallic = texelFetch(baseColorMetallicTexture, pixel, 0);
    const vec4 emissiveOcclusion = texelFetch(emissiveOcclusionTexture, pixel, 0);
    const vec3 p = worldFromDepth(frame.invViewProj, uv, depth);
    const vec3 n = gbufferNormal(normalRoughness);  // never NaN: a zero-length normal reads as +y
    const vec3 v = viewDirection(frame.cameraPosition - p, n);

    vec3 radiance = emissiveOcclusion.rgb;
    const int lightCount = int(frame.lighting.lightCount);
    const int shadowLight = frame.lighting.shadowLight;
    for (int i = 0; i < lightCount; ++i) {
        const IncidentLight light = incidentLight(lights[i], p);
        vec3 reflected = light.radiance * evalBrdfCosine(n, v, light.towardsLight, baseColorMetallic.rgb,
                                                         baseColorMetallic.a, normalRoughness.w);
        if (i == shadowLight && any(greaterThan(reflected, vec3(0.0)))) reflected *= shadowVisibility(p, n);
        radiance += reflected;
    }
    // The environment, only with GI off (with GI on, composite adds the cone-traced indirect light instead),
    // unoccluded but for the material's occlusion: its cosine-weighted mean radiance (what the six diffuse
    // cones read of an open sky) × the diffuse albedo, plus what the specular cone would read × F0. A uniform
    // environment L gives L·(albedo + F0), the constant ambient term this replaced.
    if ((frame.flags & VCT_FLAG_GI) == 0u) {
        const vec3 albedo = diffuseAlbedo(baseColorMetallic.rgb, baseColorMetallic.a);
        const vec3 f0 = f0FromMetallic(baseColorMetallic.rgb, baseColorMetallic.a);
        const float alpha = alphaFromPerceptual(normalRoughness.w);
        const vec3 specular = environmentCone(specularConeDirection(n, v), specularConeTanHalf(alpha));
        radiance += (environmentDiffuse(n) * albedo + specular * f0) * emissiveOcclusion.a;
    }
    imageStore(outputImage, pixel, vec4(radiance, 1.0));
}
