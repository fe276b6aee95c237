#include "render/voxel_grid.h"

#include <algorithm>
#include <bit>
#include <string>

#include "core/error.h"
#include "lib/shared.h"
#include "vk/check.h"

namespace vct {

uint32_t chooseVoxelResolution(const vk::Context& context, const RenderSettings& settings) {
    uint32_t n = settings.voxelResolution;
    if (n == 0) {
        // A software rasterizer pays for every voxel on the CPU each frame (resolve, inject, mips), so it
        // gets 64³ (8× fewer voxels); GPUs get 128³, enough for room-sized scenes at 1–2 voxels per 10 cm.
        n = context.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? 64u : 128u;
    }
    if (n < 32 || n > 256 || !std::has_single_bit(n))
        throw UsageError("voxel resolution " + std::to_string(n) + " must be a power of two in 32..256");
    return n;
}

Aabb voxelSceneBounds(const Scene& scene) {
    Aabb box = scene.bounds();
    float duration = 0.0f;
    for (const Animation& animation : scene.animations) duration = std::max(duration, animation.duration);
    if (duration <= 0.0f) return box;
    // Sampled, not exact: moving geometry may poke out between samples by a little (dropped voxels there).
    constexpr int kSamples = 32;
    for (int s = 1; s <= kSamples; ++s)
        for (const Instance& instance : scene.instances(duration * float(s) / float(kSamples)))
            if (instance.moving)
                for (uint32_t p : scene.meshes[size_t(instance.mesh)].primitives)
                    if (p < scene.primitives.size()) box.extend(scene.primitives[p].bounds.transformed(instance.world));
    return box;
}

VoxelGrid::VoxelGrid(const vk::Context& context, const Scene& scene, uint32_t resolution)
    : context_(context), resolution_(resolution) {
    mipCount_ = uint32_t(std::countr_zero(resolution)) + 1;
    Aabb bounds = voxelSceneBounds(scene);
    if (bounds.empty()) bounds = Aabb{glm::vec3(-1.0f), glm::vec3(1.0f)};
    originSize_ = glsl::voxelGridFit(bounds.min, bounds.max, float(resolution));

    auto volume = [&](VkFormat format, uint32_t mips, VkImageUsageFlags usage) {
        vk::ImageDesc desc;
        desc.width = desc.height = desc.depth = resolution;
        desc.mipLevels = mips;
        desc.format = format;
        desc.usage = usage;
        return vk::Image(context, desc);
    };
    // TRANSFER_SRC so that later tools (OpenVDB export, tests) can read them back.
    constexpr VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    radiance_ = volume(VK_FORMAT_R16G16B16A16_SFLOAT, mipCount_, storage | VK_IMAGE_USAGE_SAMPLED_BIT);
    albedo_ = volume(VK_FORMAT_R8G8B8A8_UNORM, 1, storage);
    normal_ = volume(VK_FORMAT_R16G16B16A16_SFLOAT, 1, storage);
    emission_ = volume(VK_FORMAT_R16G16B16A16_SFLOAT, 1, storage);

    const VkDeviceSize accumBytes = VkDeviceSize(resolution) * resolution * resolution * VCT_VOXEL_ACCUM_STRIDE * 4;
    constexpr VkBufferUsageFlags accumUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    staticAccum_ = vk::Buffer(context, accumBytes, accumUsage, vk::MemoryUsage::DeviceLocal);
    // Only scenes with animated instances pay for the second accumulator.
    bool moving = false;
    for (const Instance& instance : scene.instances(0.0f)) moving |= instance.moving;
    if (moving) dynamicAccum_ = vk::Buffer(context, accumBytes, accumUsage, vk::MemoryUsage::DeviceLocal);

    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = VK_FILTER_LINEAR;
    info.minFilter = VK_FILTER_LINEAR;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    info.borderColor = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;  // outside the grid: empty, no light
    info.minLod = 0.0f;
    info.maxLod = float(mipCount_ - 1);
    VK_CHECK(vkCreateSampler(context.device(), &info, nullptr, &sampler_));
}

VoxelGrid::~VoxelGrid() { vkDestroySampler(context_.device(), sampler_, nullptr); }

}  // namespace vct
