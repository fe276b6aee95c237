// The built-in `hall`: a large interior for the speed-at-every-size measurements (issue 19).
#pragma once

#include "scene/scene.h"

namespace vct {

// A 40 m × 10 m × 16 m hall (see builtinSceneDescription("hall")).
Scene hallScene();

}  // namespace vct
