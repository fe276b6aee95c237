#version 460
#extension GL_GOOGLE_include_directive : require
// gbuffer: material evaluation (glTF metallic-roughness) and normal mapping.
#include "lib/shared.h"

layout(set = 0, binding = VCT_DRAW_BINDING_MATERIALS) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 0, binding = VCT_DRAW_BINDING_BASE_COLOR) uniform sampler2D baseColorTexture;
layout(set = 0, binding = VCT_DRAW_BINDING_METALLIC_ROUGHNESS) uniform sampler2D metallicRoughnessTexture;
layout(set = 0, binding = VCT_DRAW_BINDING_NORMAL) uniform sampler2D normalTexture;
layout(set = 0, binding = VCT_DRAW_BINDING_EMISSIVE) uniform sampler2D emissiveTexture;
layout(set = 0, binding = VCT_DRAW_BINDING_OCCLUSION) uniform sampler2D occlusionTexture;
layout(push_constant) uniform Push { DrawPushConstants draw; };

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec4 inTangent;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inClip;
layout(location = 4) in vec4 inPrevClip;

layout(location = 0) out vec4 outNormalRoughness;
layout(location = 1) out vec4 outBaseColorMetallic;
layout(location = 2) out vec4 outEmissiveOcclusion;
layout(location = 3) out vec2 outMotion;

// Unit vector or, when v is degenerate (zero or not finite), the fallback.
vec3 safeNormalize(vec3 v, vec3 fallback) {
    const float len2 = dot(v, v);
    return (len2 > 1e-20 && !isinf(len2) && !isnan(len2)) ? v * inversesqrt(len2) : fallback;
}

void main() {
    const GpuMaterial material = materials[draw.indices.y];
    const vec4 baseColor = material.baseColorFactor * texture(baseColorTexture, inUv);
    if (material.flags.x == VCT_ALPHA_MASK && baseColor.a < material.metallicRoughnessCutoffAo.z) discard;

    // Geometric frame; back faces of double-sided surfaces see the flipped normal.
    vec3 normal = safeNormalize(inNormal, vec3(0.0, 0.0, 1.0));
    vec3 tangent = inTangent.xyz - normal * dot(normal, inTangent.xyz);
    tangent = safeNormalize(tangent, abs(normal.x) < 0.9 ? normalize(cross(normal, vec3(1, 0, 0)))
                                                         : normalize(cross(normal, vec3(0, 1, 0))));
    const float handedness = inTangent.w < 0.0 ? -1.0 : 1.0;
    if (!gl_FrontFacing) normal = -normal;
    const vec3 bitangent = cross(normal, tangent) * handedness;

    // Tangent-space normal (glTF: scaled in x, y). The texel's length is kept until here: mips of a normal
    // map average unit normals, and |N̄| < 1 tells how much they disagreed (Toksvig, next issue).
    const vec3 mapped = texture(normalTexture, inUv).xyz * 2.0 - 1.0;
    const vec3 scaled = vec3(mapped.xy * material.emissiveNormalScale.w, mapped.z);
    const vec3 shadingNormal = safeNormalize(tangent * scaled.x + bitangent * scaled.y + normal * scaled.z, normal);

    const vec4 mr = texture(metallicRoughnessTexture, inUv);
    const float metallic = clamp(material.metallicRoughnessCutoffAo.x * mr.b, 0.0, 1.0);
    const float roughness = clamp(material.metallicRoughnessCutoffAo.y * mr.g, 0.0, 1.0);
    const vec3 emissive = material.emissiveNormalScale.rgb * texture(emissiveTexture, inUv).rgb;
    const float occlusion = 1.0 + material.metallicRoughnessCutoffAo.w * (texture(occlusionTexture, inUv).r - 1.0);

    outNormalRoughness = vec4(shadingNormal, roughness);
    outBaseColorMetallic = vec4(clamp(baseColor.rgb, 0.0, 1.0), metallic);
    outEmissiveOcclusion = vec4(emissive, occlusion);
    // Motion in UV units (y down, like the image): uv_previous = uv_current - motion.
    const vec2 ndc = inClip.xy / inClip.w;
    const vec2 prevNdc = inPrevClip.xy / inPrevClip.w;
    outMotion = (ndc - prevNdc) * 0.5;
}
