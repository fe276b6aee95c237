#include "vk/timer.h"

#include <algorithm>
#include <cmath>

#include "vk/check.h"

namespace vct::vk {

PassTiming summarize(const std::string& name, std::vector<double> samples) {
    PassTiming timing;
    timing.name = name;
    timing.samples = samples.size();
    if (samples.empty()) return timing;
    std::sort(samples.begin(), samples.end());
    const size_t n = samples.size();
    timing.medianMs = n % 2 ? samples[n / 2] : 0.5 * (samples[n / 2 - 1] + samples[n / 2]);
    // Nearest-rank p95.
    timing.p95Ms = samples[std::min(n - 1, size_t(std::ceil(0.95 * double(n))) - 1)];
    timing.minMs = samples.front();
    return timing;
}

GpuTimer::GpuTimer(const Context& context, uint32_t maxScopes) : context_(context), maxScopes_(maxScopes) {
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = 2 * maxScopes;
    VK_CHECK(vkCreateQueryPool(context.device(), &info, nullptr, &pool_));
    uint32_t familyCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(context.physicalDevice(), &familyCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(familyCount);
    vkGetPhysicalDeviceQueueFamilyProperties(context.physicalDevice(), &familyCount, families.data());
    const uint32_t bits = families[context.queueFamily()].timestampValidBits;
    validMask_ = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
}

GpuTimer::~GpuTimer() { vkDestroyQueryPool(context_.device(), pool_, nullptr); }

void GpuTimer::beginFrame(VkCommandBuffer cmd) {
    vkCmdResetQueryPool(cmd, pool_, 0, 2 * maxScopes_);
    scopeNames_.clear();
    openScope_ = -1;
}

void GpuTimer::beginScope(VkCommandBuffer cmd, const std::string& name) {
    if (openScope_ >= 0) throw Error("GpuTimer: scope '" + name + "' opened inside '" + scopeNames_.back() + "'");
    if (scopeNames_.size() == maxScopes_) throw Error("GpuTimer: more than " + std::to_string(maxScopes_) + " passes");
    openScope_ = int(scopeNames_.size());
    scopeNames_.push_back(name);
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, 2 * uint32_t(openScope_));
}

void GpuTimer::endScope(VkCommandBuffer cmd) {
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, 2 * uint32_t(openScope_) + 1);
    openScope_ = -1;
}

void GpuTimer::collect(bool record) {
    lastFrame_.clear();
    if (scopeNames_.empty()) return;
    std::vector<uint64_t> stamps(2 * scopeNames_.size());
    VK_CHECK(vkGetQueryPoolResults(context_.device(), pool_, 0, uint32_t(stamps.size()),
                                   stamps.size() * sizeof(uint64_t), stamps.data(), sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    const double msPerTick = double(context_.properties().limits.timestampPeriod) * 1e-6;
    auto ticks = [&](uint64_t begin, uint64_t end) { return double((end - begin) & validMask_) * msPerTick; };
    for (size_t i = 0; i < scopeNames_.size(); ++i) {
        const double ms = ticks(stamps[2 * i], stamps[2 * i + 1]);
        lastFrame_.emplace_back(scopeNames_[i], ms);
        if (!record) continue;
        auto it = std::find(passOrder_.begin(), passOrder_.end(), scopeNames_[i]);
        if (it == passOrder_.end()) {
            passOrder_.push_back(scopeNames_[i]);
            passSamples_.emplace_back();
            it = passOrder_.end() - 1;
        }
        passSamples_[size_t(it - passOrder_.begin())].push_back(ms);
    }
    if (record) frameSamples_.push_back(ticks(stamps.front(), stamps.back()));
}

std::vector<PassTiming> GpuTimer::passStats() const {
    std::vector<PassTiming> stats;
    for (size_t i = 0; i < passOrder_.size(); ++i) stats.push_back(summarize(passOrder_[i], passSamples_[i]));
    return stats;
}

PassTiming GpuTimer::frameStats() const { return summarize("frame", frameSamples_); }

}  // namespace vct::vk
