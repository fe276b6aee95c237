#include "render/gpu_deform.h"

#include <cstring>

#include "core/error.h"
#include "scene/deform.h"

namespace vct {

namespace {

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;

}  // namespace

GpuDeform::GpuDeform(const vk::Context& context, const Scene& scene, const std::vector<Instance>& instances,
                     uint32_t framesInFlight)
    : scene_(scene) {
    uint32_t joints = 0, weights = 0;
    firstSlot_.assign(instances.size(), -1);
    jointBase_.assign(instances.size(), 0);
    weightBase_.assign(instances.size(), 0);
    for (size_t i = 0; i < instances.size(); ++i) {
        const Instance& instance = instances[i];
        if (!instance.deformed) continue;
        firstSlot_[i] = int32_t(slotOffsets_.size());
        jointBase_[i] = joints;
        weightBase_[i] = weights;
        const uint32_t jointCount =
            instance.skin >= 0 ? uint32_t(scene.skins[size_t(instance.skin)].joints.size()) : 0u;
        const uint32_t targets = uint32_t(instance.morphWeights.size());
        for (uint32_t p : scene.meshes[size_t(instance.mesh)].primitives) {
            const Primitive& prim = scene.primitives[p];
            slotOffsets_.push_back(int32_t(deformedVertices_));
            Job job{};
            const bool skinned = instance.skin >= 0 && prim.skinVertexOffset >= 0;
            job.push.vertices = glm::uvec4(uint32_t(prim.vertexOffset), prim.vertexCount, deformedVertices_,
                                           skinned ? uint32_t(prim.skinVertexOffset) : VCT_SKIN_NONE);
            job.push.morph =
                glm::uvec4(prim.morphDeltaOffset, std::min(prim.morphTargetCount, targets), weights, joints);
            job.push.flags = glm::uvec4(0, jointCount, 0, 0);
            if (prim.vertexCount > 0) jobs_.push_back(job);
            deformedVertices_ += prim.vertexCount;
        }
        joints += jointCount;
        weights += targets;
    }
    // The draws bind the deformed buffers as vertex input, the voxelization and the G-buffer's motion as
    // storage; both stay within the device's storage range like the static vertices (GpuScene checks those).
    const VkDeviceSize bytes = VkDeviceSize(std::max(deformedVertices_, 1u)) * sizeof(Vertex);
    const VkDeviceSize maxRange = context.properties().limits.maxStorageBufferRange;
    if (bytes > maxRange)
        throw Error("scene '" + scene.name + "': its deformed vertices take " + std::to_string(bytes) +
                    " bytes, more than the device's maxStorageBufferRange (" + std::to_string(maxRange) +
                    ")");
    const VkBufferUsageFlags deformedUsage = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | kStorage |
                                             VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                             VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    current_ = vk::Buffer(context, bytes, deformedUsage, vk::MemoryUsage::DeviceLocal);
    previous_ = vk::Buffer(context, bytes, deformedUsage, vk::MemoryUsage::DeviceLocal);
    if (!active()) return;  // the placeholders above are all a static scene needs
    skinVertices_ = vk::Buffer::withData(context, scene.skinVertices.data(),
                                         scene.skinVertices.size() * sizeof(SkinVertex), kStorage);
    morphDeltas_ = vk::Buffer::withData(context, scene.morphDeltas.data(),
                                        scene.morphDeltas.size() * sizeof(MorphDelta), kStorage);
    jointMatrices_ =
        vk::Buffer(context, std::max(joints, 1u) * sizeof(glm::mat4), kStorage, vk::MemoryUsage::HostVisible);
    morphWeights_ =
        vk::Buffer(context, std::max(weights, 1u) * sizeof(float), kStorage, vk::MemoryUsage::HostVisible);
    if (framesInFlight > 1) {
        spareJointMatrices_ = vk::Buffer(context, std::max(joints, 1u) * sizeof(glm::mat4), kStorage,
                                         vk::MemoryUsage::HostVisible);
        spareMorphWeights_ = vk::Buffer(context, std::max(weights, 1u) * sizeof(float), kStorage,
                                        vk::MemoryUsage::HostVisible);
    }
    joints_.assign(joints, glm::mat4(1.0f));
    weights_.assign(weights, 0.0f);
}

void GpuDeform::useFrameSlot(uint32_t slot) {
    if (slot == frameSlot_ || spareJointMatrices_.handle() == VK_NULL_HANDLE) return;
    std::swap(jointMatrices_, spareJointMatrices_);
    std::swap(morphWeights_, spareMorphWeights_);
    frameSlot_ = slot;
}

int32_t GpuDeform::deformedOffset(uint32_t instance, uint32_t slot) const {
    if (!deformed(instance)) return -1;
    return slotOffsets_[size_t(firstSlot_[instance]) + slot];
}

bool GpuDeform::update(const std::vector<Instance>& instances, const std::vector<glm::mat4>& world,
                       bool cut) {
    if (!active()) return false;
    std::vector<glm::mat4> joints(joints_.size());
    std::vector<float> weights(weights_.size());
    for (size_t i = 0; i < instances.size() && i < firstSlot_.size(); ++i) {
        if (firstSlot_[i] < 0) continue;
        const std::vector<glm::mat4> matrices = vct::jointMatrices(scene_, instances[i].skin, world);
        std::copy(matrices.begin(), matrices.end(), joints.begin() + jointBase_[i]);
        std::copy(instances[i].morphWeights.begin(), instances[i].morphWeights.end(),
                  weights.begin() + weightBase_[i]);
    }
    // Exact comparison: a paused or finished animation gives the very same floats.
    const bool changed = !hasUpdated_ || joints != joints_ || weights != weights_;
    changedBefore_ = changed_;
    changed_ = changed;
    cut_ = cut || !hasUpdated_;
    hasUpdated_ = true;
    joints_ = std::move(joints);
    weights_ = std::move(weights);
    if (!joints_.empty())
        std::memcpy(jointMatrices_.mapped(), joints_.data(), joints_.size() * sizeof(glm::mat4));
    if (!weights_.empty())
        std::memcpy(morphWeights_.mapped(), weights_.data(), weights_.size() * sizeof(float));
    return changed;
}

}  // namespace vct
