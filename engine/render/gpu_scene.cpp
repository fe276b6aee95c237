#include "render/gpu_scene.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <string>

#include "render/scene_lights.h"
#include "vk/check.h"

namespace vct {

// The shaders that read vertices as floats (voxelize, skin, gbuffer.vert) step by these.
static_assert(sizeof(Vertex) == VCT_FLOATS_PER_VERTEX * sizeof(float));
static_assert(offsetof(Vertex, color) == VCT_VERTEX_COLOR_OFFSET * sizeof(float));

namespace {

VkSamplerAddressMode addressMode(TextureWrap wrap) {
    switch (wrap) {
        case TextureWrap::ClampToEdge:
            return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        case TextureWrap::MirroredRepeat:
            return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
        default:
            return VK_SAMPLER_ADDRESS_MODE_REPEAT;
    }
}

Texture solidTexture(TextureKind kind, uint8_t r, uint8_t g, uint8_t b, uint8_t a) {
    Texture texture;
    texture.kind = kind;
    texture.width = texture.height = 1;
    texture.mips = {{r, g, b, a}};
    return texture;
}

// Normals transform by the inverse transpose. A flattened instance (a zero scale on one axis, an animation
// to scale 0) has no inverse: its cofactor matrix, the inverse transpose times the determinant, still gives
// the normals' direction (the shaders normalise), where the inverse would give NaN.
glm::mat4 normalMatrix(const glm::mat4& world) {
    const glm::mat3 linear(world);
    const float det = glm::determinant(linear);
    if (det != 0.0f && std::isfinite(det)) {
        const glm::mat4 inverseTranspose = glm::transpose(glm::inverse(world));
        bool finite = true;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) finite = finite && std::isfinite(inverseTranspose[c][r]);
        if (finite) return inverseTranspose;
    }
    const glm::mat3 cofactor(glm::cross(linear[1], linear[2]), glm::cross(linear[2], linear[0]),
                             glm::cross(linear[0], linear[1]));
    return glm::mat4(cofactor);
}

}  // namespace

uint32_t chooseAnisotropy(const vk::Context& context, uint32_t requested) {
    uint32_t level = requested;
    if (level == kAnisotropyFromDevice)
        level = context.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? 0u : 8u;
    VkPhysicalDeviceFeatures features;
    vkGetPhysicalDeviceFeatures(context.physicalDevice(), &features);
    if (!features.samplerAnisotropy) return 0;
    // The limit is a float ≥ 16 where the feature exists; keep the largest power of two within it.
    const float limit = context.properties().limits.maxSamplerAnisotropy;
    while (level > 1 && float(level) > limit) level /= 2;
    return level < 2 ? 0 : level;
}

