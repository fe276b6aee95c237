#include "app/demo/window.h"

#define GLFW_INCLUDE_VULKAN  // declares glfwCreateWindowSurface
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include "core/error.h"
#include "vk/check.h"

namespace vct {

namespace {

// GLFW reports failures through a callback; keep the last one for the exception message.
std::string gGlfwError;

void onGlfwError(int, const char* description) {
    gGlfwError = description ? description : "unknown GLFW error";
}

bool envSet(const char* name) {
    const char* value = std::getenv(name);
    return value && *value;
}

Error windowError() {
    if (!envSet("DISPLAY") && !envSet("WAYLAND_DISPLAY"))
        return Error("cannot open a window: no display (run under xvfb-run)");
    return Error("cannot open a window: " + (gGlfwError.empty() ? std::string("GLFW failed") : gGlfwError));
}

}  // namespace

Window::Window(const std::string& title, uint32_t width, uint32_t height) {
    glfwSetErrorCallback(onGlfwError);
    if (!glfwInit()) throw windowError();
    if (!glfwVulkanSupported()) {
        glfwTerminate();
        throw Error("cannot open a window: GLFW found no Vulkan loader");
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);  // Vulkan presents; no OpenGL context
    window_ = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
    if (!window_) {
        Error error = windowError();
        glfwTerminate();
        throw error;
    }
    glfwSetWindowUserPointer(window_, this);
    glfwSetFramebufferSizeCallback(window_, onFramebufferSize);
    glfwSetDropCallback(window_, onDrop);
}

Window::~Window() {
    glfwDestroyWindow(window_);
    glfwTerminate();
}

void Window::onFramebufferSize(GLFWwindow* window, int, int) {
    static_cast<Window*>(glfwGetWindowUserPointer(window))->resized_ = true;
}

std::vector<const char*> Window::requiredInstanceExtensions() const {
    uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    if (!names) throw Error("cannot open a window: GLFW found no Vulkan surface extensions");
    return std::vector<const char*>(names, names + count);
}

VkExtent2D Window::framebufferSize() const {
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    return {uint32_t(std::max(width, 0)), uint32_t(std::max(height, 0))};
}

void Window::onDrop(GLFWwindow* window, int count, const char** paths) {
    if (count > 0 && paths[0]) static_cast<Window*>(glfwGetWindowUserPointer(window))->dropped_ = paths[0];
}

std::string Window::takeDroppedFile() {
    return std::exchange(dropped_, std::string());
}

bool Window::takeResized() {
    return std::exchange(resized_, false);
}

Swapchain::Swapchain(const vk::Context& context, Window& window) : context_(context), window_(window) {
    VK_CHECK(glfwCreateWindowSurface(context.instance(), window.handle(), nullptr, &surface_));
    VkBool32 canPresent = VK_FALSE;
    VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(context.physicalDevice(), context.queueFamily(), surface_,
                                                  &canPresent));
    if (!canPresent) {
        vkDestroySurfaceKHR(context.instance(), surface_, nullptr);
        throw Error(context.deviceName() +
                    " cannot present to this window from its queue (try another --device)");
    }
    format_ = chooseFormat();
    VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    for (VkSemaphore& s : available_) VK_CHECK(vkCreateSemaphore(context.device(), &info, nullptr, &s));
}

Swapchain::~Swapchain() {
    // Nothing may still use the semaphores or images; the queue's presents finish with the device idle.
    const VkDevice device = context_.device();
    vkDeviceWaitIdle(device);
    for (VkSemaphore s : rendered_) vkDestroySemaphore(device, s, nullptr);
    for (VkSemaphore s : available_) vkDestroySemaphore(device, s, nullptr);
    vkDestroySwapchainKHR(device, swapchain_, nullptr);
    vkDestroySurfaceKHR(context_.instance(), surface_, nullptr);
}

VkSurfaceFormatKHR Swapchain::chooseFormat() const {
    uint32_t count = 0;
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(context_.physicalDevice(), surface_, &count, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(count);
    VK_CHECK(
        vkGetPhysicalDeviceSurfaceFormatsKHR(context_.physicalDevice(), surface_, &count, formats.data()));
    auto blittable = [&](VkFormat format) {
        VkFormatProperties props;
        vkGetPhysicalDeviceFormatProperties(context_.physicalDevice(), format, &props);
        return (props.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_DST_BIT) != 0;
    };
    // The frame is already sRGB-encoded, so a UNORM image shows it as is; an _SRGB one would encode it twice.
    for (VkFormat wanted : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_B8G8R8A8_SRGB,
                            VK_FORMAT_R8G8B8A8_SRGB}) {
        for (const VkSurfaceFormatKHR& f : formats) {
            if (f.format != wanted || f.colorSpace != VK_COLOR_SPACE_SRGB_NONLINEAR_KHR ||
                !blittable(f.format))
                continue;
            if (wanted == VK_FORMAT_B8G8R8A8_SRGB || wanted == VK_FORMAT_R8G8B8A8_SRGB)
                std::printf(
                    "note: the window offers only sRGB swapchain formats; the image will look too bright\n");
            return f;
        }
    }
    throw Error(context_.deviceName() + ": no 8-bit RGBA/BGRA swapchain format that can be blitted to");
}

