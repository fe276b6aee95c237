// The shaders' shared math (shaders/lib/*.glsl), compiled as C++ for the CPU tests, CPU-side tables and the
// path-traced reference.
#pragma once

#include "lib/cpp_glsl.h"
#include "lib/shared.h"

namespace vct::glsl {
using namespace glm;
using gpu::GpuLight;
#include "lib/brdf.glsl"
#include "lib/color.glsl"
#include "lib/cone.glsl"
#include "lib/environment.glsl"
#include "lib/indirect_pack.glsl"
#include "lib/lights.glsl"
#include "lib/toksvig.glsl"
#include "lib/upsample_weights.glsl"
#include "lib/voxel.glsl"
#include "lib/voxel_specular.glsl"
}  // namespace vct::glsl
