// fault_injection.cpp: parses IDK_TEST_FAIL_SUBMIT once and counts submissions (see fault_injection.hpp).
#include "vk/fault_injection.hpp"

#include <atomic>
#include <charconv>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace idk::vk {
namespace {

struct Plan {
    VkResult result = VK_SUCCESS;
    uint64_t at = 0;
};

Plan parsePlan() {
    const char* env = std::getenv("IDK_TEST_FAIL_SUBMIT");
    if (!env || !*env) return {};
    const std::string text = env;
    const std::string kind = text.substr(0, text.find(':'));
    Plan plan;
    plan.at = 1;
    if (kind == "device-lost") plan.result = VK_ERROR_DEVICE_LOST;
    else if (kind == "out-of-device-memory") plan.result = VK_ERROR_OUT_OF_DEVICE_MEMORY;
    else throw std::runtime_error("IDK_TEST_FAIL_SUBMIT='" + text + "': use device-lost[:N] or out-of-device-memory[:N]");
    if (const size_t colon = text.find(':'); colon != std::string::npos) {
        const char* first = text.data() + colon + 1;
        const char* last = text.data() + text.size();
        const auto [end, error] = std::from_chars(first, last, plan.at);
        if (error != std::errc() || end != last || plan.at == 0)
            throw std::runtime_error("IDK_TEST_FAIL_SUBMIT='" + text + "': N must be a submission number >= 1");
    }
    return plan;
}

}  // namespace

InjectedFailure nextSubmission() {
    static const Plan plan = parsePlan();
    static std::atomic<uint64_t> count{0};
    const uint64_t n = ++count;
    return {n == plan.at ? plan.result : VK_SUCCESS, n};
}

}  // namespace idk::vk
