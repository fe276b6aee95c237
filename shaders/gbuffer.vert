#version 460
#extension GL_GOOGLE_include_directive : require
// gbuffer: world-space attributes, and the current and previous clip positions for motion vectors.
#include "lib/shared.h"

// Resources: bound by engine/passes/../render/scene_draw.cpp (its resource table gives these binding numbers and is checked
// against them when the pipeline is made).
layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) readonly buffer Instances { GpuInstance instances[]; };
layout(push_constant) uniform Push { DrawPushConstants draw; };
// Last frame's deformed vertices (Vertex layout as floats), for skinned and morphed instances (draw.indices.z
// = 1): their motion starts where the skin pass put them a frame ago (engine/passes/skin_pass.h).
layout(set = 0, binding = 8) readonly buffer PreviousVertices { float previousVertexData[]; };

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inTangent;
layout(location = 4) in vec4 inColor;  // COLOR_0 (white without one; used where draw.indices.w = 1)

layout(location = 0) out vec3 outNormal;
layout(location = 1) out vec4 outTangent;
layout(location = 2) out vec2 outUv;
layout(location = 3) out vec4 outClip;
layout(location = 4) out vec4 outPrevClip;
layout(location = 5) out vec3 outWorld;
layout(location = 6) out vec4 outColor;
layout(constant_id = VCT_SPEC_VERTEX_COLORS) const bool VERTEX_COLORS = true;  // any COLOR_0 in the scene

void main() {
    const GpuInstance instance = instances[draw.indices.x];
    const vec4 world = instance.world * vec4(inPosition, 1.0);
    outNormal = mat3(instance.normalMatrix) * inNormal;
    outTangent = vec4(mat3(instance.world) * inTangent.xyz, inTangent.w);
    outUv = inUv;
    outColor = VERTEX_COLORS ? inColor : vec4(1.0);
    outWorld = world.xyz;
    outClip = frame.viewProj * world;
    vec3 prevPosition = inPosition;
    if (draw.indices.z != 0u) {
        const uint v = uint(gl_VertexIndex) * VCT_FLOATS_PER_VERTEX;
        prevPosition = vec3(previousVertexData[v], previousVertexData[v + 1], previousVertexData[v + 2]);
    }
    outPrevClip = frame.prevViewProj * (instance.prevWorld * vec4(prevPosition, 1.0));
    gl_Position = outClip;
}
