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

// Which of the scene's primitives a pass draws: all (shadow), all but those with an alphaMode BLEND material
// (gbuffer: they are drawn by the blend pass), or only those.
enum class DrawSet : uint8_t { All, Opaque, Blended };

// Whether the primitives of `material` are in `set`.
bool inDrawSet(const Material& material, DrawSet set);

// One draw: an instance and the index of a primitive in its mesh.
struct DrawItem {
    uint32_t instance;
    uint32_t meshPrimitive;
};

// The set's draws in the scene's order (instances, then their mesh's primitives).
std::vector<DrawItem> sceneDrawItems(const GpuScene& scene, DrawSet set);

// The pipelines of a pass that shades materials (gbuffer, blend), by the texture slots they sample
// (VCT_SPEC_TEXTURED_SLOTS, lib/surface.glsl). On a CPU device one per set of textured slots among the drawn
// materials, so that a missing texture is not filtered (lavapipe runs both sides of a branch; benchmarks/README.md
// round 8); on a GPU one with every slot, whose shader skips the material's missing textures by its flags.
class MaterialPipelines {
  public:
    // `desc.specialization` is extended with VCT_SPEC_TEXTURED_SLOTS and VCT_SPEC_TEXTURE_LOD0 (`textureLod0`,
    // RenderSettings::textureLod0); pipelines only for the materials in `set`.
    MaterialPipelines() = default;
    MaterialPipelines(const vk::Context& context, vk::Pipeline::GraphicsDesc desc, const Scene& scene,
                      DrawSet set, bool textureLod0);
    const vk::Pipeline& forMaterial(uint32_t material) const;
    size_t count() const { return pipelines_.size(); }

  private:
    std::vector<vk::Pipeline> pipelines_;
    std::vector<uint32_t> pipelineOfMaterial_;  // index into pipelines_, per scene material
};

// `resources`: the pass's table, which starts with sceneDrawRows(). Draws `items` in their order. Skinned and
// morphed instances are drawn from the deformed vertex buffer (render/gpu_deform.h), with
// DrawPushConstants.indices.z = 1; where `previousVerticesBinding` is a binding, last frame's deformed vertices
// are written there (gbuffer's motion).
void drawItems(const FrameContext& frame, const vk::Pipeline& pipeline, const ResourceTable& resources,
               const std::vector<DrawItem>& items, uint32_t previousVerticesBinding = kNoBinding);
// The same, each draw with its material's pipeline.
void drawItems(const FrameContext& frame, const MaterialPipelines& pipelines, const ResourceTable& resources,
               const std::vector<DrawItem>& items, uint32_t previousVerticesBinding = kNoBinding);

// Begins dynamic rendering over the whole `extent` into `colors` (in order) and `depth`, and sets the viewport and
// scissor (dynamic state of every scene-drawing pipeline) to that extent.
void beginSceneRendering(VkCommandBuffer cmd, VkExtent2D extent,
                         const std::vector<VkRenderingAttachmentInfo>& colors,
                         const VkRenderingAttachmentInfo& depth);

// drawItems of the set's draws in the scene's order.
void drawScene(const FrameContext& frame, const vk::Pipeline& pipeline, const ResourceTable& resources,
               uint32_t previousVerticesBinding = kNoBinding, DrawSet set = DrawSet::All);
void drawScene(const FrameContext& frame, const MaterialPipelines& pipelines, const ResourceTable& resources,
               uint32_t previousVerticesBinding = kNoBinding, DrawSet set = DrawSet::All);

}  // namespace vct
