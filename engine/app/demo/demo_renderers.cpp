#include "app/demo/demo_renderers.h"

#include <chrono>
#include <cstdio>

#include "core/error.h"
#include "render/setting_table.h"

namespace vct {

RenderSettings withViewNeeds(RenderSettings settings, AuxView view) {
    settings.writeWeightSum = view == AuxView::Resample || view == AuxView::Weights;
    return settings;
}

DemoRenderers::DemoRenderers(const vk::Context& context, std::unique_ptr<Scene> scene,
                             const RenderSettings& settings, uint32_t framesInFlight)
    : context_(context), framesInFlight_(framesInFlight), scene_(std::move(scene)), appliedA_(settings) {
    a_ = make(*scene_, settings);
}

DemoRenderers::~DemoRenderers() {
    // Renderers before the scene they reference.
    b_.reset();
    a_.reset();
}

std::unique_ptr<Renderer> DemoRenderers::make(const Scene& scene, const RenderSettings& settings) {
    const auto start = std::chrono::steady_clock::now();
    auto renderer = std::make_unique<Renderer>(context_, scene, settings, framesInFlight_);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    char buffer[128];
    std::snprintf(buffer, sizeof(buffer), "new renderer in %.0f ms (trace scale %u, %u^3 voxels)", ms,
                  renderer->settings().traceScale, renderer->settings().voxelResolution);
    lastRebuild_ = buffer;
    return renderer;
}

void DemoRenderers::bring(std::unique_ptr<Renderer>& current, const RenderSettings& wanted,
                          const char* side) {
    if (current) {
        // What the change needs, by the setting table (render/setting_table.h).
        const SettingApply needs = settingsChange(current->settings(), wanted);
        if (needs == SettingApply::Live) {
            current->applyLive(wanted);
            return;
        }
        // Only the size changed: new targets, same passes and voxel grid.
        if (needs == SettingApply::Resize) {
            current->resize(wanted.width, wanted.height);
            current->applyLive(wanted);
            return;
        }
    }
    try {
        std::unique_ptr<Renderer> made = make(*scene_, wanted);
        current = std::move(made);  // the old renderer waits for the device in its destructor
    } catch (const Error& e) {
        throw Error(std::string(side) + ": " + e.what());
    }
}

void DemoRenderers::sync(DemoControls& controls) {
    try {
        bring(a_, withViewNeeds(controls.settings, controls.view), "renderer A");
        appliedA_ = controls.settings;
    } catch (const Error&) {
        const uint32_t w = controls.settings.width, h = controls.settings.height;
        controls.settings = appliedA_;
        controls.settings.width = w;
        controls.settings.height = h;
        throw;
    }
    if (!controls.rendersB()) {
        b_.reset();
        return;
    }
    try {
        bring(b_, withViewNeeds(controls.settingsB(), controls.view), "renderer B");
    } catch (const Error&) {
        controls.split = false;
        b_.reset();
        throw;
    }
}

void DemoRenderers::render(const FrameInput& input) {
    a_->render(input);
    if (b_) b_->render(input);
}

void DemoRenderers::finishFrames() {
    a_->finishFrames();
    if (b_) b_->finishFrames();
}

void DemoRenderers::replaceScene(std::unique_ptr<Scene> scene, const DemoControls& controls) {
    std::unique_ptr<Renderer> a = make(*scene, withViewNeeds(controls.settings, controls.view));
    std::unique_ptr<Renderer> b;
    if (controls.rendersB()) b = make(*scene, withViewNeeds(controls.settingsB(), controls.view));
    b_ = std::move(b);
    a_ = std::move(a);
    // After the renderers that referenced the old one are gone; a reference tracer still running on the old
    // scene holds its own share of it.
    scene_ = std::move(scene);
}

void DemoRenderers::rebuild(const DemoControls& controls) {
    std::unique_ptr<Renderer> a = make(*scene_, withViewNeeds(controls.settings, controls.view));
    std::unique_ptr<Renderer> b;
    if (controls.rendersB()) b = make(*scene_, withViewNeeds(controls.settingsB(), controls.view));
    b_ = std::move(b);
    a_ = std::move(a);
}

}  // namespace vct
