#include "vk/timer.h"

#include <algorithm>
#include <cmath>

#include "vk/check.h"

namespace vct::vk {

PassTiming summarize(const std::string& name, std::vector<double> samples) {
    PassTiming timing;
    timing.name = name;
    timing.samples = timing.runs = samples.size();
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

GpuTimer::~GpuTimer() {
    vkDestroyQueryPool(context_.device(), pool_, nullptr);
}

void GpuTimer::beginFrame(VkCommandBuffer cmd) {
    vkCmdResetQueryPool(cmd, pool_, 0, 2 * maxScopes_);
    scopes_.clear();
    timedScopes_ = 0;
    openScope_ = -1;
}

void GpuTimer::beginScope(VkCommandBuffer cmd, const std::string& name) {
    if (openScope_ >= 0)
        throw Error("GpuTimer: scope '" + name + "' opened inside '" + scopes_.back().name + "'");
    if (timedScopes_ == maxScopes_)
        throw Error("GpuTimer: more than " + std::to_string(maxScopes_) + " passes");
    openScope_ = int(timedScopes_++);
    scopes_.push_back({name, openScope_});
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, 2 * uint32_t(openScope_));
}

void GpuTimer::skipScope(const std::string& name) {
    if (openScope_ >= 0)
        throw Error("GpuTimer: scope '" + name + "' skipped inside '" + scopes_.back().name + "'");
    scopes_.push_back({name, -1});
}

void GpuTimer::endScope(VkCommandBuffer cmd) {
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, 2 * uint32_t(openScope_) + 1);
    openScope_ = -1;
}

void GpuTimer::collect(bool record) {
    lastFrame_.clear();
    if (timedScopes_ == 0) return;
    std::vector<uint64_t> stamps(2 * size_t(timedScopes_));
    VK_CHECK(vkGetQueryPoolResults(context_.device(), pool_, 0, uint32_t(stamps.size()),
                                   stamps.size() * sizeof(uint64_t), stamps.data(), sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    const double msPerTick = double(context_.properties().limits.timestampPeriod) * 1e-6;
    auto ticks = [&](uint64_t begin, uint64_t end) { return double((end - begin) & validMask_) * msPerTick; };
    for (const Scope& scope : scopes_) {
        const size_t q = size_t(scope.query);
        const double ms = scope.query >= 0 ? ticks(stamps[2 * q], stamps[2 * q + 1]) : 0.0;
        lastFrame_.emplace_back(scope.name, ms);
        if (!record) continue;
        auto it = std::find(passOrder_.begin(), passOrder_.end(), scope.name);
        if (it == passOrder_.end()) {
            passOrder_.push_back(scope.name);
            passSamples_.emplace_back();
            passRuns_.push_back(0);
            it = passOrder_.end() - 1;
        }
        const size_t pass = size_t(it - passOrder_.begin());
        passSamples_[pass].push_back(ms);
        passRuns_[pass] += scope.query >= 0 ? 1 : 0;
    }
    if (record) frameSamples_.push_back(ticks(stamps.front(), stamps.back()));
}

std::vector<PassTiming> GpuTimer::passStats() const {
    std::vector<PassTiming> stats;
    for (size_t i = 0; i < passOrder_.size(); ++i) {
        stats.push_back(summarize(passOrder_[i], passSamples_[i]));
        stats.back().runs = passRuns_[i];
    }
    return stats;
}

PassTiming GpuTimer::frameStats() const {
    return summarize("frame", frameSamples_);
}

}  // namespace vct::vk
