// Per-pass GPU timers from timestamp queries. The code that runs the passes opens a scope per pass by name;
// nobody numbers query indices by hand. Durations use the device's timestampPeriod.
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
    GpuTimer(const Context& context, uint32_t maxScopes = 64);
    ~GpuTimer();
    GpuTimer(const GpuTimer&) = delete;
    GpuTimer& operator=(const GpuTimer&) = delete;

    // Resets the queries for a new frame (recorded into the frame's command buffer).
    void beginFrame(VkCommandBuffer cmd);
    void beginScope(VkCommandBuffer cmd, const std::string& name);
    void endScope(VkCommandBuffer cmd);
    // A pass with nothing to do this frame: no timestamps, a 0 ms sample (it cost the frame nothing), and
    // not counted in PassTiming::runs.
    void skipScope(const std::string& name);
    // After the frame's fence: reads the timestamps; keeps them as samples when `record` is true.
    void collect(bool record);

    // Median/p95/min per pass over the recorded frames, in the order the passes first ran.
    std::vector<PassTiming> passStats() const;
    PassTiming frameStats() const;  // first timestamp to last, per frame
    // The last collected frame's duration per pass (for the on-screen overlay).
    const std::vector<std::pair<std::string, double>>& lastFrame() const { return lastFrame_; }

  private:
    const Context& context_;
    VkQueryPool pool_ = VK_NULL_HANDLE;
    uint32_t maxScopes_;
    uint64_t validMask_;
    struct Scope {
        std::string name;
        int query = -1;  // index of its pair of timestamps; -1: skipped
    };
    std::vector<Scope> scopes_;  // this frame's scopes, in order
    uint32_t timedScopes_ = 0;   // how many of them have timestamps
    int openScope_ = -1;
    std::vector<std::string> passOrder_;
    std::vector<std::vector<double>> passSamples_;  // parallel to passOrder_
    std::vector<size_t> passRuns_;                  // parallel to passOrder_
    std::vector<double> frameSamples_;
    std::vector<std::pair<std::string, double>> lastFrame_;
};

// Median / p95 / min of a list of samples (by value: sorts a copy); runs = the number of samples.
PassTiming summarize(const std::string& name, std::vector<double> samples);

}  // namespace vct::vk
