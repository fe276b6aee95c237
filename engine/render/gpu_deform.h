// Skinned and morphed instances on the GPU (docs/design.md §2.5): the skin pass's inputs (the rest vertices'
// skin influences and morph deltas, uploaded once; this frame's joint matrices and morph weights, written by
// update()) and its outputs, the deformed vertex buffer the draws and the voxelization take those instances'
// vertices from, and last frame's copy of it (their motion vectors). A scene without skins or morph targets
// has none of this: inactive(), the placeholders bound where a layout needs a buffer, and no skin pass.
#pragma once

#include <vector>

#include "lib/shared.h"
#include "scene/scene.h"
#include "vk/buffer.h"

namespace vct {

class GpuDeform {
  public:
    // `instances`: Scene::instances, whose order every later update keeps. `framesInFlight` (1 or 2): copies
    // of the joint matrices and morph weights, which the CPU writes while the GPU may run the frame before.
    GpuDeform(const vk::Context& context, const Scene& scene, const std::vector<Instance>& instances,
              uint32_t framesInFlight = 1);

    bool active() const { return !jobs_.empty(); }
    // Makes copy `slot` of the joint matrices and morph weights the one update() writes and the skin pass
    // binds (jointMatrices(), morphWeights() keep naming the same objects: the copies are swapped into them).
    void useFrameSlot(uint32_t slot);
    // This frame's joint matrices and morph weights (`world`: Scene::evaluate at the frame's time). Returns
    // whether they differ from the last update's (the first: true).
    bool update(const std::vector<Instance>& instances, const std::vector<glm::mat4>& world, bool cut);
    // Whether the skin pass has work this frame: the deformation changed in this update or the last one (the
    // previous buffer must then catch up), or a cut (both buffers written).
    bool needsWork() const { return changed_ || changedBefore_ || cut_; }
    bool cut() const { return cut_; }

    // Where the draws find instance `instance`'s primitive `slot` (its index in its mesh's list): the first
    // vertex in the deformed buffer, or -1 when the instance is not deformed.
    int32_t deformedOffset(uint32_t instance, uint32_t slot) const;
    bool deformed(uint32_t instance) const {
        return instance < firstSlot_.size() && firstSlot_[instance] >= 0;
    }

    // One dispatch of the skin pass.
    struct Job {
        gpu::SkinPushConstants push;
    };
    const std::vector<Job>& jobs() const { return jobs_; }

    vk::Buffer& skinVertices() { return skinVertices_; }
    vk::Buffer& morphDeltas() { return morphDeltas_; }
    vk::Buffer& jointMatrices() { return jointMatrices_; }
    vk::Buffer& morphWeights() { return morphWeights_; }
    vk::Buffer& current() { return current_; }
    vk::Buffer& previous() { return previous_; }
    VkBuffer currentBuffer() const { return current_.handle(); }
    VkBuffer previousBuffer() const { return previous_.handle(); }
    uint32_t deformedVertexCount() const { return deformedVertices_; }

  private:
    const Scene& scene_;
    std::vector<int32_t> firstSlot_;    // per instance: its first entry in slotOffsets_, -1 if static
    std::vector<int32_t> slotOffsets_;  // per deformed instance × primitive: first deformed vertex
    std::vector<uint32_t> jointBase_, weightBase_;  // per instance
    std::vector<Job> jobs_;
    uint32_t deformedVertices_ = 0;
    std::vector<glm::mat4> joints_;  // this frame's, as written
    std::vector<float> weights_;
    vk::Buffer skinVertices_, morphDeltas_, jointMatrices_, morphWeights_, current_, previous_;
    vk::Buffer spareJointMatrices_, spareMorphWeights_;  // the other frame's, with two in flight
    uint32_t frameSlot_ = 0;
    bool changed_ = true, changedBefore_ = true, cut_ = true, hasUpdated_ = false;
};

}  // namespace vct
