#version 460
#extension GL_GOOGLE_include_directive : require
// shadow: transforms the scene into the main light's clip space (depth only).
#include "lib/shared.h"

// Resources: bound by engine/passes/../render/scene_draw.cpp (its resource table gives these binding numbers and is checked
// against them when the pipeline is made).
layout(set = 0, binding = VCT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) readonly buffer Instances { GpuInstance instances[]; };
layout(push_constant) uniform Push { DrawPushConstants draw; };

layout(location = 0) in vec3 inPosition;

void main() {
    const GpuInstance instance = instances[draw.indices.x];
    gl_Position = frame.lightViewProj * (instance.world * vec4(inPosition, 1.0));
}
