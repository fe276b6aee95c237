// Punctual lights (KHR_lights_punctual) as the direct and inject passes evaluate them. GLSL only (it has an
// out parameter), unlike the shared math headers.
#ifndef VCT_LIGHTS_GLSL
#define VCT_LIGHTS_GLSL

// Radiance arriving from light `light` at p, and the direction towards it (KHR_lights_punctual).
vec3 incidentLight(GpuLight light, vec3 p, out vec3 towardsLight) {
    const int type = int(light.directionType.w);
    if (type == VCT_LIGHT_DIRECTIONAL) {
        towardsLight = -light.directionType.xyz;
        return light.colorIntensity.rgb;
    }
    const vec3 delta = light.positionRange.xyz - p;
    const float distance2 = max(dot(delta, delta), 1e-8);
    towardsLight = delta * inversesqrt(distance2);
    float attenuation = 1.0 / distance2;
    const float range = light.positionRange.w;
    if (range > 0.0) {
        // glTF's recommended smooth window to zero at the range.
        const float ratio = sqrt(distance2) / range;
        attenuation *= clamp(1.0 - ratio * ratio * ratio * ratio, 0.0, 1.0);
    }
    if (type == VCT_LIGHT_SPOT) {
        const float cd = dot(light.directionType.xyz, -towardsLight);
        const float spot = clamp(cd * light.spotScaleOffset.x + light.spotScaleOffset.y, 0.0, 1.0);
        attenuation *= spot * spot;
    }
    return light.colorIntensity.rgb * attenuation;
}

#endif
