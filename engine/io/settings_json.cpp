#include "io/settings_json.h"

namespace vct {

nlohmann::json settingsJson(const RenderSettings& s) {
    return {{"gi", s.gi},
            {"voxels", s.voxelResolution},
            {"trace_scale", s.traceScale},
            {"weights", weightsName(s.weights)},
            {"beta", s.beta},
            {"kappa", s.kappa},
            {"sigma_n", s.sigmaN},
            {"diffuse_sharpness", s.diffuseSharpness},
            {"gamma", s.gamma},
            {"temporal", s.temporal},
            {"adaptive", s.adaptive},
            {"tau", resampleThreshold(s)},
            {"toksvig", s.toksvig},
            {"specular_aa", s.specularAA},
            {"anisotropy", s.anisotropy},
            {"exposure", s.exposure}};
}

}  // namespace vct
