// What the demo window shows, composed after the renderers' frames in one submit of its own:
//   1. each side's picture into the display image: the renderer's LDR frame (a GPU blit), or a view made on
//      the CPU from the frame's buffers (app/cli/aux_output.h viewImage, uploaded); with the split view, the left
//      of the wipe from side A and the right from side B;
//   2. Dear ImGui (panel, timers) drawn over it, unless hidden;
//   3. the display image blitted into the swapchain image.
// The display image (not the swapchain image) holds the composed picture so that screenshots can read it back
// with or without the panel. Each step has a GPU timestamp scope (view, ui, blit): the panel's own cost.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "app/demo/window.h"
#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/image.h"
#include "vk/timer.h"

namespace vct {

// One side's picture: a GPU image of the display's size (the LDR frame), or RGBA8 pixels from the CPU.
struct DisplaySource {
    vk::Image* image = nullptr;
    const std::vector<uint8_t>* pixels = nullptr;
};

class DemoDisplay {
  public:
    // Sets up Dear ImGui (context, GLFW and Vulkan backends, font upload) for `window`. `framesInFlight` (1
    // or 2): frames submitted and not yet waited for, as for the renderers.
    DemoDisplay(const vk::Context& context, Window& window, uint32_t framesInFlight);
    ~DemoDisplay();
    DemoDisplay(const DemoDisplay&) = delete;
    DemoDisplay& operator=(const DemoDisplay&) = delete;

    // Starts an ImGui frame (input from GLFW); the caller then issues ImGui calls for this frame.
    void beginUi();
    // Composes, draws the UI when `ui` (ImGui::Render is called either way), blits to `target` and submits;
    // with one frame in flight it then waits for it. `b` and `wipe` (a fraction of the width) only when
    // `split`.
    void present(Swapchain& swapchain, const SwapchainImage& target, const DisplaySource& a,
                 const DisplaySource& b, bool split, float wipe, bool ui);
    // The last presented picture, RGBA8 at the display's size.
    std::vector<uint8_t> read();
    // Waits for the frames in flight and takes their timings.
    void finishFrames();
    uint32_t width() const { return display_.width(); }
    uint32_t height() const { return display_.height(); }
    const vk::GpuTimer& timer() const { return timer_; }

  private:
    void resize(uint32_t width, uint32_t height);
    void compose(VkCommandBuffer cmd, const DisplaySource& a, const DisplaySource& b, bool split, float wipe);
    vk::Image& sourceImage(VkCommandBuffer cmd, const DisplaySource& source, int side);

    const vk::Context& context_;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkRenderPass renderPass_ = VK_NULL_HANDLE;
    VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
    vk::Image display_;
    vk::Image uploads_[2];  // CPU-made views of side A and B
    vk::Buffer staging_[2];
    vk::GpuTimer timer_;
    struct FrameSlot {
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        VkFence fence = VK_NULL_HANDLE;
        bool pending = false;  // submitted, its fence not waited yet
    };
    void finishSlot(FrameSlot& slot);
    std::vector<FrameSlot> slots_;  // frame k uses slot k mod size
    uint32_t submitted_ = 0;
};

}  // namespace vct
