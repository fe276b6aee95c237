// Runs one frame: updates the scene's per-frame data, then runs the passes in order, each inside a GPU
// timestamp scope (each pass emits the barriers its resource table calls for).
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <vector>

#include "render/camera.h"
#include "render/dfg_lut.h"
#include "render/environment.h"
#include "render/frame_targets.h"
#include "render/gpu_environment.h"
#include "render/gpu_scene.h"
#include "render/pass.h"
#include "render/settings.h"
#include "render/voxel_grid.h"
#include "vk/buffer.h"
#include "vk/sampler.h"
#include "vk/timer.h"

namespace vct {

struct FrameInput {
    CameraView camera;
    float timeSeconds = 0.0f;
    bool cut = false;            // no valid previous frame (first frame, camera jump): no motion history
    bool recordTimings = false;  // keep this frame's pass timings in the statistics (after warm-up)
};

struct CameraPath;

// Frame `index` of a headless run at a fixed 1/60 s step from t = 0, seen from the scene's camera (or from
// `path` at the same time, with the scene camera's lens where the path sets none): a cut on the first frame
// (no history), timed from frame `warmup` on.
FrameInput fixedStepFrame(const Scene& scene, uint32_t index, uint32_t warmup,
                          const CameraPath* path = nullptr);

// Optional extra work after the passes (the window's blit to the swapchain) and its synchronisation.
struct FrameSubmit {
    std::function<void(VkCommandBuffer)> afterPasses;
    VkSemaphore wait = VK_NULL_HANDLE;
    VkPipelineStageFlags waitStage = 0;
    VkSemaphore signal = VK_NULL_HANDLE;
};

class CompositePass;
class DirectPass;
class GBufferPass;
class ShadowPass;
class VoxelViewPass;

class Renderer {
  public:
    // `framesInFlight` (1 or 2): how many frames may be submitted and not yet finished. With 1 (headless
    // runs, tests, benchmarks) render() waits for its frame; with 2 (the demo) it returns after the submit
    // and waits, before it records a frame, for the one two frames back: the CPU records frame k + 1 while the
    // GPU runs frame k. What the CPU writes for a frame (uniforms, instance transforms, lights, joint
    // matrices, morph weights) and reads back (timestamps, the re-trace count) has one copy per frame in
    // flight; everything else is GPU-only and ordered by the queue.
    Renderer(const vk::Context& context, const Scene& scene, const RenderSettings& settings,
             uint32_t framesInFlight = 1);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Records and submits one frame. With one frame in flight it then waits for it and reads its timestamps;
    // with two, the timestamps (timer()) and the re-trace fraction are those of the last frame finished.
    void render(const FrameInput& input, const FrameSubmit& submit = {});
    // Waits for every submitted frame and reads its timestamps (the demo before it reports statistics).
    // Image readbacks need no call: they are submitted after the frames and wait for them.
    void finishFrames();
    void resize(uint32_t width, uint32_t height);
    // The demo's live controls. True when going from the settings this renderer runs with to `wanted` changes
    // only what the next frame reads from its uniforms and specialization constants: every setting that
    // differs is SettingApply::Live in the setting table (render/setting_table.h, settingsChange); false when
    // one changes targets, passes or the voxel grid: those need resize() (SettingApply::Resize) or a new
    // Renderer.
    bool canApplyLive(const RenderSettings& wanted) const;
    // Takes those live settings from `wanted` for the next frame; throws when !canApplyLive(wanted).
    void applyLive(const RenderSettings& wanted);

    FrameTargets& targets() { return targets_; }
    const vk::GpuTimer& timer() const { return timer_; }
    const RenderSettings& settings() const { return settings_; }
    const GpuScene& gpuScene() const { return gpuScene_; }
    // The environment the frame sees (docs/design.md §5.9), as made from the settings and the scene.
    const EnvironmentMap& environment() const { return *environmentMap_; }
    // The same, shared (the demo's path-traced reference renders with it).
    std::shared_ptr<const EnvironmentMap> sharedEnvironment() const { return environmentMap_; }
    // The voxel grid of cone tracing; null when GI is off.
    VoxelGrid* voxelGrid() { return voxelGrid_.get(); }
    // The voxel grid ray-marched at `mip` (0 .. mipCount − 1) from the last frame's camera: radiance, RGBA16F at
    // the frame's size (passes/voxel_view_pass.h). On demand, in a submit of its own after render(): not part
    // of the frame or its timings. Throws when GI is off (no grid) or the mip is out of range.
    vk::Image& renderVoxelView(uint32_t mip);

    // Fraction of the pixels the resample pass re-traced in the last finished frame (0 without adaptive
    // re-tracing).
    float resampledFraction() const;
    // Shadow-map texels the last frame redrew (0 when the map was kept whole: nothing moved), and the map's size.
    uint64_t shadowTexelsRedrawn() const;
    uint64_t shadowTexels() const;
    // Whether the last frame's direct light was recomputed only where moving instances can change it (false:
    // every pixel, or not at all).
    bool directLightPartial() const;
    uint64_t directPixelsDispatched() const;
    // G-buffer pixels the last frame redrew (0 when it was reused: scene and camera unchanged).
    uint64_t gbufferPixelsRedrawn() const;

