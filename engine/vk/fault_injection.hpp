// fault_injection.hpp: the test hook that simulates a failing GPU. With the environment variable
//     IDK_TEST_FAIL_SUBMIT=device-lost[:N]  or  IDK_TEST_FAIL_SUBMIT=out-of-device-memory[:N]
// the Nth queue submission of the process (1-based, default 1; counted over every vk::Context the process creates)
// returns VK_ERROR_DEVICE_LOST / VK_ERROR_OUT_OF_DEVICE_MEMORY instead of being submitted. It fires once, so a
// device recreated after the failure (the viewer's retry) works. Tests use it to check the message, the exit code
// and that no output file is written; no real driver can be made to fail on demand.
#pragma once
#include <volk.h>

#include <cstdint>

namespace idk::vk {

struct InjectedFailure {
    VkResult result = VK_SUCCESS;  // VK_SUCCESS: submit for real
    uint64_t submission = 0;       // the process-wide number of this submission
};

// Counts one submission; says whether it must fail. Thread-safe. Throws std::runtime_error naming the variable
// when its value is malformed.
InjectedFailure nextSubmission();

}  // namespace idk::vk
