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

GpuTimer::GpuTimer(const Context& context, uint32_t maxScopes, uint32_t framesInFlight)
    : context_(context), maxScopes_(maxScopes), frames_(std::max(framesInFlight, 1u)) {
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = 2 * maxScopes * uint32_t(frames_.size());
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
    // All sets in use by frames not collected: a caller that submits more frames than it declared in flight
    // loses the oldest one's timestamps rather than reading queries that are reset again.
    if (begun_ - collected_ == frames_.size()) ++collected_;
    vkCmdResetQueryPool(cmd, pool_, firstQuery(begun_), 2 * maxScopes_);
    ++begun_;
    recording() = FrameQueries{};
    openScope_ = -1;
}

void GpuTimer::cancelFrame() {
    if (begun_ > collected_) --begun_;
    openScope_ = -1;
}

void GpuTimer::beginScope(VkCommandBuffer cmd, const std::string& name) {
    FrameQueries& frame = recording();
    if (openScope_ >= 0)
        throw Error("GpuTimer: scope '" + name + "' opened inside '" + frame.scopes.back().name + "'");
    if (frame.timedScopes == maxScopes_)
        throw Error("GpuTimer: more than " + std::to_string(maxScopes_) + " passes");
    openScope_ = int(frame.timedScopes++);
    frame.scopes.push_back({name, openScope_});
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_,
                         firstQuery(begun_ - 1) + 2 * uint32_t(openScope_));
}

void GpuTimer::skipScope(const std::string& name) {
    FrameQueries& frame = recording();
    if (openScope_ >= 0)
        throw Error("GpuTimer: scope '" + name + "' skipped inside '" + frame.scopes.back().name + "'");
    frame.scopes.push_back({name, -1});
}

void GpuTimer::endScope(VkCommandBuffer cmd) {
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_,
                         firstQuery(begun_ - 1) + 2 * uint32_t(openScope_) + 1);
    openScope_ = -1;
}

void GpuTimer::collect(bool record) {
    if (collected_ == begun_) return;
    const uint32_t first = firstQuery(collected_);
    const FrameQueries& frame = frames_[collected_++ % frames_.size()];
    lastFrame_.clear();
    if (frame.timedScopes == 0) return;
    std::vector<uint64_t> stamps(2 * size_t(frame.timedScopes));
    VK_CHECK(vkGetQueryPoolResults(context_.device(), pool_, first, uint32_t(stamps.size()),
                                   stamps.size() * sizeof(uint64_t), stamps.data(), sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    const double msPerTick = double(context_.properties().limits.timestampPeriod) * 1e-6;
    auto ticks = [&](uint64_t begin, uint64_t end) { return double((end - begin) & validMask_) * msPerTick; };
    for (const Scope& scope : frame.scopes) {
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
