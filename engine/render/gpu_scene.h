// The scene as the GPU sees it: geometry, textures (with their mip chains), materials and lights uploaded
// once; per frame only the instance transforms (current and previous) are written.
#pragma once

#include <iterator>
#include <map>
#include <memory>
#include <vector>

#include "lib/shared.h"
#include "render/gpu_deform.h"
#include "render/settings.h"
#include "scene/scene.h"
#include "vk/buffer.h"
#include "vk/image.h"
#include "vk/sampler.h"

namespace vct {

// The anisotropic filtering level the material sampler gets: `requested` (0, 2, 4, 8 or 16), or for
// kAnisotropyFromDevice 0 on a CPU device (lavapipe emulates anisotropy with many bilinear taps per sample:
// DamagedHelmet's gbuffer pass takes seconds instead of milliseconds) and 8 on a GPU; then clamped to the
// device's maxSamplerAnisotropy, and 0 without the samplerAnisotropy feature.
uint32_t chooseAnisotropy(const vk::Context& context, uint32_t requested);

class GpuScene {
  public:
    // `anisotropy`: the material sampler's level, as chosen by chooseAnisotropy (0: off). `framesInFlight`
    // (1 or 2): how many copies of what update() writes (instances, lights, joints, morph weights) there are.
    GpuScene(const vk::Context& context, const Scene& scene, uint32_t anisotropy,
             uint32_t framesInFlight = 1);
    ~GpuScene();
    GpuScene(const GpuScene&) = delete;
    GpuScene& operator=(const GpuScene&) = delete;

    const Scene& scene() const { return scene_; }
    VkBuffer vertexBuffer() const { return vertices_.handle(); }
    VkBuffer indexBuffer() const { return indices_.handle(); }
    VkBuffer materialBuffer() const { return materials_.handle(); }
    VkBuffer instanceBuffer() const { return instanceBuffer_.handle(); }
    VkBuffer lightBuffer() const { return lightBuffer_.handle(); }

    // Makes copy `slot` (< framesInFlight) of the per-frame buffers the one that update() writes and the
    // passes bind, its frame's fence having been waited for.
    void useFrameSlot(uint32_t slot);
    // Writes this frame's instances (world and previous-world matrices) and lights at time t.
    // The first call (or one after a cut) uses the current transforms as the previous ones.
    void update(float timeSeconds, bool cut);
    // Whether the last update() moved an instance or changed a light against the update before it (the first
    // update: true). The voxel grid depends on nothing else of the scene.
    bool changedInLastUpdate() const { return changed_; }
    // Whether what changed in the last update was only instances moving (no light, no cut, not the first
    // update), and the world bounds of those instances before and after their move (empty: nothing moved).
    bool onlyInstancesMovedInLastUpdate() const { return onlyInstancesMoved_; }
    const Aabb& movedBounds() const { return movedBounds_; }
    const std::vector<Instance>& instances() const { return instances_; }
    // Whether an instance draws a primitive with an alphaMode BLEND material (the blend pass runs).
    bool hasBlended() const { return hasBlended_; }
    // Whether a material emits (a non-zero emissive factor) / darkens its indirect light (an occlusion texture
    // of non-zero strength). Without, the G-buffer's emissiveOcclusion target is (0, 0, 0, 1) on every pixel and
    // direct and composite do not read it (their specialization constants, lib/shared.h).
    bool hasEmission() const { return hasEmission_; }
    bool hasOcclusion() const { return hasOcclusion_; }
    // The same of one material.
    static bool emits(const Material& material);
    static bool occludes(const Material& material);
    // Skinned and morphed instances: their deformed vertices (the skin pass writes them; render/gpu_deform.h).
    const GpuDeform& deform() const { return *deform_; }
    GpuDeform& deform() { return *deform_; }
    uint32_t lightCount() const { return uint32_t(lights_.size()); }
    const std::vector<gpu::GpuLight>& lights() const { return lights_; }
    // The main light: the first directional or spot light, which casts the shadow map; -1 when none.
    int shadowLightIndex() const { return shadowLight_; }
    // World → the main light's clip space, fitted to the scene bounds; and the world size of one shadow texel.
    const glm::mat4& lightViewProj() const { return lightViewProj_; }
    float shadowTexelWorldSize() const { return shadowTexelWorld_; }

    // The image view for a texture slot; a neutral 1x1 default when the material has none (bound so that every
    // descriptor is valid; the shaders do not sample it: GpuMaterial.flags.y).
    enum class Slot {
        BaseColor = VCT_TEXTURE_SLOT_BASE_COLOR,
        MetallicRoughness = VCT_TEXTURE_SLOT_METALLIC_ROUGHNESS,
        Normal = VCT_TEXTURE_SLOT_NORMAL,
        Emissive = VCT_TEXTURE_SLOT_EMISSIVE,
        Occlusion = VCT_TEXTURE_SLOT_OCCLUSION,
    };
    static constexpr Slot kSlots[] = {Slot::BaseColor, Slot::MetallicRoughness, Slot::Normal, Slot::Emissive,
                                      Slot::Occlusion};
    static_assert(VCT_EVERY_TEXTURE_SLOT == (1u << std::size(kSlots)) - 1u, "a slot missing from kSlots");
    // GpuMaterial.flags.y: bit (1 << slot) for each slot in which `material` has a texture.
    static uint32_t texturedSlots(const Material& material);
    VkImageView textureView(const Material& material, Slot slot) const;
    VkSampler textureSampler(const Material& material, Slot slot) const;

  private:
    void uploadTextures();
    vk::Image uploadTexture(const Texture& texture);
    VkSampler samplerFor(TextureWrap s, TextureWrap t);

    const vk::Context& context_;
    const Scene& scene_;
    uint32_t anisotropy_ = 0;
    vk::Buffer vertices_, indices_, materials_, instanceBuffer_, lightBuffer_;
    // The other frame's instance and light buffers with two frames in flight (swapped by useFrameSlot).
    vk::Buffer spareInstanceBuffer_, spareLightBuffer_;
    uint32_t frameSlot_ = 0;
    std::vector<vk::Image> textures_;
    std::vector<VkSampler> textureSamplers_;  // parallel to textures_
    vk::Image defaultWhite_, defaultNormal_, defaultBlack_;
    VkSampler defaultSampler_ = VK_NULL_HANDLE;
    std::map<std::pair<int, int>, vk::Sampler> samplers_;
    std::vector<Instance> instances_;
    std::unique_ptr<GpuDeform> deform_;
    std::vector<glm::mat4> previousWorld_;  // per instance
    std::vector<gpu::GpuLight> lights_;
    int shadowLight_ = -1;
    glm::mat4 lightViewProj_{1.0f};
    float shadowTexelWorld_ = 0.0f;
    bool changed_ = true;
    bool hasUpdated_ = false;
    Aabb bounds_;
    Aabb movedBounds_;
    bool onlyInstancesMoved_ = false;
    bool hasBlended_ = false;
    bool hasEmission_ = false;
    bool hasOcclusion_ = false;
    void fitShadow();
};

}  // namespace vct
