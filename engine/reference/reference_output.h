// The reference directory `vct reference --out DIR` writes, in vct's own units so that it compares pixel for
// pixel with `vct render --aux`: final, direct, diffuse_indirect, specular_indirect, indirect (= final −
// direct) (EXR, linear HDR, RGBA float, A = 1) with the variance of each mean (`*_variance.exr`),
// surface_id.exr (R: the surface id of the primary hit at the pixel centre, −1 background), final.png
// (tone-mapped sRGB) and reference.json (settings, samples, seed, rays/s, wall time, the surface table with
// per-surface sums, noise).
#pragma once

#include <filesystem>
#include <string>

#include "reference/path_tracer.h"

namespace vct::reference {

struct ReferenceRunInfo {
    std::string scene;
    uint32_t frame = 0;
    float timeSeconds = 0.0f;
    std::string cameraPath;  // empty: the scene's camera
    float exposure = 1.0f;
};

// Writes every file into `dir` (which must exist) and returns their names.
std::vector<std::string> writeReferenceDirectory(const std::filesystem::path& dir, const PathTracer& tracer,
                                                 const ReferenceImages& images, const ReferenceRunInfo& info);

}  // namespace vct::reference