    // Copies an image of this frame to the host (RGBA32F for float images, RGBA8 for 8-bit ones); not
    // FrameTargets::hdr, which the frames do not write (readFinalHdr).
    std::vector<float> readFloatImage(vk::Image& image);
    // The last frame's linear HDR result (final.exr), RGBA32F: composite run again on what the frame left, in a
    // submit of its own that writes the HDR image too (the frames write only the tone-mapped one; lib/shared.h,
    // VCT_COMPOSITE_SPEC_HDR). Not part of the frame or its timings. Throws before the first frame.
    std::vector<float> readFinalHdr();
    std::vector<uint8_t> readLdr();
    // This frame's full-res demodulated indirect light (FrameTargets::indirect, unpacked): RGBA32F, rgb the
    // radiance, a its accumulated weight. Throws when GI is off (nothing traced).
    struct IndirectLight {
        std::vector<float> diffuse;
        std::vector<float> specular;
    };
    IndirectLight readIndirect();

  private:
    // What one frame in flight owns (see the constructor).
    struct FrameSlot {
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        VkFence fence = VK_NULL_HANDLE;
        vk::Buffer uniforms;  // gpu::FrameUniforms
        vk::Buffer
            resampleCount;     // the re-trace count copied back (FrameTargets::resampleCount while recorded)
        bool pending = false;  // submitted, its fence not waited yet
        bool recordTimings = false;
    };
    // Waits for the slot's frame if it is pending: its timestamps, its re-trace count.
    void finishSlot(FrameSlot& slot);
    FrameSlot& lastSubmitted() { return slots_[(submitted_ + slots_.size() - 1) % slots_.size()]; }
    vk::Buffer copyToHost(vk::Image& image);
    std::vector<float> readImage(vk::Image& image);
    // Records work on what the last frame left (its targets, its uniforms) in a submit of its own, and waits:
    // readFinalHdr, renderVoxelView.
    void runAfterFrame(const std::function<void(const FrameContext&)>& record);
    void writeFrameUniforms(const FrameInput& input, vk::Buffer& uniforms);
    void createSamplers();

    const vk::Context& context_;
    RenderSettings settings_;
    GpuScene gpuScene_;
    FrameTargets targets_;
    std::array<vk::Sampler, 3> samplerOwners_;  // linear, nearest, shadow compare: what samplers_ names
    Samplers samplers_;
    std::vector<FrameSlot> slots_;   // one per frame in flight; frame k uses slot k mod size
    uint32_t submitted_ = 0;         // frames submitted
    uint32_t resampleCount_ = 0;     // re-traced pixels of the last finished frame
    gpu::FrameUniforms uniforms_{};  // this frame's, as written to its slot's uniform buffer
    vk::GpuTimer timer_;
    std::shared_ptr<const EnvironmentMap> environmentMap_;
    std::unique_ptr<GpuEnvironment> gpuEnvironment_;  // before passes_: they bind it
    // The split-sum DFG table (inject, blend and composite read it), made once per renderer: its integral costs
    // ~45 ms of CPU. Before passes_: they bind it.
    std::unique_ptr<DfgLut> dfg_;
    std::unique_ptr<VoxelGrid> voxelGrid_;  // before passes_: the passes that use it are destroyed first
    std::vector<std::unique_ptr<Pass>> passes_;
    ShadowPass* shadowPass_ = nullptr;          // one of passes_, for its redrawn texels
    GBufferPass* gbufferPass_ = nullptr;        // one of passes_, for its redrawn pixels
    DirectPass* directPass_ = nullptr;          // one of passes_, for whether it recomputed every pixel
    CompositePass* composite_ = nullptr;        // in passes_; readFinalHdr runs it again
    std::unique_ptr<VoxelViewPass> voxelView_;  // made by the first renderVoxelView; never in passes_
    glm::mat4 previousViewProj_{1.0f};
    glm::mat4 previousInvViewProj_{1.0f};
    glm::vec3 previousCameraPosition_{0.0f};
    uint32_t frameIndex_ = 0;  // frames rendered: picks the trace offset o_k and turns the diffuse cones
    // A frame has built what depends only on the scene (shadow map, voxel grid); reset by resize().
    bool sceneBuilt_ = false;
    // Consecutive frames whose scene and camera equal the previous frame's (0: this frame changed something).
    uint32_t stableFrames_ = 0;
    // `--bounces all` (passes/voxel_bounce_pass.h): the frames its gathers go on after the grid last changed, and
    // how many of them are left (0 otherwise).
    uint32_t voxelLightSettleFrames_ = 0;
    uint32_t voxelLightFramesLeft_ = 0;
    bool hasPrevious_ = false;
};

}  // namespace vct
