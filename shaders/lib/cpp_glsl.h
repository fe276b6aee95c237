// Lets the math headers in shaders/lib (*.glsl) compile as C++ too, so the CPU tests exercise the very code
// the GPU runs. GLM supplies GLSL's types and built-ins; engine/render/shader_math.h includes the shared
// headers inside namespace vct::glsl after this one.
//
// Rules for a shared header: no #version, an include guard, pure functions (no in/out/inout parameters),
// float literals with an `f` suffix (GLSL 4.x accepts it; C++ needs it for GLM's templates).
#pragma once
#include <glm/glm.hpp>
#include <glm/gtc/packing.hpp>  // packHalf2x16 / unpackHalf2x16
