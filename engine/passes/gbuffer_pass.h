// gbuffer: full-resolution depth, shading normal (normal-mapped) + roughness, base colour + metallic,
// emission + occlusion, and motion vectors (camera and moving objects). When only instances moved under a camera
// that stood still, only the rectangle where they were and are is redrawn (docs/design.md §5.8).
#pragma once

#include <cstring>
#include <map>
#include <optional>
#include <vector>

#include "render/moved_rect.h"
#include "render/pass.h"
#include "render/scene_draw.h"
#include "vk/pipeline.h"

namespace vct {

class GBufferPass : public Pass {
  public:
    // `vertexColors`: whether any primitive of the scene has COLOR_0 (VCT_SPEC_VERTEX_COLORS). One pipeline per
    // set of textured slots of the scene's materials on CPU devices (MaterialPipelines); `textureLod0`:
    // RenderSettings::textureLod0.
    GBufferPass(const vk::Context& context, const Scene& scene, bool vertexColors, bool textureLod0);
    const char* name() const override { return "gbuffer"; }
    PassReuse reuse() const override { return PassReuse::WhileViewUnchanged; }
    void execute(const FrameContext& frame) override;
    // A frame that skipped the pass (scene and camera unchanged): nothing redrawn.
    void skipped() override { lastRect_ = TexelRect{}; }

    // The pixels the last run redrew: nullopt when it drew the whole frame (tests, timings.json).
    const std::optional<TexelRect>& lastRect() const { return lastRect_; }

  private:
    // What a run drew with: the frame uniforms the G-buffer's shaders read (compared bytewise), and what moved in
    // its scene update.
    struct Inputs {
        glm::mat4 viewProj, prevViewProj;
        ViewInputs view;
        bool operator==(const Inputs& other) const { return std::memcmp(this, &other, sizeof(Inputs)) == 0; }
    };
    struct Run {
        Inputs inputs;
        bool onlyInstancesMoved;
        Aabb movedBounds;
    };
    vk::Pipeline::GraphicsDesc pipelineDesc(bool vertexColors) const;
    Inputs inputsOf(const FrameContext& frame) const;
    // The pixels this run must redraw, or nullopt for the whole frame (docs/design.md §5.8).
    std::optional<TexelRect> updateRect(const FrameContext& frame,
                                        const std::vector<const vk::Image*>& targets, const Run& run) const;

    ResourceTable resources_;
    MaterialPipelines pipelines_;
    // The runs so far, the last kKeptRuns of them kept; each attachment's image remembers the run that drew it.
    std::vector<Run> runs_;
    uint64_t runCount_ = 0;
    std::map<VkImage, uint64_t> drawnBy_;
    std::optional<TexelRect> lastRect_;
};

}  // namespace vct
