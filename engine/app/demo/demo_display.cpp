#include "app/demo/demo_display.h"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <algorithm>
#include <cstring>

#include "vk/check.h"

namespace vct {

namespace {

constexpr VkFormat kDisplayFormat = VK_FORMAT_R8G8B8A8_UNORM;

void checkImGuiVk(VkResult result) {
    if (result != VK_SUCCESS) vk::throwVkError(result, "Dear ImGui Vulkan backend");
}

}  // namespace

DemoDisplay::DemoDisplay(const vk::Context& context, Window& window, uint32_t framesInFlight)
    : context_(context),
      timer_(context, 8, std::clamp(framesInFlight, 1u, 2u)),
      slots_(std::clamp(framesInFlight, 1u, 2u)) {
    const VkDevice device = context.device();
    // ImGui's font texture needs one combined-image-sampler set; a little room for more.
    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 8}};
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    poolInfo.maxSets = 8;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = sizes;
    VK_CHECK(vkCreateDescriptorPool(device, &poolInfo, nullptr, &pool_));

    // ImGui 1.86 draws inside a render pass. It loads what the view step composed and leaves the image as a
    // colour attachment; vk::Image's tracked access makes the barriers on both sides.
    VkAttachmentDescription attachment{};
    attachment.format = kDisplayFormat;
    attachment.samples = VK_SAMPLE_COUNT_1_BIT;
    attachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachment.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachment.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachment.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    attachment.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    VkAttachmentReference colorRef{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &colorRef;
    VkSubpassDependency dependency{};
    dependency.srcSubpass = VK_SUBPASS_EXTERNAL;
    dependency.dstSubpass = 0;
    dependency.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependency.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependency.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependency.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    VkRenderPassCreateInfo rpInfo{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rpInfo.attachmentCount = 1;
    rpInfo.pAttachments = &attachment;
    rpInfo.subpassCount = 1;
    rpInfo.pSubpasses = &subpass;
    rpInfo.dependencyCount = 1;
    rpInfo.pDependencies = &dependency;
    VK_CHECK(vkCreateRenderPass(device, &rpInfo, nullptr, &renderPass_));

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // no imgui.ini left in the working directory
    ImGui::StyleColorsDark();
    ImGui::GetStyle().Alpha = 0.92f;
    ImGui_ImplGlfw_InitForVulkan(window.handle(), true);
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = context.instance();
    info.PhysicalDevice = context.physicalDevice();
    info.Device = device;
    info.QueueFamily = context.queueFamily();
    info.Queue = context.queue();
    info.DescriptorPool = pool_;
    info.MinImageCount = 2;
    // ImGui's vertex buffers, one per frame in rotation: the one frame k writes was last drawn by frame k − 2,
    // whose fence present() has waited for (with one frame in flight every frame is waited for anyway).
    info.ImageCount = 2;
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = checkImGuiVk;
    ImGui_ImplVulkan_Init(&info, renderPass_);
    context.submitAndWait([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
    ImGui_ImplVulkan_DestroyFontUploadObjects();

    for (FrameSlot& slot : slots_) {
        VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        alloc.commandPool = context.commandPool();
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        VK_CHECK(vkAllocateCommandBuffers(device, &alloc, &slot.cmd));
        VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        VK_CHECK(vkCreateFence(device, &fenceInfo, nullptr, &slot.fence));
    }
}

DemoDisplay::~DemoDisplay() {
    const VkDevice device = context_.device();
    vkDeviceWaitIdle(device);
    ImGui_ImplVulkan_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    for (FrameSlot& slot : slots_) {
        vkDestroyFence(device, slot.fence, nullptr);
        vkFreeCommandBuffers(device, context_.commandPool(), 1, &slot.cmd);
    }
    vkDestroyFramebuffer(device, framebuffer_, nullptr);
    vkDestroyRenderPass(device, renderPass_, nullptr);
    vkDestroyDescriptorPool(device, pool_, nullptr);
}

void DemoDisplay::resize(uint32_t width, uint32_t height) {
    if (display_.valid() && display_.width() == width && display_.height() == height) return;
    VK_CHECK(vkDeviceWaitIdle(context_.device()));
    vkDestroyFramebuffer(context_.device(), framebuffer_, nullptr);
    display_ = vk::Image(context_, {width, height, 1, 1, kDisplayFormat,
                                    VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                        VK_IMAGE_USAGE_TRANSFER_DST_BIT});
    VkImageView view = display_.view();
    VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    info.renderPass = renderPass_;
    info.attachmentCount = 1;
    info.pAttachments = &view;
    info.width = width;
    info.height = height;
    info.layers = 1;
    VK_CHECK(vkCreateFramebuffer(context_.device(), &info, nullptr, &framebuffer_));
}

void DemoDisplay::beginUi() {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

vk::Image& DemoDisplay::sourceImage(VkCommandBuffer cmd, const DisplaySource& source, int side) {
    if (source.image) return *source.image;
    // A CPU-made view: through a host-visible staging buffer into an image the blit can read.
    const uint32_t w = display_.width(), h = display_.height();
    const VkDeviceSize bytes = VkDeviceSize(w) * h * 4;
    if (source.pixels->size() != bytes) throw Error("demo view: picture size does not match the window");
    vk::Image& upload = uploads_[side];
    if (!upload.valid() || upload.width() != w || upload.height() != h)
        upload = vk::Image(context_, {w, h, 1, 1, kDisplayFormat,
                                      VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                          VK_IMAGE_USAGE_SAMPLED_BIT});
    if (!staging_[side].mapped() || staging_[side].size() != bytes)
        staging_[side] =
            vk::Buffer(context_, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, vk::MemoryUsage::HostVisible);
    std::memcpy(staging_[side].mapped(), source.pixels->data(), bytes);
    upload.use(cmd, vk::ImageAccess::TransferDst);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {w, h, 1};
    vkCmdCopyBufferToImage(cmd, staging_[side].handle(), upload.handle(),
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    return upload;
}

void DemoDisplay::compose(VkCommandBuffer cmd, const DisplaySource& a, const DisplaySource& b, bool split,
                          float wipe) {
    const int32_t w = int32_t(display_.width()), h = int32_t(display_.height());
    // Side A covers [0, x), side B [x, w): each column comes from one side only, at the same position.
    const int32_t x = split ? std::clamp(int32_t(wipe * float(w) + 0.5f), 0, w) : w;
    struct Part {
        const DisplaySource* source;
        int side;
        int32_t x0, x1;
    };
    const Part parts[] = {{&a, 0, 0, x}, {&b, 1, x, w}};
    vk::Image* images[2] = {nullptr, nullptr};
    for (const Part& part : parts)
        if (part.x1 > part.x0) images[part.side] = &sourceImage(cmd, *part.source, part.side);
    display_.use(cmd, vk::ImageAccess::TransferDst);
    for (const Part& part : parts) {
        if (!images[part.side]) continue;
        vk::Image& src = *images[part.side];
        src.use(cmd, vk::ImageAccess::TransferSrc);
        // Sources have the display's size, except for the frame after a resize (then scaled).
        const float sx = float(src.width()) / float(w);
        VkImageBlit region{};
        region.srcSubresource = region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.srcOffsets[0] = {int32_t(float(part.x0) * sx), 0, 0};
        region.srcOffsets[1] = {int32_t(float(part.x1) * sx), int32_t(src.height()), 1};
        region.dstOffsets[0] = {part.x0, 0, 0};
        region.dstOffsets[1] = {part.x1, h, 1};
        vkCmdBlitImage(cmd, src.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, display_.handle(),
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region, VK_FILTER_NEAREST);
    }
}

void DemoDisplay::finishSlot(FrameSlot& slot) {
    if (!slot.pending) return;
    VK_CHECK(vkWaitForFences(context_.device(), 1, &slot.fence, VK_TRUE, UINT64_MAX));
    slot.pending = false;
    timer_.collect(false);
}

void DemoDisplay::finishFrames() {
    for (size_t k = 0; k < slots_.size(); ++k) finishSlot(slots_[(submitted_ + k) % slots_.size()]);
}

void DemoDisplay::present(Swapchain& swapchain, const SwapchainImage& target, const DisplaySource& a,
                          const DisplaySource& b, bool split, float wipe, bool ui) {
    ImGui::Render();  // ends the ImGui frame even when nothing is drawn
    const VkExtent2D extent = swapchain.extent();
    resize(extent.width, extent.height);
    FrameSlot& slot = slots_[submitted_ % slots_.size()];
    finishSlot(slot);
    // A picture made on the CPU goes through one staging buffer per side, which the frame before may still
    // be copying from.
    if (a.pixels || b.pixels) finishFrames();
    const VkCommandBuffer cmd = slot.cmd;

    VK_CHECK(vkResetCommandBuffer(cmd, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    timer_.beginFrame(cmd);
    timer_.beginScope(cmd, "view");
    compose(cmd, a, b, split, wipe);
    timer_.endScope(cmd);
    if (ui) {
        timer_.beginScope(cmd, "ui");
        display_.use(cmd, vk::ImageAccess::ColorAttachment);
        VkRenderPassBeginInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
        rp.renderPass = renderPass_;
        rp.framebuffer = framebuffer_;
        rp.renderArea.extent = {display_.width(), display_.height()};
        vkCmdBeginRenderPass(cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
        ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
        vkCmdEndRenderPass(cmd);
        timer_.endScope(cmd);
    } else {
        timer_.skipScope("ui");
    }
    timer_.beginScope(cmd, "blit");
    swapchain.recordBlit(cmd, display_, target);
    timer_.endScope(cmd);
    VK_CHECK(vkEndCommandBuffer(cmd));

    const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
    VkSubmitInfo info{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    info.commandBufferCount = 1;
    info.pCommandBuffers = &cmd;
    info.waitSemaphoreCount = 1;
    info.pWaitSemaphores = &target.available;
    info.pWaitDstStageMask = &waitStage;
    info.signalSemaphoreCount = 1;
    info.pSignalSemaphores = &target.rendered;
    VK_CHECK(vkResetFences(context_.device(), 1, &slot.fence));
    VK_CHECK(vkQueueSubmit(context_.queue(), 1, &info, slot.fence));
    slot.pending = true;
    ++submitted_;
    if (slots_.size() == 1) finishSlot(slot);
}

std::vector<uint8_t> DemoDisplay::read() {
    const VkDeviceSize bytes = VkDeviceSize(display_.width()) * display_.height() * 4;
    vk::Buffer staging(context_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUsage::HostVisible);
    context_.submitAndWait([&](VkCommandBuffer cmd) {
        display_.use(cmd, vk::ImageAccess::TransferSrc);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {display_.width(), display_.height(), 1};
        vkCmdCopyImageToBuffer(cmd, display_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.handle(),
                               1, &region);
    });
    const auto* src = static_cast<const uint8_t*>(staging.mapped());
    return std::vector<uint8_t>(src, src + bytes);
}

}  // namespace vct
