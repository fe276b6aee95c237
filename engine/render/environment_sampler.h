// Importance sampling of an environment map (docs/design.md §9.2): directions drawn with a pdf proportional
// to the luminance of the level-0 texel they fall in, uniform in solid angle within the texel (PBRT's
// piecewise-constant 2D distribution, Pharr et al. 2016 §13.6.7, with the sin θ folded into the texel's
// solid angle). The path-traced reference combines it with BSDF sampling by the balance heuristic.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "render/environment.h"

namespace vct {

class EnvironmentSampler {
  public:
    explicit EnvironmentSampler(const EnvironmentMap& map);

    struct Sample {
        glm::vec3 direction{0.0f};
        glm::vec3 radiance{0.0f};
        float pdf = 0.0f;  // per unit solid angle; 0 when the map is black (no sample)
    };
    // u uniform in [0, 1)².
    Sample sample(glm::vec2 u) const;
    // The pdf of `dir` under sample(): luminance(texel) / Σ luminance·solid angle.
    float pdf(glm::vec3 dir) const;

  private:
    const EnvironmentMap& map_;
    double total_ = 0.0;             // Σ luminance · solid angle over level 0
    std::vector<double> rowCdf_;     // height + 1 entries, rowCdf_[0] = 0, last = 1
    std::vector<double> columnCdf_;  // per row, width + 1 entries
};

}  // namespace vct
