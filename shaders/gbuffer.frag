#version 460
#extension GL_GOOGLE_include_directive : require
// gbuffer: material evaluation (glTF metallic-roughness) and normal mapping.
#include "lib/shared.h"
#include "lib/brdf.glsl"
#include "lib/toksvig.glsl"

// Resources: bound by engine/passes/../render/scene_draw.cpp (its resource table gives these binding numbers and is checked
// against them when the pipeline is made).
layout(set = 0, binding = 2) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 0, binding = 3) uniform sampler2D baseColorTexture;
layout(set = 0, binding = 4) uniform sampler2D metallicRoughnessTexture;
layout(set = 0, binding = 5) uniform sampler2D normalTexture;
layout(set = 0, binding = 6) uniform sampler2D emissiveTexture;
layout(set = 0, binding = 7) uniform sampler2D occlusionTexture;
layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(push_constant) uniform Push { DrawPushConstants draw; };

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec4 inTangent;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inClip;
layout(location = 4) in vec4 inPrevClip;
layout(location = 5) in vec3 inWorld;
layout(location = 6) in vec4 inColor;
layout(constant_id = VCT_SPEC_VERTEX_COLORS) const bool VERTEX_COLORS = true;  // any COLOR_0 in the scene

layout(location = 0) out vec4 outNormalRoughness;
layout(location = 1) out vec4 outBaseColorMetallic;
layout(location = 2) out vec4 outEmissiveOcclusion;
layout(location = 3) out vec2 outMotion;

#include "lib/surface.glsl"

void main() {
    const vec3 faceNormal =
        surfaceFaceNormal(inWorld);  // before the discard below, while the whole quad runs
    const GpuMaterial material = materials[draw.indices.y];
    const vec4 baseColor = surfaceBaseColor(material, inUv, inColor, VERTEX_COLORS && draw.indices.w != 0u);
    if (material.flags.x == VCT_ALPHA_MASK && baseColor.a < material.metallicRoughnessCutoffAo.z) discard;
    const Surface surface = evaluateSurface(material, faceNormal, inNormal, inTangent, inUv, gl_FrontFacing);

    outNormalRoughness = vec4(surface.shadingNormal, surface.roughness);
    outBaseColorMetallic = vec4(clamp(baseColor.rgb, 0.0, 1.0), surface.metallic);
    outEmissiveOcclusion = vec4(surface.emissive, surface.occlusion);
    // Motion in UV units (y down, like the image): uv_previous = uv_current - motion.
    const vec2 ndc = inClip.xy / inClip.w;
    const vec2 prevNdc = inPrevClip.xy / inPrevClip.w;
    outMotion = (ndc - prevNdc) * 0.5;
}
