// timestamps.hpp: GPU time per named scope (one scope per render-graph pass) from timestamp query pairs.
// Results are read after the submission that wrote them has completed.
#pragma once
#include <volk.h>

#include <string>
#include <vector>

namespace idk::vk {

class Context;

struct ScopeTiming {
    std::string name;
    double milliseconds = 0.0;
};

class TimestampQueries {
public:
    TimestampQueries(Context& ctx, uint32_t maxScopes = 128);
    ~TimestampQueries();
    TimestampQueries(const TimestampQueries&) = delete;
    TimestampQueries& operator=(const TimestampQueries&) = delete;

    void reset(VkCommandBuffer cmd);  // record at the start of the command buffer
    uint32_t begin(VkCommandBuffer cmd, const std::string& name);  // returns the scope index
    void end(VkCommandBuffer cmd, uint32_t scope);
    // Reads all scopes recorded since reset(); the caller has waited for the submission.
    std::vector<ScopeTiming> read() const;
    bool supported() const noexcept { return pool_ != VK_NULL_HANDLE; }

private:
    Context& ctx_;
    VkQueryPool pool_ = VK_NULL_HANDLE;
    uint32_t maxScopes_;
    std::vector<std::string> names_;
};

}  // namespace idk::vk
