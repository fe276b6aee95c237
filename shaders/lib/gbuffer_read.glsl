// Reading the G-buffer back in screen-space compute passes: pixel → UV → world position.
#ifndef VCT_GBUFFER_READ_GLSL
#define VCT_GBUFFER_READ_GLSL

// World position of a pixel centre from its depth (Vulkan depth range [0, 1]).
vec3 worldFromDepth(mat4 invViewProj, vec2 uv, float depth) {
    const vec4 clip = vec4(uv * 2.0 - 1.0, depth, 1.0);
    const vec4 world = invViewProj * clip;
    return world.xyz / world.w;
}

bool isBackground(float depth) { return depth >= 1.0; }

#endif
