#include "render/scene_lights.h"

#include <algorithm>
#include <cmath>

namespace vct {

std::vector<gpu::GpuLight> sceneLights(const Scene& scene, const std::vector<glm::mat4>& world,
                                       const std::vector<glm::quat>& worldRotations) {
    std::vector<gpu::GpuLight> lights;
    for (size_t n = 0; n < scene.nodes.size(); ++n) {
        if (scene.nodes[n].light < 0) continue;
        const Light& light = scene.lights[size_t(scene.nodes[n].light)];
        gpu::GpuLight g{};
        const glm::vec3 position = glm::vec3(world[n][3]);
        // Lights shine along local -Z, scale ignored (a zero scale keeps the composed rotation's direction).
        const glm::vec3 direction = -worldAxes(world[n], worldRotations[n])[2];
        int type = light.type == LightType::Directional ? VCT_LIGHT_DIRECTIONAL
                   : light.type == LightType::Point     ? VCT_LIGHT_POINT
                                                        : VCT_LIGHT_SPOT;
        g.positionRange = glm::vec4(position, light.range);
        g.directionType = glm::vec4(direction, float(type));
        g.colorIntensity = glm::vec4(light.color * light.intensity, 0.0f);
        // KHR_lights_punctual angular attenuation, precomputed as scale and offset on cos(angle).
        const float cosOuter = std::cos(light.outerConeAngle);
        const float cosInner = std::cos(light.innerConeAngle);
        const float scale = 1.0f / std::max(0.001f, cosInner - cosOuter);
        g.spotScaleOffset = glm::vec4(scale, -cosOuter * scale, 0.0f, 0.0f);
        lights.push_back(g);
    }
    return lights;
}

}  // namespace vct
