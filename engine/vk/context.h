// The Vulkan instance, the chosen physical device, the logical device and its one queue.
// Vulkan 1.3 core (dynamic rendering, synchronization2) plus VK_KHR_push_descriptor, which lavapipe and
// every desktop driver have. Validation (--validate) counts every message so the run can fail at the end.
#pragma once

#include <vulkan/vulkan.h>

#include <functional>
#include <string>
#include <vector>

namespace vct::vk {

struct ContextOptions {
    bool validation = false;
    std::string deviceSubstring;                  // choose the first device whose name contains it
    std::vector<const char*> instanceExtensions;  // e.g. what GLFW needs for a window surface
    bool swapchain = false;                       // enable VK_KHR_swapchain on the device
};

// Number of validation messages (warnings and errors) this process has seen, including those emitted while a
// Context was being destroyed.
uint32_t validationMessageCount();

class Context {
  public:
    explicit Context(const ContextOptions& options);
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queueFamily() const { return queueFamily_; }
    VkCommandPool commandPool() const { return commandPool_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    std::string deviceName() const { return properties_.deviceName; }
    uint32_t memoryType(uint32_t typeBits, VkMemoryPropertyFlags flags) const;

    // Records commands into a fresh command buffer, submits and waits (uploads, readbacks).
    void submitAndWait(const std::function<void(VkCommandBuffer)>& record) const;

    PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet = nullptr;

  private:
    static VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                        VkDebugUtilsMessageTypeFlagsEXT types,
                                                        const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                        void* user);
    void createInstance(const ContextOptions& options);
    void pickPhysicalDevice(const std::string& substring);
    void createDevice(const ContextOptions& options);

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memoryProperties_{};
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queueFamily_ = 0;
    VkCommandPool commandPool_ = VK_NULL_HANDLE;
};

}  // namespace vct::vk
