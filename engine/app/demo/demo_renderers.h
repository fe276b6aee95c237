// The demo's scene and its renderers: side A always, side B while the split view is on. Both render the same
// scene and frame input; B is a second, complete Renderer (its own targets, history and voxel grid), so the
// split view costs a second frame. With the split view's B source the path-traced reference
// (DemoControls::showsReference) there is no renderer B: app/demo/demo_reference.h traces it. Settings reach them
// through sync(): live where the Renderer allows it (next frame), else by a new Renderer made between frames,
// the old one kept if making it fails.
#pragma once

#include <memory>
#include <string>

#include "app/demo/demo_controls.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "vk/context.h"

namespace vct {

class DemoRenderers {
  public:
    // `framesInFlight` (1 or 2): what every renderer it makes is given (render/renderer.h).
    DemoRenderers(const vk::Context& context, std::unique_ptr<Scene> scene, const RenderSettings& settings,
                  uint32_t framesInFlight);
    ~DemoRenderers();

    // Brings A (and B when controls.rendersB()) to the controls' settings. When a new renderer cannot be made
    // (an Error), the controls are set back to what runs and the error is rethrown for the panel.
    void sync(DemoControls& controls);
    // Renders the frame on A and, with the split view, on B.
    void render(const FrameInput& input);
    // Both renderers' frames still in flight waited for (their timings taken).
    void finishFrames();
    // A new scene: renderers for it are made first; on failure the old scene and renderers keep running.
    void replaceScene(std::unique_ptr<Scene> scene, const DemoControls& controls);
    // New renderers (pipelines from the current shader directory: hot reload); the old ones kept on failure.
    void rebuild(const DemoControls& controls);

    Renderer& a() { return *a_; }
    Renderer* b() { return b_.get(); }
    const Scene& scene() const { return *scene_; }
    // The scene, shared with what must keep it alive beyond a replaceScene (the reference's tracer).
    std::shared_ptr<const Scene> sharedScene() const { return scene_; }
    // What the last new renderer was and how long making it took, for the panel.
    std::string lastRebuild() const { return lastRebuild_; }

  private:
    std::unique_ptr<Renderer> make(const Scene& scene, const RenderSettings& settings);
    // Live update, resize, or a new renderer; `current` is replaced only when a new one was made.
    void bring(std::unique_ptr<Renderer>& current, const RenderSettings& wanted, const char* side);

    const vk::Context& context_;
    uint32_t framesInFlight_;
    std::shared_ptr<const Scene> scene_;
    std::unique_ptr<Renderer> a_, b_;
    RenderSettings appliedA_;  // the controls' settings A last accepted (the fallback on failure)
    std::string lastRebuild_;
};

// The settings a view needs on top of the controls' (the sum of weights for the resample and weights views).
RenderSettings withViewNeeds(RenderSettings settings, AuxView view);

}  // namespace vct
