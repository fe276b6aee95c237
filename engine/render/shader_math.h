// The shaders' shared math (shaders/lib/*.glsl), compiled as C++ for the CPU tests and CPU-side tables.
#pragma once

#include "lib/cpp_glsl.h"

namespace vct::glsl {
using namespace glm;
#include "lib/brdf.glsl"
#include "lib/color.glsl"
#include "lib/cone.glsl"
#include "lib/indirect_pack.glsl"
#include "lib/toksvig.glsl"
#include "lib/upsample_weights.glsl"
}  // namespace vct::glsl