GpuScene::GpuScene(const vk::Context& context, const Scene& scene, uint32_t anisotropy,
                   uint32_t framesInFlight)
    : context_(context), scene_(scene), anisotropy_(anisotropy) {
    // The voxelize pass binds both whole as storage buffers.
    const VkDeviceSize maxRange = context.properties().limits.maxStorageBufferRange;
    for (auto [bytes, what] : {std::pair{VkDeviceSize(scene.vertices.size() * sizeof(Vertex)), "vertices"},
                               {VkDeviceSize(scene.indices.size() * sizeof(uint32_t)), "indices"}})
        if (bytes > maxRange)
            throw Error("scene '" + scene.name + "': its " + what + " take " + std::to_string(bytes) +
                        " bytes, more than the device's maxStorageBufferRange (" + std::to_string(maxRange) +
                        ")");
    vertices_ = vk::Buffer::withData(context, scene.vertices.data(), scene.vertices.size() * sizeof(Vertex),
                                     VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    indices_ = vk::Buffer::withData(context, scene.indices.data(), scene.indices.size() * sizeof(uint32_t),
                                    VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);

    std::vector<gpu::GpuMaterial> materials;
    for (const Material& m : scene.materials) {
        gpu::GpuMaterial g{};
        g.baseColorFactor = m.baseColorFactor;
        g.emissiveNormalScale = glm::vec4(m.emissiveFactor, m.normalScale);
        g.metallicRoughnessCutoffAo =
            glm::vec4(m.metallicFactor, m.roughnessFactor, m.alphaCutoff, m.occlusionStrength);
        // Mask keeps its cut-out; blend is drawn by the blend pass (docs/design.md §2.6).
        g.flags = glm::uvec4(m.alphaMode == AlphaMode::Mask    ? VCT_ALPHA_MASK
                             : m.alphaMode == AlphaMode::Blend ? VCT_ALPHA_BLEND
                                                               : VCT_ALPHA_OPAQUE,
                             texturedSlots(m), 0, 0);
        materials.push_back(g);
        hasEmission_ = hasEmission_ || emits(m);
        hasOcclusion_ = hasOcclusion_ || occludes(m);
    }
    materials_ = vk::Buffer::withData(context, materials.data(), materials.size() * sizeof(gpu::GpuMaterial),
                                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);

    instances_ = scene.instances(0.0f);
    for (const Instance& instance : instances_)
        for (uint32_t p : scene.meshes[size_t(instance.mesh)].primitives)
            hasBlended_ =
                hasBlended_ || scene.materials[scene.primitives[p].material].alphaMode == AlphaMode::Blend;
    deform_ = std::make_unique<GpuDeform>(context, scene, instances_, framesInFlight);
    bounds_ = scene.bounds();
    instanceBuffer_ = vk::Buffer(context, std::max<size_t>(1, instances_.size()) * sizeof(gpu::GpuInstance),
                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::HostVisible);
    size_t lightNodes = 0;
    for (const Node& node : scene.nodes) lightNodes += node.light >= 0 ? 1 : 0;
    lightBuffer_ = vk::Buffer(context, std::max<size_t>(1, lightNodes) * sizeof(gpu::GpuLight),
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::HostVisible);
    if (framesInFlight > 1) {
        spareInstanceBuffer_ = vk::Buffer(context, instanceBuffer_.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                          vk::MemoryUsage::HostVisible);
        spareLightBuffer_ = vk::Buffer(context, lightBuffer_.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                       vk::MemoryUsage::HostVisible);
    }
    uploadTextures();
    update(0.0f, true);
}

GpuScene::~GpuScene() = default;

VkSampler GpuScene::samplerFor(TextureWrap s, TextureWrap t) {
    auto key = std::make_pair(int(s), int(t));
    if (auto it = samplers_.find(key); it != samplers_.end()) return it->second.handle();
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = VK_FILTER_LINEAR;
    info.minFilter = VK_FILTER_LINEAR;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    info.addressModeU = addressMode(s);
    info.addressModeV = addressMode(t);
    info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    info.maxLod = VK_LOD_CLAMP_NONE;
    // chooseAnisotropy has checked the feature and the device's limit.
    info.anisotropyEnable = anisotropy_ >= 2 ? VK_TRUE : VK_FALSE;
    info.maxAnisotropy = anisotropy_ >= 2 ? float(anisotropy_) : 1.0f;
    // Owned (RAII): a texture the device refuses, after some samplers exist, must not leak them.
    return (samplers_[key] = vk::Sampler(context_, info)).handle();
}

vk::Image GpuScene::uploadTexture(const Texture& texture) {
    // A texture larger than the device allows starts at the first mip that fits (the chain is made at load).
    const uint32_t maxSize = context_.properties().limits.maxImageDimension2D;
    uint32_t first = 0;
    while (first + 1 < texture.mips.size() && (std::max(1u, texture.width >> first) > maxSize ||
                                               std::max(1u, texture.height >> first) > maxSize))
        ++first;
    const uint32_t width = std::max(1u, texture.width >> first),
                   height = std::max(1u, texture.height >> first);
    if (width > maxSize || height > maxSize)
        throw Error("texture '" + texture.name + "' (" + std::to_string(texture.width) + "x" +
                    std::to_string(texture.height) + ") exceeds the device's maxImageDimension2D " +
                    std::to_string(maxSize));
    if (first > 0)
        std::printf(
            "note: texture '%s' (%ux%u) exceeds the device's maxImageDimension2D %u: using its mip %u "
            "(%ux%u)\n",
            texture.name.c_str(), texture.width, texture.height, maxSize, first, width, height);
    const uint32_t levels = uint32_t(texture.mips.size()) - first;
    vk::ImageDesc desc;
    desc.width = width;
    desc.height = height;
    desc.mipLevels = levels;
    desc.format = texture.kind == TextureKind::Color ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    vk::Image image(context_, desc);

    size_t total = 0;
    for (uint32_t level = 0; level < levels; ++level) total += texture.mips[first + level].size();
    vk::Buffer staging(context_, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, vk::MemoryUsage::HostVisible);
    std::vector<VkBufferImageCopy> regions;
    size_t offset = 0;
    for (uint32_t level = 0; level < levels; ++level) {
        const std::vector<uint8_t>& mip = texture.mips[first + level];
        std::memcpy(static_cast<uint8_t*>(staging.mapped()) + offset, mip.data(), mip.size());
        VkBufferImageCopy region{};
        region.bufferOffset = offset;
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
        region.imageExtent = {std::max(1u, width >> level), std::max(1u, height >> level), 1};
        regions.push_back(region);
        offset += mip.size();
    }
    context_.submitAndWait([&](VkCommandBuffer cmd) {
        image.use(cmd, vk::ImageAccess::TransferDst);
        vkCmdCopyBufferToImage(cmd, staging.handle(), image.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               uint32_t(regions.size()), regions.data());
        image.use(cmd, vk::ImageAccess::Sampled);
    });
    return image;
}

void GpuScene::uploadTextures() {
    for (const Texture& texture : scene_.textures) {
        textures_.push_back(uploadTexture(texture));
        textureSamplers_.push_back(samplerFor(texture.wrapS, texture.wrapT));
    }
    defaultWhite_ = uploadTexture(solidTexture(TextureKind::Linear, 255, 255, 255, 255));
    defaultNormal_ = uploadTexture(
        solidTexture(TextureKind::Normal, VCT_FLAT_NORMAL_TEXEL, VCT_FLAT_NORMAL_TEXEL, 255, 255));
    defaultBlack_ = uploadTexture(solidTexture(TextureKind::Linear, 0, 0, 0, 255));
    defaultSampler_ = samplerFor(TextureWrap::Repeat, TextureWrap::Repeat);
}

namespace {
int textureIndex(const Material& material, GpuScene::Slot slot) {
    switch (slot) {
        case GpuScene::Slot::BaseColor:
            return material.baseColorTexture;
        case GpuScene::Slot::MetallicRoughness:
            return material.metallicRoughnessTexture;
        case GpuScene::Slot::Normal:
            return material.normalTexture;
        case GpuScene::Slot::Emissive:
            return material.emissiveTexture;
        case GpuScene::Slot::Occlusion:
            return material.occlusionTexture;
    }
    return -1;
}
}  // namespace

// lib/surface.glsl: emission = factor × texture, occlusion = 1 + strength × (texture − 1).
bool GpuScene::emits(const Material& material) {
    return material.emissiveFactor != glm::vec3(0.0f);
}

bool GpuScene::occludes(const Material& material) {
    return material.occlusionTexture >= 0 && material.occlusionStrength != 0.0f;
}

uint32_t GpuScene::texturedSlots(const Material& material) {
    uint32_t bits = 0;
    for (Slot slot : kSlots)
        if (textureIndex(material, slot) >= 0) bits |= 1u << uint32_t(slot);
    return bits;
}

VkImageView GpuScene::textureView(const Material& material, Slot slot) const {
    const int index = textureIndex(material, slot);
    if (index >= 0) return textures_[size_t(index)].view();
    // Neutral defaults, bound so that every descriptor is valid; the shaders read GpuMaterial.flags.y and use
    // the neutral values themselves, never these (lib/surface.glsl). White multiplies by 1 (emissive too, since
    // glTF's emissive = factor × texture).
    return slot == Slot::Normal ? defaultNormal_.view() : defaultWhite_.view();
}

VkSampler GpuScene::textureSampler(const Material& material, Slot slot) const {
    const int index = textureIndex(material, slot);
    return index >= 0 ? textureSamplers_[size_t(index)] : defaultSampler_;
}

void GpuScene::useFrameSlot(uint32_t slot) {
    deform_->useFrameSlot(slot);
    if (slot == frameSlot_ || spareInstanceBuffer_.handle() == VK_NULL_HANDLE) return;
    // update() writes every instance and light each frame, so the copy swapped in needs nothing carried over.
    std::swap(instanceBuffer_, spareInstanceBuffer_);
    std::swap(lightBuffer_, spareLightBuffer_);
    frameSlot_ = slot;
}

void GpuScene::update(float timeSeconds, bool cut) {
    std::vector<glm::quat> rotations;
    const std::vector<glm::mat4> world = scene_.evaluate(timeSeconds, &rotations);
    std::vector<Instance> next = scene_.instances(timeSeconds);
    if (cut || previousWorld_.size() != next.size()) {
        previousWorld_.clear();
        for (const Instance& instance : next) previousWorld_.push_back(instance.world);
    }
    auto* gpuInstances = static_cast<gpu::GpuInstance*>(instanceBuffer_.mapped());
    for (size_t i = 0; i < next.size(); ++i) {
        gpuInstances[i].world = next[i].world;
        gpuInstances[i].prevWorld = previousWorld_[i];
        gpuInstances[i].normalMatrix = normalMatrix(next[i].world);
        previousWorld_[i] = next[i].world;
    }
    // Exact comparison: a scene without animation evaluates to the very same matrices every time.
    bool changed = !hasUpdated_ || next.size() != instances_.size();
    onlyInstancesMoved_ = !changed;
    movedBounds_ = Aabb{};
    for (size_t i = 0; onlyInstancesMoved_ && i < next.size(); ++i)
        if (next[i].world != instances_[i].world) {
            changed = true;
            // Where the instance was and where it is: the voxels whose content its move changed.
            movedBounds_.extend(instances_[i].bounds);
            movedBounds_.extend(next[i].bounds);
        }
    // Joints or morph weights that moved change the geometry as a moved instance does: the deformed instances'
    // bounds before and after join the moved bounds.
    if (deform_->update(next, world, cut)) {
        changed = true;
        for (size_t i = 0; onlyInstancesMoved_ && i < next.size(); ++i)
            if (next[i].deformed) {
                movedBounds_.extend(instances_[i].bounds);
                movedBounds_.extend(next[i].bounds);
            }
    }
    instances_ = std::move(next);

    const std::vector<gpu::GpuLight> previousLights = std::move(lights_);
    lights_ = sceneLights(scene_, world, rotations);
    const bool lightsChanged = previousLights.size() != lights_.size() ||
                               (!lights_.empty() && std::memcmp(previousLights.data(), lights_.data(),
                                                                lights_.size() * sizeof(gpu::GpuLight)) != 0);
    changed = changed || lightsChanged;
    onlyInstancesMoved_ = onlyInstancesMoved_ && !lightsChanged && !cut;
    changed_ = changed;
    hasUpdated_ = true;
    fitShadow();
    if (!lights_.empty())
        std::memcpy(lightBuffer_.mapped(), lights_.data(), lights_.size() * sizeof(gpu::GpuLight));
}

void GpuScene::fitShadow() {
    shadowLight_ = -1;
    for (size_t i = 0; i < lights_.size(); ++i) {
        const int type = int(lights_[i].directionType.w);
        if (type == VCT_LIGHT_DIRECTIONAL || type == VCT_LIGHT_SPOT) {
            shadowLight_ = int(i);
            break;
        }
    }
    if (shadowLight_ < 0) return;
    const gpu::GpuLight& light = lights_[size_t(shadowLight_)];
    const glm::vec3 direction = glm::vec3(light.directionType);
    const glm::vec3 center = 0.5f * (bounds_.min + bounds_.max);
    const float radius = std::max(1e-3f, 0.5f * glm::length(bounds_.max - bounds_.min));
    // Any up vector not parallel to the light direction.
    const glm::vec3 up = std::abs(direction.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    if (int(light.directionType.w) == VCT_LIGHT_DIRECTIONAL) {
        // Orthographic box around the bounding sphere of the scene.
        const glm::vec3 eye = center - direction * (2.0f * radius);
        const glm::mat4 view = glm::lookAt(eye, center, up);
        const glm::mat4 proj = glm::ortho(-radius, radius, -radius, radius, radius * 0.5f, radius * 3.5f);
        lightViewProj_ = proj * view;
        shadowTexelWorld_ = 2.0f * radius / float(VCT_SHADOW_MAP_SIZE);
    } else {
        // Perspective over the spot's cone (clamped so the projection stays well conditioned).
        const glm::vec3 eye = glm::vec3(light.positionRange);
        const float cosOuter = -light.spotScaleOffset.y / light.spotScaleOffset.x;
        const float outer = std::acos(std::clamp(cosOuter, -1.0f, 1.0f));
        const float fov = std::clamp(2.0f * outer + 0.1f, 0.2f, 2.8f);
        const float farPlane = glm::length(eye - center) + radius;
        const float nearPlane = std::max(1e-3f, farPlane * 1e-3f);
        lightViewProj_ =
            glm::perspective(fov, 1.0f, nearPlane, farPlane) * glm::lookAt(eye, eye + direction, up);
        // Texel size at the scene's centre distance.
        shadowTexelWorld_ =
            2.0f * std::tan(0.5f * fov) * glm::length(eye - center) / float(VCT_SHADOW_MAP_SIZE);
    }
}

}  // namespace vct