bool Swapchain::recreate() {
    VkSurfaceCapabilitiesKHR caps;
    VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(context_.physicalDevice(), surface_, &caps));
    VkExtent2D extent = caps.currentExtent;
    if (extent.width == UINT32_MAX) {  // the surface takes its size from the swapchain: use the window's
        const VkExtent2D size = window_.framebufferSize();
        extent.width = std::clamp(size.width, caps.minImageExtent.width, caps.maxImageExtent.width);
        extent.height = std::clamp(size.height, caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    const VkExtent2D framebuffer = window_.framebufferSize();
    if (extent.width == 0 || extent.height == 0 || framebuffer.width == 0 || framebuffer.height == 0)
        return false;
    if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
        throw Error(context_.deviceName() + ": swapchain images cannot be transfer destinations here");

    uint32_t imageCount = caps.minImageCount + 1;
    if (caps.maxImageCount > 0) imageCount = std::min(imageCount, caps.maxImageCount);
    VkCompositeAlphaFlagBitsKHR alpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    if (!(caps.supportedCompositeAlpha & alpha))  // the lowest supported mode; every surface has one
        alpha = VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);

    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = surface_;
    info.minImageCount = imageCount;
    info.imageFormat = format_.format;
    info.imageColorSpace = format_.colorSpace;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    info.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = alpha;
    info.presentMode =
        VK_PRESENT_MODE_FIFO_KHR;  // the one mode every driver has; paces the loop to the display
    info.clipped = VK_TRUE;
    info.oldSwapchain = swapchain_;

    const VkDevice device = context_.device();
    VK_CHECK(vkDeviceWaitIdle(device));  // the old images may still be read by a blit
    VkSwapchainKHR created = VK_NULL_HANDLE;
    VK_CHECK(vkCreateSwapchainKHR(device, &info, nullptr, &created));
    vkDestroySwapchainKHR(device, swapchain_, nullptr);
    swapchain_ = created;
    extent_ = extent;

    uint32_t count = 0;
    VK_CHECK(vkGetSwapchainImagesKHR(device, swapchain_, &count, nullptr));
    images_.resize(count);
    VK_CHECK(vkGetSwapchainImagesKHR(device, swapchain_, &count, images_.data()));
    VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    while (rendered_.size() < count) {
        VK_CHECK(vkCreateSemaphore(device, &semaphoreInfo, nullptr, &rendered_.emplace_back()));
    }
    stale_ = false;
    return true;
}

bool Swapchain::acquire(SwapchainImage& out) {
    const VkSemaphore available = available_[acquires_ % available_.size()];
    const VkResult result = vkAcquireNextImageKHR(context_.device(), swapchain_, UINT64_MAX, available,
                                                  VK_NULL_HANDLE, &out.index);
    if (result == VK_ERROR_OUT_OF_DATE_KHR) {
        stale_ = true;
        return false;
    }
    // Suboptimal still delivers an image (and signals the semaphore): show it, then recreate.
    if (result == VK_SUBOPTIMAL_KHR)
        stale_ = true;
    else
        VK_CHECK(result);
    out.image = images_[out.index];
    out.available = available;
    ++acquires_;  // only an acquire that signals moves on: an out-of-date one left the semaphore unsignalled
    out.rendered = rendered_[out.index];
    return true;
}

void Swapchain::present(const SwapchainImage& image) {
    VkPresentInfoKHR info{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    info.waitSemaphoreCount = 1;
    info.pWaitSemaphores = &image.rendered;
    info.swapchainCount = 1;
    info.pSwapchains = &swapchain_;
    info.pImageIndices = &image.index;
    const VkResult result = vkQueuePresentKHR(context_.queue(), &info);
    if (result == VK_ERROR_OUT_OF_DATE_KHR || result == VK_SUBOPTIMAL_KHR)
        stale_ = true;
    else
        VK_CHECK(result);
}

void Swapchain::recordBlit(VkCommandBuffer cmd, vk::Image& source, const SwapchainImage& target) const {
    source.use(cmd, vk::ImageAccess::TransferSrc);
    // The acquire semaphore is waited at the transfer stage, so the layout change is ordered after it.
    VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    barrier.srcStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    barrier.dstStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    barrier.dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    barrier.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;  // the whole image is overwritten
    barrier.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = target.image;
    barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.imageMemoryBarrierCount = 1;
    dependency.pImageMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dependency);

    VkImageBlit region{};
    region.srcSubresource = region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.srcOffsets[1] = {int32_t(source.width()), int32_t(source.height()), 1};
    region.dstOffsets[1] = {int32_t(extent_.width), int32_t(extent_.height), 1};
    // A blit (not a copy) because it converts RGBA to the swapchain's BGRA; the sizes match, so NEAREST is
    // exact.
    vkCmdBlitImage(cmd, source.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target.image,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region, VK_FILTER_NEAREST);

    // The submit's semaphore signal covers all prior work, so the present needs no further stages here.
    barrier.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    barrier.dstStageMask = VK_PIPELINE_STAGE_2_NONE;
    barrier.dstAccessMask = VK_ACCESS_2_NONE;
    barrier.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    barrier.newLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    vkCmdPipelineBarrier2(cmd, &dependency);
}

}  // namespace vct
