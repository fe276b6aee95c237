// Per-pass GPU timers from timestamp queries. The code that runs the passes opens a scope per pass by name;
// nobody numbers query indices by hand. Durations use the device's timestampPeriod. With several frames in
// flight each frame has its own queries: beginFrame() takes the next set, collect() reads the oldest frame
// not yet collected (after its fence), so every sample is still one frame's.
#pragma once

#include <vulkan/vulkan.h>

#include <string>
#include <vector>

#include "vk/context.h"

namespace vct::vk {

struct PassTiming {
    std::string name;
    double medianMs = 0.0;
    double p95Ms = 0.0;
    double minMs = 0.0;
    size_t samples = 0;  // recorded frames
    size_t runs = 0;     // recorded frames in which the pass ran (the others were skipped: 0 ms samples)
};

class GpuTimer {
  public:
    // `framesInFlight`: how many frames may be recorded before the first of them is collected.
    GpuTimer(const Context& context, uint32_t maxScopes = 64, uint32_t framesInFlight = 1);
    ~GpuTimer();
    GpuTimer(const GpuTimer&) = delete;
    GpuTimer& operator=(const GpuTimer&) = delete;

    // Resets the next frame's queries (recorded into the frame's command buffer).
    void beginFrame(VkCommandBuffer cmd);
    void beginScope(VkCommandBuffer cmd, const std::string& name);
    void endScope(VkCommandBuffer cmd);
    // A pass with nothing to do this frame: no timestamps, a 0 ms sample (it cost the frame nothing), and
    // not counted in PassTiming::runs.
    void skipScope(const std::string& name);
    // The frame begun last will not be submitted (an error while it was recorded): its queries are never
    // written, so it is never collected.
    void cancelFrame();
    // After the fence of the oldest frame begun and not yet collected: reads its timestamps; keeps them as
    // samples when `record` is true. Does nothing when no frame is waiting.
    void collect(bool record);

    // Median/p95/min per pass over the recorded frames, in the order the passes first ran.
    std::vector<PassTiming> passStats() const;
    PassTiming frameStats() const;  // first timestamp to last, per frame
    // The last collected frame's duration per pass (for the on-screen overlay).
    const std::vector<std::pair<std::string, double>>& lastFrame() const { return lastFrame_; }

  private:
    const Context& context_;
    VkQueryPool pool_ = VK_NULL_HANDLE;  // framesInFlight sets of 2 · maxScopes queries
    uint32_t maxScopes_;
    uint64_t validMask_;
    struct Scope {
        std::string name;
        int query = -1;  // index of its pair of timestamps in the frame's set; -1: skipped
    };
    struct FrameQueries {
        std::vector<Scope> scopes;  // the frame's scopes, in order
        uint32_t timedScopes = 0;   // how many of them have timestamps
    };
    std::vector<FrameQueries> frames_;  // one per frame in flight
    uint32_t begun_ = 0;                // frames begun
    uint32_t collected_ = 0;            // frames collected (the oldest pending is collected_ % size)
    int openScope_ = -1;
    FrameQueries& recording() { return frames_[(begun_ - 1) % frames_.size()]; }
    uint32_t firstQuery(uint32_t frame) const { return uint32_t(frame % frames_.size()) * 2 * maxScopes_; }
    std::vector<std::string> passOrder_;
    std::vector<std::vector<double>> passSamples_;  // parallel to passOrder_
    std::vector<size_t> passRuns_;                  // parallel to passOrder_
    std::vector<double> frameSamples_;
    std::vector<std::pair<std::string, double>> lastFrame_;
};

// Median / p95 / min of a list of samples (by value: sorts a copy); runs = the number of samples.
PassTiming summarize(const std::string& name, std::vector<double> samples);

}  // namespace vct::vk
