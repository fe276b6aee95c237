// Draws every mesh instance of the scene with a scene-drawing pipeline (shadow, gbuffer): binds the geometry,
// pushes per-draw descriptors (frame, instances, materials, the material's textures) and the draw's indices.
#pragma once

#include "render/pass.h"
#include "vk/pipeline.h"

namespace vct {

// The descriptor bindings every scene-drawing pipeline declares (see VCT_DRAW_BINDING_* in lib/shared.h).
std::vector<vk::Binding> sceneDrawBindings();

void drawScene(const FrameContext& frame, const vk::Pipeline& pipeline);

}  // namespace vct
