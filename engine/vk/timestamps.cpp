// timestamps.cpp: a query pool of 2 * maxScopes timestamps; scopes past the limit are not timed.
#include "vk/timestamps.hpp"

#include "vk/check.hpp"
#include "vk/context.hpp"

namespace idk::vk {

TimestampQueries::TimestampQueries(Context& ctx, uint32_t maxScopes) : ctx_(ctx), maxScopes_(maxScopes) {
    if (!ctx.info().timestampsSupported) return;
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = maxScopes * 2;
    check(vkCreateQueryPool(ctx.device(), &info, nullptr, &pool_));
    // SPEC: queries must be reset before first use; hostQueryReset (baseline) allows it from the CPU.
    vkResetQueryPool(ctx.device(), pool_, 0, info.queryCount);
}

TimestampQueries::~TimestampQueries() {
    if (pool_) vkDestroyQueryPool(ctx_.device(), pool_, nullptr);
}

void TimestampQueries::reset(VkCommandBuffer cmd) {
    names_.clear();
    if (pool_) vkCmdResetQueryPool(cmd, pool_, 0, maxScopes_ * 2);
}

uint32_t TimestampQueries::begin(VkCommandBuffer cmd, const std::string& name) {
    auto scope = static_cast<uint32_t>(names_.size());
    names_.push_back(name);
    if (pool_ && scope < maxScopes_) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, pool_, scope * 2);
    return scope;
}

void TimestampQueries::end(VkCommandBuffer cmd, uint32_t scope) {
    if (pool_ && scope < maxScopes_)
        vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, pool_, scope * 2 + 1);
}

std::vector<ScopeTiming> TimestampQueries::read() const {
    std::vector<ScopeTiming> out;
    uint32_t count = std::min(static_cast<uint32_t>(names_.size()), maxScopes_);
    if (!pool_ || count == 0) return out;
    std::vector<uint64_t> ticks(count * 2);
    check(vkGetQueryPoolResults(ctx_.device(), pool_, 0, count * 2, ticks.size() * sizeof(uint64_t), ticks.data(),
                                sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    double period = ctx_.info().timestampPeriodNs;
    for (uint32_t i = 0; i < count; ++i) {
        double ns = double(ticks[i * 2 + 1] - ticks[i * 2]) * period;
        out.push_back({names_[i], ns * 1e-6});
    }
    return out;
}

}  // namespace idk::vk
