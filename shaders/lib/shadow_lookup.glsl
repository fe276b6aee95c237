// The main light's shadow at a surface point: 3×3 PCF on its shadow map (lib/shadow_pcf.glsl's four bilinear
// compare taps). Shared by direct.comp (opaque pixels) and blend.frag (blended fragments). GLSL only.
// Expects before inclusion: `frame` (FrameUniforms), `shadowMap` (sampler2DShadow), lib/shadow_pcf.
#ifndef VCT_SHADOW_LOOKUP_GLSL
#define VCT_SHADOW_LOOKUP_GLSL

// The position is pushed along the normal by a texel or so, which removes acne on surfaces at grazing light
// angles without detaching shadows.
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

#endif  // VCT_SHADOW_LOOKUP_GLSL
