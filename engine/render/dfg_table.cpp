#include "render/dfg_table.h"

#include "render/shader_math.h"

namespace vct {

std::vector<glm::vec2> makeDfgTable(uint32_t size, uint32_t sampleCount) {
    std::vector<glm::vec2> table(size_t(size) * size);
    for (uint32_t row = 0; row < size; ++row) {
        // Texel centres: the edges (n·v = 0, a perfect mirror) are reached by clamp-to-edge filtering.
        float perceptualRoughness = (float(row) + 0.5f) / float(size);
        float alpha = glsl::alphaFromPerceptual(perceptualRoughness);
        for (uint32_t col = 0; col < size; ++col) {
            float NoV = (float(col) + 0.5f) / float(size);
            table[size_t(row) * size + col] = glsl::integrateDFG(NoV, alpha, int(sampleCount));
        }
    }
    return table;
}

}  // namespace vct
