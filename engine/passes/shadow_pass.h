// shadow: light-space depth of the main (shadow-casting) light, for the direct and inject passes. When only instances
// moved since the map was drawn, it redraws only the texels their move can change (render/moved_rect.h).
#pragma once

#include <glm/glm.hpp>
#include <optional>

#include "render/moved_rect.h"
#include "render/pass.h"
#include "vk/pipeline.h"

namespace vct {

class ShadowPass : public Pass {
  public:
    explicit ShadowPass(const vk::Context& context);
    const char* name() const override { return "shadow"; }
    PassReuse reuse() const override { return PassReuse::WhileSceneUnchanged; }
    void execute(const FrameContext& frame) override;
    // A frame that skipped the pass (nothing changed): the map is kept whole.
    void skipped() override { lastRect_ = TexelRect{}; }
    // What the last frame redrew: nullopt the whole map, else a rectangle (empty: nothing, also where instances
    // moved outside the map). The direct pass keeps the pixels whose shadow lookup reads none of it.
    const std::optional<TexelRect>& lastRect() const { return lastRect_; }

  private:
    // The texels this frame must redraw, or nullopt for the whole map: a rectangle only when the map holds a whole
    // drawing of the scene as it was before instances moved (the same image, light, projection and biases).
    std::optional<TexelRect> updateRect(const FrameContext& frame, const vk::Image& shadowMap) const;

    ResourceTable resources_;
    vk::Pipeline pipeline_;
    // What the map holds: drawn into `drawnImage_` with this light, projection and biases (none yet: null).
    VkImage drawnImage_ = VK_NULL_HANDLE;
    int drawnLight_ = -1;
    glm::mat4 drawnLightViewProj_{0.0f};
    glm::vec2 drawnBiases_{0.0f};
    std::optional<TexelRect> lastRect_;
};

}  // namespace vct
