// The demo's window (GLFW, no client API) and the swapchain that shows the renderer's frames in it.
// The renderer draws into its own images; each frame is blitted into a swapchain image, so the swapchain
// only needs TRANSFER_DST usage and the renderer never depends on the window.
#pragma once

#include <vulkan/vulkan.h>

#include <array>
#include <string>
#include <vector>

#include "vk/context.h"
#include "vk/image.h"

struct GLFWwindow;

namespace vct {

// Owns GLFW itself (glfwInit/glfwTerminate) and one window. No display → vct::Error.
class Window {
  public:
    Window(const std::string& title, uint32_t width, uint32_t height);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    GLFWwindow* handle() const { return window_; }
    // The instance extensions Vulkan needs to present here (the strings live as long as GLFW does).
    std::vector<const char*> requiredInstanceExtensions() const;
    VkExtent2D framebufferSize() const;
    // True once after each framebuffer resize.
    bool takeResized();
    // The first file dropped on the window since the last call (empty: none).
    std::string takeDroppedFile();

  private:
    static void onFramebufferSize(GLFWwindow* window, int width, int height);
    static void onDrop(GLFWwindow* window, int count, const char** paths);
    GLFWwindow* window_ = nullptr;
    bool resized_ = false;
    std::string dropped_;
};

// One acquired swapchain image and the semaphores its frame waits on and signals.
struct SwapchainImage {
    uint32_t index = 0;
    VkImage image = VK_NULL_HANDLE;
    VkSemaphore available = VK_NULL_HANDLE;  // signalled by the acquire; the blit waits on it
    VkSemaphore rendered = VK_NULL_HANDLE;   // signalled by the frame's submit; the present waits on it
};

class Swapchain {
  public:
    // Creates the surface and checks the context's queue can present to it; the swapchain itself comes
    // from recreate().
    Swapchain(const vk::Context& context, Window& window);
    ~Swapchain();
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;

    // (Re)creates the swapchain at the window's current size. False while the window is minimised (0×0);
    // the old swapchain, if any, is kept until a size is available.
    bool recreate();
    // True when recreate() must run before the next frame (none yet, out of date, suboptimal).
    bool stale() const { return stale_; }
    // False when the swapchain turned out of date (stale() is then true and nothing was acquired).
    bool acquire(SwapchainImage& out);
    void present(const SwapchainImage& image);
    // Records the copy of `source` (RGBA8) into the image and its transition to PRESENT_SRC.
    void recordBlit(VkCommandBuffer cmd, vk::Image& source, const SwapchainImage& target) const;

    VkExtent2D extent() const { return extent_; }

  private:
    VkSurfaceFormatKHR chooseFormat() const;

    const vk::Context& context_;
    Window& window_;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkSurfaceFormatKHR format_{};
    VkExtent2D extent_{};
    std::vector<VkImage> images_;
    // Acquire semaphores in rotation. The demo's frame k waits on its acquire's semaphore; the next acquire
    // that reuses it comes after the display has waited for frame k's fence, which with up to two frames in
    // flight is at frame k + 2's present: three are enough (one alone must not be signalled again while a
    // submitted wait on it may still be pending).
    std::array<VkSemaphore, 3> available_{};
    uint32_t acquires_ = 0;
    // One per image index: a present may still be waiting on the previous one when the next frame signals,
    // and these survive recreation because the old swapchain's presents may still hold them.
    std::vector<VkSemaphore> rendered_;
    bool stale_ = true;
};

}  // namespace vct
