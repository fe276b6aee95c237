// Draws every mesh instance of the scene with a scene-drawing pipeline (shadow, gbuffer): binds the geometry,
// pushes per-draw descriptors (frame, instances, materials, the material's textures) and the draw's indices.
#pragma once

#include "render/pass.h"
#include "vk/pipeline.h"

namespace vct {

// The resource rows every scene-drawing pass's table starts with: the frame, the scene's instances and
// materials, and the material's five textures (written per draw by drawScene). Binding numbers: those of
// shaders/gbuffer.vert, gbuffer.frag and shadow.vert.
std::vector<ResourceRow> sceneDrawRows();

// `resources`: the pass's table, which starts with sceneDrawRows(). Skinned and morphed instances are drawn
// from the deformed vertex buffer (render/gpu_deform.h), with DrawPushConstants.indices.z = 1; where
// `previousVerticesBinding` is a binding, last frame's deformed vertices are written there (gbuffer's motion).
void drawScene(const FrameContext& frame, const vk::Pipeline& pipeline, const ResourceTable& resources,
               uint32_t previousVerticesBinding = kNoBinding);

}  // namespace vct
