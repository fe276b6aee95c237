#version 460
#extension GL_GOOGLE_include_directive : require
// blend: one glTF alphaMode BLEND surface at its own fragments (docs/design.md §2.6), after the opaque frame.
// The material as the G-buffer evaluates it (lib/surface.glsl), lit as direct.comp and composite light an
// opaque pixel: every punctual light (the main one through its shadow map), emission, and the cone-traced
// indirect light traced here at full resolution (lib/cone_trace.glsl) or, with GI off, the environment's light.
// Written premultiplied by the surface's alpha, (L·a, a), and blended "over" what the farther blended surfaces
// left in the layer (blend_pass.cpp: ONE, ONE_MINUS_SRC_ALPHA).
#include "lib/shared.h"
#include "lib/constants.glsl"
#include "lib/brdf.glsl"
#include "lib/toksvig.glsl"
#include "lib/cone.glsl"
#include "lib/gbuffer_read.glsl"
#include "lib/lights.glsl"
#include "lib/shadow_pcf.glsl"

// Resources: bound by engine/passes/blend_pass.cpp (its resource table gives these binding numbers and is
// checked against them when the pipeline is made); 0–7 are the scene-drawing rows (render/scene_draw.cpp).
layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 2) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 0, binding = 3) uniform sampler2D baseColorTexture;
layout(set = 0, binding = 4) uniform sampler2D metallicRoughnessTexture;
layout(set = 0, binding = 5) uniform sampler2D normalTexture;
layout(set = 0, binding = 6) uniform sampler2D emissiveTexture;
layout(set = 0, binding = 7) uniform sampler2D occlusionTexture;
layout(set = 0, binding = 9) readonly buffer Lights { GpuLight lights[]; };
layout(set = 0, binding = 10) uniform sampler2DShadow shadowMap;
layout(set = 0, binding = 11)
    uniform sampler3D voxels;  // radiance (premultiplied rgb) + opacity, mips 1.. (lib/cone_trace.glsl)
layout(set = 0, binding = 12) uniform sampler2D environmentMap;  // lib/environment_sample.glsl
layout(set = 0, binding = 13) uniform sampler2D dfgTable;        // split-sum DFG, uv = (n·v, roughness)
layout(push_constant) uniform Push { DrawPushConstants draw; };

// gbuffer.vert's outputs.
layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec4 inTangent;
layout(location = 2) in vec2 inUv;
layout(location = 5) in vec3 inWorld;
layout(location = 6) in vec4 inColor;  // COLOR_0 (gbuffer.vert; used where draw.indices.w = 1)
layout(constant_id = VCT_SPEC_VERTEX_COLORS) const bool VERTEX_COLORS = true;  // any COLOR_0 in the scene

layout(location = 0) out vec4 outColor;  // premultiplied radiance, alpha

#include "lib/surface.glsl"
#include "lib/shadow_lookup.glsl"
#include "lib/cone_trace.glsl"

void main() {
    const vec3 faceNormal = surfaceFaceNormal(inWorld);
    const GpuMaterial material = materials[draw.indices.y];
    const vec4 baseColor = surfaceBaseColor(material, inUv, inColor, VERTEX_COLORS && draw.indices.w != 0u);
    const Surface surface = evaluateSurface(material, faceNormal, inNormal, inTangent, inUv, gl_FrontFacing);
    // The G-buffer stores the base colour clamped to [0, 1]; the same here.
    const vec3 color = clamp(baseColor.rgb, 0.0, 1.0);
    const float coverage = saturate(baseColor.a);
    // Nothing to draw where the surface is fully transparent (cut-out texels of foliage): no light, no cones.
    if (coverage <= 0.0) {
        outColor = vec4(0.0);
        return;
    }

    const vec3 p = inWorld;
    const vec3 n = surface.shadingNormal;
    const vec3 v = viewDirection(frame.cameraPosition - p, n);
    const float roughness = surface.roughness;
    // direct.comp's sum.
    vec3 radiance = surface.emissive;
    const int lightCount = int(frame.lighting.lightCount);
    const int shadowLight = frame.lighting.shadowLight;
    for (int i = 0; i < lightCount; ++i) {
        const IncidentLight light = incidentLight(lights[i], p);
        vec3 reflected =
            light.radiance * evalBrdfCosine(n, v, light.towardsLight, color, surface.metallic, roughness);
        if (i == shadowLight && any(greaterThan(reflected, vec3(0.0)))) reflected *= shadowVisibility(p, n);
        radiance += reflected;
    }
    if ((frame.flags & VCT_FLAG_GI) != 0u) {
        // composite's re-modulation of the demodulated cone-traced light, traced at this fragment.
        if (frame.voxels.voxelSize > 0.0) {
            // The fixed cone set: a blended fragment has no history to average jittered cones.
            const IndirectSample s = traceSurface(voxels, p, n, v, roughness, FIXED_CONE_SET);
            const float NoV = max(dot(n, v), MIN_N_DOT_V);
            const vec2 dfg = textureLod(dfgTable, vec2(NoV, saturate(roughness)), 0.0).rg;
            const vec3 albedo = diffuseAlbedo(color, surface.metallic);
            const vec3 f0 = f0FromMetallic(color, surface.metallic);
            radiance += albedo * s.diffuse * surface.occlusion + specularDfg(f0, dfg) * s.specular;
        }
    } else {
        radiance += environmentReflected(n, v, color, surface.metallic, roughness) * surface.occlusion;
    }
    outColor = vec4(radiance * coverage, coverage);
}
